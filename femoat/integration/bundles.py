"""The compiled loop's data, grouped by role: plain tuples that numba compiles (one signature
for every run: :func:`femoat.integration.driver.run_chunk` takes one of each).

* :class:`Model`: what is integrated (matrices, elements, contacts, the ground record, and
  ``Minv``, the inverse of the mass block the explicit step integrates); read only.
* :class:`State`: what the loop advances (time, the ground acceleration now, kinematics,
  committed element, plan-bearing and contact states with their forces and work (``c_ft``,
  ``c_Wt``: the walls' friction), energies, counters, limit-state times, the running peaks of
  :mod:`~femoat.integration.recording.peaks` and each contact's running episode of
  :mod:`~femoat.integration.recording.episodes`, and the step controller's state: the next
  step ``h``, the cruising step ``h_cruise``, a pending landing on a kink or an event
  ``shortened`` and the contact it lands on ``landing``, the samples since the last record
  ``since_record``, each an array of one); the loop's only persistent output besides the
  recorder.
* :class:`Settings`: the method, the step controller and the events, by name (filled by
  :func:`femoat.integration.solve.integrate` from the
  :class:`~femoat.integration.settings.Integrator`), the error scales and the limit rows.
* :class:`Work`: scratch arrays of a step (trial kinematics, forces, tangents, the linear system,
  the ground acceleration at the step's end ``ag1`` and at a stage ``ag_stage``;
  for the explicit steps (:mod:`femoat.integration.methods.dp5`, ``ark5``) their stages ``kv``,
  ``ka``, error ``eu``, ``ev``, energy increments ``de`` and the walls' cached propagators; for
  the coupled-friction step the plan bearings that carry their friction state ``b_rate`` (flag
  per bearing: the width of its state, 0 when not carried; cleared before every step attempt
  and at the commit), that state at the current stage ``bz`` (nb, nq) and its stage rates ``kz``
  (stages, nb, nq), nq the registry's ``rate_width()``, and one scratch array ``rq``
  (4 + 2·nq, nq + 1) for a stage's solve and the kink and turn searches, read through
  :func:`rate_scratch` (one array: every array in the bundle is passed field by field to each
  compiled function that takes the bundle, and six small ones cost the plan step ~20 %)).
* :class:`Recorder`: the history buffers of :mod:`~femoat.integration.recording.channels` (one
  row per recorded sample; sample k in row k modulo their length: a ring of
  ``recorder.RING_ROWS`` rows when the run keeps no history; a channel with zero columns is not
  recorded), and ``episodes``, the impact table (one row per finished episode).

Units: kip, in, s.
"""

from collections import namedtuple

from femoat.compilation.jit import njit

from femoat.integration.recording.channels import BUFFERS

Model = namedtuple("Model", [
    "M", "C", "K",      # (n, n) mass, damping, stiffness
    "r", "ag",          # the ground load −r·a_g: r (n, components), a_g (samples, components)
    "dof_axis",         # (n,) the ground component each DOF moves along (absolute accelerations)
    "base_xy",          # (2,) the base mat's x and y DOFs in plan (−1, −1 in 1D)
    "el_i", "el_j", "el_code", "el_P",  # two-node uniaxial elements
    "b_kind", "b_dofs", "b_P",  # plan bearings: kind (femoat.bearings), (nb, 2) DOFs x, y; params
    "c_B", "c_gap", "c_code", "c_P",    # contacts: δ = c_B·u − gap, law, params
    "c_T", "c_mu",      # the walls' tangent rows and friction coefficients (plan)
    "Minv",             # inverse of the mass block the explicit step integrates
])
State = namedtuple("State", ["t", "ag_now", "u", "v", "a", "F", "el_S", "el_f", "el_d",
                             "el_W", "b_S", "b_f", "b_W", "c_H", "c_f", "c_d", "c_W", "c_ft",
                             "c_Wt", "c_closed", "energy", "stats",
                             "first_exceed", "pk", "pk_ring", "pk_n", "ep",
                             "h", "h_cruise", "shortened", "landing", "since_record"])
Settings = namedtuple("Settings", [
    # the method
    "method",          # code of the open phase's method (femoat.integration.methods)
    "quintic_peaks",   # bool: the open phase's acceleration crests from the quintic interpolant
    "beta", "gamma", "alpha",  # Newmark/HHT-α [-]
    "newton_tol",      # [-] Newton's convergence, relative to the DOF scales
    "max_newton",      # Newton iterations per step attempt
    "n_coupled",       # DOFs solved densely while no contact can act (lazy walls)
    "n_explicit",      # DOFs the explicit step integrates (the building; the walls exactly)
    "n_struct",        # building DOFs (the first ones)
    # the step controller
    "rtol",            # [-] local error tolerance
    "h_max", "h_min",  # [s] largest and smallest step
    "t_end",           # [s] the run's end
    "dt_record",       # [s] the ground record's sample interval
    "scale_open", "scale_contact", "err_ref", "scale_accel",  # error scales (solve.error_scales)
    "episode_dofs",    # (n,) 1 where a contact-phase error is scaled to the episode's indentation
    "episode_floor", "episode_tighten",  # [-] that scale's floor and factor (solve.episode_scaling)
    # contact events
    "h_contact",       # [s] the step after a closure
    "gap_tol",         # [in] a crossing is located within this of δ = 0
    # recording and limits
    "record_every",    # keep every k-th step of the open phase
    "ring",            # bool: the recorder is a ring (a run without history)
    "stop_at_limit",   # bool: a criterion row ends the run (a runaway row always does)
    "limits",          # the limit rows (femoat.integration.limits)
])
Work = namedtuple("Work", ["u", "v", "a", "F", "KT", "CT", "A", "b", "ef", "ed", "bf", "cf",
                           "cd", "cft", "ag1", "ag_stage", "k22",
                           "kv", "ka", "eu", "ev", "de", "wexp", "wexp_h",
                           "wscratch", "s_tmp", "b_rate", "bz", "kz", "rq"])
Recorder = namedtuple("Recorder", [*BUFFERS, "episodes"])


@njit(cache=True, inline="always")
def rate_scratch(work):
    """(z0, g, w, v, J, A): the views :func:`rate_views` of ``work.rq``."""
    return rate_views(work.rq)


FSAL_ROWS = 9
"""Rows of ``kz`` after the method's stages (:func:`fsal_views`): where the last coupled trial
ended for each bearing (z, (u_x, u_y), (v_x, v_y), its rate's regime code) and the first-stage
rate a step starting at a recorded point takes (rate, z, u, v, code): the coupled-friction
step's first same as last for a stiff rate (``femoat.bearings.registry.RATE_KERNELS``,
``plan_rate_fsal``). NaN until written (no point matches)."""


@njit(cache=True, inline="always")
def fsal_views(kz, e):
    """Bearing ``e``'s rows of ``kz`` (:data:`FSAL_ROWS`): (its rate at the method's last stage,
    trial end z, u, v, code, recorded rate, z, u, v, code)."""
    n = kz.shape[0] - FSAL_ROWS
    return (kz[n - 1, e], kz[n, e], kz[n + 1, e], kz[n + 2, e], kz[n + 3, e], kz[n + 4, e],
            kz[n + 5, e], kz[n + 6, e], kz[n + 7, e], kz[n + 8, e])


@njit(cache=True, inline="always")
def rate_views(rq):
    """(z0, g, w, v, J, A): views of the rate scratch ``rq``, four vectors of at least nq
    entries, J (nq, nq + 1: a kind uses its first nq columns) and A (nq, nq + 1)."""
    nq = rq.shape[1] - 1
    return rq[0], rq[1], rq[2], rq[3], rq[4:4 + nq], rq[4 + nq:4 + 2 * nq]
