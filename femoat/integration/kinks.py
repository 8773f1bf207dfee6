"""Element kinks: a step in which an element changes branch (stick to slip, yield, capping) is
shortened to end just past the kink (:func:`find_kink`), so that a sample sits on the corner of
the force; an explicit step, whose stages are all evaluated from the committed state, also
lands on the turning points where a yielding element unloads (:func:`find_turn`)."""

import numpy as np

from femoat.bearings.dispatch import (
    bearing_plan_branch,
    bearing_plan_rate,
    bearing_plan_rate_branch,
    bearing_plan_rate_fsal,
    bearing_plan_rate_state,
    bearing_plan_rate_turn,
    bearing_plan_turn_direction,
)
from femoat.compilation.jit import njit
from femoat.integration.bundles import fsal_views, rate_scratch
from femoat.integration.interpolants import crossing, hermite
from femoat.structure.materials.kernels import material_commit, material_trial


KINK_RATIO = 0.5
"""An element's tangent that changes by more than this fraction of the larger of its start and
end values within a step marks a kink (a branch change: stick to slip, yield, capping)."""


KINK_BISECTIONS = 12
"""Bisections locating a kink: the step lands within 2^-12 of its length past it."""


KINK_RESOLUTION = 2.0 ** -KINK_BISECTIONS
"""A kink closer than this fraction to the start of a step is not landed on."""


FINE_BISECTIONS = 24
"""Bisections locating a plan bearing's change of branch off a line in a step of a method that
carries the friction state (``methods.FINE_LANDING``): the sliver of the step past the kink
follows the stage paths (first order in the sliver), so its error is (2^-24)², not (2^-12)², of
the step's; on a line the stage path is exact and the landing stays the one-axis element's."""
FINE_RESOLUTION = 2.0 ** -FINE_BISECTIONS


@njit(cache=True, inline="always")
def _element_rates(e, model, v):
    i, j = model.el_i[e], model.el_j[e]
    return v[i] - (v[j] if j >= 0 else 0.0)


@njit(cache=True, inline="always")
def _bearing_path(e, th, hh, model, state, work):
    """The plan bearing ``e``'s displacement (u_x, u_y) [in] at fraction ``th`` of the trial
    step, on the cubic Hermite interpolant of each component."""
    ix, iy = model.b_dofs[e, 0], model.b_dofs[e, 1]
    ux, _ = hermite(th, hh, state.u[ix], state.v[ix], work.u[ix], work.v[ix])
    uy, _ = hermite(th, hh, state.u[iy], state.v[iy], work.u[iy], work.v[iy])
    return ux, uy


@njit(cache=True, inline="always")
def _off_line(e, model, state, work):
    """Whether the plan bearing ``e``'s step leaves the line of its displacement increment: the
    velocities at both ends or the committed hysteretic direction (the first two entries of its
    rate-form state) are not parallel to it (the test of ``friction_pendulum._path_z``; a kind
    without a rate form: always)."""
    ix, iy = model.b_dofs[e, 0], model.b_dofs[e, 1]
    dx, dy = work.u[ix] - state.u[ix], work.u[iy] - state.u[iy]
    z, _, _, _, _, _ = rate_scratch(work)
    if bearing_plan_rate_state(model.b_kind[e], model.b_P[e], state.b_S[e], z) == 0:
        return True
    zx, zy = z[0], z[1]
    if not (np.isfinite(zx) and np.isfinite(zy)):
        return True
    cross = (abs(dx * state.v[iy] - dy * state.v[ix]) + abs(dx * work.v[iy] - dy * work.v[ix])
             + abs(dx * zy - dy * zx))
    return cross != 0.0


@njit(cache=True, inline="always")
def _carried_branch(kind, p, s, th, hh, u0x, u0y, v0x, v0y, u1x, u1y, v1x, v1y, nq, moved, z1,
                    z0, g0, g1, zt):
    """The carried bearing's branch at fraction ``th`` of the step: the displacement on the
    step's cubic Hermite path, z on the cubic Hermite of its values and rates at both ends."""
    ux, _ = hermite(th, hh, u0x, v0x, u1x, v1x)
    uy, _ = hermite(th, hh, u0y, v0y, u1y, v1y)
    for q in range(nq):
        if moved:
            zt[q], _ = hermite(th, hh, z0[q], g0[q], z1[q], g1[q])
        else:
            zt[q] = z0[q]
    return bearing_plan_rate_branch(kind, p, s, ux, uy, zt)


@njit(cache=True)
def _carried_kink(kind, p, s, hh, u0x, u0y, v0x, v0y, u1x, u1y, v1x, v1y, z1, z0, g0, g1, zt, J,
                  bisections, first, last):
    """Fraction θ just past the change of branch of a bearing whose step carried its friction
    state (``kind``'s ``plan_rate_branch``, z following the step: its cubic Hermite from its
    values and rates at both ends, exact to the step's order where the branch is a function of
    z, as a triple pendulum's sticking elements are), 2 when it stays on one branch (``z0``,
    ``g0``, ``g1``, ``zt``, ``J`` scratch; its own compiled function, as :func:`_carried_turn`).
    A stiff rate (the kind's ``plan_rate_fsal`` ≥ 0) is the step's own at its first and last
    stages (``first``, ``last``: evaluated at the ends, it adds a relaxation the step never
    took)."""
    nq = bearing_plan_rate_state(kind, p, s, z0)
    moved = False
    for q in range(nq):
        if z1[q] != z0[q]:
            moved = True
    if moved and bearing_plan_rate_fsal(kind, p, s) >= 0:
        for q in range(nq):
            g0[q] = first[q]
            g1[q] = last[q]
    elif moved:
        bearing_plan_rate(kind, p, s, u0x, u0y, v0x, v0y, z0, g0, J)
        bearing_plan_rate(kind, p, s, u1x, u1y, v1x, v1y, z1, g1, J)
    lo, hi = 2.0 ** -bisections, 1.0
    branch0 = _carried_branch(kind, p, s, lo, hh, u0x, u0y, v0x, v0y, u1x, u1y, v1x, v1y, nq,
                              moved, z1, z0, g0, g1, zt)
    if bearing_plan_rate_branch(kind, p, s, u1x, u1y, z1) == branch0:
        return 2.0
    for _ in range(bisections):
        mid = 0.5 * (lo + hi)
        if _carried_branch(kind, p, s, mid, hh, u0x, u0y, v0x, v0y, u1x, u1y, v1x, v1y, nq,
                           moved, z1, z0, g0, g1, zt) == branch0:
            lo = mid
        else:
            hi = mid
    return hi


@njit(cache=True, inline="always")
def _bearing_kink(e, hh, model, state, work, fine):
    """Fraction θ just past the plan bearing ``e``'s change of branch (e.g. between sticking and
    sliding) inside the trial step (along the step's path, each point from the committed
    state), 2 when it stays on one branch; ``fine``: off a line, to FINE_BISECTIONS."""
    kind, p, s = model.b_kind[e], model.b_P[e], state.b_S[e]
    bisections = FINE_BISECTIONS if fine and _off_line(e, model, state, work) else \
        KINK_BISECTIONS
    if work.b_rate[e] != 0:
        # (a branch that is the same a resolution into the step, z still the committed one, and
        # at the end is the answer of most steps: the search's own call only when it differs)
        ix, iy = model.b_dofs[e, 0], model.b_dofs[e, 1]
        z0, g0, g1, zt, J, _ = rate_scratch(work)
        bearing_plan_rate_state(kind, p, s, z0)
        ux, uy = _bearing_path(e, 2.0 ** -bisections, hh, model, state, work)
        if bearing_plan_rate_branch(kind, p, s, ux, uy, z0) == bearing_plan_rate_branch(
                kind, p, s, work.u[ix], work.u[iy], work.bz[e]):
            return 2.0
        last = fsal_views(work.kz, e)[0]
        return _carried_kink(kind, p, s, hh, state.u[ix], state.u[iy], state.v[ix], state.v[iy],
                             work.u[ix], work.u[iy], work.v[ix], work.v[iy], work.bz[e], z0, g0,
                             g1, zt, J, bisections, work.kz[0, e], last)
    lo, hi = 2.0 ** -bisections, 1.0
    ux, uy = _bearing_path(e, lo, hh, model, state, work)
    branch0 = bearing_plan_branch(kind, p, s, ux, uy)
    ix, iy = model.b_dofs[e, 0], model.b_dofs[e, 1]
    if bearing_plan_branch(kind, p, s, work.u[ix], work.u[iy]) == branch0:
        return 2.0
    for _ in range(bisections):
        mid = 0.5 * (lo + hi)
        ux, uy = _bearing_path(e, mid, hh, model, state, work)
        if bearing_plan_branch(kind, p, s, ux, uy) == branch0:
            lo = mid
        else:
            hi = mid
    return hi


@njit(cache=True)
def _carried_turn(kind, p, s, u0x, u0y, v0x, v0y, a0x, a0y, u1x, u1y, v1x, v1y, a1x, a1y, z1,
                  z0, g, J):
    """(r0, ṙ0, r1, ṙ1, z moved) of the kind's loading measure r (the pendulum's z·v, with
    ṙ = g(z; u, v)·v + z·a) over a step that carried the bearing's friction state from the
    committed ``s`` to ``z1`` (``z0``, ``g``, ``J`` scratch; its own compiled function: called
    only for a carried bearing, compiled once, not inside the loop)."""
    nq = bearing_plan_rate_state(kind, p, s, z0)
    r0, dr0 = bearing_plan_rate_turn(kind, p, s, u0x, u0y, v0x, v0y, a0x, a0y, z0, g, J)
    r1, dr1 = bearing_plan_rate_turn(kind, p, s, u1x, u1y, v1x, v1y, a1x, a1y, z1, g, J)
    moved = False
    for q in range(nq):
        if z1[q] != z0[q]:
            moved = True
    return r0, dr0, r1, dr1, moved


@njit(cache=True, inline="always")
def _bearing_turn(e, hh, model, state, work, fine):
    """Fraction θ just past the point where the plan bearing ``e`` turns back (its velocity along
    its committed turning direction, e.g. a sliding bearing's friction direction, crosses zero:
    it unloads), 2 when it does not turn inside the step or has no such direction; ``fine``:
    off a line, FINE_RESOLUTION past it. A step that carried the bearing's friction state z
    (``work.b_rate``) turns where z·v crosses zero, z moving in the step: r = z·v with
    ṙ = g(z, v)·v + z·a at both ends (z's rate g from the kind's rate form, zero on a line,
    where this is the committed direction's search to the bit). Landed there, the next step
    starts unloading and does not carry z past the turn."""
    kind = model.b_kind[e]
    zx, zy = bearing_plan_turn_direction(kind, state.b_S[e])
    if zx == 0.0 and zy == 0.0:
        return 2.0
    ix, iy = model.b_dofs[e, 0], model.b_dofs[e, 1]
    v0x, v0y, v1x, v1y = state.v[ix], state.v[iy], work.v[ix], work.v[iy]
    r0 = zx * v0x + zy * v0y
    dr0 = zx * state.a[ix] + zy * state.a[iy]
    moved = False
    if work.b_rate[e]:
        z0, g, _, _, J, _ = rate_scratch(work)
        r0, dr0, r1, dr1, moved = _carried_turn(
            kind, model.b_P[e], state.b_S[e], state.u[ix], state.u[iy], v0x, v0y, state.a[ix],
            state.a[iy], work.u[ix], work.u[iy], v1x, v1y, work.a[ix], work.a[iy], work.bz[e],
            z0, g, J)
    else:
        r1 = zx * v1x + zy * v1y
        dr1 = zx * work.a[ix] + zy * work.a[iy]
    if not (r0 > 0.0 and r1 < 0.0):
        return 2.0
    th = crossing(r0, dr0, r1, dr1, hh)
    res = FINE_RESOLUTION if fine and _off_line(e, model, state, work) else KINK_RESOLUTION
    if th >= 1.0:
        return 2.0
    if th <= res:
        # a turn at the step's start: the landing before fell just short of it (its crossing
        # is an estimate). A carried z that moves must not run past it: a sliver past it.
        return 2.0 * res if moved else 2.0
    return min(1.0, th + res)


@njit(cache=True, inline="always")
def find_kink(hh, model, state, work, fine):
    """Fraction θ of the trial step just past the earliest element kink inside it (2: none).

    An element's tangent at the start (its committed branch) and at the trial end are compared;
    when they differ by more than KINK_RATIO, the branch change is located by bisection on the
    element's deformation along the step's cubic Hermite interpolant, each point evaluated from
    the committed state. Landing the step there puts a sample on the corner of the force (and
    of the accelerations), which step ends would otherwise cut off.
    """
    theta = 2.0
    el_code, el_P, el_S = model.el_code, model.el_P, state.el_S
    last = el_S.shape[1] - 1
    for e in range(el_code.size):
        if el_S[e, last] != -1.0:
            continue  # its tangent depends on the step's duration (materials.kernels.DURATION)
        d0, d1 = state.el_d[e], work.ed[e]
        dv0 = _element_rates(e, model, state.v)
        dv1 = _element_rates(e, model, work.v)
        # the start's branch is read a resolution into the step: at the committed point itself
        # a material may sit on the boundary of two branches (a sliding bearing at |z| = 1)
        lo, hi = KINK_RESOLUTION, 1.0
        d, dth = hermite(lo, hh, d0, dv0, d1, dv1)
        _, k0, _ = material_trial(el_code[e], el_P[e], el_S[e], d, dth / hh)
        _, k1, _ = material_trial(el_code[e], el_P[e], el_S[e], d1, dv1)
        if abs(k1 - k0) <= KINK_RATIO * max(abs(k0), abs(k1)):
            continue
        for _ in range(KINK_BISECTIONS):
            mid = 0.5 * (lo + hi)
            d, dth = hermite(mid, hh, d0, dv0, d1, dv1)
            _, k, _ = material_trial(el_code[e], el_P[e], el_S[e], d, dth / hh)
            if abs(k - k0) <= abs(k - k1):
                lo = mid
            else:
                hi = mid
        if hi < theta:
            theta = hi
    for e in range(model.b_dofs.shape[0]):
        th = _bearing_kink(e, hh, model, state, work, fine)
        if th < theta:
            theta = th
    return theta


@njit(cache=True, inline="always")
def find_turn(hh, model, state, work, fine):
    """Fraction θ of the trial step just past the earliest turning point of an element's
    deformation inside it where the element changes branch (2: none).

    Every stage of a step is evaluated from the state committed at its start, as if the
    deformation went straight there; a reversal inside the step (a sliding bearing or a
    yielding story turning back, which unloads it) is then not seen, and at a fifth-order
    step's length that costs the order. A turning point is where the element's deformation
    rate crosses zero along the cubic Hermite interpolant of the rate (its values and the
    accelerations at the step's ends); it is a kink when the material, committed there, has a
    tangent for the way back that differs by more than KINK_RATIO from the tangent it reached.
    """
    theta = 2.0
    el_code, el_P, el_S = model.el_code, model.el_P, state.el_S
    s_tmp = work.s_tmp
    for e in range(el_code.size):
        dv0 = _element_rates(e, model, state.v)
        dv1 = _element_rates(e, model, work.v)
        if dv0 * dv1 >= 0.0:
            continue
        da0 = _element_rates(e, model, state.a)
        da1 = _element_rates(e, model, work.a)
        th = crossing(dv0, da0, dv1, da1, hh)
        if th <= KINK_RESOLUTION or th >= 1.0:
            continue
        d, _ = hermite(th, hh, state.el_d[e], dv0, work.ed[e], dv1)
        _, k_on, _ = material_trial(el_code[e], el_P[e], el_S[e], d, 0.0)
        for k in range(s_tmp.size):
            s_tmp[k] = el_S[e, k]
        material_commit(el_code[e], el_P[e], s_tmp, d, 0.0)
        back = d - TURN_PROBE * (abs(d) + abs(state.el_d[e]) + 1e-6) * (1.0 if dv0 > 0.0 else -1.0)
        _, k_back, _ = material_trial(el_code[e], el_P[e], s_tmp, back, 0.0)
        if abs(k_back - k_on) <= KINK_RATIO * max(abs(k_on), abs(k_back)):
            continue
        th = min(1.0, th + KINK_RESOLUTION)
        if th < theta:
            theta = th
    for e in range(model.b_dofs.shape[0]):
        th = _bearing_turn(e, hh, model, state, work, fine)
        if th < theta:
            theta = th
    return theta


TURN_PROBE = 1e-9
"""A turning point's way back is probed this fraction of the deformation's size back from it."""
