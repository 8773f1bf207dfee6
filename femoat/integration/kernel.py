"""The compiled time-stepping loop: implicit Newmark / HHT-α with Newton, adaptive steps, and
contact events located inside the step.

Everything here works on plain arrays grouped by role (:mod:`femoat.integration.bundles`:
model, state, settings, workspace, recorder) prepared by :func:`femoat.integration.solve.solve`,
the friendly, validated API; nothing is allocated per step.

:func:`run_chunk` is the driver. Each step: choose the step's end (:func:`_step_end`), solve it
by Newton (:func:`newton_step`; on failure :func:`_after_newton_failure` shrinks the step or
opens the contact episode the step ran into), judge its local error (:func:`local_error`, the
controller :func:`_step_factor` with its constants ``SAFETY``, ``SHRINK_MIN``, ``GROW_MAX``,
``ERROR_EXPONENT``), look for contact events inside it (:func:`find_events`: a crossing shortens
the step onto it; one at the committed state opens or closes the episode there,
:func:`_declare_event`), then accept it (:func:`accept`), choose the next step, and record
(:func:`record`, the only kernel that knows the output channels). The helpers are inlined into
the driver by numba (``inline="always"``): the bundles cost nothing at run time.

Model (relative to the ground, n DOFs)::

    M·ü + C·u̇ + K·u + Σ_e f_e(u_i − u_j, u̇_i − u̇_j)·(e_i − e_j) + Σ_c f_c(δ_c, δ̇_c)·b_c = −r·a_g(t)

with nonlinear two-node elements e (node j = −1 is the ground) and contacts c of indentation
δ_c = b_c·u − gap_c (compressive force f_c ≥ 0 pushes the bodies apart).

HHT-α (α in [−1/3, 0]; α = 0 is Newmark) balances
M·a₁ + (1+α)·F(u₁, v₁) − α·F(u₀, v₀) = (1+α)·p₁ − α·p₀ with Newmark's kinematics.

Step control: the Zienkiewicz-Xie local error h²·|β − 1/6|·|Δa| per DOF, measured in the DOF's
own coordinate (a floor by its story's drift, Δa_i − Δa_ref(i)) and scaled by rtol·scale_i (the
story's yield drift, the gap; a separate, tighter scale vector while any contact is closed),
and while all gaps are open each building DOF's acceleration error (K_T·e)_i/m_i against its
own scale (see :func:`femoat.integration.solve.error_scales`); a step in which an element
changes branch (stick to slip, yield) is shortened to end just past the kink
(:func:`find_kink`), so that a sample sits on the corner of the force; steps never
cross a sample of the ground record (a_g is linear between samples); a gap closing or opening
inside a step shortens the step until it ends within gap_tol of δ = 0, where the contact episode
starts (capturing δ̇₀) or ends.
"""

import numpy as np

from femoat.compilation.jit import njit
from femoat.contact.kernels import (
    contact_closure,
    contact_force,
    recorded_force,
    step_commit,
)
from femoat.integration.forces import (  # noqa: F401  (ground_accel, internal_force: entry points)
    _internal_force,
    _solve_dense,
    ground_accel,
    internal_force,
)
from femoat.integration import explicit
from femoat.integration.limits import (
    CRITERION_EXCEEDED,
    RUNAWAY_EXCEEDED,
    check_limits,
)
from femoat.integration.episodes import finish_episodes, push_episodes, start_episodes  # noqa: F401
from femoat.integration.rows import row
from femoat.integration.peaks import finish_peaks, push_sample, start_peaks  # noqa: F401
from femoat.structure.materials.kernels import material_commit, material_trial

from femoat.integration.options import (  # noqa: F401  (the option slots, one home)
    BUFFER_FULL,
    DONE,
    E_INPUT,
    E_VISCOUS,
    F_ALPHA,
    F_BETA,
    F_DTREC,
    F_GAMMA,
    F_GAPTOL,
    F_HCONTACT,
    F_HMAX,
    F_HMIN,
    F_NTOL,
    F_RTOL,
    F_TEND,
    I_MAXIT,
    I_METHOD,
    I_N_COUPLED,
    I_N_EXPLICIT,
    I_N_STRUCT,
    I_RECORD_EVERY,
    I_RING,
    I_STOP_AT_LIMIT,
    LIMIT_REACHED,
    METHOD_DP5,
    METHOD_NEWMARK,
    N_ENERGY,
    N_FOPT,
    N_IOPT,
    N_STATS,
    NEWTON_FAILED,
    S_EVENTS,
    S_IMPACTS,
    S_NEWTON,
    S_NOUT,
    S_REJECT_ERR,
    S_REJECT_NEWTON,
    S_STEPS,
    STEP_TOO_SMALL,
    STOPPED,
)


@njit(cache=True)
def _restart(model, state, work):
    """Re-establish equilibrium accelerations after a contact event changed the forces.

    A located closure or separation is a discontinuity of the force law; the trapezoidal rule
    must restart from a = M⁻¹·(p − F) at the event instead of the pre-event acceleration.
    """
    u, v, a, Fn = state.u, state.v, state.a, state.F
    M, r = model.M, model.r
    w_A, w_b = work.A, work.b
    ag_now = state.ag_now[0]
    n = u.size
    _internal_force(u, v, model, state.el_S, state.c_H, state.c_closed, work.ef, work.ed,
                    state.c_f, state.c_d, Fn, work.KT, work.CT, False, n)
    for i in range(n):
        w_b[i] = -r[i] * ag_now - Fn[i]
        for j in range(n):
            w_A[i, j] = M[i, j]
    _solve_dense(w_A, w_b, n)
    for i in range(n):
        a[i] = w_b[i]


@njit(cache=True, inline="always")
def _rate(c_B, c, v):
    """δ̇ [in/s] of contact ``c`` at velocities ``v``."""
    dd = 0.0
    for i in range(v.size):
        dd += c_B[c, i] * v[i]
    return dd


@njit(cache=True, inline="always")
def _open_episode(c, v_close, state):
    """Open contact ``c``'s episode (gap closure at approach velocity ``v_close`` [in/s])."""
    state.c_closed[c] = 1
    contact_closure(state.c_H[c], v_close)
    state.stats[S_EVENTS] += 1


@njit(cache=True, inline="always")
def _close_episode(c, state):
    """End contact ``c``'s episode (the located separation)."""
    state.c_closed[c] = 0
    state.stats[S_EVENTS] += 1


@njit(cache=True, inline="always")
def _mark_last_sample(c, t, model, state, rec):
    """An episode opened or closed at the committed state: if that state (time ``t``) is the
    last recorded sample, record the contact's new flag there, and for an opened episode the
    law's force at that state (recorded before, with the episode not yet open, as zero; within
    gap_tol of the wall it is tiny but not zero)."""
    k = state.stats[S_NOUT]
    last = row(k - 1, rec.t.shape[0])
    if k > 0 and rec.t[last] == t:
        rec.closed[last, c] = state.c_closed[c]
        if state.c_closed[c] and rec.cf[last, c] == 0.0 and state.c_d[c] > 0.0:
            rec.cf[last, c] = contact_force(model.c_code[c], model.c_P[c], state.c_H[c],
                                             state.c_d[c], _rate(model.c_B, c, state.v))[0]


@njit(cache=True)
def _sample_before_event(t, model, state, settings, rec):
    """Before an episode opens or closes at the committed state (time ``t`` > 0): record that
    state if it was skipped (``record_every`` > 1), so that the event has its sample."""
    k = state.stats[S_NOUT]
    if t > 0.0 and (k == 0 or rec.t[row(k - 1, rec.t.shape[0])] != t):
        record(t, model, state, settings, rec)


@njit(cache=True)
def _first_contact_step(v_close, h_start, h_contact, gap_tol):
    """Step after a closure: small (h_start) for a real impact, whose force law may rise
    steeply from δ = 0; the ordinary contact step for a grazing closure that would not even
    indent gap_tol in h_start (a body settling on the wall must not restart tiny every time)."""
    return h_start if v_close * h_start > gap_tol else h_contact


@njit(cache=True, inline="always")
def _hermite(th, h, x0, dx0, x1, dx1):
    """The cubic Hermite interpolant of a step of length ``h`` (values x0, x1 and time
    derivatives dx0, dx1 at its ends) at fraction ``th``, and its derivative in ``th``."""
    t2 = th * th
    t3 = t2 * th
    x = (2 * t3 - 3 * t2 + 1) * x0 + (t3 - 2 * t2 + th) * h * dx0 \
        + (-2 * t3 + 3 * t2) * x1 + (t3 - t2) * h * dx1
    dx = (6 * t2 - 6 * th) * x0 + (3 * t2 - 4 * th + 1) * h * dx0 \
        + (-6 * t2 + 6 * th) * x1 + (3 * t2 - 2 * th) * h * dx1
    return x, dx


@njit(cache=True, inline="always")
def _quintic(th, h, x0, dx0, ddx0, x1, dx1, ddx1):
    """The quintic Hermite interpolant of a step of length ``h`` (values, first and second time
    derivatives at its ends) at fraction ``th`` (the coefficients of
    :func:`femoat.dense_peaks.quintic_accel_abs_max`)."""
    c1 = h * dx0
    c2 = 0.5 * h * h * ddx0
    r0 = x1 - x0 - c1 - c2
    r1 = h * dx1 - c1 - 2.0 * c2
    r2 = h * h * ddx1 - 2.0 * c2
    c3 = 10.0 * r0 - 4.0 * r1 + 0.5 * r2
    c4 = -15.0 * r0 + 7.0 * r1 - r2
    c5 = 6.0 * r0 - 3.0 * r1 + 0.5 * r2
    return x0 + th * (c1 + th * (c2 + th * (c3 + th * (c4 + th * c5))))


@njit(cache=True)
def _crossing(d0, dd0, d1, dd1, h):
    """Fraction θ in [0, 1] where the cubic Hermite interpolant of δ crosses zero.

    Safeguarded Newton on the bracket [0, 1] (the endpoints have opposite signs); without a sign
    change the crossing is taken at the start of the step (θ = 0).
    """
    if d0 == 0.0 or d0 * d1 > 0.0:
        return 0.0
    lo, hi = 0.0, 1.0
    th = d0 / (d0 - d1)
    for _ in range(100):
        p, dp = _hermite(th, h, d0, dd0, d1, dd1)
        if p == 0.0:
            return th
        if (p > 0.0) == (d0 > 0.0):
            lo = th
        else:
            hi = th
        th_new = th - p / dp if dp != 0.0 else 0.5 * (lo + hi)
        if not (lo < th_new < hi):
            th_new = 0.5 * (lo + hi)
        if hi - lo < 1e-15 or abs(th_new - th) < 1e-16:
            return th_new
        th = th_new
    return th


# ---- the step controller ------------------------------------------------------------------

SAFETY = 0.9
"""Fraction of the step the error estimate allows that the controller takes."""
SHRINK_MIN = 0.2
"""Smallest factor a step is multiplied by (after a rejection or a rough step)."""
GROW_MAX = 2.0
"""Largest factor a step grows by after an accepted one."""
ERROR_EXPONENT = -1.0 / 3.0
"""h ∝ err^(−1/3): the Zienkiewicz-Xie estimate is O(h³)."""


@njit(cache=True, inline="always")
def _step_factor(err):
    """Factor of the next step from a local error ``err`` (1 = at the tolerance)."""
    return max(SHRINK_MIN, SAFETY * err ** ERROR_EXPONENT)


@njit(cache=True, inline="always")
def _step_end(t, h, t_goal, shortened, fopt, n_samples):
    """(hh, t1): the step from ``t`` of at most ``h``, never crossing a record sample nor the
    goal, landing exactly on the goal or a sample when within round-off of it (not after an
    event shortening, which the snap would undo)."""
    hmax, dt_rec = fopt[F_HMAX], fopt[F_DTREC]
    k_next = int(np.floor(t / dt_rec + 1e-9)) + 1
    hh = min(h, hmax, t_goal - t)
    if k_next <= n_samples - 1:
        t_sample = k_next * dt_rec
        if t_sample - t < hh:
            hh = t_sample - t
    t1 = t + hh
    if not shortened and t_goal - t1 < 1e-9 * hh:
        t1 = t_goal
    elif not shortened and k_next <= n_samples - 1 and abs(t1 - k_next * dt_rec) < 1e-9 * hh:
        t1 = k_next * dt_rec
    return t1 - t, t1


@njit(cache=True, inline="always")
def local_error(hh, any_closed, model, state, settings, work):
    """The largest scaled Zienkiewicz-Xie local error h²·|β − 1/6|·|Δa|/(rtol·scale) of the
    step (1 = at the tolerance), each DOF measured in its own coordinate: a story's drift
    against its floor below (``err_ref``); while all gaps are open also each building DOF's
    acceleration error (K_T·e)_i/m_i against rtol·``scale_accel``."""
    fopt = settings.fopt
    err_coef = abs(fopt[F_BETA] - 1.0 / 6.0)
    rtol = fopt[F_RTOL]
    scale = settings.scale_contact if any_closed else settings.scale_open
    err_ref = settings.err_ref
    a, w_a = state.a, work.a
    err = 0.0
    for i in range(a.size):
        sc = scale[i]
        da = w_a[i] - a[i]
        j = err_ref[i]
        if j >= 0:
            da -= w_a[j] - a[j]
        q = hh * hh * err_coef * abs(da) / (rtol * sc)
        if q > err:
            err = q
    if not any_closed:
        # the acceleration error of each building DOF, (K_T·e)_i / m_i with e the displacement
        # errors above (the walls are uncoupled from the building while all gaps are open)
        s_acc, KT, M = settings.scale_accel, work.KT, model.M
        n_struct = settings.iopt[I_N_STRUCT]
        for i in range(n_struct):
            s = 0.0
            for j in range(n_struct):
                s += KT[i, j] * (w_a[j] - a[j])
            q = hh * hh * err_coef * abs(s) / (M[i, i] * rtol * s_acc[i])
            if q > err:
                err = q
    return err


# ---- Newton on the Newmark/HHT step -----------------------------------------------------------
# in the acceleration a₁ (the displacement form loses digits to cancellation in
# (u₁ − u₀ − h·v₀)/(βh²) when steps are tiny)

RESIDUAL_MARGIN = 1e4
"""A residual's estimated correction, times this, must be below the tolerance to stop Newton
without another solve (so that the state is as converged as after one more update)."""
ACCEL_TOL_FACTOR = 1e2
"""Acceleration corrections are judged against ntol·ACCEL_TOL_FACTOR·(max |a| + 1 in/s²)."""


@njit(cache=True, inline="always")
def _trial_kinematics(hh, bh2, gh, beta, gamma, state, work):
    """Newmark's u₁, v₁ from the trial acceleration a₁ (``work.a``); returns max |a₁|."""
    u, v, a = state.u, state.v, state.a
    w_u, w_v, w_a = work.u, work.v, work.a
    amax = 0.0
    for i in range(u.size):
        w_u[i] = u[i] + hh * v[i] + hh * hh * (0.5 - beta) * a[i] + bh2 * w_a[i]
        w_v[i] = v[i] + hh * (1.0 - gamma) * a[i] + gh * w_a[i]
        if abs(w_a[i]) > amax:
            amax = abs(w_a[i])
    return amax


@njit(cache=True, inline="always")
def _dense_size(n_coupled, any_closed, model, work):
    """Lazy wall work: the block solved densely, the building only while no contact can act."""
    n = work.u.size
    nd = n
    if n_coupled < n and not any_closed:
        nd = n_coupled
        c_B, c_gap = model.c_B, model.c_gap
        for c in range(c_gap.size):
            d = -c_gap[c]
            for i in range(n):
                d += c_B[c, i] * work.u[i]
            if d > 0.0:
                nd = n
    return nd


@njit(cache=True, inline="always")
def _residual(bh2, gh, alpha, ag0, ag1, nd, model, state, work):
    """The HHT residual (−, into ``work.b``) and iteration matrix (``work.A``) at the trial."""
    M, r = model.M, model.r
    Fn = state.F
    w_a, w_F, w_KT, w_CT, w_A, w_b = work.a, work.F, work.KT, work.CT, work.A, work.b
    for i in range(w_a.size):
        p1 = -r[i] * ag1
        p0 = -r[i] * ag0
        if i < nd:
            s = 0.0
            for j in range(nd):
                s += M[i, j] * w_a[j]
            for j in range(nd):
                w_A[i, j] = M[i, j] + (1.0 + alpha) * (gh * w_CT[i, j] + bh2 * w_KT[i, j])
        else:
            s = M[i, i] * w_a[i]
            w_A[i, i] = M[i, i] + (1.0 + alpha) * (gh * w_CT[i, i] + bh2 * w_KT[i, i])
        w_b[i] = -(s + (1.0 + alpha) * (w_F[i] - p1) - alpha * (Fn[i] - p0))


@njit(cache=True, inline="always")
def _residual_is_small(bh2, ntol, amax, scale, work):
    """After a Newton update: is the correction the residual asks for (estimated from the
    diagonal of the iteration matrix, with a margin) below the tolerance? The forces just
    evaluated are then those of the converged state, so neither another solve nor a final
    evaluation is needed. In a step where every spring stays on its branch the update was exact
    (the residual is round-off), which is most steps; this saves a third of the work."""
    w_A, w_b = work.A, work.b
    for i in range(w_b.size):
        if w_A[i, i] <= 0.0:  # (a softening tangent: no estimate, solve instead)
            return False
        est = RESIDUAL_MARGIN * abs(w_b[i]) / w_A[i, i]
        if bh2 * est / scale[i] >= ntol or est >= ntol * ACCEL_TOL_FACTOR * (amax + 1.0):
            return False
    return True


@njit(cache=True, inline="always")
def _update(bh2, nd, scale, work):
    """Solve for the correction and apply it to a₁; (solved and finite, |Δu|/scale, |Δa|)."""
    w_A, w_b, w_a = work.A, work.b, work.a
    if not _solve_dense(w_A, w_b, nd):
        return False, 0.0, 0.0
    n = w_a.size
    for i in range(nd, n):
        w_b[i] /= w_A[i, i]
    du = 0.0
    da = 0.0
    finite = True
    for i in range(n):
        w_a[i] += w_b[i]
        q = bh2 * abs(w_b[i]) / scale[i]
        if q > du:
            du = q
        if abs(w_b[i]) > da:
            da = abs(w_b[i])
        if not np.isfinite(w_a[i]):
            finite = False
    return finite, du, da


@njit(cache=True, inline="always")
def newton_step(hh, ag1, any_closed, model, state, settings, work):
    """Solve the step of length ``hh`` (ground acceleration ``ag1`` [in/s²] at its end) for a₁
    (``work``: the trial state and its forces at convergence); True when Newton converged."""
    fopt, iopt = settings.fopt, settings.iopt
    beta, gamma, alpha = fopt[F_BETA], fopt[F_GAMMA], fopt[F_ALPHA]
    ntol, maxit, n_coupled = fopt[F_NTOL], iopt[I_MAXIT], iopt[I_N_COUPLED]
    scale = settings.scale_contact
    bh2 = beta * hh * hh
    gh = gamma * hh
    ag0 = state.ag_now[0]
    for i in range(state.a.size):
        work.a[i] = state.a[i]
    converged = False
    evaluated = False
    it = 0
    nd = work.u.size
    while it < maxit:
        it += 1
        amax = _trial_kinematics(hh, bh2, gh, beta, gamma, state, work)
        nd = _dense_size(n_coupled, any_closed, model, work)
        _internal_force(work.u, work.v, model, state.el_S, state.c_H, state.c_closed, work.ef,
                        work.ed, work.cf, work.cd, work.F, work.KT, work.CT, True, nd)
        _residual(bh2, gh, alpha, ag0, ag1, nd, model, state, work)
        if it > 1 and _residual_is_small(bh2, ntol, amax, scale, work):
            converged = True
            evaluated = True
            break
        finite, du, da = _update(bh2, nd, scale, work)
        if not finite:
            break
        # converged: the displacement correction is below ntol·scale and the acceleration
        # correction below ntol relative to the accelerations (or 1 in/s² absolute)
        if du < ntol and da < ntol * ACCEL_TOL_FACTOR * (amax + 1.0):
            converged = True
            break
    state.stats[S_NEWTON] += it
    if converged and not evaluated:
        # final kinematics and forces at the converged acceleration
        _trial_kinematics(hh, bh2, gh, beta, gamma, state, work)
        _internal_force(work.u, work.v, model, state.el_S, state.c_H, state.c_closed, work.ef,
                        work.ed, work.cf, work.cd, work.F, work.KT, work.CT, False, nd)
    return converged


@njit(cache=True, inline="always")
def _after_newton_failure(t, hh, model, state, settings, work, rec):
    """A step Newton could not solve: (next step, False), or (h, True) when it cannot shrink.

    A gap closing inside the step can defeat Newton when the law jumps at δ = 0⁺ (Kelvin-Voigt):
    land just before the closure, or start the episode right here.
    """
    fopt = settings.fopt
    hmin, gap_tol, h_contact = fopt[F_HMIN], fopt[F_GAPTOL], fopt[F_HCONTACT]
    c_B, c_d, c_closed = model.c_B, state.c_d, state.c_closed
    state.stats[S_REJECT_NEWTON] += 1
    started = False
    v_close = 0.0
    h_cross = hh
    for c in range(c_d.size):
        if not c_closed[c]:
            dd0 = _rate(c_B, c, state.v)
            if dd0 <= 0.0 or c_d[c] + dd0 * hh <= 0.0:
                continue
            # the gap closes within this step (straight-line estimate)
            if -c_d[c] / dd0 >= hmin and c_d[c] < -gap_tol:
                # aim short of the crossing so that the step converges and progresses
                h_cross = min(h_cross, 0.9 * (-c_d[c] / dd0))
                continue
            _sample_before_event(t, model, state, settings, rec)
            _open_episode(c, dd0, state)
            _mark_last_sample(c, t, model, state, rec)
            started = True
            v_close = max(v_close, dd0)
    if not started and h_cross < 0.999 * hh:
        return h_cross, False
    if started:
        _restart(model, state, work)
        return min(hh, _first_contact_step(v_close, H_START * h_contact, h_contact, gap_tol)), \
            False
    h = hh * 0.25
    return h, h < hmin


# ---- contact events -----------------------------------------------------------------------

H_START = 1e-3
"""After a closure the force law is not smooth (Kelvin-Voigt jumps, Jankowski rises as
δ^(1/4)): restart at this fraction of the contact step and let the controller grow the step."""


@njit(cache=True, inline="always")
def find_events(hh, look_inside, model, state, settings, work):
    """(θ, c, c_now): the earliest crossing of δ = 0 inside the trial step at fraction θ of it
    (θ = 2: none) by contact c (a closure, or the separation of an open episode), and c_now ≥ 0
    a contact whose gap closes in the step while it was already touching at its start.

    ``look_inside`` (the long steps of the explicit method): a gap open at both ends of the
    step may still close inside it, near a turning point of δ; where δ approaches at the start,
    recedes at the end and its quintic interpolant (δ, δ̇ and δ̈ at the ends) crests above
    gap_tol, the step is shortened to end at the crest, where the ordinary crossing search
    takes over."""
    gap_tol = settings.fopt[F_GAPTOL]
    c_B, c_closed = model.c_B, state.c_closed
    theta = 2.0
    c_min = -1
    event_now = -1
    for c in range(c_closed.size):
        d0, d1 = state.c_d[c], work.cd[c]
        dd0 = 0.0
        dd1 = 0.0
        for i in range(state.v.size):
            dd0 += c_B[c, i] * state.v[i]
            dd1 += c_B[c, i] * work.v[i]
        if not c_closed[c] and d1 > 0.0:
            if d0 >= -gap_tol:
                event_now = c  # already touching at the start of the step
            else:
                th = _crossing(d0, dd0, d1, dd1, hh)
                if th < theta:
                    theta = th
                    c_min = c
        elif c_closed[c] and d1 < -gap_tol:
            th = _crossing(d0, dd0, d1, dd1, hh)
            if th < theta:
                theta = th
                c_min = c
        elif look_inside and not c_closed[c] and dd0 > 0.0 and dd1 < 0.0:
            dda0 = 0.0
            dda1 = 0.0
            for i in range(state.a.size):
                dda0 += c_B[c, i] * state.a[i]
                dda1 += c_B[c, i] * work.a[i]
            th = _crossing(dd0, dda0, dd1, dda1, hh)
            crest = _quintic(th, hh, d0, dd0, dda0, d1, dd1, dda1)
            # (a crest within gap_tol of the wall is a touch, not an impact; a crest at the
            # step's very end is the one the step was already shortened to; one closer than the
            # smallest step to the start is left to the next step, never declared here)
            if crest > gap_tol and 0.0 < th < min(theta, 1.0 - KINK_RESOLUTION) \
                    and th * hh >= settings.fopt[F_HMIN]:
                theta = th
                c_min = c
    return theta, c_min, event_now


# ---- material kinks -------------------------------------------------------------------------

KINK_RATIO = 0.5
"""An element's tangent that changes by more than this fraction of the larger of its start and
end values within a step marks a kink (a branch change: stick to slip, yield, capping)."""
KINK_BISECTIONS = 12
"""Bisections locating a kink: the step lands within 2^-12 of its length past it."""
KINK_RESOLUTION = 2.0 ** -KINK_BISECTIONS
"""A kink closer than this fraction to the start of a step is not landed on."""


@njit(cache=True, inline="always")
def _element_rates(e, model, v):
    i, j = model.el_i[e], model.el_j[e]
    return v[i] - (v[j] if j >= 0 else 0.0)


@njit(cache=True, inline="always")
def find_kink(hh, model, state, work):
    """Fraction θ of the trial step just past the earliest element kink inside it (2: none).

    An element's tangent at the start (its committed branch) and at the trial end are compared;
    when they differ by more than KINK_RATIO, the branch change is located by bisection on the
    element's deformation along the step's cubic Hermite interpolant, each point evaluated from
    the committed state. Landing the step there puts a sample on the corner of the force (and
    of the accelerations), which step ends would otherwise cut off.
    """
    theta = 2.0
    el_code, el_P, el_S = model.el_code, model.el_P, state.el_S
    for e in range(el_code.size):
        d0, d1 = state.el_d[e], work.ed[e]
        dv0 = _element_rates(e, model, state.v)
        dv1 = _element_rates(e, model, work.v)
        # the start's branch is read a resolution into the step: at the committed point itself
        # a material may sit on the boundary of two branches (a sliding bearing at |z| = 1)
        lo, hi = KINK_RESOLUTION, 1.0
        d, dth = _hermite(lo, hh, d0, dv0, d1, dv1)
        _, k0, _ = material_trial(el_code[e], el_P[e], el_S[e], d, dth / hh)
        _, k1, _ = material_trial(el_code[e], el_P[e], el_S[e], d1, dv1)
        if abs(k1 - k0) <= KINK_RATIO * max(abs(k0), abs(k1)):
            continue
        for _ in range(KINK_BISECTIONS):
            mid = 0.5 * (lo + hi)
            d, dth = _hermite(mid, hh, d0, dv0, d1, dv1)
            _, k, _ = material_trial(el_code[e], el_P[e], el_S[e], d, dth / hh)
            if abs(k - k0) <= abs(k - k1):
                lo = mid
            else:
                hi = mid
        if hi < theta:
            theta = hi
    return theta


@njit(cache=True, inline="always")
def find_turn(hh, model, state, work):
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
        th = _crossing(dv0, da0, dv1, da1, hh)
        if th <= KINK_RESOLUTION or th >= 1.0:
            continue
        d, _ = _hermite(th, hh, state.el_d[e], dv0, work.ed[e], dv1)
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
    return theta


TURN_PROBE = 1e-9
"""A turning point's way back is probed this fraction of the deformation's size back from it."""


# ---- accepting and recording a step -----------------------------------------------------------


@njit(cache=True, inline="always")
def accept(ag1, landing, explicit_step, model, state, settings, work):
    """Commit the trial step: energies, element and contact states, episode changes (a closure
    within gap_tol, the located separation of contact ``landing``), kinematics. Returns
    (an episode opened or closed, the largest approach velocity of the closures).

    Energies: input and viscous by the trapezoidal rule of the Newmark step, or the explicit
    step's own quadrature (``work.de``) when ``explicit_step``; element work by the trapezoidal
    rule for both (exact on a branch that is linear in the deformation)."""
    C, r, c_B = model.C, model.r, model.c_B
    u, v, a, Fn = state.u, state.v, state.a, state.F
    energy = state.energy
    gap_tol = settings.fopt[F_GAPTOL]
    ag0 = state.ag_now[0]
    n = u.size
    if explicit_step:
        energy[E_INPUT] += work.de[E_INPUT]
        energy[E_VISCOUS] += work.de[E_VISCOUS]
    else:
        for i in range(n):
            du_i = work.u[i] - u[i]
            energy[E_INPUT] += 0.5 * (-r[i] * ag0 - r[i] * ag1) * du_i
            cv0 = 0.0
            cv1 = 0.0
            for j in range(n):
                cv0 += C[i, j] * v[j]
                cv1 += C[i, j] * work.v[j]
            energy[E_VISCOUS] += 0.5 * (cv0 + cv1) * du_i
    el_i, el_j = model.el_i, model.el_j
    el_f, el_d, w_ef, w_ed = state.el_f, state.el_d, work.ef, work.ed
    for e in range(el_f.size):
        # the trapezoidal rule is the exact work of a piecewise-linear branch, and no step
        # changes branch (kinks and turning points are landed on)
        state.el_W[e] += 0.5 * (el_f[e] + w_ef[e]) * (w_ed[e] - el_d[e])
        i, j = el_i[e], el_j[e]
        dv = work.v[i] - (work.v[j] if j >= 0 else 0.0)
        material_commit(model.el_code[e], model.el_P[e], state.el_S[e], w_ed[e], dv)
        el_f[e] = w_ef[e]
        el_d[e] = w_ed[e]
    toggled = False
    v_close = 0.0
    c_f, c_d, w_cf, w_cd, c_closed = state.c_f, state.c_d, work.cf, work.cd, state.c_closed
    for c in range(c_f.size):
        state.c_W[c] += 0.5 * (c_f[c] + w_cf[c]) * (w_cd[c] - c_d[c])
        step_commit(model.c_code[c], model.c_P[c], state.c_H[c], w_cd[c])
        c_f[c] = w_cf[c]
        c_d[c] = w_cd[c]
        dd1 = _rate(c_B, c, work.v)
        if not c_closed[c] and w_cd[c] >= -gap_tol and w_cd[c] <= 0.0 and dd1 > 0.0:
            _open_episode(c, dd1, state)
            v_close = max(v_close, dd1)
            toggled = True
        elif c_closed[c] and landing == c and w_cd[c] <= gap_tol and dd1 < 0.0:
            # separation only at the located crossing (the step was shortened onto it; a
            # closed contact whose trial step ends below −gap_tol never gets here, the event
            # search shortens the step or opens it at the committed state). A contact
            # resting within ±gap_tol of δ = 0 stays closed (it carries no force there)
            # instead of opening and closing at every step.
            _close_episode(c, state)
            toggled = True
    for i in range(n):
        u[i] = work.u[i]
        v[i] = work.v[i]
        a[i] = work.a[i]
        Fn[i] = work.F[i]
    state.ag_now[0] = ag1
    return toggled, v_close


@njit(cache=True, inline="always")
def record(t, model, state, settings, rec):
    """Append the committed state at time ``t`` as sample ``k`` to the recorder, in its row
    ``k`` modulo its length (a ring without history; a channel whose buffer has no columns was
    not requested: nothing is written), and pass it to the running peaks and episodes."""
    u, v, a = state.u, state.v, state.a
    n_out = state.stats[S_NOUT]
    k = row(n_out, rec.t.shape[0])
    rec.t[k] = t
    rec.ag[k] = state.ag_now[0]
    for i in range(rec.u.shape[1]):
        rec.u[k, i] = u[i]
    for i in range(rec.v.shape[1]):
        rec.v[k, i] = v[i]
    for i in range(rec.a.shape[1]):
        rec.a[k, i] = a[i]
    for e in range(rec.ef.shape[1]):
        rec.ef[k, e] = state.el_f[e]
        rec.ed[k, e] = state.el_d[e]
    c_f, c_d, c_closed = state.c_f, state.c_d, state.c_closed
    for c in range(c_f.size):
        dd1 = _rate(model.c_B, c, v)
        # the law's force at the recorded state; the Hertz laws' step force differs
        # from it by the discrete gradient's O(Δδ²) trapezoidal defect
        rec.cf[k, c] = c_f[c]
        if c_closed[c]:
            rec.cf[k, c] = recorded_force(model.c_code[c], model.c_P[c], state.c_H[c], c_d[c],
                                          dd1, c_f[c])
        rec.cd[k, c] = c_d[c]
        rec.cv[k, c] = dd1
        rec.closed[k, c] = c_closed[c]
    state.stats[S_NOUT] = n_out + 1
    push_sample(t, n_out, model, state, settings, rec)
    push_episodes(n_out, state, rec)


@njit(cache=True, inline="always")
def _any_closed(c_closed):
    for c in range(c_closed.size):
        if c_closed[c]:
            return True
    return False


# ---- the driver ---------------------------------------------------------------------------


@njit(cache=True, inline="always")
def _declare_event(c, t, hh, h, model, state, settings, work, rec):
    """An event at the committed state (time ``t``): contact ``c``'s gap closed while it was
    already touching, or its crossing is closer than the smallest step. Open (or close) the
    episode there, restart, and return the step to redo (``h`` unless an episode opened)."""
    _sample_before_event(t, model, state, settings, rec)
    if state.c_closed[c]:
        _close_episode(c, state)
    else:
        dd0 = _rate(model.c_B, c, state.v)
        _open_episode(c, max(dd0, 0.0), state)
        h_contact, gap_tol = settings.fopt[F_HCONTACT], settings.fopt[F_GAPTOL]
        h = min(hh, _first_contact_step(dd0, H_START * h_contact, h_contact, gap_tol))
    _mark_last_sample(c, t, model, state, rec)
    _restart(model, state, work)
    return h


@njit(cache=True, inline="always")
def _limit_reached(t, model, state, settings):
    """Check the limit states (:mod:`femoat.integration.limits`) after an accepted step: does
    the run end here?"""
    hit = check_limits(t, settings.iopt[I_N_STRUCT], model, state, settings.limits,
                       state.first_exceed)
    return hit == RUNAWAY_EXCEEDED or (hit == CRITERION_EXCEEDED
                                       and settings.iopt[I_STOP_AT_LIMIT] == 1)


@njit(cache=True, inline="always")
def _stop(status, t, h, h_cruise, shortened, landing, since_record, state):
    """Leave the loop at time ``t`` with the controller's state kept for the next call (the
    next step ``h``, the cruising step, a pending landing and the samples since the last record),
    so that a run does not depend on where it was re-entered (a grown recorder, a progress
    display's chunks)."""
    state.t[0] = t
    state.h[0] = h
    state.h[1] = h_cruise
    state.ctl[0] = 1 if shortened else 0
    state.ctl[1] = landing
    state.ctl[2] = since_record
    return status


@njit(cache=True)
def run_chunk(t_stop, model, state, settings, work, rec):
    """Advance ``state`` from state.t[0] to min(t_stop, t_end), recording into ``rec``; return a
    status code (see module)."""
    fopt = settings.fopt
    hmin, t_end, h_contact, gap_tol = fopt[F_HMIN], fopt[F_TEND], fopt[F_HCONTACT], fopt[F_GAPTOL]
    rec_every, method = settings.iopt[I_RECORD_EVERY], settings.iopt[I_METHOD]
    ring = settings.iopt[I_RING] == 1
    # room for the episodes one loop pass can end and finish_episodes after the last
    impacts_room = rec.episodes.shape[0] - 3 * model.c_gap.size
    c_closed, stats = state.c_closed, state.stats
    t, h = state.t[0], state.h[0]
    t_goal = min(t_stop, t_end)  # this call returns after the first step reaching it
    stalls = 0
    h_cruise = state.h[1]  # the explicit method's step before landings and sample cuts
    shortened = state.ctl[0] == 1
    landing = state.ctl[1]  # the contact whose located separation the shortened step lands on
    since_record = state.ctl[2]
    while t < t_goal * (1.0 - 1e-15) and t_goal - t > 1e-14:
        stalls += 1
        if stalls > 100000:  # no step accepted after 100000 attempts: report, don't spin
            return _stop(STEP_TOO_SMALL, t, h, h_cruise, shortened, landing, since_record, state)
        if (stats[S_NOUT] >= rec.t.size and not ring) or stats[S_IMPACTS] > impacts_room:
            return _stop(BUFFER_FULL, t, h, h_cruise, shortened, landing, since_record, state)
        h_asked = h
        hh, t1 = _step_end(t, h, t_end, shortened, fopt, model.ag.size)
        ag1 = ground_accel(model.ag, fopt[F_DTREC], t1)
        any_closed = _any_closed(c_closed)
        explicit_now = method == METHOD_DP5 and not any_closed
        if explicit_now:
            err = explicit.explicit_step(hh, ag1, model, state, settings, work)
            if not np.isfinite(err):
                if hh <= hmin:
                    return _stop(NEWTON_FAILED, t, h, h_cruise, shortened, landing,
                                 since_record, state)
                stats[S_REJECT_ERR] += 1
                h = max(hh * explicit.SHRINK_MIN, hmin)
                continue
            if err > 1.0 and hh > hmin:
                stats[S_REJECT_ERR] += 1
                h = max(hh * explicit.step_factor(err), hmin)
                continue
        else:
            if not newton_step(hh, ag1, any_closed, model, state, settings, work):
                h, failed = _after_newton_failure(t, hh, model, state, settings, work, rec)
                if failed:
                    return _stop(NEWTON_FAILED, t, h, h_cruise, shortened, landing,
                                 since_record, state)
                continue
            err = local_error(hh, any_closed, model, state, settings, work)
            if err > 1.0 and hh > hmin:
                stats[S_REJECT_ERR] += 1
                h = max(hh * _step_factor(err), hmin)
                continue
        theta, c_min, event_now = find_events(hh, explicit_now, model, state, settings, work)
        if event_now >= 0:  # closure at the committed state: start there, redo the step small
            h = _declare_event(event_now, t, hh, h, model, state, settings, work, rec)
            continue
        if theta > 1.0 and not shortened:
            theta_k = find_kink(hh, model, state, work)
            if explicit_now:
                theta_k = min(theta_k, find_turn(hh, model, state, work))
            if theta_k < 1.0 and hh * theta_k >= hmin:
                stats[S_REJECT_ERR] += 1
                h = hh * theta_k
                shortened = True
                landing = -1
                continue
        if theta <= 1.0:
            # shorten by more than the time round-off, or the same step would repeat forever
            h_new = min(hh * theta, hh - 64.0 * 2.3e-16 * abs(t1))
            if h_new >= hmin:
                stats[S_REJECT_ERR] += 1
                h = h_new
                shortened = True
                landing = c_min if c_closed[c_min] else -1
            else:  # the crossing is closer than the smallest step: declare it where we are
                h = _declare_event(c_min, t, hh, h, model, state, settings, work, rec)
            continue

        toggled, v_close = accept(ag1, landing, explicit_now, model, state, settings, work)
        t = t1
        stalls = 0
        cut_short = shortened or hh < h_asked * (1.0 - 1e-12)
        shortened = False
        landing = -1
        if toggled:
            _restart(model, state, work)
        stats[S_STEPS] += 1
        now_closed = _any_closed(c_closed)
        if explicit_now:
            h = max(hh * explicit.step_factor(err), hmin)
            # a step cut short (landed on a kink, a turning point or an event, or ending on a
            # sample) says nothing about the step the solution allows: resume the cruising
            # step (the error control rejects it once if it has become too long)
            if cut_short:
                h = max(h, h_cruise)
            else:
                h_cruise = h
        else:
            h = hh * (GROW_MAX if err < 1e-12 else min(GROW_MAX, _step_factor(err)))
            if method == METHOD_DP5 and toggled and not now_closed:
                h = max(h, h_cruise)  # back to the open phase: its cruising step
        if toggled and now_closed:
            h = min(h, _first_contact_step(v_close, H_START * h_contact, h_contact, gap_tol))
        since_record += 1
        if since_record >= rec_every or now_closed or any_closed or toggled or t >= t_end:
            since_record = 0
            record(t, model, state, settings, rec)
        if _limit_reached(t, model, state, settings):
            return _stop(LIMIT_REACHED, t, h, h_cruise, shortened, landing, since_record, state)
    return _stop(DONE if t >= t_end * (1.0 - 1e-15) or t_end - t <= 1e-14 else STOPPED, t, h,
                 h_cruise, shortened, landing, since_record, state)
