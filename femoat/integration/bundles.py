"""The compiled loop's data, grouped by role: plain tuples of arrays that numba compiles and the
ahead-of-time module exports (:func:`femoat.integration.kernel.run_chunk` takes one of each).

* :class:`Model`: what is integrated (matrices, elements, contacts, the ground record, and
  ``Minv``, the inverse of the mass block the explicit step integrates); read only.
* :class:`State`: what the loop advances (time, step, kinematics, committed element and contact
  states, energies, counters, limit-state times, the running peaks of
  :mod:`femoat.integration.peaks` and each contact's running episode of
  :mod:`femoat.integration.episodes`); the loop's only persistent output besides the recorder.
* :class:`Settings`: the method, the step controller and the events (float and integer options,
  see the ``F_*``/``I_*`` indices of :mod:`femoat.integration.kernel`), the error scales and the
  limit states.
* :class:`Work`: scratch arrays of a step (trial kinematics, forces, tangents, the linear system;
  for the explicit step of :mod:`femoat.integration.explicit` its stages ``kv``, ``ka``,
  error ``eu``, ``ev``, energy increments ``de`` and the walls' cached propagators).
* :class:`Recorder`: the history buffers, one row per recorded step (sample k in row k modulo
  their length: a ring of ``options.RING_ROWS`` rows when the run keeps no history); a channel
  with zero columns is not recorded; and ``episodes``, the impact table (one row per finished
  episode). A new channel is a new field here, its line in
  :func:`~femoat.integration.kernel.record` and its width in
  :data:`femoat.integration.solve.RECORDER_COLUMNS` (plus, to reach users, its entry in
  ``RawHistory`` and :mod:`femoat.results`).

Units: kip, in, s.
"""

from collections import namedtuple

Model = namedtuple("Model", ["M", "C", "K", "r", "ag", "el_i", "el_j", "el_code", "el_P", "c_B",
                             "c_gap", "c_code", "c_P", "Minv"])
State = namedtuple("State", ["t", "h", "ag_now", "u", "v", "a", "F", "el_S", "el_f", "el_d",
                             "el_W", "c_H", "c_f", "c_d", "c_W", "c_closed", "energy", "stats",
                             "first_exceed", "pk", "pk_ring", "pk_n", "ep", "ctl"])
Settings = namedtuple("Settings", ["fopt", "iopt", "scale_open", "scale_contact", "err_ref",
                                   "scale_accel", "limits"])
Work = namedtuple("Work", ["u", "v", "a", "F", "KT", "CT", "A", "b", "ef", "ed", "cf", "cd",
                           "kv", "ka", "eu", "ev", "de", "wexp", "wexp_h",
                           "wscratch", "s_tmp"])
Recorder = namedtuple("Recorder", ["t", "u", "v", "a", "ag", "ef", "ed", "cf", "cd", "cv",
                                   "closed", "episodes"])
