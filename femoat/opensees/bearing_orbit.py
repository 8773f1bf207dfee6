"""A plan bearing's OpenSees twin driven along an imposed orbit: its shear forces, point by point.

The twin is the bearing kind's own ``opensees_plan_element`` between a fixed node and a node
loaded by −W in z (the normal force a slider's element needs, put on by a static step first);
the orbit's x and y displacements are imposed on the upper node, one analysis step per point:
static steps when no step duration is given (a rate-independent bearing), else transient steps
of that duration (a bearing whose friction reads a rate over the step: OpenSees takes the rate
from the analysis' time step; the node carries a negligible mass, which a transient analysis
needs).
"""

import numpy as np

from femoat.opensees.available import import_opensees

_SETUP = (("constraints", "Plain"), ("numberer", "Plain"), ("system", "BandGeneral"),
          ("test", "NormDispIncr", 1e-12, 20), ("algorithm", "Newton"),
          ("integrator", "LoadControl", 1.0), ("analysis", "Static"))
"""The gravity step (the vertical material linear: one load step is exact)."""

MASS = 1e-9
"""The upper node's mass in x, y, z [kip·s²/in] in a transient drive (a transient analysis needs
one; the imposed displacements make its inertia forces negligible)."""


def orbit_forces(bearing, path, dt=None):
    """The twin's shear forces (n, 2) [kip] along ``path`` (n, 2) [in], imposed from rest one
    analysis step per point: static steps for ``dt`` None, else transient steps of ``dt`` [s].

    Raises ImportError (with what to install) without openseespy, RuntimeError if OpenSees
    fails at a point (naming it)."""
    ops = import_opensees()
    path = np.asarray(path, dtype=float)
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.node(2, 0.0, 0.0, 0.0)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.fix(2, 0, 0, 0, 1, 1, 1)
    if dt is not None:
        ops.mass(2, MASS, MASS, MASS, 0.0, 0.0, 0.0)
    commands, slider = bearing_commands(bearing)
    for name, *args in commands:
        getattr(ops, name)(*args)
    if slider:  # the normal force N = W its element reads
        ops.timeSeries("Constant", 1)
        ops.pattern("Plain", 1, 1)
        ops.load(2, 0.0, 0.0, -bearing.W, 0.0, 0.0, 0.0)
        for name, *args in _SETUP:
            getattr(ops, name)(*args)
        if ops.analyze(1) != 0:
            ops.wipe()
            raise RuntimeError("OpenSees: the gravity step of the bearing's twin failed.")
        ops.loadConst("-time", 0.0)
        ops.wipeAnalysis()
    step = 1.0 if dt is None else float(dt)
    for dof in (1, 2):  # the imposed displacements: one Path series per direction
        values = [0.0, *map(float, path[:, dof - 1]), float(path[-1, dof - 1])]
        ops.timeSeries("Path", 10 + dof, "-dt", step, "-values", *values)
        ops.pattern("Plain", 10 + dof, 10 + dof)
        ops.sp(2, dof, 1.0)
    if dt is None:
        analysis = (("test", "NormDispIncr", 1e-12, 20), ("algorithm", "Linear"),
                    ("integrator", "LoadControl", 1.0), ("analysis", "Static"))
    else:
        analysis = (("test", "NormDispIncr", 1e-12, 50), ("algorithm", "Newton"),
                    ("integrator", "Newmark", 0.5, 0.25), ("analysis", "Transient"))
    for name, *args in (("constraints", "Transformation"), ("numberer", "Plain"),
                        ("system", "BandGeneral"), *analysis):
        getattr(ops, name)(*args)
    out = np.zeros((len(path), 2))
    for i in range(len(path)):
        ok = ops.analyze(1) if dt is None else ops.analyze(1, step)
        if ok != 0:
            ops.wipe()
            raise RuntimeError(f"OpenSees: the bearing's twin failed at point {i} of the orbit "
                               f"({path[i, 0]!r}, {path[i, 1]!r}) [in].")
        force = ops.eleResponse(1, "globalForce")
        out[i] = force[6], force[7]
    ops.wipe()
    return out


def bearing_commands(bearing):
    """(the openseespy calls of ``bearing``'s twin element: tag 1, nodes 1 and 2, materials from
    tag 1, its kind's ``opensees_plan_element``; whether the element reads a normal force, its
    kind's ``OPENSEES_AXIAL_LOAD``)."""
    from femoat.bearings import registry

    kind = registry.kind_of(bearing)
    mod = None if kind is None else registry.module(kind)
    if mod is None or not hasattr(mod, "opensees_plan_element"):
        raise ValueError(f"bearing = {bearing!r}: its kind has no OpenSees plan twin.")
    commands, _ = mod.opensees_plan_element(bearing, 1, 1, 2, 1)
    return commands, bool(getattr(mod, "OPENSEES_AXIAL_LOAD", False))
