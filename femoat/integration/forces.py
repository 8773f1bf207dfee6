"""Forces of the model at a state: the ground record, F = C·v + K·u + element and contact
forces with their tangents, and the small dense solver. Shared by every integration method
(:mod:`femoat.integration.methods`), the events and the recorder.

Units: kip, in, s.
"""

from collections import namedtuple

import numpy as np

from femoat.compilation.jit import njit
from femoat.contact.kernels import step_force
from femoat.bearings.dispatch import bearing_plan_rate_force, bearing_plan_trial
from femoat.structure.materials.kernels import material_trial


@njit(cache=True)
def ground_accel(ag, dt_rec, t, out):
    """a_g(t) [in/s²] of each ground component (the columns of ``ag``, one row per sample)
    into ``out``: linear between samples, zero after the record."""
    x = t / dt_rec
    i = int(np.floor(x))
    last = ag.shape[0] - 1
    for k in range(out.size):
        if i < 0:
            out[k] = 0.0
        elif i >= last:
            out[k] = ag[last, k] if i == last and x - i < 1e-9 else 0.0
        else:
            w = x - i
            out[k] = (1.0 - w) * ag[i, k] + w * ag[i + 1, k]


@njit(cache=True, inline="always")
def ground_load(r, i, ag):
    """p_i = −Σ_k r_ik·a_g,k [kip]: DOF i's ground load under the components ``ag`` [in/s²]."""
    s = r[i, 0] * ag[0]
    for k in range(1, ag.size):
        s += r[i, k] * ag[k]
    return -s


@njit(cache=True, inline="always")
def contact_rate(c_B, c, v):
    """δ̇ [in/s] of contact ``c`` at velocities ``v``."""
    dd = 0.0
    for i in range(v.size):
        dd += c_B[c, i] * v[i]
    return dd


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



Outputs = namedtuple("Outputs", ["el_f", "el_d", "c_f", "c_d", "F", "b_f", "c_ft"])
"""Where :func:`_internal_force` writes: element forces and deformations, contact forces and
indentations, F, the bearings' forces (x, y), the walls' friction forces (a trial writes into the
work bundle's, :func:`trial_outputs`; an evaluation at the state itself into the state's)."""


@njit(cache=True, inline="always")
def trial_outputs(work):
    """:class:`Outputs` into the work bundle (a trial state)."""
    return Outputs(work.ef, work.ed, work.cf, work.cd, work.F, work.bf, work.cft)


@njit(cache=True, inline="always")
def _internal_force(u, v, model, state, work, out, want_tangent, nd, u0, v0, tau):
    """F = C·v + K·u + element, bearing and contact forces at (u, v); tangents ``work.KT``,
    ``work.CT`` if asked.

    Element states, bearing states and contact histories are the ``state``'s committed ones
    (read only, as its open episodes ``c_closed``); the forces go to ``out``
    (:class:`Outputs`); ``work.k22`` is (3, 2, 2) scratch. A plan bearing follows the path of
    the step from the committed state (``u0``, ``v0`` at its start, duration ``tau`` [s]; 0 at
    the committed state itself). Rows and columns from ``nd`` on are treated as diagonal
    (uncoupled wall modes while no contact carries force); ``nd = n`` is the general dense case.
    Contacts act only while their episode is open (between a located closure and the located
    separation); a Kelvin-Voigt contact then acts at δ = 0⁺ too (its dashpot force c·δ̇ jumps on
    at closure), so that the step after a located closure starts from the right force.
    """
    el_S, c_H, c_closed, b_S = state.el_S, state.c_H, state.c_closed, state.b_S
    el_f, el_d, c_f, c_d, F, b_f, c_ft = out
    KT, CT, k22 = work.KT, work.CT, work.k22
    C, K = model.C, model.K
    el_i, el_j, el_code, el_P = model.el_i, model.el_j, model.el_code, model.el_P
    c_B, c_gap, c_code, c_P = model.c_B, model.c_gap, model.c_code, model.c_P
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
    # the plan bearings first: the isolator is the first element of a 1D model (the same sums)
    if b_f.shape[0] > 0:
        _plan_bearings(u, v, model, b_S, b_f, F, KT, CT, k22, want_tangent, u0, v0, tau,
                       work.b_rate, work.bz)
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
        c_ft[c] = 0.0
        if not c_closed[c]:
            # no episode open: no force (a trial step that closes the gap is shortened to the
            # located closure; a gap that has just opened within gap_tol carries nothing)
            c_f[c] = 0.0
            continue
        f, kf, cf = step_force(c_code[c], c_P[c], c_H[c], d, dv)
        c_f[c] = f
        if model.c_mu[c] > 0.0 and f > 0.0:
            _wall_friction(c, f, kf, cf, u, v, model, c_ft, F, KT, CT, want_tangent)
        if f != 0.0 or kf != 0.0 or cf != 0.0:
            for i in range(n):
                if b[i] != 0.0:
                    F[i] += f * b[i]
                    if want_tangent:
                        for j in range(n):
                            if b[j] != 0.0:
                                KT[i, j] += kf * b[i] * b[j]
                                CT[i, j] += cf * b[i] * b[j]


@njit(cache=True, python=False)
def _plan_bearings(u, v, model, b_S, b_f, F, KT, CT, k22, want_tangent, u0, v0, tau, b_rate,
                   b_z):
    """Each plan bearing's force and tangents at (u, v) from its committed state, scattered into
    F, KT, CT (a function of its own: the kinds' kernels stay out of the callers' code). A
    bearing flagged in ``b_rate`` (a step of the coupled-friction method carries its friction
    state) takes its state from ``b_z`` (the rate form), every other one follows the step's
    path from its committed state."""
    for e in range(b_f.shape[0]):
        kb, cb = k22[0], k22[1]
        dofs = model.b_dofs[e]
        ix, iy = dofs[0], dofs[1]
        if b_rate[e] != 0:
            bearing_plan_rate_force(model.b_kind[e], model.b_P[e], b_S[e], u[ix], u[iy], v[ix],
                                    v[iy], b_z[e], b_f[e], kb, cb)
        else:
            bearing_plan_trial(model.b_kind[e], model.b_P[e], b_S[e], u0[ix], u0[iy], v0[ix],
                               v0[iy], u[ix], u[iy], v[ix], v[iy], tau, b_f[e], kb, cb)
        _scatter(dofs, b_f[e], kb, cb, F, KT, CT, want_tangent)


@njit(cache=True, inline="always")
def _scatter(dofs, f, k, c, F, KT, CT, want_tangent):
    """Bᵀf into F, BᵀkB and BᵀcB into KT and CT: a bearing's forces ``f`` (m,) and tangents ``k``,
    ``c`` (m, m) on its DOFs ``dofs`` (m,), the gather B the unit rows of those DOFs."""
    m = f.size
    for a in range(m):
        F[dofs[a]] += f[a]
    if want_tangent:
        for a in range(m):
            for b in range(m):
                KT[dofs[a], dofs[b]] += k[a, b]
        for a in range(m):
            for b in range(m):
                CT[dofs[a], dofs[b]] += c[a, b]


WALL_SLIP_SPEED = 0.1
"""[in/s] The wall friction's regularisation: f_t = μ·f_n·tanh(v_t / WALL_SLIP_SPEED), full
Coulomb friction μ·f_n once the base mat slides along the wall faster than a few times this."""


@njit(cache=True, inline="always")
def _wall_friction(c, f, kf, cf, u, v, model, c_ft, F, KT, CT, want_tangent):
    """Wall ``c``'s Coulomb friction during contact, regularised: f_t = μ·f·tanh(v_t/ε) along
    the wall's tangent row t (v_t = t·v the base mat's slip rate), resisting the slip; its
    tangents through the normal force f(δ, δ̇) (kf, cf) and the slip rate."""
    t_row, b = model.c_T[c], model.c_B[c]
    n = u.size
    vt = 0.0
    for i in range(n):
        vt += t_row[i] * v[i]
    mu = model.c_mu[c]
    th = np.tanh(vt / WALL_SLIP_SPEED)
    ft = mu * f * th
    c_ft[c] = ft
    for i in range(n):
        if t_row[i] != 0.0:
            F[i] += ft * t_row[i]
            if want_tangent:
                for j in range(n):
                    KT[i, j] += mu * th * kf * t_row[i] * b[j]
                    CT[i, j] += t_row[i] * (mu * th * cf * b[j]
                                            + mu * f * (1.0 - th * th) / WALL_SLIP_SPEED
                                            * t_row[j])


@njit(cache=True)
def internal_force(model, state, work):
    """The state's forces at its own (u, v), without tangents (the initial equilibrium): element
    and contact forces into ``state``, F = C·v + K·u + ... into ``state.F``."""
    out = Outputs(state.el_f, state.el_d, state.c_f, state.c_d, state.F, state.b_f, state.c_ft)
    _internal_force(state.u, state.v, model, state, work, out, False, state.u.size, state.u,
                    state.v, 0.0)
