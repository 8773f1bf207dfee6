"""A plan bearing's kernels driven along an imposed orbit: femoat's side of
:mod:`femoat.opensees.bearing_orbit` (the tests' and benchmarks' closed forms and twins)."""

import numpy as np

from femoat.bearings import registry


def orbit_forces(bearing, path, dt=0.0, velocities=None):
    """(forces (n, 2) [kip], the final committed state): ``bearing``'s plan kernels (its kind's
    ``plan_trial`` then ``plan_commit``) at each point of ``path`` (n, 2) [in] in turn, from
    rest at the origin, each a step of ``dt`` [s] (0: the chord, no duration) from the previous
    point, ``velocities`` (n, 2) [in/s] at the points (default at rest) shaping a curved step's
    path and the start of the next."""
    kind = registry.kind_of(bearing)
    if kind is None:
        raise ValueError(f"bearing = {bearing!r}: not a bearing kind of femoat.bearings.")
    mod = registry.module(kind)
    path = np.asarray(path, dtype=float)
    vel = np.zeros_like(path) if velocities is None else np.asarray(velocities, dtype=float)
    p, s = bearing.params(), bearing.initial_state_plan()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    u0, v0 = np.zeros(2), np.zeros(2)
    out = np.zeros((len(path), 2))
    for j in range(len(path)):
        args = (u0[0], u0[1], v0[0], v0[1], path[j, 0], path[j, 1], vel[j, 0], vel[j, 1],
                float(dt))
        mod.plan_trial(p, s, *args, f, k, c)
        mod.plan_commit(p, s, *args)
        out[j] = f
        u0, v0 = path[j], vel[j]
    return out, s
