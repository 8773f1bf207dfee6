"""The OpenSees twin of a femoat model: one builder for a model on one axis
(:class:`~femoat.structure.pounding.PoundingModel`, the 1D twin) and a model in plan
(:class:`~femoat.plan.model.PlanModel`, the 3D twin).

:func:`twin_commands` writes a model as a list of openseespy calls from its layout
(:meth:`model.layout() <femoat.structure.layout.Layout>`: one axis or two); what differs between
the two is the model space (:mod:`femoat.opensees.frame`), the isolator's twin (a bearing kind's
1D material or 3D element) and a slider's gravity step, each a branch here.
:func:`femoat.opensees.building.opensees_commands` and
:func:`femoat.opensees.plan.opensees_plan_commands` check what has no twin and call it;
:func:`twin_rows` maps femoat's DOFs to the twin's node DOFs for both runs.

OpenSees model (written once here)
----------------------------------
* On one axis ``-ndm 1 -ndf 1``, every node moving along x; in plan ``-ndm 3 -ndf 6``, every
  node's unused DOFs fixed: floors move in x, y (DOFs 1, 2), the base mat also in z under a
  slider (the bearing's axial DOF, massless), a wall node along its axis only. Displacements are
  relative to the ground: a ``UniformExcitation`` per layout axis (directions 1 and 2; ``Path``
  series 1 and 2 of the ground acceleration [in/s²] along x and y at the record's dt, linear
  between samples, zero after the last, as femoat) applies −m·a_g to every lumped mass, as
  femoat's ``R`` does.
* Nodes (:mod:`femoat.opensees.tags`): 1 ground (fixed); 2 base mat; 3, 4, … floors bottom to
  top; wall i of ``model.walls`` (in plan in the order +x, −x, +y, −y) is a chain of nodes along
  its axis, the first 100 + i, the last the impact point (:mod:`femoat.opensees.wall_chain`:
  the modal wall's chain, an SDOF wall one node with ``Elastic K1 C_imp`` to the ground). A
  wall node's displacement along its axis is side·q for an SDOF wall, q positive away from the
  building (side +1 for +x and +y).
* Isolator, ground → base mat, the bearing kind's twin (:mod:`femoat.bearings`): on one axis its
  uniaxial material (``opensees_axis_material``; a constant-μ friction pendulum is
  ``Parallel(Elastic W/R, ElasticPP μW/u_y u_y)``, its EPP friction spring exactly) in a
  ``zeroLength`` element 1; in plan its 3D element (``opensees_plan_element``: the friction
  pendulum's ``flatSliderBearing`` with ``Coulomb`` or ``VelDependent`` friction in parallel
  with a W/R spring in x and y, ``elastomericBearingBoucWen``, ``TripleFrictionPendulum``). A
  slider (``OPENSEES_AXIAL_LOAD``) takes its normal force N = W from a static gravity step
  (load −W on the base mat's z) held constant (``loadConst``) before the transient. An Elastic
  isolator is a ``zeroLength`` spring (element 1 on one axis, 2 in x and y in plan); none when
  ``isolator is None``.
* Story k, floor k−1 → floor k: one ``zeroLength`` with one material per axis (``-dir 1`` or
  ``-dir 1 2``), the story's twin (``Elastic k`` / ``Steel01 Fy k0 b`` (Bilinear) / ``Bilin …``
  (IMKBilinear, :meth:`~femoat.structure.materials.IMKBilinear.opensees_bilin_args`)) in
  ``Parallel`` with its dashpot ``Elastic 0 c`` (c = β·k0, as the pack's C) and, with P-Delta,
  ``Elastic −P/h`` (the linear geometric stiffness femoat adds to K).
* Contact, along the wall's axis: base mat → impact node for a + side, impact node → base mat
  for a − side, so that closing the gap makes the strain negative on both; the gap material is
  :func:`~femoat.opensees.single_impact.opensees_contact_material` (compression convention: gap
  −g0, stress −f in contact).
* Analysis (:mod:`femoat.opensees.transient`): initial accelerations at equilibrium,
  a0 = M⁻¹(−R·a_g(0) − C·v0), as femoat starts (OpenSees would otherwise start from a0 = 0);
  Newmark average acceleration (γ = 1/2, β = 1/4), Newton, ``NormDispIncr``, fixed dt, one
  ``analyze(n, dt)`` call with ``-binary`` recorders.
"""

import numpy as np

from femoat.bearings import registry as bearing_registry
from femoat.opensees.frame import frame_of
from femoat.opensees.single_impact import opensees_contact_material
from femoat.opensees.tags import (
    BASE,
    BEARING_ELE,
    CONTACT_ELE,
    ELASTIC_SPRING_ELE,
    GRAVITY,
    GROUND,
    STORY_ELE,
)
from femoat.opensees.wall_chain import (
    wall_chain_commands,
    wall_chain_nodes,
    wall_chain_transform,
    wall_load_commands,
)
from femoat.structure.materials import Bilinear, Elastic, IMKBilinear
from femoat.units import G


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


def story_commands(mat, dashpot, geometric, tag):
    """A story material with its dashpot ``dashpot`` [kip·s/in] and P-Delta spring
    ``geometric`` [kip/in] in ``Parallel`` (each left out when zero), from material ``tag``:
    returns (commands, tag of the top material, next free tag)."""
    spring = story_material(mat)
    cmds, parts = [("uniaxialMaterial", spring[0], tag, *spring[1:])], [tag]
    for k, c in ((0.0, dashpot), (geometric, 0.0)):
        if k != 0.0 or c != 0.0:
            parts.append(tag + len(parts))
            cmds.append(("uniaxialMaterial", "Elastic", parts[-1], k, c))
    if len(parts) == 1:
        return cmds, tag, tag + 1
    top = tag + len(parts)
    cmds.append(("uniaxialMaterial", "Parallel", top, *parts))
    return cmds, top, top + 1


def axis_twin(kind):
    """The 1D twin builder ``opensees_axis_material(bearing, mat_tag)`` of bearing kind ``kind``
    (:mod:`femoat.bearings`); ValueError when the kind has none."""
    mod = bearing_registry.module(kind)
    if not hasattr(mod, "opensees_axis_material"):
        raise ValueError(f"isolator: the {mod.KEY!r} bearing has no 1D OpenSees twin; check it "
                         "in plan (femoat.opensees.plan) with the record along x and y at rest.")
    return mod.opensees_axis_material


def plan_twin(kind):
    """The module of bearing kind ``kind`` (:mod:`femoat.bearings`), which builds its 3D twin
    (``opensees_plan_element``, ``OPENSEES_AXIAL_LOAD``); ValueError when it has none."""
    mod = bearing_registry.module(kind)
    if not hasattr(mod, "opensees_plan_element"):
        raise ValueError(f"isolator: the {mod.KEY!r} bearing has no OpenSees twin.")
    return mod


def isolator_commands(isolator, n_axes, mat):
    """The isolator's twin between the ground and the base mat along ``n_axes`` axes (1 or 2)
    from material ``mat`` (module docstring): returns (commands, next free material tag, whether
    it is a slider that needs the gravity step)."""
    if isolator is None:
        return [], mat, False
    dirs = tuple(range(1, n_axes + 1))
    if isinstance(isolator, Elastic):
        ele = BEARING_ELE if n_axes == 1 else ELASTIC_SPRING_ELE
        return [("uniaxialMaterial", "Elastic", mat, isolator.k),
                ("element", "zeroLength", ele, GROUND, BASE, "-mat", *[mat] * n_axes,
                 "-dir", *dirs)], mat + 1, False
    kind = bearing_registry.kind_of(isolator)
    if n_axes == 1:  # the kind's uniaxial material; its last material is the bearing
        made, mat = axis_twin(kind)(isolator, mat)
        return [*made, ("element", "zeroLength", BEARING_ELE, GROUND, BASE, "-mat", mat - 1,
                        "-dir", 1)], mat, False
    twin = plan_twin(kind)  # the kind's 3D element (elements BEARING_ELE, the next)
    made, mat = twin.opensees_plan_element(isolator, BEARING_ELE, GROUND, BASE, mat)
    return made, mat, bool(twin.OPENSEES_AXIAL_LOAD)


def gravity_step_commands(weight):
    """A slider's normal force N = ``weight`` [kip]: a static load −W on the base mat's z in one
    step, then held constant (``loadConst``) and the static analysis wiped."""
    return [("timeSeries", "Constant", GRAVITY), ("pattern", "Plain", GRAVITY, GRAVITY),
            ("load", BASE, 0.0, 0.0, -weight, 0.0, 0.0, 0.0),
            ("constraints", "Plain"), ("numberer", "Plain"), ("system", "BandGeneral"),
            ("test", "NormDispIncr", 1e-12, 20), ("algorithm", "Newton"),
            ("integrator", "LoadControl", 1.0), ("analysis", "Static"), ("analyze", 1),
            ("loadConst", "-time", 0.0), ("wipeAnalysis",)]


def ground_components(ground, n_axes):
    """(accelerations [in/s²] along each of ``n_axes`` axes, as lists of floats; dt [s]) of a
    GroundMotion (one axis) or a RecordPair's applied components (two)."""
    if n_axes == 1:
        return [[float(a) for a in ground.accel]], ground.dt
    return [[float(a) for a in row] for row in np.asarray(ground.accel_g) * G], ground.dt


def twin_commands(model, ground):
    """The openseespy calls that build ``model`` (a PoundingModel or a PlanModel: its layout's
    axes decide) under ``ground`` (a GroundMotion on one axis, a RecordPair in plan): a list of
    ``(function name, *args)`` tuples, ending with the excitation patterns (no transient
    analysis; in plan a slider's gravity step before them). The model is not checked for what
    has no twin: the callers do (``opensees_commands``, ``opensees_plan_commands``)."""
    names = model.layout().axes  # ("x",) or ("x", "y")
    n_axes = len(names)
    frame = frame_of(n_axes)
    axes = tuple(range(n_axes))
    b = model.building
    iso_cmds, mat, slider = isolator_commands(b.isolator, n_axes, 1)
    cmds = [("wipe",), frame.model(), frame.node(GROUND), *frame.fix(GROUND)]
    for k, w in enumerate([b.base_weight, *b.floor_weights]):
        free = axes + ((2,) if k == 0 and slider else ())
        cmds += [frame.node(BASE + k), *frame.fix(BASE + k, free),
                 ("mass", BASE + k, *frame.vector({a: w / G for a in axes}))]
    cmds += iso_cmds
    beta, geometric = b.story_damping_beta, b.geometric_stiffnesses()
    for k in range(len(b.floor_weights)):
        tops = []
        for axis in names:
            story = b.stories_along(axis)[k]
            made, top, mat = story_commands(story, beta * story.initial_stiffness, geometric[k],
                                            mat)
            cmds += made
            tops.append(top)
        cmds.append(("element", "zeroLength", STORY_ELE + k, BASE + k, BASE + k + 1,
                     "-mat", *tops, "-dir", *[a + 1 for a in axes]))
    loads = []
    for i, w in enumerate(model.walls):
        made, node, mat, load = wall_chain_commands(i, w.wall, frame, w.axis, mat)
        contact = opensees_contact_material(w.law, w.gap)
        ni, nj = (BASE, node) if w.sign > 0 else (node, BASE)
        cmds += [*made, ("uniaxialMaterial", contact[0], mat, *contact[1:]),
                 ("element", "zeroLength", CONTACT_ELE + i, ni, nj, "-mat", mat,
                  "-dir", w.axis + 1)]
        mat += 1
        loads.append(load)
    if slider:  # N = W on the slider: a static gravity step, then held constant
        cmds += gravity_step_commands(b.isolator.W)
    accel, dt = ground_components(ground, n_axes)
    for d in range(1, n_axes + 1):
        cmds += [("timeSeries", "Path", d, "-dt", float(dt), "-values", *accel[d - 1]),
                 ("pattern", "UniformExcitation", d, d, "-accel", d)]
    for i, (w, load) in enumerate(zip(model.walls, loads)):
        cmds += wall_load_commands(i, load, accel[w.axis], dt, frame, w.axis)
    return cmds


def twin_rows(model):
    """The twin's (node, OpenSees DOF) rows in femoat's DOF order (the layout's) and T (rows ×
    DOFs): the node displacements are T·u for femoat's DOFs u. The building's rows are its
    floors' translations, one per axis; a wall's rows are its chain's nodes along its axis
    (:func:`~femoat.opensees.wall_chain.wall_chain_transform`)."""
    layout = model.layout()
    rows = [(BASE + k, a + 1) for k in range(layout.floor_dofs.shape[0])
            for a in range(len(layout.axes))]
    ns = len(rows)
    blocks = [wall_chain_transform(w.wall, w.sign) for w in model.walls]
    n = ns + sum(len(block) for block in blocks)
    T = np.zeros((n, n))
    T[:ns, :ns] = np.eye(ns)
    col = ns
    for i, (w, block) in enumerate(zip(model.walls, blocks)):
        rows += [(node, w.axis + 1) for node in wall_chain_nodes(i, w.wall)]
        T[col:col + len(block), col:col + len(block)] = block
        col += len(block)
    return rows, T
