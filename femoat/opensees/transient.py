"""The transient analysis every OpenSees twin runs (1D and 3D): its arguments checked, the model
built with OpenSees' messages captured, the initial state set, Newmark's fixed steps in one
``analyze`` call with ``-binary`` recorders (:func:`recorded_analysis`), and a failed or
non-finite history turned into :class:`OpenSeesFailure`.

What differs between the twins (the model's commands, from the one builder
:mod:`femoat.opensees.twin`; which node DOFs carry the initial velocities and accelerations;
which recorders, and how their columns map back to femoat's DOFs) is passed in; :func:`femoat.opensees.building.opensees_run` and
:func:`femoat.opensees.plan.opensees_plan_run` are the two callers.
"""

import contextlib
import math
import os
import tempfile
import time as _time

import numpy as np

from femoat.opensees.available import import_opensees


class OpenSeesFailure(RuntimeError):
    """OpenSees could not finish the analysis (Newton failed, or the state went non-finite).
    ``kind`` is "diverged" or "nan"; ``time`` [s] and ``step`` where it happened."""

    def __init__(self, message, kind, time, step):
        super().__init__(message)
        self.kind, self.time, self.step = kind, time, step


def analysis_commands(tol, max_iter):
    """Newmark average acceleration, Newton, ``NormDispIncr`` at ``tol`` [in] in ``max_iter``
    iterations: the analysis of every twin."""
    return [("constraints", "Plain"), ("numberer", "Plain"), ("system", "BandGeneral"),
            ("test", "NormDispIncr", tol, max_iter), ("algorithm", "Newton"),
            ("integrator", "Newmark", 0.5, 0.25), ("analysis", "Transient")]


def checked_duration(dt, duration, record_duration):
    """The analysis time [s]: ``duration``, or the record plus 2 s (as :func:`femoat.run.run`);
    raises unless it and the fixed step ``dt`` [s] are positive and finite."""
    if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt = {dt!r} must be a positive time step [s].")
    if duration is None:
        duration = record_duration + 2.0
    if not (isinstance(duration, (int, float)) and math.isfinite(duration) and duration > 0):
        raise ValueError(f"duration = {duration!r} must be a positive time [s].")
    return duration


def run_twin(cmds, initial, history, tol, max_iter):
    """Build the model from ``cmds`` (openseespy calls), let ``initial(ops)`` set its initial
    state, set up :func:`analysis_commands` and return ``history(ops)`` (which analyses and
    reads the results). OpenSees' messages go to a buffer, and the end of them is added to an
    :class:`OpenSeesFailure`'s message; the interpreter is wiped before returning."""
    ops = import_opensees()
    log = []
    try:
        with captured_stderr(log):
            for name, *args in cmds:
                getattr(ops, name)(*args)
            initial(ops)
            for name, *args in analysis_commands(tol, max_iter):
                getattr(ops, name)(*args)
            return history(ops)
    except OpenSeesFailure as exc:
        tail = " ".join(" ".join(log).split()[-40:])
        raise OpenSeesFailure(f"{exc} OpenSees said: {tail}", exc.kind, exc.time,
                              exc.step) from None
    finally:
        ops.wipe()


def set_initial_state(ops, rows, velocities, accelerations):
    """Set each (node, DOF) of ``rows`` to its initial velocity [in/s] (when not zero) and
    acceleration [in/s²], committed."""
    for (node, dof), vi, ai in zip(rows, velocities, accelerations):
        if vi != 0.0:
            ops.setNodeVel(node, dof, float(vi), "-commit")
        ops.setNodeAccel(node, dof, float(ai), "-commit")


def timed_analysis(ops, n_steps, dt):
    """``analyze(n_steps, dt)`` in one call, then the recorders removed (flushed and closed);
    returns (OpenSees' status, process time of the call [s], recorders included)."""
    cpu0 = _time.process_time()
    status = ops.analyze(n_steps, dt)
    ops.remove("recorders")
    return status, _time.process_time() - cpu0


def recorded_analysis(ops, n_steps, dt, recorders):
    """``analyze(n_steps, dt)`` in one call (:func:`timed_analysis`) with ``-binary`` recorders
    (the cheapest way to keep histories in OpenSees: a Python loop reading results after every
    step costs more than the analysis itself). ``recorders``: one ``(columns, kind, *args)`` per
    recorder, ``ops.recorder(kind, "-binary", file, *args)`` writing ``columns`` values a step.
    Returns (OpenSees' status, process time of the call [s], one array (steps, columns) per
    recorder, all cut to the steps every one of them holds)."""
    with tempfile.TemporaryDirectory(prefix="femoat_opensees_") as folder:
        paths = [os.path.join(folder, f"{k}.bin") for k in range(len(recorders))]
        for path, (_, kind, *args) in zip(paths, recorders):
            ops.recorder(kind, "-binary", path, *args)
        status, cpu = timed_analysis(ops, n_steps, dt)
        rows = [read_binary(path, columns) for path, (columns, *_) in zip(paths, recorders)]
    done = min(r.shape[0] for r in rows)
    return status, cpu, [r[:done] for r in rows]


def check_history(finite, status, done, n_steps, dt, hint=""):
    """Raise :class:`OpenSeesFailure` at the first step whose state is not finite (``finite``:
    one bool per recorded step, the initial state first) or, when OpenSees stopped early
    (``status`` not 0 or ``done`` < ``n_steps`` steps recorded), at the step it failed."""
    bad = ~np.asarray(finite)
    if bad.any():
        k = int(np.argmax(bad))
        raise OpenSeesFailure(f"OpenSees returned a non-finite state at step {k} "
                              f"(t = {k * dt:.6g} s).", "nan", k * dt, k)
    if status != 0 or done < n_steps:
        raise OpenSeesFailure(
            f"OpenSees did not converge at step {done + 1} (t = {(done + 1) * dt:.6g} s, "
            f"dt = {dt:g} s); a smaller dt may help, or a looser tol (the NormDispIncr test "
            f"[in]{hint}).", "diverged", (done + 1) * dt, done + 1)


def read_binary(path, ncol):
    """Rows of an OpenSees ``-binary`` recorder file: ncol float64 values then a newline byte."""
    raw = np.fromfile(path, dtype=np.uint8)
    width = 8 * ncol + 1
    rows = raw.size // width
    return raw[: rows * width].reshape(rows, width)[:, : 8 * ncol].copy().view("<f8")


@contextlib.contextmanager
def captured_stderr(sink):
    """Collect what OpenSees writes to file descriptor 2 (material banners, warnings) into
    ``sink`` (a list) instead of the terminal."""
    try:
        fd = os.dup(2)
    except OSError:  # no real stderr: nothing to capture
        yield
        return
    with tempfile.TemporaryFile(mode="w+b") as tmp:
        os.dup2(tmp.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(fd, 2)
            os.close(fd)
            tmp.seek(0)
            sink.append(tmp.read().decode("utf-8", "replace"))
