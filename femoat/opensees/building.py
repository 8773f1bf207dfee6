"""An OpenSees twin of a femoat building run, for cross-checks in the tool engineers know.

:func:`opensees_run` writes a :class:`~femoat.structure.pounding.PoundingModel` (SDOF or modal
walls) as the equivalent openseespy model, runs it at a fixed time step and summarises it with
the keys of :attr:`femoat.results.RunResult.peaks`. :func:`opensees_commands` returns the same
model as a list of openseespy calls; :func:`write_opensees_script` writes them as a standalone
script.

OpenSees model (written once here)
----------------------------------
* 1-D, one DOF per node, every displacement relative to the ground (``UniformExcitation``
  applies −m·a_g to every lumped mass, as femoat's ``r`` vector does for the building and an
  SDOF wall).
* Nodes: 1 ground (fixed); 2 base mat; 3, 4, … floors bottom to top; then each wall's chain
  (below): its first node ``_WALL_NODE + i`` for wall i of ``model.walls``, its later nodes
  ``_MODE_TAG + 100·i + j``. A wall node's displacement x is along +x, so femoat's wall
  coordinate q (positive away from the building) is q = side·x for an SDOF wall.
* A wall of N modes (m_i, k_i, c_i, impact shape φ_i, ground participation L_i; an SDOF wall is
  one mode with φ = 1 and L = m) is a chain of N nodes along the axis (:func:`wall_chain`):
  with s_i = φ_i·q_i the mode's displacement at the impact point, chain node j moves
  X_j = side·Σ_{i≤j} s_i, so the last node is the impact point. Mode i's equation divided by
  φ_i, (m_i/φ_i²)·s̈_i + (c_i/φ_i²)·ṡ_i + (k_i/φ_i²)·s_i = −(L_i/φ_i)·a_g + F, is a spring and
  dashpot (``zeroLength``, ``Elastic k/φ² c/φ²``) between nodes j−1 and j (the ground for the
  first) and the mass m/φ² on the relative motion: lumped on the first node, an
  ``InertiaTruss`` (inerter: force m·(ẍ_j − ẍ_{j−1})) for later modes. The excitation loads
  only the lumped mass, so a ``Plain`` pattern of the same a_g adds the difference on each
  chain node (P_j = L_{j+1}/φ_{j+1} − L_j/φ_j, plus m_1/φ_1² on the first; none for an SDOF
  wall). This is femoat's modal wall exactly (the contact force F acts on every s_i, i.e.
  φ_i·F on q_i); ``InertiaTruss`` prints its inertance on every step (to the captured
  stderr).
* Elements (all ``zeroLength``, ``-dir 1``; strain = u_j − u_i):
    - isolator, ground → base: ``Parallel(Elastic W/R, ElasticPP μW/u_y u_y)`` for a constant-μ
      friction pendulum (its EPP friction spring is ElasticPP exactly); ``Elastic k`` for an
      elastic isolator; none when ``isolator is None``;
    - story k, floor k−1 → floor k: ``Elastic k`` / ``Steel01 Fy k0 b`` (Bilinear) /
      ``Bilin …`` (IMKBilinear, :meth:`~femoat.structure.materials.IMKBilinear.opensees_bilin_args`)
      in ``Parallel`` with ``Elastic 0 c``, the story dashpot c = β·k0 of
      :meth:`PoundingModel.pack`;
    - wall modes: the chain above (an SDOF wall: ``Elastic K1 C_imp``, ground → wall);
    - contact: base → wall for side +1, wall → base for side −1, so that closing the gap makes
      the strain negative on both sides; the gap material is
      :func:`~femoat.opensees.single_impact.opensees_contact_material` (compression
      convention: gap −g0, stress −f in contact).
* Ground motion: ``Path`` time series of a_g [in/s²] at the record's dt (linear between samples,
  zero after the last, as femoat). Initial accelerations are set to equilibrium,
  a0 = M⁻¹(−r·a_g(0) − C·v0), as femoat starts (OpenSees would otherwise start from a0 = 0).
* Analysis: Newmark average acceleration (γ = 1/2, β = 1/4), Newton, ``NormDispIncr`` test,
  fixed dt, one ``analyze(n, dt)`` call with ``-binary`` recorders of the node displacements,
  the base and floor accelerations and the contact stresses (``cpu_seconds`` is the process
  time of that call, recorders included; see ``benchmarks/README.md``).

Differences from femoat that remain (see :mod:`femoat.opensees.single_impact` for the contact
materials): OpenSees' ViscoelasticGap pulls in tension (femoat's V cuts it unless
``allow_tension=True``); Hertzdamp takes δ̇₀ at the end of the first contact step and
ImpactMaterial carries a first-step offset, both O(dt); a fixed step does not locate gap
closure or separation, which costs O(dt) in impulse and O(dt²) elsewhere.
"""

import math
import os
import tempfile

import numpy as np

from femoat.contact.laws import ContactLaw
from femoat.opensees.transient import (  # noqa: F401  (OpenSeesFailure, read_binary, ...: here before)
    OpenSeesFailure,
    analysis_commands,
    captured_stderr,
    check_history,
    checked_duration,
    read_binary,
    run_twin,
    set_initial_state,
    timed_analysis,
)
from femoat.opensees.single_impact import opensees_contact_material
from femoat.bearings import registry as bearing_registry
from femoat.structure.materials import Bilinear, Elastic, IMKBilinear
from femoat.structure.pounding import PoundingModel, wall_modes
from femoat.units import G

_GROUND, _BASE, _WALL_NODE = 1, 2, 100
_ISO_ELE, _STORY_ELE, _WALL_ELE, _CONTACT_ELE = 1, 10, 100, 200
_MODE_TAG = 1000
"""Nodes and elements of a wall's second and later modes: ``_MODE_TAG + 100·wall + mode``."""
_INERTER_TAG = 100000
"""The inerter of wall i's mode j >= 2: ``_INERTER_TAG + 100·i + j``."""
_WALL_SERIES = 100
"""Time series and pattern of wall i's ground-load correction: ``_WALL_SERIES + i``."""


def story_material(mat):
    """``(type, *args)`` of the OpenSees twin of a story material."""
    if isinstance(mat, Elastic):
        return ("Elastic", mat.k)
    if isinstance(mat, Bilinear):
        return ("Steel01", mat.Fy, mat.k0, mat.b)
    if isinstance(mat, IMKBilinear):
        return ("Bilin", *mat.opensees_bilin_args())
    raise ValueError(f"stories: {type(mat).__name__} has no OpenSees twin "
                     "(use Elastic, Bilinear or IMKBilinear).")


def axis_twin(kind):
    """The 1D twin builder ``opensees_axis_material(bearing, mat_tag)`` of bearing kind ``kind``
    (:mod:`femoat.bearings`); ValueError when the kind has none."""
    mod = bearing_registry.module(kind)
    if not hasattr(mod, "opensees_axis_material"):
        raise ValueError(f"isolator: the {mod.KEY!r} bearing has no 1D OpenSees twin; check it "
                         "in plan (femoat.opensees.plan) with the record along x and y at rest.")
    return mod.opensees_axis_material


def _check_model(model):
    if not isinstance(model, PoundingModel):
        raise ValueError("model must be a PoundingModel (femoat.structure.pounding).")
    if model.building.p_delta:
        raise ValueError("building: the OpenSees twin has no P-Delta (p_delta=True); build the "
                         "Building with p_delta=False to cross-check it.")
    for w in model.walls:
        if not isinstance(w.law, ContactLaw):
            raise ValueError("walls: each wall needs a ContactLaw.")


def opensees_commands(model, motion):
    """The openseespy calls that build ``model`` under ``motion``: a list of
    ``(function name, *args)`` tuples, ending with the analysis set-up (no ``analyze``).

    Raises ValueError for what has no OpenSees twin (velocity-dependent friction, P-Delta).
    """
    _check_model(model)
    b = model.building
    cmds = [("wipe",), ("model", "basic", "-ndm", 1, "-ndf", 1),
            ("node", _GROUND, 0.0), ("fix", _GROUND, 1)]
    for k, w in enumerate([b.base_weight, *b.floor_weights]):
        cmds += [("node", _BASE + k, 0.0), ("mass", _BASE + k, w / G)]
    mat = 1
    iso = b.isolator
    kind = None if iso is None else bearing_registry.kind_of(iso)
    if kind is not None:  # the bearing kind's own 1D twin: its last material is the bearing
        made, mat = axis_twin(kind)(iso, mat)
        cmds += [*made,
                 ("element", "zeroLength", _ISO_ELE, _GROUND, _BASE, "-mat", mat - 1, "-dir", 1)]
    elif isinstance(iso, Elastic):
        cmds += [("uniaxialMaterial", "Elastic", mat, iso.k),
                 ("element", "zeroLength", _ISO_ELE, _GROUND, _BASE, "-mat", mat, "-dir", 1)]
        mat += 1
    beta = b.story_damping_beta
    for k, story in enumerate(b.stories):
        spring = story_material(story)
        cmds.append(("uniaxialMaterial", spring[0], mat, *spring[1:]))
        c = beta * story.initial_stiffness
        if c > 0.0:
            cmds += [("uniaxialMaterial", "Elastic", mat + 1, 0.0, c),
                     ("uniaxialMaterial", "Parallel", mat + 2, mat, mat + 1)]
            top = mat + 2
        else:
            top = mat
        cmds.append(("element", "zeroLength", _STORY_ELE + k, _BASE + k, _BASE + k + 1,
                     "-mat", top, "-dir", 1))
        mat = top + 1
    loads = []
    for i, w in enumerate(model.walls):
        made, node, mat, load = wall_chain_commands(i, w.wall, 1, 0, mat)
        cmds += made
        contact = opensees_contact_material(w.law, w.gap)
        ni, nj = (_BASE, node) if w.sign > 0 else (node, _BASE)
        cmds += [("uniaxialMaterial", contact[0], mat, *contact[1:]),
                 ("element", "zeroLength", _CONTACT_ELE + i, ni, nj, "-mat", mat, "-dir", 1)]
        mat += 1
        loads.append(load)
    accel = [float(x) for x in motion.accel]
    cmds += [("timeSeries", "Path", 1, "-dt", float(motion.dt), "-values", *accel),
             ("pattern", "UniformExcitation", 1, 1, "-accel", 1)]
    for i, load in enumerate(loads):
        cmds += wall_load_commands(i, load, accel, motion.dt, 1, 0)
    return cmds


def wall_chain(wall):
    """A wall's modes as the twin's chain of nodes (module docstring): per mode i the chain
    mass m_i/φ_i² [kip·s²/in], stiffness k_i/φ_i² [kip/in] and damping c_i/φ_i² [kip·s/in], and
    the ground-load correction P_i [kip·s²/in] on chain node i (the load P_i·a_g that turns the
    excitation's −m·a_g on the first node into the modes' −L·a_g)."""
    m, k, c, phi, L = wall_modes(wall)
    scale = phi * phi
    masses = m / scale
    participation = L / phi  # the load −L_i·a_g on q_i is −(L_i/φ_i)·a_g on s_i = φ_i·q_i
    correction = np.append(participation[1:], 0.0) - participation
    correction[0] += masses[0]
    return masses, k / scale, c / scale, correction


def wall_chain_nodes(i, wall):
    """Node tags of wall i's chain, first mode first; the last is the impact point."""
    n = len(wall_modes(wall)[0])
    if n > 99:  # the tags _MODE_TAG + 100·i + j would collide
        raise ValueError(f"walls: a wall of {n} modes; the OpenSees twins take at most 99 "
                         "(ModalWall.from_fe(..., n_modes=...) chooses fewer).")
    return [_WALL_NODE + i] + [_MODE_TAG + 100 * i + j for j in range(1, n)]


def wall_chain_transform(wall, side):
    """T (modes × modes): chain node displacements X = T·q from the modal coordinates q (each
    positive away from the building): X_j = side·Σ_{i≤j} φ_i·q_i."""
    phi = wall_modes(wall)[3]
    return side * np.tril(np.ones((phi.size, phi.size))) * phi[None, :]


def wall_chain_commands(i, wall, ndm, axis, mat):
    """Commands of wall i's chain along ``axis`` (0 x, 1 y) in a ``-ndm`` 1 or 3 model from the
    material tag ``mat``: returns (commands, impact node, next material tag, load corrections).

    Chain node j sits at j along the axis (the inerters need a length; the zero-length
    springs between nodes apart only warn); its displacement is Σ_{i≤j} s_i with s_i = φ_i·q_i
    the mode's displacement at the impact point. Mode 1 is a lumped mass m_1/φ_1² on node 1
    and a spring and dashpot to the ground; mode j ≥ 2 is a spring and dashpot and an
    ``InertiaTruss`` of inertance m_j/φ_j² (force m·(ẍ_j − ẍ_{j−1})) between nodes j−1 and j, so
    each mode's equation is the modal one. A one-mode wall with φ = 1 and L = m (an SDOF wall)
    is one node with its mass and spring, as before.
    """
    masses, stiffs, damps, correction = wall_chain(wall)
    nodes = wall_chain_nodes(i, wall)
    cmds, prev = [], _GROUND
    for j, node in enumerate(nodes):
        where = [0.0] * ndm
        if ndm == 3:
            where[axis] = float(j)
            fixed = [1] * 6
            fixed[axis] = 0
            cmds += [("node", node, *where), ("fix", node, *fixed)]
        else:
            cmds.append(("node", node, float(j)))
        if j == 0:
            mass = [0.0] * (6 if ndm == 3 else 1)
            mass[axis] = float(masses[0])
            cmds.append(("mass", node, *mass))
        ele = _WALL_ELE + i if j == 0 else _MODE_TAG + 100 * i + j
        cmds += [("uniaxialMaterial", "Elastic", mat, float(stiffs[j]), float(damps[j])),
                 ("element", "zeroLength", ele, prev, node, "-mat", mat, "-dir", axis + 1)]
        if j > 0:
            cmds.append(("element", "InertiaTruss", _INERTER_TAG + 100 * i + j, prev, node,
                         float(masses[j])))
        mat += 1
        prev = node
    return cmds, nodes[-1], mat, correction


def wall_load_commands(i, correction, accel, dt, ndm, axis):
    """The ground-load corrections of wall i (:func:`wall_chain`): a ``Plain`` pattern of the
    ground acceleration ``accel`` [in/s²] along the wall's axis; none when all are zero."""
    nodes_loads = [(j, p) for j, p in enumerate(correction) if p != 0.0]
    if not nodes_loads:
        return []
    tag = _WALL_SERIES + i
    cmds = [("timeSeries", "Path", tag, "-dt", float(dt), "-values", *accel),
            ("pattern", "Plain", tag, tag)]
    nodes = [_WALL_NODE + i] + [_MODE_TAG + 100 * i + j for j in range(1, len(correction))]
    for j, p in nodes_loads:
        load = [0.0] * (6 if ndm == 3 else 1)
        load[axis] = float(p)
        cmds.append(("load", nodes[j], *load))
    return cmds


def _initial_state(model, motion, v0):
    """Node tags (the building's, then every wall's chain), T (nodes × DOFs: node displacements
    X = T·u from femoat's DOFs u) and the initial velocities and equilibrium accelerations per
    femoat DOF."""
    packed = model.pack()
    n, ns = packed.n, packed.n_struct
    nodes = [_BASE + k for k in range(ns)]
    T = np.zeros((n, n))
    T[:ns, :ns] = np.eye(ns)
    col = ns
    for i, w in enumerate(model.walls):
        block = wall_chain_transform(w.wall, w.sign)
        T[col:col + len(block), col:col + len(block)] = block
        nodes += wall_chain_nodes(i, w.wall)
        col += len(block)
    v = np.zeros(n) if v0 is None else np.array(v0, dtype=float)
    if v.shape != (n,) or not np.all(np.isfinite(v)):
        raise ValueError(f"v0 must be {n} finite velocities [in/s] ({packed.dof_names}).")
    ag0 = float(motion.accel[0])
    a = np.linalg.solve(packed.M, -packed.r * ag0 - packed.C @ v)
    return packed, nodes, T, v, a


def chain_to_modes(X, wall, side):
    """Modal coordinates q [in] (..., modes) of a wall from its chain node displacements X [in]
    (..., modes), inverting :func:`wall_chain_transform`: q_j = side·(X_j − X_{j−1})/φ_j."""
    phi = wall_modes(wall)[3]
    X = np.asarray(X, dtype=float)
    s = np.diff(X, axis=-1, prepend=0.0) if phi.size > 1 else X
    return side * s / phi


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
        Building and moat walls, SDOF or modal (constant-μ friction pendulum, Elastic or no
        isolator).
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
    """``analyze(n_steps, dt)`` in one call with binary recorders (the cheapest way to keep
    histories in OpenSees: a Python loop reading results after every step costs more than
    the analysis itself); returns the histories and the process time of the analysis."""
    tags = [_CONTACT_ELE + i for i in range(nw)]
    x0 = _to_dofs(np.array([ops.nodeDisp(nd, 1) for nd in nodes]), model, ns)
    a0 = np.array([ops.nodeAccel(nd, 1) for nd in nodes[:ns]])
    with tempfile.TemporaryDirectory(prefix="femoat_opensees_") as folder:
        paths = [os.path.join(folder, name) for name in ("disp.bin", "accel.bin", "force.bin")]
        ops.recorder("Node", "-binary", paths[0], "-time", "-node", *nodes, "-dof", 1, "disp")
        ops.recorder("Node", "-binary", paths[1], "-node", *nodes[:ns], "-dof", 1, "accel")
        if nw:
            ops.recorder("Element", "-binary", paths[2], "-ele", *tags, "material", "1", "stress")
        status, cpu = timed_analysis(ops, n_steps, dt)
        disp = read_binary(paths[0], 1 + len(nodes))
        acc = read_binary(paths[1], ns)
        force = -read_binary(paths[2], nw) if nw else np.zeros((disp.shape[0], 0))
    m = min(disp.shape[0], acc.shape[0], force.shape[0])
    x = np.vstack([x0, _to_dofs(disp[:m, 1:], model, ns)])  # femoat's DOFs
    acc = np.vstack([a0, acc[:m]])
    f = np.vstack([np.zeros(nw), force[:m]])
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
        tags = ", ".join(str(_CONTACT_ELE + i) for i in range(len(model.walls)))
        lines.append(f"ops.recorder('Element', '-file', {stem + '_contact.out'!r}, '-time', "
                     f"'-ele', {tags}, 'material', '1', 'stress')")
    for name, *args in analysis_commands(tol, max_iter):
        lines.append(f"ops.{name}({', '.join(repr(a) for a in args)})")
    lines += [f"status = ops.analyze({n_steps}, {float(dt)!r})",
              "ops.wipe()", "print('analyze returned', status)", ""]
    write_text(path, "\n".join(lines))
    return path
