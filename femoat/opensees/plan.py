"""The OpenSees twin in 3D of a plan model (:class:`femoat.plan.PlanModel`) under a record pair.

:func:`opensees_plan_run` builds the model in openseespy, runs it at a fixed step and returns
its histories; :func:`opensees_plan_commands` returns the model as a list of openseespy calls.
The model is the one twin builder's in plan (:mod:`femoat.opensees.twin`, where the OpenSees
model is written once: ``-ndm 3 -ndf 6``, two ``UniformExcitation`` patterns of the pair's
applied components a_x, a_y, the isolator kind's 3D element and a slider's gravity step; the
walls' chains along their axes: :mod:`femoat.opensees.wall_chain`), the 1D twin's
(:mod:`femoat.opensees.building`) with every element acting along a plan direction.

How exact the friction pendulum's 3D twin is:

* Constant μ: the ``flatSliderBearing`` under N = W with ``Coulomb`` friction and kInit =
  μW/u_y; along one axis its circular Coulomb rule is the 1D twin's ``ElasticPP`` (μW/u_y, u_y)
  exactly.
* Velocity-dependent friction (``mu_fast``): the ``VelDependent`` friction model, μ = μ_fast −
  (μ_fast − μ_slow)·exp(−a·|v|) at the slider's trial velocity, with kInit = μ_slow·W/u_y. How
  exact: while the bearing slides both resist with μ(|v|)·W along the sliding direction
  (femoat smooths |v| with ε = ``v_reg``: |Δμ| ≤ (μ_fast − μ_slow)·a·ε); at rest both stick
  with μ_slow·W/u_y. They differ in the elastic phase after each reversal: femoat's friction is
  μ(|v|)·W·z with z of fixed yield displacement u_y (its sticking stiffness μ(|v|)·W/u_y),
  OpenSees keeps kInit and lets only the yield force μ(|v|)·N grow (its yield displacement
  μ(|v|)·N/kInit). No kInit removes that (it is a different hysteretic rule); measured against
  femoat's 1D solver along x (paper building, μ 0.04/0.10, a = 1 s/in, far-field record 1 ×2,
  6 s): peak base displacement 7e-4 apart, the history 4e-3 of the peak, drifts 0.6-1 %
  (``tests/test_opensees_plan_friction.py``).

No twin (refused with a sentence): wall friction (μ_w > 0). What OpenSees offers, and why it is
not femoat's wall friction:

* The only OpenSees elements whose friction takes its normal force from another material are
  the bearings (``flatSliderBearing``, ``singleFPBearing``, ...): N is their axial material's
  compressive force. ``zeroLengthContact3D`` and ``zeroLengthImpact3D`` have Coulomb friction
  too, but their normal force is their own penalty or impact spring, not the five contact laws.
* A ``flatSliderBearing`` oriented along the wall's normal (basic x the normal, y the wall's
  tangent), its axial material the contact law's twin and ``Coulomb`` μ_w, carries the normal
  law faithfully: with μ_w → 0 it reproduces the ``zeroLength`` contact (J, H, E laws: contact
  forces 1.5e-7 of the peak apart, base 3e-8 in, FEMA far-field pair 1 ×2, every wall hit),
  and it cuts the ViscoelasticGap's tension as femoat's V does (its uplift branch: no force,
  no friction, the slip spring reset while the wall is open).
* Its friction is elastic-plastic in the slip: a sticking spring kInit and a circular yield
  surface μ_w·N (in the tangent and the vertical, which also couples the base mat's free z).
  femoat's wall friction is regularised by the slip rate instead (no sticking state). Both are
  Coulomb's μ_w·F_n against the slip while the base mat slides along the wall; they differ
  whenever the slip rate passes through zero during a contact, by the two regularisations,
  which is not a cross-check at 1e-3. A femoat wall friction written as the bearing's rule
  (a slip spring reset at each contact, yield μ_w·F_n) would make this element its exact twin.
"""

import importlib
import math

import numpy as np

from femoat.ground_motions.pair import RecordPair
from femoat.opensees.tags import BASE, BEARING_ELE, CONTACT_ELE
from femoat.opensees.transient import (
    check_history,
    checked_duration,
    recorded_analysis,
    run_twin,
    set_initial_state,
)
from femoat.opensees.twin import twin_commands, twin_rows
from femoat.opensees.wall_chain import wall_chain_nodes
from femoat.plan.bearing import BidirectionalFrictionPendulum
from femoat.plan.model import PlanModel
from femoat.units import G


def _check(model, pair):
    if not isinstance(model, PlanModel):
        raise ValueError("model must be a PlanModel (femoat.plan).")
    if not isinstance(pair, RecordPair):
        raise ValueError("pair must be a RecordPair (femoat.ground_motions).")
    for w in model.walls:
        if w.friction != 0.0:
            raise ValueError(f"wall {w.side}: friction = {w.friction!r} has no faithful OpenSees "
                             "twin (OpenSees' contact friction is elastic-plastic in the slip, "
                             "femoat's is regularised by the slip rate: module docstring); set "
                             "friction=0.0 to cross-check.")


def opensees_plan_commands(model, pair):
    """The openseespy calls that build ``model`` under ``pair``: a list of ``(function name,
    *args)`` tuples: the model, the gravity step (under a friction pendulum, ending with
    ``loadConst`` and ``wipeAnalysis``) and the two excitation patterns; no transient analysis:
    the one builder :func:`~femoat.opensees.twin.twin_commands` in plan.

    Raises ValueError for what has no OpenSees twin (module docstring).
    """
    _check(model, pair)
    return twin_commands(model, pair)


def opensees_plan_run(model, pair, dt, duration=None, v0=None, tol=1e-10, max_iter=50):
    """Run the OpenSees twin of ``model`` under ``pair`` at the fixed step ``dt``.

    Replaces any model in the openseespy interpreter (``wipe`` before and after).

    Parameters
    ----------
    model : PlanModel
        SDOF or modal walls without wall friction; a friction pendulum (constant or
        velocity-dependent μ: module docstring), Elastic or no isolator.
    pair : RecordPair
        The ground motion: its applied components (angle and scale included), x and y.
    dt, duration, v0, tol, max_iter
        As :func:`femoat.opensees.building.opensees_run`: the fixed step [s], the analysis time
        [s] (default: the record plus 2 s), initial velocities [in/s] per femoat DOF, the
        ``NormDispIncr`` tolerance [in] and the Newton iterations per step.

    Returns
    -------
    dict
        ``time`` [s] (t = n·dt, shape (steps + 1,)); ``base_displacement`` [in] (steps + 1, 2);
        ``base_velocity`` [in/s] (steps + 1, 2); ``bearing_friction`` [kip] (steps + 1, 2), the
        slider's friction force (its basic shear forces, without the W/R springs; None without
        a slider); ``floor_displacement`` [in] (steps + 1, floors, 2); ``acceleration``
        [in/s²] absolute, (steps + 1, floors + 1, 2), base mat first; ``wall_displacement``
        [in] (the impact points, away from the building), ``contact_force`` [kip]
        (compression positive) and ``indentation`` [in], each (steps + 1, walls); ``walls``
        (the sides, in that column order);
        ``bearing_normal_force`` [kip] (N after the gravity step of a slider, the single or
        the triple friction pendulum; None on a bearing without one);
        ``peaks``: ``plan_base_displacement`` (largest |u| of the base mat) [in],
        ``base_displacement`` (x, y) [in], ``drift`` (floors, 2) [in],
        ``floor_acceleration`` (floors, 2) [g], and per wall ``impact_force`` [kip] (largest
        sample) and ``impacts`` (closures); ``cpu_seconds`` (the ``analyze`` call); ``steps``;
        ``dt``; ``commands``.

    Raises
    ------
    OpenSeesFailure
        Newton failed at a step, or the state went NaN/inf.
    """
    duration = checked_duration(dt, duration, pair.duration)
    cmds = opensees_plan_commands(model, pair)
    packed = model.pack()
    n = packed.n
    v = np.zeros(n) if v0 is None else np.array(v0, dtype=float)
    if v.shape != (n,) or not np.all(np.isfinite(v)):
        raise ValueError(f"v0 must be {n} finite velocities [in/s] ({model.dof_names()}).")
    ag0 = np.asarray(pair.accel_g)[:, 0] * G
    a = np.linalg.solve(packed.M, -packed.R @ ag0 - packed.C @ v)
    n_steps = int(math.ceil(duration / dt - 1e-9))
    normal = []

    def initial(ops):
        if _slider(model):  # N = W (the basic axial force, compression negative)
            normal.append(-ops.eleResponse(BEARING_ELE, "basicForce")[0])
        rows, T = twin_rows(model)
        set_initial_state(ops, rows, T @ v, T @ a)

    hist = run_twin(cmds, initial, lambda ops: _step_loop(ops, model, n_steps, dt), tol,
                    max_iter)
    normal = normal[0] if normal else None
    return _summarise(hist, model, pair, dt, normal, cmds)


def _slider(model):
    """Whether the model's isolator is a slider whose twin carries the normal force N = W from
    a gravity step (its bearing kind's module says so: ``OPENSEES_AXIAL_LOAD``; read from the
    module that defines the isolator's class, so that it holds whatever kinds the process's
    loop was compiled for)."""
    isolator = model.building.isolator
    home = importlib.import_module(type(isolator).__module__)
    return bool(getattr(home, "OPENSEES_AXIAL_LOAD", False))


def _step_loop(ops, model, n_steps, dt):
    """``analyze(n_steps, dt)`` with binary recorders (:func:`recorded_analysis`, as the 1D
    twin): displacements of every node in x and y, accelerations of the building's nodes,
    contact forces, the base mat's velocity and, under the single pendulum, its friction force
    (the basic shear forces of its flat slider, the W/R springs apart; the triple pendulum's
    element gives the whole bearing force there, not its friction)."""
    nf = len(model.building.floor_weights) + 1
    nw = len(model.walls)
    slider = isinstance(model.building.isolator, BidirectionalFrictionPendulum)
    struct = [BASE + k for k in range(nf)]
    nodes = struct + [node for i, w in enumerate(model.walls)
                      for node in wall_chain_nodes(i, w.wall)]
    x0 = np.array([[ops.nodeDisp(nd, d) for d in (1, 2)] for nd in nodes]).reshape(-1)
    a0 = np.array([[ops.nodeAccel(nd, d) for d in (1, 2)] for nd in struct]).reshape(-1)
    v0 = np.array([ops.nodeVel(BASE, d) for d in (1, 2)])
    q0 = np.array(ops.eleResponse(BEARING_ELE, "basicForce")[1:3]) if slider else np.zeros(2)
    recorders = [(1 + 2 * len(nodes), "Node", "-time", "-node", *nodes, "-dof", 1, 2, "disp"),
                 (2 * nf, "Node", "-node", *struct, "-dof", 1, 2, "accel"),
                 (2, "Node", "-node", BASE, "-dof", 1, 2, "vel")]
    if nw:
        recorders.append((nw, "Element", "-ele", *[CONTACT_ELE + i for i in range(nw)],
                          "material", "1", "stress"))
    if slider:
        recorders.append((6, "Element", "-ele", BEARING_ELE, "basicForce"))
    status, cpu, (disp, acc, vel, *rest) = recorded_analysis(ops, n_steps, dt, recorders)
    m = disp.shape[0]
    force = -rest.pop(0) if nw else np.zeros((m, 0))
    # basic shear forces: local y, z are the global x, y (the slider's orientation)
    shear = rest.pop(0)[:, 1:3] if slider else None
    x = np.vstack([x0, disp[:, 1:]]).reshape(m + 1, len(nodes), 2)
    acc = np.vstack([a0, acc]).reshape(m + 1, nf, 2)
    f = np.vstack([np.zeros(nw), force])
    check_history(np.all(np.isfinite(x), axis=(1, 2)) & np.all(np.isfinite(f), axis=1), status,
                  m, n_steps, dt)
    return dict(x=x, acc=acc, f=f, cpu=cpu, vel=np.vstack([v0, vel]),
                friction=np.vstack([q0, shear]) if slider else None)


def _summarise(hist, model, pair, dt, normal, cmds):
    x, acc, f = hist["x"], hist["acc"], hist["f"]
    nf = acc.shape[1]
    t = np.arange(x.shape[0]) * dt
    base = x[:, 0, :]
    ends = np.cumsum([len(wall_chain_nodes(i, w.wall)) for i, w in enumerate(model.walls)])
    walls = np.column_stack([w.sign * x[:, nf + ends[i] - 1, w.axis]  # the impact points
                             for i, w in enumerate(model.walls)]) \
        if model.walls else np.zeros((t.size, 0))
    indent = np.column_stack([base @ np.array(w.normal) - w.gap - walls[:, i]
                              for i, w in enumerate(model.walls)]) \
        if model.walls else np.zeros((t.size, 0))
    ag = np.array([np.interp(t, pair.time, row, right=0.0) for row in np.asarray(pair.accel_g)])
    absacc = acc + (G * ag.T)[:, None, :]
    closed = indent > 0.0
    impacts = np.sum(closed & ~np.vstack([np.zeros((1, closed.shape[1]), bool), closed[:-1]]),
                     axis=0)
    peaks = dict(
        plan_base_displacement=float(np.hypot(base[:, 0], base[:, 1]).max()),
        base_displacement=np.abs(base).max(axis=0),
        drift=np.abs(np.diff(x[:, :nf, :], axis=1)).max(axis=0),
        floor_acceleration=np.abs(absacc[:, 1:, :]).max(axis=0) / G,
        impact_force=np.maximum(f, 0.0).max(axis=0, initial=0.0) + 0.0,
        impacts=impacts.astype(int),
    )
    return dict(time=t, base_displacement=base, base_velocity=hist["vel"],
                bearing_friction=hist["friction"], floor_displacement=x[:, 1:nf, :],
                acceleration=absacc, wall_displacement=walls, contact_force=f,
                indentation=indent, walls=[w.side for w in model.walls],
                bearing_normal_force=normal, peaks=peaks, cpu_seconds=hist["cpu"],
                steps=int(t.size - 1), dt=float(dt), commands=cmds)
