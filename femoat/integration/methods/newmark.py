"""Newmark/HHT-α: the implicit step solved by Newton, its local error, and its step sizes.

HHT-α (α in [−1/3, 0]; α = 0 is Newmark) balances
M·a₁ + (1+α)·F(u₁, v₁) − α·F(u₀, v₀) = (1+α)·p₁ − α·p₀ with Newmark's kinematics.

Step control: the Zienkiewicz-Xie local error h²·|β − 1/6|·|Δa| per DOF, measured in the DOF's
own coordinate (a floor by its story's drift, Δa_i − Δa_ref(i)) and scaled by rtol·scale_i (the
story's yield drift, the gap; a separate, tighter scale vector while any contact is closed),
and while all gaps are open each building DOF's acceleration error (K_T·e)_i/m_i against its
own scale (see :func:`femoat.integration.solve.error_scales`). In the contact phase of a run
whose open phase is explicit, the DOFs the contacts move are measured against the smallest
episode under way instead (:func:`episode_indentation`, :func:`femoat.integration.solve.
episode_scaling`): a small impact's force is held as closely as a large one's.

The method's interface (:mod:`femoat.integration.methods`): :func:`step` (the trial step: is
it solved, and its scaled error), :func:`retry` (the step to try after one that could not be
solved), and the controller's constants ``SAFETY``, ``SHRINK_MIN``, ``GROW_MAX``,
``ERROR_EXPONENT``. This is also the method of every contact phase.
"""

import numpy as np

from femoat.compilation.jit import njit
from femoat.integration.codes import S_NEWTON, S_REJECT_NEWTON
from femoat.integration.events import H_START, first_contact_step, open_episode, restart
from femoat.integration.forces import (
    _internal_force,
    _solve_dense,
    contact_rate,
    ground_load,
    trial_outputs,
)
from femoat.integration.recording.recorder import mark_last_sample, sample_before_event
from femoat.integration.recording.episodes import EP_MAX_INDENT, EP_PHASE, OPEN
from femoat.structure.materials.kernels import stamp_duration

NAME = "newmark"
"""The method's name (``Integrator(method=...)``)."""
EXPLICIT = False
"""Newton iterates on the step's end: no turning-point landing, no cruising step."""
QUINTIC_DENSE = False
"""Its accelerations are linear inside a step: the peaks take them at the samples."""
DEFAULT_RTOL = 1e-5
"""Every peak within 1e-3 of a converged run (``benchmarks/peak_accuracy.py`` measures it)."""
SAFETY = 0.9
"""Fraction of the step the error estimate allows that the controller takes."""


SHRINK_MIN = 0.2
"""Smallest factor a step is multiplied by (after a rejection or a rough step)."""


GROW_MAX = 2.0
"""Largest factor a step grows by after an accepted one."""


ERROR_EXPONENT = -1.0 / 3.0
"""h ∝ err^(−1/3): the Zienkiewicz-Xie estimate is O(h³)."""


@njit(cache=True, inline="always")
def step_factor(err):
    """Factor of the next step from a local error ``err`` (1 = at the tolerance)."""
    return max(SHRINK_MIN, SAFETY * err ** ERROR_EXPONENT)


@njit(cache=True, inline="always")
def episode_indentation(any_closed, state, work):
    """The size of the smallest contact episode under way [in]: over the closed contacts, the
    largest of the episode's indentation so far and the trial step's end indentation (inf when
    none is closed). A small impact's force is then controlled on its own scale, not on δ_me's
    (:func:`femoat.integration.solve.episode_scaling`)."""
    d_ep = np.inf
    if not any_closed:
        return d_ep
    for c in range(state.c_closed.size):
        if state.c_closed[c]:
            d = work.cd[c]
            if state.ep[c, EP_PHASE] == OPEN and state.ep[c, EP_MAX_INDENT] > d:
                d = state.ep[c, EP_MAX_INDENT]
            if d < d_ep:
                d_ep = d
    return d_ep


@njit(cache=True, inline="always")
def local_error(hh, any_closed, model, state, settings, work):
    """The largest scaled Zienkiewicz-Xie local error h²·|β − 1/6|·|Δa|/(rtol·scale) of the
    step (1 = at the tolerance), each DOF measured in its own coordinate: a story's drift
    against its floor below (``err_ref``); while all gaps are open also each building DOF's
    acceleration error (K_T·e)_i/m_i against rtol·``scale_accel``."""
    err_coef = abs(settings.beta - 1.0 / 6.0)
    rtol = settings.rtol
    scale = settings.scale_contact if any_closed else settings.scale_open
    err_ref = settings.err_ref
    a, w_a = state.a, work.a
    d_ep = episode_indentation(any_closed, state, work)
    err = 0.0
    for i in range(a.size):
        sc = scale[i]
        if any_closed and settings.episode_dofs[i]:
            sc = min(sc, max(d_ep, settings.episode_floor * sc)) * settings.episode_tighten
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
        n_struct = settings.n_struct
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
        p1 = ground_load(r, i, ag1)
        p0 = ground_load(r, i, ag0)
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
    beta, gamma, alpha = settings.beta, settings.gamma, settings.alpha
    ntol, maxit, n_coupled = settings.newton_tol, settings.max_newton, settings.n_coupled
    scale = settings.scale_contact
    bh2 = beta * hh * hh
    gh = gamma * hh
    ag0 = state.ag_now
    for i in range(state.a.size):
        work.a[i] = state.a[i]
    stamp_duration(state.el_S, hh)  # (read by a material whose return depends on it)
    converged = False
    evaluated = False
    it = 0
    nd = work.u.size
    while it < maxit:
        it += 1
        amax = _trial_kinematics(hh, bh2, gh, beta, gamma, state, work)
        nd = _dense_size(n_coupled, any_closed, model, work)
        _internal_force(work.u, work.v, model, state, work, trial_outputs(work), True, nd,
                        state.u, state.v, hh)
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
        _internal_force(work.u, work.v, model, state, work, trial_outputs(work), False, nd,
                        state.u, state.v, hh)
    return converged


@njit(cache=True, inline="always")
def retry_after_failure(t, hh, model, state, settings, work, rec):
    """A step Newton could not solve: (next step, False), or (h, True) when it cannot shrink.

    A gap closing inside the step can defeat Newton when the law jumps at δ = 0⁺ (Kelvin-Voigt):
    land just before the closure, or start the episode right here.
    """
    hmin, gap_tol, h_contact = settings.h_min, settings.gap_tol, settings.h_contact
    c_B, c_d, c_closed = model.c_B, state.c_d, state.c_closed
    state.stats[S_REJECT_NEWTON] += 1
    started = False
    v_close = 0.0
    h_cross = hh
    for c in range(c_d.size):
        if not c_closed[c]:
            dd0 = contact_rate(c_B, c, state.v)
            if dd0 <= 0.0 or c_d[c] + dd0 * hh <= 0.0:
                continue
            # the gap closes within this step (straight-line estimate)
            if -c_d[c] / dd0 >= hmin and c_d[c] < -gap_tol:
                # aim short of the crossing so that the step converges and progresses
                h_cross = min(h_cross, 0.9 * (-c_d[c] / dd0))
                continue
            sample_before_event(t, model, state, settings, rec)
            open_episode(c, dd0, state)
            mark_last_sample(c, t, model, state, rec)
            started = True
            v_close = max(v_close, dd0)
    if not started and h_cross < 0.999 * hh:
        return h_cross, False
    if started:
        restart(model, state, work)
        return min(hh, first_contact_step(v_close, H_START * h_contact, h_contact, gap_tol)), \
            False
    h = hh * 0.25
    return h, h < hmin



# ---- the method's interface (femoat.integration.methods) ------------------------------------


@njit(cache=True, inline="always")
def step(hh, ag1, any_closed, model, state, settings, work):
    """(Newton converged, the step's scaled local error; inf when it did not converge)."""
    if not newton_step(hh, ag1, any_closed, model, state, settings, work):
        return False, np.inf
    return True, local_error(hh, any_closed, model, state, settings, work)


@njit(cache=True, inline="always")
def retry(t, hh, h, model, state, settings, work, rec):
    """After a step Newton could not solve: :func:`retry_after_failure`."""
    return retry_after_failure(t, hh, model, state, settings, work, rec)


@njit(cache=True, inline="always")
def next_step(hh, err, h_min):
    """The step after an accepted one of length ``hh`` and scaled error ``err``."""
    return hh * (GROW_MAX if err < 1e-12 else min(GROW_MAX, step_factor(err)))
