"""The compiled time-stepping loop: implicit Newmark / HHT-α with Newton, adaptive steps, and
contact events located inside the step.

Everything here works on plain arrays prepared by :mod:`femoat.integration.packing`; nothing is
allocated per step. The friendly, validated API is :func:`femoat.integration.solve.solve`.

Model (relative to the ground, n DOFs)::

    M·ü + C·u̇ + K·u + Σ_e f_e(u_i − u_j, u̇_i − u̇_j)·(e_i − e_j) + Σ_c f_c(δ_c, δ̇_c)·b_c = −r·a_g(t)

with nonlinear two-node elements e (node j = −1 is the ground) and contacts c of indentation
δ_c = b_c·u − gap_c (compressive force f_c ≥ 0 pushes the bodies apart).

HHT-α (α in [−1/3, 0]; α = 0 is Newmark) balances
M·a₁ + (1+α)·F(u₁, v₁) − α·F(u₀, v₀) = (1+α)·p₁ − α·p₀ with Newmark's kinematics.

Step control: the Zienkiewicz-Xie local error h²·|β − 1/6|·|Δa| per DOF, measured in the DOF's
own coordinate (a floor by its story's drift, Δa_i − Δa_ref(i)) and scaled by rtol·scale_i (the
story's yield drift, the gap; a separate, tighter scale vector while any contact is closed;
see :func:`femoat.integration.solve.error_scales`); steps never
cross a sample of the ground record (a_g is linear between samples); a gap closing or opening
inside a step shortens the step until it ends within gap_tol of δ = 0, where the contact episode
starts (capturing δ̇₀) or ends.
"""

from pathlib import Path

import numpy as np
from femoat.jit import njit

from femoat.numba_cache import drop_stale_cache

_PKG = Path(__file__).resolve().parent.parent
drop_stale_cache(__file__, [*sorted((_PKG / "contact").glob("*.py")),
                            *sorted((_PKG / "structure" / "materials").glob("*.py"))])

from femoat.contact.kernels import (  # noqa: E402
    contact_closure,
    recorded_force,
    step_commit,
    step_force,
)
from femoat.structure.materials.kernels import material_commit, material_trial  # noqa: E402

# Status codes returned by run_chunk.
DONE, STOPPED, BUFFER_FULL, NEWTON_FAILED, STEP_TOO_SMALL, LIMIT_REACHED = 0, 1, 2, 3, 4, 5

# Float options (fopt)
F_BETA, F_GAMMA, F_ALPHA, F_RTOL, F_HMAX, F_HMIN, F_NTOL, F_TEND, F_DTREC, F_HCONTACT, \
    F_GAPTOL = range(11)
N_FOPT = 11
# Integer options (iopt)
I_MAXIT, I_RECORD_EVERY, I_N_COUPLED, I_LIMITS, I_N_STRUCT = 0, 1, 2, 3, 4
N_IOPT = 5
# I_LIMITS: what the limit states (collapse criteria) do
LIMITS_OFF, LIMITS_RECORD, LIMITS_STOP = 0, 1, 2
# Stats (stats), integer
S_STEPS, S_REJECT_ERR, S_REJECT_NEWTON, S_NEWTON, S_NOUT, S_EVENTS, S_FAIL_INFO = range(7)
N_STATS = 7
# Energies (energy), float
E_INPUT, E_VISCOUS = 0, 1
N_ENERGY = 2


@njit(cache=True)
def ground_accel(ag, dt_rec, t):
    """a_g(t) [in/s²], linear between samples, zero after the record."""
    x = t / dt_rec
    i = int(np.floor(x))
    if i < 0:
        return 0.0
    if i >= ag.size - 1:
        if i == ag.size - 1 and x - i < 1e-9:
            return ag[ag.size - 1]
        return 0.0
    w = x - i
    return (1.0 - w) * ag[i] + w * ag[i + 1]


@njit(cache=True)
def _solve_dense(A, b, n):
    # Gaussian elimination with partial pivoting, in place; the solution overwrites b.
    for k in range(n):
        p = k
        amax = abs(A[k, k])
        for i in range(k + 1, n):
            if abs(A[i, k]) > amax:
                amax = abs(A[i, k])
                p = i
        if amax == 0.0:
            return False
        if p != k:
            for j in range(n):
                tmp = A[k, j]
                A[k, j] = A[p, j]
                A[p, j] = tmp
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
        piv = A[k, k]
        for i in range(k + 1, n):
            f = A[i, k] / piv
            if f != 0.0:
                for j in range(k, n):
                    A[i, j] -= f * A[k, j]
                b[i] -= f * b[k]
    for k in range(n - 1, -1, -1):
        s = b[k]
        for j in range(k + 1, n):
            s -= A[k, j] * b[j]
        b[k] = s / A[k, k]
    return True


@njit(cache=True)
def _internal_force(u, v, M, C, K, el_i, el_j, el_code, el_P, el_S, el_f, el_d,
                    c_B, c_gap, c_code, c_P, c_H, c_closed, c_f, c_d, F, KT, CT, want_tangent,
                    nd):
    """F = C·v + K·u + element and contact forces at (u, v); tangents KT, CT if asked.

    Rows and columns from ``nd`` on are treated as diagonal (uncoupled wall modes while no
    contact carries force); ``nd = n`` is the general dense case.
    Contacts act only while their episode is open (between a located closure and the located
    separation); a Kelvin-Voigt contact then acts at δ = 0⁺ too (its dashpot force c·δ̇ jumps on
    at closure), so that the step after a located closure starts from the right force.
    """
    n = u.size
    for i in range(nd):
        s = 0.0
        for j in range(nd):
            s += C[i, j] * v[j] + K[i, j] * u[j]
        F[i] = s
    for i in range(nd, n):
        F[i] = C[i, i] * v[i] + K[i, i] * u[i]
    if want_tangent:
        for i in range(nd):
            for j in range(nd):
                KT[i, j] = K[i, j]
                CT[i, j] = C[i, j]
        for i in range(nd, n):
            KT[i, i] = K[i, i]
            CT[i, i] = C[i, i]
    for e in range(el_code.size):
        i, j = el_i[e], el_j[e]
        d = u[i] - (u[j] if j >= 0 else 0.0)
        dv = v[i] - (v[j] if j >= 0 else 0.0)
        f, kf, cf = material_trial(el_code[e], el_P[e], el_S[e], d, dv)
        el_f[e] = f
        el_d[e] = d
        F[i] += f
        if j >= 0:
            F[j] -= f
        if want_tangent:
            KT[i, i] += kf
            CT[i, i] += cf
            if j >= 0:
                KT[j, j] += kf
                KT[i, j] -= kf
                KT[j, i] -= kf
                CT[j, j] += cf
                CT[i, j] -= cf
                CT[j, i] -= cf
    for c in range(c_code.size):
        b = c_B[c]
        d = -c_gap[c]
        dv = 0.0
        for i in range(n):
            d += b[i] * u[i]
            dv += b[i] * v[i]
        c_d[c] = d
        if not c_closed[c]:
            # no episode open: no force (a trial step that closes the gap is shortened to the
            # located closure; a gap that has just opened within gap_tol carries nothing)
            c_f[c] = 0.0
            continue
        f, kf, cf = step_force(c_code[c], c_P[c], c_H[c], d, dv)
        c_f[c] = f
        if f != 0.0 or kf != 0.0 or cf != 0.0:
            for i in range(n):
                if b[i] != 0.0:
                    F[i] += f * b[i]
                    if want_tangent:
                        for j in range(n):
                            if b[j] != 0.0:
                                KT[i, j] += kf * b[i] * b[j]
                                CT[i, j] += cf * b[i] * b[j]


@njit(cache=True)
def _restart(u, v, a, Fn, ag_now, M, C, K, r, el_i, el_j, el_code, el_P, el_S, c_B, c_gap,
             c_code, c_P, c_H, c_closed, c_f, c_d, w_ef, w_ed, w_KT, w_CT, w_A, w_b):
    """Re-establish equilibrium accelerations after a contact event changed the forces.

    A located closure or separation is a discontinuity of the force law; the trapezoidal rule
    must restart from a = M⁻¹·(p − F) at the event instead of the pre-event acceleration.
    """
    n = u.size
    _internal_force(u, v, M, C, K, el_i, el_j, el_code, el_P, el_S, w_ef, w_ed, c_B, c_gap,
                    c_code, c_P, c_H, c_closed, c_f, c_d, Fn, w_KT, w_CT, False, n)
    for i in range(n):
        w_b[i] = -r[i] * ag_now - Fn[i]
        for j in range(n):
            w_A[i, j] = M[i, j]
    _solve_dense(w_A, w_b, n)
    for i in range(n):
        a[i] = w_b[i]


@njit(cache=True)
def _first_contact_step(v_close, h_start, h_contact, gap_tol):
    """Step after a closure: small (h_start) for a real impact, whose force law may rise
    steeply from δ = 0; the ordinary contact step for a grazing closure that would not even
    indent gap_tol in h_start (a body settling on the wall must not restart tiny every time)."""
    return h_start if v_close * h_start > gap_tol else h_contact


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
        t2 = th * th
        t3 = t2 * th
        p = (2 * t3 - 3 * t2 + 1) * d0 + (t3 - 2 * t2 + th) * h * dd0 \
            + (-2 * t3 + 3 * t2) * d1 + (t3 - t2) * h * dd1
        dp = (6 * t2 - 6 * th) * d0 + (3 * t2 - 4 * th + 1) * h * dd0 \
            + (-6 * t2 + 6 * th) * d1 + (3 * t2 - 2 * th) * h * dd1
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


@njit(cache=True)
def _check_limits(t, u, el_d, c_f, c_B, n_struct, limits, first):
    """Record the first time each limit is exceeded; 1 when a limit of row 0 is exceeded now,
    2 when one of row 1 (runaway bounds: the run cannot mean anything beyond them), else 0.

    Each row of ``limits`` holds, per element, a bound on |deformation| [in], then per contact
    a bound on the wall's displacement at the impact point [in], then per contact a bound on the
    contact force [kip] (math.inf: none); ``first`` the time each bound of row 0 was first
    exceeded (−1: not yet).
    """
    nel, ncon = el_d.size, c_f.size
    hit = 0
    for e in range(nel):
        x = abs(el_d[e])
        if x > limits[0, e]:
            hit = max(hit, 1)
            if first[e] < 0.0:
                first[e] = t
        if x > limits[1, e]:
            hit = 2
    for c in range(ncon):
        w = 0.0
        for i in range(n_struct, u.size):
            w -= c_B[c, i] * u[i]
        for k in range(2):
            j = nel + c + k * ncon
            x = abs(w) if k == 0 else c_f[c]
            if x > limits[0, j]:
                hit = max(hit, 1)
                if first[j] < 0.0:
                    first[j] = t
            if x > limits[1, j]:
                hit = 2
    return hit


@njit(cache=True)
def run_chunk(t_stop, state_t, h_state, u, v, a, Fn, pn_state,
              M, C, K, r, ag,
              el_i, el_j, el_code, el_P, el_S, el_f, el_d, el_W,
              c_B, c_gap, c_code, c_P, c_H, c_f, c_d, c_W, c_closed,
              scale_open, scale_contact, err_ref, fopt, iopt,
              energy, stats, limits, first_exceed,
              out_t, out_u, out_v, out_a, out_ag, out_ef, out_ed, out_cf, out_cd, out_cv,
              out_closed,
              w_u, w_v, w_a, w_F, w_KT, w_CT, w_A, w_b, w_ef, w_ed, w_cf, w_cd):
    """Advance from state_t[0] to min(t_stop, t_end); return a status code (see module)."""
    n = u.size
    beta, gamma, alpha = fopt[F_BETA], fopt[F_GAMMA], fopt[F_ALPHA]
    rtol, hmax, hmin, ntol = fopt[F_RTOL], fopt[F_HMAX], fopt[F_HMIN], fopt[F_NTOL]
    t_end, dt_rec, h_contact, gap_tol = fopt[F_TEND], fopt[F_DTREC], fopt[F_HCONTACT], fopt[F_GAPTOL]
    maxit, rec_every = iopt[I_MAXIT], iopt[I_RECORD_EVERY]
    limit_mode = iopt[I_LIMITS]
    # Lazy wall work: while no contact carries force, the wall DOFs (diagonal modal blocks) are
    # uncoupled from the building: dense elimination on the first n_coupled DOFs only, one
    # division per wall mode.
    n_coupled = iopt[I_N_COUPLED]
    # After a closure the force law is not smooth (Kelvin-Voigt jumps, Jankowski rises as
    # δ^(1/4)): restart small and let the controller grow the step (at most ×2 per step).
    h_start = 1e-3 * h_contact
    nel, ncon = el_code.size, c_code.size
    err_coef = abs(beta - 1.0 / 6.0)
    n_samples = ag.size
    t = state_t[0]
    h = h_state[0]
    since_record = 0
    t_goal = min(t_stop, t_end)

    stalls = 0
    shortened = False
    landing = -1  # the contact whose located separation the shortened step lands on
    while t < t_goal * (1.0 - 1e-15) and t_goal - t > 1e-14:
        stalls += 1
        if stalls > 100000:
            # no step accepted after 100000 attempts: report instead of spinning
            state_t[0] = t
            h_state[0] = h
            return STEP_TOO_SMALL
        if stats[S_NOUT] >= out_t.size:
            state_t[0] = t
            h_state[0] = h
            return BUFFER_FULL
        # --- step size: never cross a record sample, never pass the goal
        k_next = int(np.floor(t / dt_rec + 1e-9)) + 1
        hh = min(h, hmax, t_goal - t)
        if k_next <= n_samples - 1:
            t_sample = k_next * dt_rec
            if t_sample - t < hh:
                hh = t_sample - t
        t1 = t + hh
        # land exactly on the goal or a sample when within round-off of it
        # (not after an event shortening, which the snap would undo)
        if not shortened and t_goal - t1 < 1e-9 * hh:
            t1 = t_goal
        elif not shortened and k_next <= n_samples - 1 and abs(t1 - k_next * dt_rec) < 1e-9 * hh:
            t1 = k_next * dt_rec
        hh = t1 - t

        any_closed = False
        for c in range(ncon):
            if c_closed[c]:
                any_closed = True
        # --- Newton on the Newmark/HHT step, in the acceleration a₁ (the displacement form
        # loses digits to cancellation in (u₁ − u₀ − h·v₀)/(βh²) when steps are tiny)
        bh2 = beta * hh * hh
        gh = gamma * hh
        ag1 = ground_accel(ag, dt_rec, t1)
        ag0 = pn_state[0]
        for i in range(n):
            w_a[i] = a[i]
        converged = False
        evaluated = False
        it = 0
        nd = n
        while it < maxit:
            it += 1
            amax = 0.0
            for i in range(n):
                w_u[i] = u[i] + hh * v[i] + hh * hh * (0.5 - beta) * a[i] + bh2 * w_a[i]
                w_v[i] = v[i] + hh * (1.0 - gamma) * a[i] + gh * w_a[i]
                if abs(w_a[i]) > amax:
                    amax = abs(w_a[i])
            # lazy wall work: a dense block only over the building while no contact can act
            nd = n
            if n_coupled < n and not any_closed:
                nd = n_coupled
                for c in range(ncon):
                    d = -c_gap[c]
                    for i in range(n):
                        d += c_B[c, i] * w_u[i]
                    if d > 0.0:
                        nd = n
            _internal_force(w_u, w_v, M, C, K, el_i, el_j, el_code, el_P, el_S, w_ef, w_ed,
                            c_B, c_gap, c_code, c_P, c_H, c_closed, w_cf, w_cd, w_F, w_KT, w_CT,
                            True, nd)
            for i in range(n):
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
            if it > 1:
                # after a Newton update, a residual whose correction (estimated from the
                # diagonal of the iteration matrix, with a margin of 1e4 so that the state is
                # as converged as after one more update) is below the tolerance means
                # convergence: the forces just evaluated are those of the converged state, so
                # neither another solve nor a final evaluation is needed. In a step where every
                # spring stays on its branch the update was exact (the residual is round-off),
                # which is most steps; this saves a third of the work.
                small = True
                for i in range(n):
                    if w_A[i, i] <= 0.0:  # (a softening tangent: no estimate, solve instead)
                        small = False
                        break
                    est = 1e4 * abs(w_b[i]) / w_A[i, i]
                    if bh2 * est / scale_contact[i] >= ntol or est >= ntol * 1e2 * (amax + 1.0):
                        small = False
                        break
                if small:
                    converged = True
                    evaluated = True
                    break
            if not _solve_dense(w_A, w_b, nd):
                break
            for i in range(nd, n):
                w_b[i] /= w_A[i, i]
            du = 0.0
            da = 0.0
            finite = True
            for i in range(n):
                w_a[i] += w_b[i]
                q = bh2 * abs(w_b[i]) / scale_contact[i]
                if q > du:
                    du = q
                if abs(w_b[i]) > da:
                    da = abs(w_b[i])
                if not np.isfinite(w_a[i]):
                    finite = False
            if not finite:
                break
            # converged: the displacement correction is below ntol·scale and the acceleration
            # correction below ntol relative to the accelerations (or 1 in/s² absolute)
            if du < ntol and da < ntol * 1e2 * (amax + 1.0):
                converged = True
                break
        stats[S_NEWTON] += it
        if converged and not evaluated:
            # final kinematics and forces at the converged acceleration
            for i in range(n):
                w_u[i] = u[i] + hh * v[i] + hh * hh * (0.5 - beta) * a[i] + bh2 * w_a[i]
                w_v[i] = v[i] + hh * (1.0 - gamma) * a[i] + gh * w_a[i]
            _internal_force(w_u, w_v, M, C, K, el_i, el_j, el_code, el_P, el_S, w_ef, w_ed,
                            c_B, c_gap, c_code, c_P, c_H, c_closed, w_cf, w_cd, w_F, w_KT, w_CT,
                            False, nd)
        if not converged:
            stats[S_REJECT_NEWTON] += 1
            # A gap closing inside the step can defeat Newton when the law jumps at δ = 0⁺
            # (Kelvin-Voigt): land just before the closure, or start the episode right here.
            started = False
            v_close = 0.0
            h_cross = hh
            for c in range(ncon):
                if not c_closed[c]:
                    dd0 = 0.0
                    for i in range(n):
                        dd0 += c_B[c, i] * v[i]
                    if dd0 <= 0.0 or c_d[c] + dd0 * hh <= 0.0:
                        continue
                    # the gap closes within this step (straight-line estimate)
                    if -c_d[c] / dd0 >= hmin and c_d[c] < -gap_tol:
                        # aim short of the crossing so that the step converges and progresses
                        h_cross = min(h_cross, 0.9 * (-c_d[c] / dd0))
                        continue
                    c_closed[c] = 1
                    contact_closure(c_H[c], dd0)
                    if stats[S_NOUT] > 0 and out_t[stats[S_NOUT] - 1] == t:
                        out_closed[stats[S_NOUT] - 1, c] = 1
                    stats[S_EVENTS] += 1
                    started = True
                    v_close = max(v_close, dd0)
            if not started and h_cross < 0.999 * hh:
                h = h_cross
                continue
            if started:
                _restart(u, v, a, Fn, pn_state[0], M, C, K, r, el_i, el_j, el_code, el_P, el_S, c_B,
                         c_gap, c_code, c_P, c_H, c_closed, c_f, c_d, w_ef, w_ed, w_KT, w_CT,
                         w_A, w_b)
                h = min(hh, _first_contact_step(v_close, h_start, h_contact, gap_tol))
                continue
            h = hh * 0.25
            if h < hmin:
                state_t[0] = t
                h_state[0] = h
                stats[S_FAIL_INFO] = -1
                return NEWTON_FAILED
            continue

        # --- local error
        err = 0.0
        for i in range(n):
            sc = scale_contact[i] if any_closed else scale_open[i]
            # measured in the DOF's own coordinate: a story's drift against its floor below
            da = w_a[i] - a[i]
            j = err_ref[i]
            if j >= 0:
                da -= w_a[j] - a[j]
            q = hh * hh * err_coef * abs(da) / (rtol * sc)
            if q > err:
                err = q
        if err > 1.0 and hh > hmin:
            stats[S_REJECT_ERR] += 1
            h = hh * max(0.2, 0.9 * err ** (-1.0 / 3.0))
            if h < hmin:
                h = hmin
            continue

        # --- contact events inside the step
        theta = 2.0
        c_min = -1
        event_now = -1
        for c in range(ncon):
            d0, d1 = c_d[c], w_cd[c]
            dd0 = 0.0
            dd1 = 0.0
            for i in range(n):
                dd0 += c_B[c, i] * v[i]
                dd1 += c_B[c, i] * w_v[i]
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
        if event_now >= 0:
            # closure at the current (committed) state: start the episode, redo the step small
            dd0 = 0.0
            for i in range(n):
                dd0 += c_B[event_now, i] * v[i]
            c_closed[event_now] = 1
            contact_closure(c_H[event_now], max(dd0, 0.0))
            if stats[S_NOUT] > 0 and out_t[stats[S_NOUT] - 1] == t:
                out_closed[stats[S_NOUT] - 1, event_now] = 1
            stats[S_EVENTS] += 1
            _restart(u, v, a, Fn, pn_state[0], M, C, K, r, el_i, el_j, el_code, el_P, el_S, c_B,
                     c_gap, c_code, c_P, c_H, c_closed, c_f, c_d, w_ef, w_ed, w_KT, w_CT, w_A,
                     w_b)
            h = min(hh, _first_contact_step(dd0, h_start, h_contact, gap_tol))
            continue
        if theta <= 1.0:
            # shorten by more than the time round-off, or the same step would repeat forever
            h_new = min(hh * theta, hh - 64.0 * 2.3e-16 * abs(t1))
            if h_new >= hmin:
                stats[S_REJECT_ERR] += 1
                h = h_new
                shortened = True
                landing = c_min if c_closed[c_min] else -1
                continue
            if h_new < hmin:
                # the crossing is closer than the smallest step: the event happens at the
                # committed state (the last recorded sample); declare it there and redo the step
                dd0 = 0.0
                for i in range(n):
                    dd0 += c_B[c_min, i] * v[i]
                if c_closed[c_min]:
                    c_closed[c_min] = 0
                else:
                    c_closed[c_min] = 1
                    contact_closure(c_H[c_min], max(dd0, 0.0))
                    h = min(hh, _first_contact_step(dd0, h_start, h_contact, gap_tol))
                if stats[S_NOUT] > 0 and out_t[stats[S_NOUT] - 1] == t:
                    out_closed[stats[S_NOUT] - 1, c_min] = c_closed[c_min]
                stats[S_EVENTS] += 1
                _restart(u, v, a, Fn, pn_state[0], M, C, K, r, el_i, el_j, el_code, el_P, el_S, c_B,
                         c_gap, c_code, c_P, c_H, c_closed, c_f, c_d, w_ef, w_ed, w_KT, w_CT, w_A,
                         w_b)
                continue

        # --- accept: energies, commits, contact episode changes, output
        for i in range(n):
            du_i = w_u[i] - u[i]
            energy[E_INPUT] += 0.5 * (-r[i] * ag0 - r[i] * ag1) * du_i
            cv0 = 0.0
            cv1 = 0.0
            for j in range(n):
                cv0 += C[i, j] * v[j]
                cv1 += C[i, j] * w_v[j]
            energy[E_VISCOUS] += 0.5 * (cv0 + cv1) * du_i
        for e in range(nel):
            el_W[e] += 0.5 * (el_f[e] + w_ef[e]) * (w_ed[e] - el_d[e])
            i, j = el_i[e], el_j[e]
            dv = w_v[i] - (w_v[j] if j >= 0 else 0.0)
            material_commit(el_code[e], el_P[e], el_S[e], w_ed[e], dv)
            el_f[e] = w_ef[e]
            el_d[e] = w_ed[e]
        toggled = False
        v_close = 0.0
        for c in range(ncon):
            c_W[c] += 0.5 * (c_f[c] + w_cf[c]) * (w_cd[c] - c_d[c])
            step_commit(c_code[c], c_P[c], c_H[c], w_cd[c])
            c_f[c] = w_cf[c]
            c_d[c] = w_cd[c]
            dd1 = 0.0
            for i in range(n):
                dd1 += c_B[c, i] * w_v[i]
            if not c_closed[c] and w_cd[c] >= -gap_tol and w_cd[c] <= 0.0 and dd1 > 0.0:
                c_closed[c] = 1
                contact_closure(c_H[c], dd1)
                v_close = max(v_close, dd1)
                toggled = True
                stats[S_EVENTS] += 1
            elif c_closed[c] and landing == c and w_cd[c] <= gap_tol and dd1 < 0.0:
                # separation only at the located crossing (the step was shortened onto it; a
                # closed contact whose trial step ends below −gap_tol never gets here, the event
                # search shortens the step or opens it at the committed state). A contact
                # resting within ±gap_tol of δ = 0 stays closed (it carries no force there)
                # instead of opening and closing at every step.
                c_closed[c] = 0
                toggled = True
                stats[S_EVENTS] += 1
        for i in range(n):
            u[i] = w_u[i]
            v[i] = w_v[i]
            a[i] = w_a[i]
            Fn[i] = w_F[i]
        pn_state[0] = ag1
        t = t1
        stalls = 0
        shortened = False
        landing = -1
        if toggled:
            _restart(u, v, a, Fn, pn_state[0], M, C, K, r, el_i, el_j, el_code, el_P, el_S, c_B,
                     c_gap, c_code, c_P, c_H, c_closed, c_f, c_d, w_ef, w_ed, w_KT, w_CT, w_A,
                     w_b)
        stats[S_STEPS] += 1
        # next step size
        grow = 2.0 if err < 1e-12 else min(2.0, max(0.2, 0.9 * err ** (-1.0 / 3.0)))
        h = hh * grow
        now_closed = False
        for c in range(ncon):
            if c_closed[c]:
                now_closed = True
        if toggled and now_closed:
            h = min(h, _first_contact_step(v_close, h_start, h_contact, gap_tol))
        # output
        since_record += 1
        if since_record >= rec_every or now_closed or any_closed or toggled or t >= t_goal:
            since_record = 0
            k = stats[S_NOUT]
            out_t[k] = t
            out_ag[k] = ag1
            # a channel whose buffer has no columns was not requested: nothing is written
            for i in range(out_u.shape[1]):
                out_u[k, i] = u[i]
            for i in range(out_v.shape[1]):
                out_v[k, i] = v[i]
            for i in range(out_a.shape[1]):
                out_a[k, i] = a[i]
            for e in range(out_ef.shape[1]):
                out_ef[k, e] = el_f[e]
                out_ed[k, e] = el_d[e]
            for c in range(ncon):
                dd1 = 0.0
                for i in range(n):
                    dd1 += c_B[c, i] * v[i]
                # the law's force at the recorded state; the Hertz laws' step force differs
                # from it by the discrete gradient's O(Δδ²) trapezoidal defect
                out_cf[k, c] = c_f[c]
                if c_closed[c]:
                    out_cf[k, c] = recorded_force(c_code[c], c_P[c], c_H[c], c_d[c], dd1, c_f[c])
                out_cd[k, c] = c_d[c]
                out_cv[k, c] = dd1
                out_closed[k, c] = c_closed[c]
            stats[S_NOUT] = k + 1
        if limit_mode != LIMITS_OFF:
            hit = _check_limits(t, u, el_d, c_f, c_B, iopt[I_N_STRUCT], limits, first_exceed)
            if hit == 2 or (hit == 1 and limit_mode == LIMITS_STOP):
                state_t[0] = t
                h_state[0] = h
                return LIMIT_REACHED
    state_t[0] = t
    h_state[0] = h
    return DONE if t >= t_end * (1.0 - 1e-15) or t_end - t <= 1e-14 else STOPPED
