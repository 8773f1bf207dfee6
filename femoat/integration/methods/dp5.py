"""The open phase's step: Dormand-Prince 5(4) for the building, the walls exactly.

While every gap is open the building (base mat and floors) is not stiff: its fastest mode is a
story mode of a few hundred rad/s at most, against record samples a few ms apart. An explicit
Runge-Kutta pair of order five then takes about one step per sample where the second-order
Newmark step needs several. The walls are different: a wall's modal DOF is a heavily damped
oscillator (the paper's SDOF walls decay at c/m ≈ 4,000-5,000 1/s), far too stiff for an explicit
step; but while every gap is open it is a linear oscillator driven by the ground alone,
uncoupled from the building, so it is advanced exactly (the matrix exponential of its
first-order form, with the ground acceleration linear inside the step).

The step (:func:`explicit_step`), for the building DOFs i < nb (``settings.n_explicit``):

* stages k_s = (v_s, a_s) of y = (u, v), a_s = M⁻¹·(−r·a_g(t + c_s·h) − F(u_s, v_s)) with every
  element evaluated from its state committed at the step's start (no branch change inside a
  step: a step that crosses a kink is shortened onto it by the driver, as with Newmark);
* the fifth-order solution (Dormand & Prince 1980; local extrapolation), first same as last:
  the seventh stage is the acceleration at the step's end, the next step's first;
* the error of the embedded fourth-order solution, measured as Newmark's is: each DOF's
  displacement error in its own coordinate (a floor against the floor below) against
  rtol·scale, and each DOF's acceleration error M⁻¹·(K_T·e_u + C_T·e_v) against rtol·scale_accel;
* input and viscous energies by the method's own quadrature (the fifth-order weights on the
  stages' powers); element work by the driver's trapezoidal rule, exact on a branch linear in
  the deformation (every material but the velocity-dependent friction, whose work is then
  second order in the step). The energy balance then measures the method's truncation, not
  round-off as Newmark's trapezoidal balance does.

The ground acceleration is linear inside a step because steps end on record samples (the
controller's :func:`~femoat.integration.controller._step_end`).

The method's interface (:mod:`femoat.integration.methods`): :func:`step`, :func:`retry`,
:func:`next_step` and the controller's constants.

Units: kip, in, s.
"""

import numpy as np

from femoat.compilation.jit import njit
from femoat.integration.forces import _internal_force, ground_load, trial_outputs
from femoat.integration.codes import E_INPUT, E_VISCOUS, S_REJECT_ERR

# ---- the Dormand-Prince 5(4) tableau -------------------------------------------------------

DP_C = np.array([0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0])
DP_A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0],
    [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0],
    [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
])
"""Stage coefficients a_sj (row s, j < s); the last row is the fifth-order weights b."""
DP_E = np.array([71.0 / 57600.0, 0.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0,
                 22.0 / 525.0, -1.0 / 40.0])
"""b − b̂: the fifth- minus the embedded fourth-order weights (the error estimate)."""
N_STAGES = 7

NAME = "dp5"
"""The method's name (``Integrator(method=...)``)."""
EXPLICIT = True
"""Every stage is evaluated from the committed state: the driver lands on the turning points of
yielding elements, looks inside a step for a gap that closes and reopens in it, and keeps a
cruising step across the steps cut short."""
QUINTIC_DENSE = True
"""Its dense output is fifth order: the running peaks read the acceleration crests inside a
step of the open phase from the quintic Hermite interpolant."""
DEFAULT_RTOL = 1e-5
"""Every peak within 1e-3 of a converged run (``benchmarks/peak_accuracy.py`` measures it)."""

ERROR_EXPONENT = -1.0 / 5.0
"""h ∝ err^(−1/5): the embedded estimate is O(h⁵)."""
SAFETY = 0.9
SHRINK_MIN = 0.2
GROW_MAX = 5.0
"""Largest factor a step grows by after an accepted one (steps never pass a record sample)."""


@njit(cache=True, inline="always")
def step_factor(err):
    """Factor of the next step from the scaled error ``err`` (1 = at the tolerance)."""
    if err < 1e-30:
        return GROW_MAX
    return min(GROW_MAX, max(SHRINK_MIN, SAFETY * err ** ERROR_EXPONENT))


# ---- the walls: exact linear propagation ------------------------------------------------------


@njit(cache=True)
def _expm(A, out, T, S):
    """out = exp(A) of a small square matrix: scaling and squaring of a Taylor series (scaled
    to a norm ≤ 1/4, 14 terms: truncation below 1e-16); T and S are scratch of A's shape."""
    n = A.shape[0]
    norm = 0.0
    for i in range(n):
        row = 0.0
        for j in range(n):
            row += abs(A[i, j])
        norm = max(norm, row)
    squarings = 0
    while norm > 0.25 and squarings < 60:
        norm *= 0.5
        squarings += 1
    scale = 0.5 ** squarings
    for i in range(n):
        for j in range(n):
            T[i, j] = 1.0 if i == j else 0.0
            out[i, j] = T[i, j]
    for k in range(1, 15):
        for i in range(n):
            for j in range(n):
                acc = 0.0
                for m in range(n):
                    acc += T[i, m] * A[m, j]
                S[i, j] = acc * scale / k
        for i in range(n):
            for j in range(n):
                T[i, j] = S[i, j]
                out[i, j] += S[i, j]
    for _ in range(squarings):
        for i in range(n):
            for j in range(n):
                acc = 0.0
                for m in range(n):
                    acc += out[i, m] * out[m, j]
                S[i, j] = acc
        for i in range(n):
            for j in range(n):
                out[i, j] = S[i, j]


@njit(cache=True)
def wall_propagator(m, c, k, h, row, scratch):
    """exp(A·h) of a wall DOF's free vibration, A = [[0, 1], [−k/m, −c/m]] (mass m
    [kip·s²/in], damping c [kip·s/in], stiffness k [kip/in]), into ``row`` (4 values, row
    by row); ``scratch`` holds four 2×2 matrices."""
    A, E, T, S = scratch[0], scratch[1], scratch[2], scratch[3]
    A[0, 0] = 0.0
    A[0, 1] = h
    A[1, 0] = -k / m * h
    A[1, 1] = -c / m * h
    _expm(A, E, T, S)
    row[0], row[1], row[2], row[3] = E[0, 0], E[0, 1], E[1, 0], E[1, 1]


@njit(cache=True, inline="always")
def walls_exact(hh, ag0, ag1, nb, model, state, work):
    """Advance the wall DOFs i ≥ nb exactly over the step (into ``work.u``, ``work.v``,
    ``work.a``, ``work.F``) and add their input and viscous energy to ``work.de``.

    m·ü + c·u̇ + k·u = p₀ + ṗ·τ (the ground load −r·a_g, linear in the step) has the particular
    solution u_p = α + β·τ (β = ṗ/k, α = (p₀ − c·β)/k); the rest w = u − u_p vibrates freely,
    w(h) = exp(A·h)·w(0), and ∫w dτ = −[m·Δẇ + c·Δw]/k (the equation integrated once)."""
    M, C, K, r = model.M, model.C, model.K, model.r
    u, v = state.u, state.v
    for i in range(nb, u.size):
        row = work.wexp[i]
        m, c, k = M[i, i], C[i, i], K[i, i]
        # steps between record samples differ in their last bits (sample times are products
        # k·dt): reuse the propagator of a step within 1e-9 of this one (the wall then moves
        # for a time off by at most 1e-9·h, an error of |v|·1e-9·h, far below gap_tol)
        if abs(work.wexp_h[i] - hh) > 1e-9 * hh:
            wall_propagator(m, c, k, hh, row, work.wscratch)
            work.wexp_h[i] = hh
        p0 = ground_load(r, i, ag0)
        p1 = ground_load(r, i, ag1)
        dp = (p1 - p0) / hh
        beta = dp / k
        alpha = (p0 - c * beta) / k
        w0 = u[i] - alpha
        wd0 = v[i] - beta
        w1 = row[0] * w0 + row[1] * wd0
        wd1 = row[2] * w0 + row[3] * wd0
        u1 = w1 + alpha + beta * hh
        v1 = wd1 + beta
        iu = alpha * hh + 0.5 * beta * hh * hh - (m * (wd1 - wd0) + c * (w1 - w0)) / k
        work.u[i] = u1
        work.v[i] = v1
        f1 = c * v1 + k * u1
        work.F[i] = f1
        work.a[i] = (p1 - f1) / m
        # ∫p·du = p₁u₁ − p₀u₀ − ṗ·∫u (p linear); what it put in and the wall does not keep in
        # kinetic and strain energy, its dashpot took
        w_in = p1 * u1 - p0 * u[i] - dp * iu
        stored = 0.5 * (m * (v1 * v1 - v[i] * v[i]) + k * (u1 * u1 - u[i] * u[i]))
        work.de[E_INPUT] += w_in
        work.de[E_VISCOUS] += w_in - stored


# ---- the building: Dormand-Prince 5(4) --------------------------------------------------------


@njit(cache=True, inline="always")
def stage_load(r, ag, nb, work):
    """A stage's load p − F of the building DOFs (ground ``ag`` [in/s²], forces ``work.F``) into
    ``work.b`` (free until the error estimate)."""
    for j in range(nb):
        work.b[j] = ground_load(r, j, ag) - work.F[j]


@njit(cache=True, inline="always")
def accel_row(i, nb, Minv, q):
    """(M⁻¹·q)_i [in/s²]; a term with M⁻¹_ij = 0 (x and y apart in plan) adds ±0 and is skipped
    (the same bits)."""
    acc = 0.0
    for j in range(nb):
        m = Minv[i, j]
        if m != 0.0:
            acc += m * q[j]
    return acc


@njit(cache=True, inline="always")
def _stages(A, C, hh, ag0, ag1, nb, model, state, work):
    """The seven stages of the pair with coefficients ``A`` (its last row the fifth-order
    weights) and stage times ``C`` (``work.kv``, ``work.ka``); after it ``work.u``, ``work.v``
    (i < nb) hold the fifth-order solution, ``work.ef``/``ed``, ``F`` and the tangents ``KT``,
    ``CT`` its forces. False when a stage is not finite."""
    Minv, r = model.Minv, model.r
    kv, ka = work.kv, work.ka
    u0, v0 = state.u, state.v
    n = u0.size
    for i in range(nb):
        kv[0, i] = v0[i]
        ka[0, i] = state.a[i]
    for i in range(nb, n):
        work.u[i] = u0[i]
        work.v[i] = v0[i]
    for s in range(1, N_STAGES):
        for i in range(nb):
            su = 0.0
            sv = 0.0
            for j in range(s):
                aij = A[s, j]
                su += aij * kv[j, i]
                sv += aij * ka[j, i]
            work.u[i] = u0[i] + hh * su
            work.v[i] = v0[i] + hh * sv
        _internal_force(work.u, work.v, model, state, work, trial_outputs(work),
                        s == N_STAGES - 1, nb, u0, v0, C[s] * hh)
        ag = work.ag_stage
        for k in range(ag.size):
            ag[k] = ag0[k] + C[s] * (ag1[k] - ag0[k])
        stage_load(r, ag, nb, work)
        for i in range(nb):
            acc = accel_row(i, nb, Minv, work.b)
            if not np.isfinite(acc):
                return False
            ka[s, i] = acc
            kv[s, i] = work.v[i]
    for i in range(nb):
        work.a[i] = ka[N_STAGES - 1, i]
    return True


@njit(cache=True, inline="always")
def stage_energy(B, CS, hh, ag0, ag1, nb, model, work):
    """Input and viscous energy of the building over the step by the quadrature of weights ``B``
    (stage times ``CS``) of the stages' powers (into ``work.de``). (Element work is the driver's
    trapezoidal rule: exact on a branch linear in the deformation, and a step never changes
    branch.)"""
    C, r = model.C, model.r
    kv = work.kv
    for s in range(B.size):
        b = B[s]
        if b == 0.0:
            continue
        ag = work.ag_stage
        for k in range(ag.size):
            ag[k] = ag0[k] + CS[s] * (ag1[k] - ag0[k])
        p_in = 0.0
        p_visc = 0.0
        for i in range(nb):
            p_in += ground_load(r, i, ag) * kv[s, i]
            cv = 0.0
            for j in range(nb):
                cv += C[i, j] * kv[s, j]
            p_visc += cv * kv[s, i]
        work.de[E_INPUT] += hh * b * p_in
        work.de[E_VISCOUS] += hh * b * p_visc


DP_B = DP_A[N_STAGES - 1, :N_STAGES - 1].copy()
"""The fifth-order weights of the stages before the last (whose weight is zero)."""
PAIR = (DP_A, DP_C, DP_B, DP_E)
"""The pair as :func:`explicit_step` reads it: (a_sj with the weights as the last row, c_s,
the weights b of the stages before the last, b − b̂ over every stage). Another seven-stage FSAL pair of order
5(4) is another such tuple on the same compiled step (:mod:`~femoat.integration.methods.tsit5`)."""


@njit(cache=True, inline="always")
def displacement_error(E, hh, nb, settings, work):
    """The embedded solution's displacement and velocity errors e_u = h·Σ E_s·kv_s,
    e_v = h·Σ E_s·ka_s (into ``work.eu``, ``work.ev``) and the largest scaled displacement
    error (each DOF in its own coordinate: a floor against the floor below)."""
    rtol = settings.rtol
    scale, err_ref = settings.scale_open, settings.err_ref
    kv, ka, eu, ev = work.kv, work.ka, work.eu, work.ev
    for i in range(nb):
        su = 0.0
        sv = 0.0
        for k in range(E.size):
            su += E[k] * kv[k, i]
            sv += E[k] * ka[k, i]
        eu[i] = hh * su
        ev[i] = hh * sv
    err = 0.0
    for i in range(nb):
        d = eu[i]
        j = err_ref[i]
        if j >= 0:
            d -= eu[j]
        q = abs(d) / (rtol * scale[i])
        if q > err:
            err = q
    return err


@njit(cache=True, inline="always")
def force_error(nb, work):
    """The force error K_T·e_u + C_T·e_v into ``work.b``."""
    KT, CT, eu, ev, df = work.KT, work.CT, work.eu, work.ev, work.b
    for j in range(nb):
        fj = 0.0
        for m in range(nb):
            fj += KT[j, m] * eu[m] + CT[j, m] * ev[m]
        df[j] = fj


@njit(cache=True, inline="always")
def acceleration_error(err, nb, model, settings, work):
    """max(``err``, the largest scaled acceleration error M⁻¹·``work.b``)."""
    rtol, s_acc = settings.rtol, settings.scale_accel
    Minv, df = model.Minv, work.b
    for i in range(nb):
        if not np.isfinite(s_acc[i]):
            continue
        da = 0.0
        for j in range(nb):
            da += Minv[i, j] * df[j]
        q = abs(da) / (rtol * s_acc[i])
        if q > err:
            err = q
    return err


@njit(cache=True, inline="always")
def _error(E, hh, nb, model, settings, work):
    """The scaled error of the embedded fourth-order solution (weights b − b̂ ``E``; 1 = at the
    tolerance): each DOF's displacement error and its acceleration error
    M⁻¹·(K_T·e_u + C_T·e_v)."""
    err = displacement_error(E, hh, nb, settings, work)
    force_error(nb, work)
    return acceleration_error(err, nb, model, settings, work)


@njit(cache=True, inline="always")
def explicit_step(pair, hh, ag1, model, state, settings, work):
    """The trial step of length ``hh`` (ground acceleration ``ag1`` [in/s²] at its end) of the
    explicit pair ``pair`` (:data:`PAIR`) while every gap is open: ``work`` holds the end state,
    its forces, the contacts' indentations and the step's energy increments (``de``). Returns
    the scaled error (inf: a stage was not finite, the step must shrink)."""
    A, C, B, E = pair
    nb = settings.n_explicit
    ag0 = state.ag_now
    work.de[E_INPUT] = 0.0
    work.de[E_VISCOUS] = 0.0
    if not _stages(A, C, hh, ag0, ag1, nb, model, state, work):
        return np.inf
    walls_exact(hh, ag0, ag1, nb, model, state, work)
    stage_energy(B, C, hh, ag0, ag1, nb, model, work)
    if not open_end(model, work):
        return np.inf
    return _error(E, hh, nb, model, settings, work)


@njit(cache=True, inline="always")
def open_end(model, work):
    """The contacts' indentations at the step's end (every gap open: no force); False when the
    end state is not finite."""
    c_B, c_gap = model.c_B, model.c_gap
    for c in range(c_gap.size):
        d = -c_gap[c]
        for i in range(work.u.size):
            d += c_B[c, i] * work.u[i]
        work.cd[c] = d
        work.cf[c] = 0.0
    for i in range(work.u.size):
        if not (np.isfinite(work.u[i]) and np.isfinite(work.v[i])):
            return False
    return True


# ---- the method's interface (femoat.integration.methods) ------------------------------------


@njit(cache=True, inline="always")
def step(hh, ag1, any_closed, model, state, settings, work):
    """(the step has a finite state, its scaled error): :func:`explicit_step` of this pair
    (only ever called while every gap is open)."""
    return pair_step(PAIR, hh, ag1, model, state, settings, work)


@njit(cache=True, inline="always")
def pair_step(pair, hh, ag1, model, state, settings, work):
    """``step`` of the explicit pair ``pair``: the loop's dispatcher calls this once, with the
    pair of the method it runs, so that one copy of the step serves every such pair."""
    err = explicit_step(pair, hh, ag1, model, state, settings, work)
    return np.isfinite(err), err


@njit(cache=True, inline="always")
def retry(t, hh, h, model, state, settings, work, rec):
    """After a step with no finite state: (the smaller step to try, False), or (``h``, True)
    when the step is already the smallest: the step asked (``h``) or taken (``hh``, which
    t + h − t rounds: at t ≈ 10 s a step asked at h_min comes out up to 1e-8 longer, which a
    test on ``hh`` alone never saw as the smallest, so a step that failed there was retried
    forever and the run stalled)."""
    if min(hh, h) <= settings.h_min:
        return h, True
    state.stats[S_REJECT_ERR] += 1
    return max(hh * SHRINK_MIN, settings.h_min), False


@njit(cache=True, inline="always")
def next_step(hh, err, h_min):
    """The step after an accepted one of length ``hh`` and scaled error ``err``."""
    return max(hh * step_factor(err), h_min)
