"""The open phase's step for coupled friction: the additive Runge-Kutta pair ARK5(4)8L[2]SA of
Kennedy & Carpenter (Appl. Numer. Math. 44, 2003; SUNDIALS ARKODE's ``ARK548L2SA``, SciML's
``KenCarp5``), the structure explicit, each sliding plan bearing's friction state implicit.

Why a pair: a plan bearing's friction direction z turns with the sliding direction. Read from a
path guessed between a step's start and a stage value (what :mod:`~femoat.integration.methods.dp5`
would do, and why it refuses plan bearings), z carries a first-order error into every stage:
Runge-Kutta stage values are first-order approximations only. Here z is a state of the step
while the bearing slides, with the bearing kind's rate form (:data:`femoat.bearings.registry.
RATE_KERNELS`; the single friction pendulum's ż = (v − (z·v)·z)/u_y). That rate is stiff (its
eigenvalues −(z·v)/u_y and −2(z·v)/u_y: h·|v|/u_y is 5-35 at the steps the structure takes),
so it is the implicit part: each stage solves, per bearing, the 2×2 system

    Z_s = z_n + h·Σ_{j<s} a^I_sj·g_j + h·γ·g(Z_s, V_s)

by Newton's method from the previous stage's Z (γ = 41/200; the structure's stage (U_s, V_s) is
explicit, from a^E, so the structure never enters a nonlinear solve), and the stage's forces use
(U_s, V_s, Z_s). The pair is stiffly accurate (the implicit weights are its last row): the step's
z is the last stage's Z. docs/coupled_friction.md measured the pair's order on the bearing alone
(4.8 on an ellipse with reversals, 3.8 on a figure-eight, 4.6-4.7 on imposed orbits; KenCarp4
and KenCarp47 lower, an explicit step on z unstable at these steps) and compares it with the
other formulations read in ARKODE, OrdinaryDiffEq and diffrax.

A bearing that sticks (its z the radial return from the committed state, an algebraic function of
the displacement) follows the step's path as in the other methods; the switches between
sticking and sliding are landed on (the kink search for stick to slip, the turn search for slip
to stick), so a step never carries a bearing across one.

**Along a line** the rate vanishes identically (z = ±d, v ∥ d: g = 0 exactly), and a step is the
fifth-order step of :mod:`~femoat.integration.methods.dp5` on (u, v, z) with z constant: this
method then takes exactly that step (a step whose carried states have a zero rate at the start,
in velocity and acceleration, is tried as a dp5 step and kept if the rate is zero at every one
of its stages). A plan run along one axis is therefore the 1D default run, and a model without
a sliding plan bearing (every 1D model) is stepped by dp5 bit for bit.

Everything else is dp5's: the walls advanced exactly, the energy by the pair's quadrature, the
error as the embedded fourth-order solution's displacement and acceleration errors, the latter
with the friction state's error as a force (f(z) − f(z − e_z) of each carried bearing).

Units: kip, in, s.
"""

from fractions import Fraction

import numpy as np

from femoat.bearings.dispatch import (
    bearing_plan_rate,
    bearing_plan_rate_active,
    bearing_plan_rate_force,
    bearing_plan_rate_fsal,
    bearing_plan_rate_state,
)
from femoat.compilation.jit import njit
from femoat.integration.bundles import fsal_views, rate_scratch, rate_views
from femoat.integration.codes import E_INPUT, E_VISCOUS
from femoat.integration.forces import _internal_force, trial_outputs
from femoat.integration.methods import dp5

# ---- the ARK5(4)8L[2]SA tableau (Kennedy & Carpenter 2003, Table 6 of their report) -----------


def _rows(rows, s):
    A = np.zeros((s, s))
    for i, row in rows.items():
        for j, x in row.items():
            A[i, j] = float(Fraction(x))
    return A


N_STAGES = 8
_GAMMA = "41/200"
ARK_AE = _rows({
    1: {0: "41/100"},
    2: {0: "367902744464/2072280473677", 1: "677623207551/8224143866563"},
    3: {0: "1268023523408/10340822734521", 2: "1029933939417/13636558850479"},
    4: {0: "14463281900351/6315353703477", 2: "66114435211212/5879490589093",
        3: "-54053170152839/4284798021562"},
    5: {0: "14090043504691/34967701212078", 2: "15191511035443/11219624916014",
        3: "-18461159152457/12425892160975", 4: "-281667163811/9011619295870"},
    6: {0: "19230459214898/13134317526959", 2: "21275331358303/2942455364971",
        3: "-38145345988419/4862620318723", 4: "-1/8", 5: "-1/8"},
    7: {0: "-19977161125411/11928030595625", 2: "-40795976796054/6384907823539",
        3: "177454434618887/12078138498510", 4: "782672205425/8267701900261",
        5: "-69563011059811/9646580694205", 6: "7356628210526/4942186776405"}}, N_STAGES)
"""The explicit part's coefficients a^E_sj (j < s): the structure's stages."""
ARK_B = np.array([float(Fraction(x)) for x in (
    "-872700587467/9133579230613", "0", "0", "22348218063261/9555858737531",
    "-1143369518992/8141816002931", "-39379526789629/19018526304540",
    "32727382324388/42900044865799", _GAMMA)])
"""The fifth-order weights, shared by both parts (the implicit part's last row)."""
ARK_BHAT = np.array([float(Fraction(x)) for x in (
    "-975461918565/9796059967033", "0", "0", "78070527104295/32432590147079",
    "-548382580838/3424219808633", "-33438840321285/15594753105479",
    "3629800801594/4656183773603", "4035322873751/18575991585200")])
"""The embedded fourth-order weights, shared by both parts."""
ARK_E = ARK_B - ARK_BHAT
"""b − b̂: the error estimate's weights."""
ARK_C = np.array([float(Fraction(x)) for x in (
    "0", "41/100", "2935347310677/11292855782101", "1426016391358/7196633302097", "92/100",
    "24/100", "3/5", "1")])
"""The stage times c_s (shared)."""
ARK_AI = _rows({
    1: {0: _GAMMA, 1: _GAMMA},
    2: {0: "41/400", 1: "-567603406766/11931857230679", 2: _GAMMA},
    3: {0: "683785636431/9252920307686", 2: "-110385047103/1367015193373", 3: _GAMMA},
    4: {0: "3016520224154/10081342136671", 2: "30586259806659/12414158314087",
        3: "-22760509404356/11113319521817", 4: _GAMMA},
    5: {0: "218866479029/1489978393911", 2: "638256894668/5436446318841",
        3: "-1179710474555/5321154724896", 4: "-60928119172/8023461067671", 5: _GAMMA},
    6: {0: "1020004230633/5715676835656", 2: "25762820946817/25263940353407",
        3: "-2161375909145/9755907335909", 4: "-211217309593/5846859502534",
        5: "-4269925059573/7827059040749", 6: _GAMMA}}, N_STAGES)
ARK_AI[N_STAGES - 1] = ARK_B
"""The implicit part's coefficients a^I_sj (j ≤ s; an explicit first stage, γ = 41/200 on the
diagonal, stiffly accurate)."""

NAME = "ark5"
"""The method's name (``Integrator(method=...)``)."""
EXPLICIT = True
"""The structure's stages are evaluated from the committed state (as dp5's): the driver lands
on turning points, looks inside a step for a gap that closes and reopens, keeps a cruising step."""
QUINTIC_DENSE = True
"""Its dense output is fifth order (the running peaks read acceleration crests inside a step)."""
FINE_LANDING = True
"""A plan bearing's stick-slip switch off a line is landed on to 2^-24 of the step, not 2^-12
(``femoat.integration.kinks.FINE_BISECTIONS``): the sliver past it, which the landing step
integrates along its stage paths, would otherwise cap the order at two for small steps."""
DEFAULT_RTOL = 1e-5
"""dp5's: every peak within 1e-3 of a converged run (``benchmarks/plan_speed.py`` measures it)."""
ERROR_EXPONENT = dp5.ERROR_EXPONENT
SAFETY = dp5.SAFETY
SHRINK_MIN = dp5.SHRINK_MIN
GROW_MAX = dp5.GROW_MAX

NEWTON_TOL = 1e-14
"""A stage's friction state is solved when Newton's last correction is at most this [-]."""
NEWTON_ACCEPT = 1e-11
"""... or, after MAX_NEWTON iterations, at most this (round-off in a very stiff stage); else the
step fails and is retried shorter."""
MAX_NEWTON = 20
NEWTON_QUADRATIC = 1e-6
"""A state wider than 2 (the triple pendulum's, whose rate costs a series solve) is also solved
when its last correction is at most this, smaller than the one before (a second iteration or
later: the model needs two corrections), and the quadratic model
of Newton's convergence puts the next correction below NEWTON_TOL: it saves the evaluation
that only confirms it. The 2-wide states keep the last-correction test (their runs bit for
bit)."""


# ---- the carried friction states ------------------------------------------------------------


@njit(cache=True, inline="always")
def _flag_carried(model, state, work):
    """Flag the plan bearings whose friction state this step carries (``work.b_rate``: the
    width of the state, nonzero; the pendulum: it slides and keeps loading), their committed
    state into ``work.bz``. Returns (any flagged, every flagged rate zero at the start: at the
    committed velocity and, as a rate at the committed acceleration, its first derivative for a
    rate linear in v)."""
    flagged = False
    still = True
    u, v, a = state.u, state.v, state.a
    _, g, _, _, J, _ = rate_scratch(work)
    for e in range(model.b_dofs.shape[0]):
        kind, p, s = model.b_kind[e], model.b_P[e], state.b_S[e]
        ix, iy = model.b_dofs[e, 0], model.b_dofs[e, 1]
        if not bearing_plan_rate_active(kind, p, s, v[ix], v[iy]):
            continue
        z = work.bz[e]
        nq = bearing_plan_rate_state(kind, p, s, z)
        work.b_rate[e] = nq
        flagged = True
        bearing_plan_rate(kind, p, s, u[ix], u[iy], v[ix], v[iy], z, g, J)
        for q in range(nq):
            if g[q] != 0.0:
                still = False
        bearing_plan_rate(kind, p, s, u[ix], u[iy], a[ix], a[iy], z, g, J)
        for q in range(nq):
            if g[q] != 0.0:
                still = False
    return flagged, still


@njit(cache=True, inline="always")
def _rates_vanish(n_stages, model, state, work):
    """Whether every carried state's rate at its (constant) value is exactly zero at each of
    the ``n_stages`` stage velocities in ``work.kv`` (at the step's end displacement): the
    step never moved it."""
    _, g, _, _, J, _ = rate_scratch(work)
    for e in range(model.b_dofs.shape[0]):
        nq = work.b_rate[e]
        if nq == 0:
            continue
        kind, p, s = model.b_kind[e], model.b_P[e], state.b_S[e]
        ix, iy = model.b_dofs[e, 0], model.b_dofs[e, 1]
        for st in range(n_stages):
            bearing_plan_rate(kind, p, s, work.u[ix], work.u[iy], work.kv[st, ix],
                              work.kv[st, iy], work.bz[e], g, J)
            for q in range(nq):
                if g[q] != 0.0:
                    return False
    return True


@njit(cache=True, inline="always")
def _stage_rates(st, hh, model, state, work):
    """g_s of each carried state into ``work.kz[st]`` (:func:`_rates_at`)."""
    _rates_at(st, hh, work.b_rate, model.b_kind, model.b_P, state.b_S, model.b_dofs, work.kz,
              work.bz, work.u, work.v, work.rq)


@njit(cache=True)
def _rates_at(st, hh, b_rate, b_kind, b_P, b_S, b_dofs, kz, bz, u, v, rq):
    """:func:`_stage_rates` on the arrays it reads (its own compiled function: the coupled step
    stays small enough for LLVM to keep its loops in registers): g_s = g(Z_s; U_s, V_s)
    evaluated, or, for a state wider than 2 at an implicit stage (st ≥ 1), deduced from the
    stage's solved equation, g_s = (Z_s − w_s)/(h·γ) (ARKODE's "deduce implicit RHS"): the
    triple pendulum's rate costs a series solve, and the deduced value is the evaluated one to
    the stage's Newton tolerance over h·γ, which the next stages and the error estimate
    multiply by h again. The 2-wide states (pendulum, lead-rubber) are evaluated: their runs
    stay bit for bit."""
    z0, g, _, _, J, _ = rate_views(rq)
    hg = hh * ARK_AI[st, st]
    for e in range(b_dofs.shape[0]):
        nq = b_rate[e]
        if nq == 0:
            continue
        if st > 0 and nq != 2:
            bearing_plan_rate_state(b_kind[e], b_P[e], b_S[e], z0)
            for q in range(nq):
                acc = 0.0
                for j in range(st):
                    acc += ARK_AI[st, j] * kz[j, e, q]
                kz[st, e, q] = (bz[e, q] - (z0[q] + hh * acc)) / hg
            continue
        ix, iy = b_dofs[e, 0], b_dofs[e, 1]
        if st == 0 and _first_same_as_last(e, nq, b_kind[e], b_P[e], b_S[e], kz, bz[e], u[ix],
                                           u[iy], v[ix], v[iy]):
            continue
        bearing_plan_rate(b_kind[e], b_P[e], b_S[e], u[ix], u[iy], v[ix], v[iy], bz[e], g, J)
        for q in range(nq):
            kz[st, e, q] = g[q]


@njit(cache=True, inline="always")
def _at(nq, rg, rz, ru, rv, rc, z, ux, uy, vx, vy, code):
    """Whether the recorded point (rz, ru, rv, rc) (:func:`fsal_views`) is (z, u, v, code), z
    compared where its recorded rate ``rg`` moves it (a state the step did not carry, rate 0,
    is committed as its kind computes it, e.g. a sticking element's radial return)."""
    if not (rc[0] == code and ru[0] == ux and ru[1] == uy and rv[0] == vx and rv[1] == vy):
        return False
    for q in range(nq):
        if rg[q] != 0.0 and rz[q] != z[q]:
            return False
    return True


@njit(cache=True, inline="always")
def _first_same_as_last(e, nq, kind, p, s, kz, z, ux, uy, vx, vy):
    """For a bearing whose rate is stiff (its kind's ``plan_rate_fsal`` ≥ 0), the first stage's
    rate ``kz[0, e]`` is the end-stage rate of the last accepted step where that step ended here
    (z, u, v) in the same regime: the last coupled trial's, recorded as this point's on the
    first trial from here (a retry after a rejection keeps it). The pair's implicit part is
    stiffly accurate, so that rate is the one the end state was solved with; the rate evaluated
    at the end state adds the relaxation from the stage's structure values to the step's
    (``femoat.bearings.triple_friction_pendulum.plan_rate_fsal``). True when it wrote that
    rate (the step then evaluates none: the same carried states, so the same zero rows)."""
    code = bearing_plan_rate_fsal(kind, p, s)
    if code < 0:
        return False
    last, tz, tu, tv, tc, sg, sz, su, sv, sc = fsal_views(kz, e)
    if _at(nq, last, tz, tu, tv, tc, z, ux, uy, vx, vy, code):
        for q in range(nq):
            sg[q] = last[q]
            sz[q] = tz[q]
        su[0], su[1], sv[0], sv[1], sc[0] = tu[0], tu[1], tv[0], tv[1], tc[0]
    if not _at(nq, sg, sz, su, sv, sc, z, ux, uy, vx, vy, code):
        return False
    for q in range(nq):
        kz[0, e, q] = sg[q]
    return True


@njit(cache=True, inline="always")
def _mark_trial_end(model, state, work):
    """Record where this coupled trial ended for each stiff carried bearing (its end z, u, v
    and rate regime; its end-stage rate stays in ``kz``'s last stage row):
    :func:`_first_same_as_last` reads it at the next step's start."""
    for e in range(model.b_dofs.shape[0]):
        nq = work.b_rate[e]
        if nq == 0:
            continue
        code = bearing_plan_rate_fsal(model.b_kind[e], model.b_P[e], state.b_S[e])
        if code < 0:
            continue
        ix, iy = model.b_dofs[e, 0], model.b_dofs[e, 1]
        _, tz, tu, tv, tc, _, _, _, _, _ = fsal_views(work.kz, e)
        for q in range(nq):
            tz[q] = work.bz[e, q]
        tu[0], tu[1], tv[0], tv[1], tc[0] = (work.u[ix], work.u[iy], work.v[ix], work.v[iy],
                                             float(code))


@njit(cache=True, inline="always")
def _solve_stage_states(st, hh, model, state, work):
    """Each carried state at stage ``st`` (:func:`_stage_states`)."""
    return _stage_states(st, hh, work.b_rate, model.b_kind, model.b_P, state.b_S, model.b_dofs,
                         work.kz, work.bz, work.u, work.v, work.rq)


@njit(cache=True)
def _stage_states(st, hh, b_rate, b_kind, b_P, b_S, b_dofs, kz, bz, u, v, rq):
    """Each carried state at stage ``st``: Z = w + h·γ·g(Z; U_s, V_s), w = z_n + h·Σ_{j<s}
    a^I_sj·g_j, by Newton's method from the previous stage's Z (into ``bz``; converged by
    :data:`NEWTON_TOL`, or for a state wider than 2 also :data:`NEWTON_QUADRATIC`). False when
    one does not converge (the step is then retried shorter)."""
    hg = hh * ARK_AI[st, st]
    z0, g, w, _, J, A = rate_views(rq)
    for e in range(b_dofs.shape[0]):
        nq = b_rate[e]
        if nq == 0:
            continue
        kind, p, s = b_kind[e], b_P[e], b_S[e]
        bearing_plan_rate_state(kind, p, s, z0)
        for q in range(nq):
            acc = 0.0
            for j in range(st):
                acc += ARK_AI[st, j] * kz[j, e, q]
            w[q] = z0[q] + hh * acc
        ix, iy = b_dofs[e, 0], b_dofs[e, 1]
        ux, uy, vx, vy = u[ix], u[iy], v[ix], v[iy]
        z = bz[e]
        step = np.inf
        done = False
        for _ in range(MAX_NEWTON):
            bearing_plan_rate(kind, p, s, ux, uy, vx, vy, z, g, J)
            if nq == 2:  # the pendulum's and the lead-rubber bearing's 2×2 solve, in closed form
                rx = z[0] - w[0] - hg * g[0]
                ry = z[1] - w[1] - hg * g[1]
                a00, a01, a10, a11 = (1.0 - hg * J[0, 0], -hg * J[0, 1], -hg * J[1, 0],
                                      1.0 - hg * J[1, 1])
                det = a00 * a11 - a01 * a10
                if not (np.isfinite(det) and det != 0.0):
                    return False
                dx = (a11 * rx - a01 * ry) / det
                dy = (a00 * ry - a10 * rx) / det
                z[0] -= dx
                z[1] -= dy
                step = abs(dx) + abs(dy)
                done = step <= NEWTON_TOL
            else:
                if not _newton_update(nq, hg, z, w, g, J, A):
                    return False
                last, step = step, 0.0
                for q in range(nq):
                    step += abs(g[q])  # (the update, returned in g)
                # converged when the quadratic model's next correction, K·step² with
                # K = step/last², is below the tolerance (what the last-correction test would
                # have spent one more rate evaluation to see)
                done = step <= NEWTON_TOL or (step <= NEWTON_QUADRATIC and step < last < np.inf
                                              and step * step * step <= NEWTON_TOL * last * last)
            if done:
                break
        if not (done or step <= NEWTON_ACCEPT):
            return False
    return True


@njit(cache=True)
def _newton_update(nq, hg, z, w, g, J, A):
    """One Newton update of z for r(z) = z − w − h·γ·g(z) (g and J = ∂g/∂z at z given): solves
    (I − h·γ·J)·Δ = r, z −= Δ, Δ into ``g``. False for a singular or non-finite system.

    A state whose row and column of J are zero (an element the bearing does not carry this
    step: its rate is identically zero) is decoupled: its row of the system is the identity's,
    so its update is its residual. The others are solved by Gaussian elimination with partial
    pivoting on their own block, gathered into ``A`` (scratch): the same operations in the same
    order as on the whole matrix (elimination never touches an identity row or column: its
    multipliers are zero and it is never a pivot), in (m/nq)³ of the time for m coupled states;
    a 2 × 2 block (the triple pendulum with one element carried, most of its carried steps) in
    closed form, as the pendulum's."""
    coupled = 0
    m = 0
    for i in range(nq):
        for j in range(nq):
            if J[i, j] != 0.0 or J[j, i] != 0.0:
                coupled |= 1 << i
                m += 1
                break
    if m == 2:  # one element of the triple pendulum carried: the 2×2 block in closed form
        ia = ib = -1
        for i in range(nq):
            if (coupled >> i) & 1:
                if ia < 0:
                    ia = i
                else:
                    ib = i
        rx = z[ia] - w[ia] - hg * g[ia]
        ry = z[ib] - w[ib] - hg * g[ib]
        a00, a01, a10, a11 = (1.0 - hg * J[ia, ia], -hg * J[ia, ib], -hg * J[ib, ia],
                              1.0 - hg * J[ib, ib])
        det = a00 * a11 - a01 * a10
        if not (np.isfinite(det) and det != 0.0):
            return False
        A[0, m] = (a11 * rx - a01 * ry) / det
        A[1, m] = (a00 * ry - a10 * rx) / det
    else:
        r = 0
        for i in range(nq):
            if not (coupled >> i) & 1:
                continue
            c = 0
            for j in range(nq):
                if (coupled >> j) & 1:
                    A[r, c] = (1.0 if i == j else 0.0) - hg * J[i, j]
                    c += 1
            A[r, m] = z[i] - w[i] - hg * g[i]
            r += 1
        for c in range(m):
            piv = c
            for i in range(c + 1, m):
                if abs(A[i, c]) > abs(A[piv, c]):
                    piv = i
            if not (np.isfinite(A[piv, c]) and A[piv, c] != 0.0):
                return False
            if piv != c:
                for j in range(m + 1):
                    A[c, j], A[piv, j] = A[piv, j], A[c, j]
            for i in range(c + 1, m):
                f = A[i, c] / A[c, c]
                if f != 0.0:
                    for j in range(c, m + 1):
                        A[i, j] -= f * A[c, j]
        for i in range(m - 1, -1, -1):  # the solution into A's last column
            acc = A[i, m]
            for j in range(i + 1, m):
                acc -= A[i, j] * A[j, m]
            A[i, m] = acc / A[i, i]
    r = 0
    for i in range(nq):
        if (coupled >> i) & 1:
            g[i] = A[r, m]
            r += 1
        else:
            g[i] = z[i] - w[i] - hg * g[i]
        if not np.isfinite(g[i]):
            return False
        z[i] -= g[i]
    return True


@njit(cache=True, inline="always")
def _friction_force_error(hh, model, state, work):
    """Add each carried state's error e_z = h·Σ (b − b̂)_s·g_s, as the force f(z) − f(z − e_z)
    at the step's end, to the force error ``work.b`` (after :func:`dp5.force_error`)."""
    f2, kb, cb = work.k22[2, 0], work.k22[0], work.k22[1]
    _, _, zc, _, _, _ = rate_scratch(work)
    for e in range(model.b_dofs.shape[0]):
        nq = work.b_rate[e]
        if nq == 0:
            continue
        for q in range(nq):
            ez = 0.0
            for st in range(N_STAGES):
                ez += ARK_E[st] * work.kz[st, e, q]
            zc[q] = work.bz[e, q] - hh * ez
        ix, iy = model.b_dofs[e, 0], model.b_dofs[e, 1]
        bearing_plan_rate_force(model.b_kind[e], model.b_P[e], state.b_S[e], work.u[ix],
                                work.u[iy], work.v[ix], work.v[iy], zc, f2, kb, cb)
        work.b[ix] += work.bf[e, 0] - f2[0]
        work.b[iy] += work.bf[e, 1] - f2[1]


# ---- the step --------------------------------------------------------------------------------


@njit(cache=True, inline="always")
def _combine(s, hh, nb, state, work):
    """The structure's (U, V) of stage ``s`` from a^E (``s`` = N_STAGES: the solution, from b)
    into ``work.u``, ``work.v``."""
    kv, ka = work.kv, work.ka
    u0, v0 = state.u, state.v
    last = s == N_STAGES
    for i in range(nb):
        su = 0.0
        sv = 0.0
        for j in range(s):
            aij = ARK_B[j] if last else ARK_AE[s, j]
            su += aij * kv[j, i]
            sv += aij * ka[j, i]
        work.u[i] = u0[i] + hh * su
        work.v[i] = v0[i] + hh * sv


@njit(cache=True, python=False)
def coupled_step(hh, ag1, model, state, settings, work):
    """The ARK5(4) trial step of length ``hh`` (ground acceleration ``ag1`` [in/s²] at its
    end) with the flagged bearings' friction states carried (``work.b_rate``, their committed
    values in ``work.bz``): ``work`` then holds the end state, forces, indentations, the energy
    increments and the carried states' end values (``work.bz``). Returns the scaled error (inf:
    a stage was not finite or a state's solve failed).

    Stages 1-7 and the solution share one force evaluation in the loop below (pass
    ``N_STAGES`` is the solution: (u, v) from the weights b, z the last stage's, stiffly
    accurate; its tangents for the error estimate): one compiled copy of the force routine."""
    nb = settings.n_explicit
    ag0 = state.ag_now
    Minv, r = model.Minv, model.r
    kv, ka = work.kv, work.ka
    u0, v0 = state.u, state.v
    n = u0.size
    work.de[E_INPUT] = 0.0
    work.de[E_VISCOUS] = 0.0
    for i in range(nb):
        kv[0, i] = v0[i]
        ka[0, i] = state.a[i]
        work.u[i] = u0[i]
        work.v[i] = v0[i]
    for i in range(nb, n):
        work.u[i] = u0[i]
        work.v[i] = v0[i]
    _stage_rates(0, hh, model, state, work)
    ag = work.ag_stage
    for s in range(1, N_STAGES + 1):
        last = s == N_STAGES
        _combine(s, hh, nb, state, work)
        if not last and not _solve_stage_states(s, hh, model, state, work):
            return np.inf
        c = 1.0 if last else ARK_C[s]
        _internal_force(work.u, work.v, model, state, work, trial_outputs(work), last, nb, u0,
                        v0, c * hh)
        for k in range(ag.size):
            ag[k] = ag1[k] if last else ag0[k] + c * (ag1[k] - ag0[k])
        dp5.stage_load(r, ag, nb, work)
        for i in range(nb):
            acc = dp5.accel_row(i, nb, Minv, work.b)
            if not np.isfinite(acc):
                return np.inf
            if last:
                work.a[i] = acc
            else:
                ka[s, i] = acc
                kv[s, i] = work.v[i]
        if not last:
            _stage_rates(s, hh, model, state, work)
    _mark_trial_end(model, state, work)
    dp5.walls_exact(hh, ag0, ag1, nb, model, state, work)
    dp5.stage_energy(ARK_B, ARK_C, hh, ag0, ag1, nb, model, work)
    if not dp5.open_end(model, work):
        return np.inf
    err = dp5.displacement_error(ARK_E, hh, nb, settings, work)
    dp5.force_error(nb, work)
    _friction_force_error(hh, model, state, work)
    return dp5.acceleration_error(err, nb, model, settings, work)


# ---- the method's interface (femoat.integration.methods) ------------------------------------


DP5_STEP = 0
""":func:`plan` answer: no carried state (no sliding plan bearing): the step is dp5's."""
DP5_IF_STILL = 1
"""Every carried state has a zero rate at the start: try dp5's step, keep it if
:func:`rates_vanish` after it, else take :func:`coupled_step`."""
COUPLED = 2
"""The step is :func:`coupled_step`."""


@njit(cache=True, python=False)
def plan(model, state, work):
    """Which step to take (:data:`DP5_STEP`, :data:`DP5_IF_STILL`, :data:`COUPLED`), the carried
    bearings flagged (:func:`_flag_carried`). The method's ``step`` is spread over
    ``femoat.integration.methods.step`` so that the loop holds one copy of dp5's step: it
    asks this, takes dp5's step where told, and this method's :func:`coupled_step` else."""
    flagged, still = _flag_carried(model, state, work)
    if not flagged:
        return DP5_STEP
    return DP5_IF_STILL if still else COUPLED


@njit(cache=True, python=False)
def rates_vanish(model, state, work):
    """After dp5's step with the carried states held: their rate was zero at every stage (the
    step is then this method's step too)."""
    return _rates_vanish(dp5.N_STAGES, model, state, work)


@njit(cache=True, inline="always")
def step(hh, ag1, any_closed, model, state, settings, work):
    """(the step has a finite state, its scaled error): :func:`coupled_step`, only ever called
    while every gap is open. Where no friction state moves (:func:`plan`) the loop's
    dispatcher, ``femoat.integration.methods.step``, takes dp5's step instead (its one copy of
    it), and this step where dp5's did not keep the states still (:func:`rates_vanish`)."""
    err = coupled_step(hh, ag1, model, state, settings, work)
    return np.isfinite(err), err


retry = dp5.retry
"""After a step with no finite state: dp5's rule (the same controller constants)."""
next_step = dp5.next_step
"""The step after an accepted one: dp5's rule (h ∝ err^(−1/5))."""
