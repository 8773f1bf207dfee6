"""An OpenSees twin of a femoat building run, for cross-checks in the tool engineers know.

:func:`opensees_run` writes a :class:`~femoat.structure.pounding.PoundingModel` (SDOF or modal
walls) as the equivalent openseespy model, runs it at a fixed time step and summarises it with
the keys of :attr:`femoat.results.RunResult.peaks`. :func:`opensees_commands` returns the same
model as a list of openseespy calls; :func:`write_opensees_script` writes them as a standalone
script.

The model is the one twin builder's on one axis (:mod:`femoat.opensees.twin`, where the OpenSees
model is written once: ``-ndm 1 -ndf 1``, one ``UniformExcitation``, the isolator kind's uniaxial
twin; the walls' chains: :mod:`femoat.opensees.wall_chain`; with P-Delta each story's
``Elastic −P/h`` beside its material, femoat's linear geometric stiffness, as in the 3D twin).
Refused with a sentence: a bearing kind without a uniaxial twin or a velocity-dependent friction
pendulum (check those in plan: :mod:`femoat.opensees.plan`).

The run records every node's displacement (mapped back to femoat's DOFs: a wall's chain to its
modal coordinates), the base and floor accelerations and the contact stresses (``cpu_seconds``
is the process time of the one ``analyze`` call, recorders included; see
``benchmarks/README.md``).

Differences from femoat that remain (see :mod:`femoat.opensees.single_impact` for the contact
materials): OpenSees' ViscoelasticGap pulls in tension (femoat's V cuts it unless
``allow_tension=True``); Hertzdamp takes δ̇₀ at the end of the first contact step and
ImpactMaterial carries a first-step offset, both O(dt); a fixed step does not locate gap
closure or separation, which costs O(dt) in impulse and O(dt²) elsewhere.
"""

import math

import numpy as np

from femoat.contact.laws import ContactLaw
from femoat.opensees.tags import CONTACT_ELE
from femoat.opensees.transient import (  # noqa: F401  (OpenSeesFailure, read_binary, ...: here before)
    OpenSeesFailure,
    analysis_commands,
    captured_stderr,
    check_history,
    checked_duration,
    read_binary,
    recorded_analysis,
    run_twin,
    set_initial_state,
    timed_analysis,
)
from femoat.opensees.twin import twin_commands, twin_rows
from femoat.opensees.wall_chain import chain_to_modes
from femoat.structure.pounding import PoundingModel, wall_modes
from femoat.units import G


def _check_model(model):
    if not isinstance(model, PoundingModel):
        raise ValueError("model must be a PoundingModel (femoat.structure.pounding).")
    for w in model.walls:
        if not isinstance(w.law, ContactLaw):
            raise ValueError("walls: each wall needs a ContactLaw.")


def opensees_commands(model, motion):
    """The openseespy calls that build ``model`` under ``motion``: a list of
    ``(function name, *args)`` tuples, ending with the excitation (no analysis set-up, no
    ``analyze``): the one builder :func:`~femoat.opensees.twin.twin_commands` on one axis.

    Raises ValueError for what has no OpenSees twin (velocity-dependent friction, a bearing
    kind without a uniaxial twin).
    """
    _check_model(model)
    return twin_commands(model, motion)


def _initial_state(model, motion, v0):
    """Node tags (the building's, then every wall's chain), T (nodes × DOFs: node displacements
    X = T·u from femoat's DOFs u) and the initial velocities and equilibrium accelerations per
    femoat DOF."""
    packed = model.pack()
    n = packed.n
    rows, T = twin_rows(model)
    nodes = [node for node, _ in rows]
    v = np.zeros(n) if v0 is None else np.array(v0, dtype=float)
    if v.shape != (n,) or not np.all(np.isfinite(v)):
        raise ValueError(f"v0 must be {n} finite velocities [in/s] ({packed.dof_names}).")
    ag0 = float(motion.accel[0])
    a = np.linalg.solve(packed.M, -packed.r * ag0 - packed.C @ v)
    return packed, nodes, T, v, a


def _to_dofs(X, model, ns):
    """femoat DOF values (..., n) from the 1D twin's node values (..., nodes)."""
    parts, col = [X[..., :ns]], ns
    for w in model.walls:
        m = len(wall_modes(w.wall)[0])
        parts.append(chain_to_modes(X[..., col:col + m], w.wall, w.sign))
        col += m
    return np.concatenate(parts, axis=-1)


def opensees_run(model, motion, dt, duration=None, v0=None, tol=1e-10, max_iter=50):
    """Run the OpenSees twin of ``model`` under ``motion`` at the fixed step ``dt``.

    Replaces any model in the openseespy interpreter (``wipe`` before and after).

    Parameters
    ----------
    model : PoundingModel
        Building and moat walls, SDOF or modal; its isolator a bearing kind with a uniaxial
        twin (constant-μ friction pendulum, lead-rubber), an Elastic spring or none.
    motion : GroundMotion
        Ground acceleration record.
    dt : float
        Fixed time step [s], > 0.
    duration : float or None
        Analysis time [s]; default: the record plus 2 s, as :func:`femoat.run.run`.
    v0 : array or None
        Initial relative velocities [in/s] per femoat DOF (``model.dof_names()``).
    tol : float
        ``NormDispIncr`` tolerance [in] of the Newton iterations.
    max_iter : int
        Newton iterations per step before OpenSees gives up (then :class:`OpenSeesFailure`).

    Returns
    -------
    dict
        ``time`` [s] (t = n·dt); ``base_displacement`` [in]; ``floor_displacement`` [in] (one
        column per floor); ``wall_displacement`` [in] (per wall, away from the building);
        ``contact_force`` [kip] (compression positive) and ``indentation`` [in] per wall;
        ``contact_names`` ("pos"/"neg"); ``peaks`` (the keys of RunResult.peaks that apply:
        impact forces with the same parabolic refinement, impact counts, displacements,
        indentation, impulse, drifts, accelerations [g], steps, cpu_seconds); ``impacts`` (one
        dict per episode: side, start, duration, peak_force, max_indentation, impulse);
        ``energy`` (``input``, ``kinetic`` [kip·in] and per-contact trapezoidal ``contact``
        work: what each contact took out of the discrete system, < 0 is energy it created);
        ``cpu_seconds`` (process time of the ``analyze`` call, recorders included);
        ``steps``; ``dt``; ``commands``.

    Raises
    ------
    OpenSeesFailure
        Newton failed at a step, or the state went NaN/inf.
    """
    duration = checked_duration(dt, duration, motion.duration)
    cmds = opensees_commands(model, motion)
    packed, nodes, T, v_init, a_init = _initial_state(model, motion, v0)
    n_steps = int(math.ceil(duration / dt - 1e-9))
    ns, nw = packed.n_struct, len(model.walls)

    def history(ops):
        hist = _step_loop(ops, nodes, n_steps, dt, ns, nw, model)
        vel = _to_dofs(np.array([ops.nodeVel(nd, 1) for nd in nodes]), model, ns)
        return hist, 0.5 * float(vel @ packed.M @ vel)

    rows = [(node, 1) for node in nodes]
    hist, kinetic = run_twin(
        cmds, lambda ops: set_initial_state(ops, rows, T @ v_init, T @ a_init), history, tol,
        max_iter)
    return _summarise(hist, model, motion, packed, dt, kinetic, cmds)


def _step_loop(ops, nodes, n_steps, dt, ns, nw, model):
    """``analyze(n_steps, dt)`` with binary recorders (:func:`recorded_analysis`) of every
    node's displacement, the building's accelerations and the contact forces; returns the
    histories in femoat's DOFs and the process time of the analysis."""
    x0 = _to_dofs(np.array([ops.nodeDisp(nd, 1) for nd in nodes]), model, ns)
    a0 = np.array([ops.nodeAccel(nd, 1) for nd in nodes[:ns]])
    recorders = [(1 + len(nodes), "Node", "-time", "-node", *nodes, "-dof", 1, "disp"),
                 (ns, "Node", "-node", *nodes[:ns], "-dof", 1, "accel")]
    if nw:
        recorders.append((nw, "Element", "-ele", *[CONTACT_ELE + i for i in range(nw)],
                          "material", "1", "stress"))
    status, cpu, (disp, acc, *force) = recorded_analysis(ops, n_steps, dt, recorders)
    m = disp.shape[0]
    force = -force[0] if nw else np.zeros((m, 0))
    x = np.vstack([x0, _to_dofs(disp[:, 1:], model, ns)])  # femoat's DOFs
    acc = np.vstack([a0, acc])
    f = np.vstack([np.zeros(nw), force])
    check_history(np.all(np.isfinite(x), axis=1) & np.all(np.isfinite(f), axis=1), status, m,
                  n_steps, dt, hint=": below ~1e-9 in, round-off can keep a stiff contact's "
                  "increments from meeting it")
    return dict(x=x, acc=acc, f=f, cpu=cpu)


def _summarise(hist, model, motion, packed, dt, kinetic, cmds):
    from femoat.dense_peaks import parabolic_peak
    from femoat.results import impact_summary

    x, acc, f = hist["x"], hist["acc"], hist["f"]
    ns, nw = packed.n_struct, len(model.walls)
    t = np.arange(x.shape[0]) * dt
    base = x[:, 0]
    walls, col = np.zeros((t.size, nw)), ns  # each impact point's displacement, away
    for c, w in enumerate(model.walls):
        phi = wall_modes(w.wall)[3]
        walls[:, c] = x[:, col:col + phi.size] @ phi
        col += phi.size
    indent = np.column_stack([w.sign * base - w.gap - walls[:, i]
                              for i, w in enumerate(model.walls)]) if nw else np.zeros((t.size, 0))
    names = ["pos" if w.sign > 0 else "neg" for w in model.walls]
    impacts = []
    for c in range(nw):
        closed = indent[:, c] > 0.0
        starts = np.flatnonzero(closed & ~np.r_[False, closed[:-1]])
        for s in starts:
            e = s
            while e + 1 < t.size and closed[e + 1]:
                e += 1
            seg = slice(max(s - 1, 0), min(e + 2, t.size))  # the open samples either side
            k = s + int(np.argmax(f[s:e + 1, c]))
            t_open = t[s] if s == 0 else (
                t[s - 1] + dt * (-indent[s - 1, c]) / (indent[s, c] - indent[s - 1, c]))
            impacts.append(dict(
                side=names[c], start=float(t_open), duration=float((e - s + 1) * dt),
                peak_force=float(parabolic_peak(t, f[:, c], k)),
                max_indentation=float(indent[s:e + 1, c].max()),
                impulse=float(np.trapezoid(f[seg, c], t[seg]))))
    impacts.sort(key=lambda r: r["start"])
    ag = np.interp(t, motion.time, motion.accel, right=0.0)
    absacc = acc + ag[:, None]
    drifts = np.diff(x[:, :ns], axis=1)
    du = np.diff(x, axis=0)
    # E_in = Σ ½(p_n + p_{n+1})·Δu with p = −r·a_g on every DOF (relative formulation)
    e_input = float(-np.sum(0.5 * (ag[:-1] + ag[1:]) * (du @ packed.r)))
    e_contact = [float(np.sum(0.5 * (f[1:, c] + f[:-1, c]) * np.diff(indent[:, c])))
                 for c in range(nw)]
    hits = impact_summary(impacts)
    peaks = {
        **{k: hits[k] for k in ("peak_impact_force", "peak_impact_force_pos",
                                "peak_impact_force_neg", "impacts_pos", "impacts_neg")},
        "peak_base_displacement": float(np.abs(base).max()),
        "peak_wall_displacement": float(np.abs(walls).max()) if nw else 0.0,
        "peak_indentation": float(max(0.0, indent.max())) if nw else 0.0,
        "peak_impulse": hits["peak_impulse"],
        "peak_drift": [float(d) for d in np.abs(drifts).max(axis=0)],
        "peak_floor_acceleration": [float(a) for a in np.abs(absacc[:, 1:]).max(axis=0) / G],
        "peak_base_acceleration": float(np.abs(absacc[:, 0]).max() / G),
        "cpu_seconds": hist["cpu"],
        "steps": int(t.size - 1),
    }
    return dict(
        time=t, base_displacement=base, floor_displacement=x[:, 1:ns], wall_displacement=walls,
        contact_force=f, indentation=indent, contact_names=names, peaks=peaks, impacts=impacts,
        energy=dict(input=e_input, kinetic=float(kinetic), contact=e_contact),
        cpu_seconds=hist["cpu"], steps=int(t.size - 1), dt=float(dt), commands=cmds)


def write_opensees_script(model, motion, dt, path, duration=None, tol=1e-10, max_iter=50):
    """Write a standalone openseespy script of ``model`` under ``motion`` (fixed step ``dt``),
    atomically; it records node displacements and contact forces to ``<path stem>_*.out``."""
    from femoat.atomic import write_text

    cmds = opensees_commands(model, motion) + analysis_commands(tol, max_iter)
    if duration is None:
        duration = motion.duration + 2.0
    n_steps = int(math.ceil(duration / dt - 1e-9))
    packed, nodes, T, _, a_init = _initial_state(model, motion, None)
    lines = [f'"""OpenSees twin of a femoat model (units kip, in, s): {motion.name}, '
             f'dt = {dt:g} s, {n_steps} steps. Written by femoat.opensees.building."""',
             "import openseespy.opensees as ops", ""]
    for name, *args in cmds[:-len(analysis_commands(tol, max_iter))]:
        lines.append(f"ops.{name}({', '.join(repr(a) for a in args)})")
    for node, ai in zip(nodes, T @ a_init):
        lines.append(f"ops.setNodeAccel({node}, 1, {float(ai)!r}, '-commit')")
    stem = str(path).rsplit(".", 1)[0]
    lines.append(f"ops.recorder('Node', '-file', {stem + '_disp.out'!r}, '-time', '-node', "
                 f"{', '.join(str(nd) for nd in nodes)}, '-dof', 1, 'disp')")
    if model.walls:
        tags = ", ".join(str(CONTACT_ELE + i) for i in range(len(model.walls)))
        lines.append(f"ops.recorder('Element', '-file', {stem + '_contact.out'!r}, '-time', "
                     f"'-ele', {tags}, 'material', '1', 'stress')")
    for name, *args in analysis_commands(tol, max_iter):
        lines.append(f"ops.{name}({', '.join(repr(a) for a in args)})")
    lines += [f"status = ops.analyze({n_steps}, {float(dt)!r})",
              "ops.wipe()", "print('analyze returned', status)", ""]
    write_text(path, "\n".join(lines))
    return path
