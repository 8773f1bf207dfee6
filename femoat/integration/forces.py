"""Forces of the model at a state: the ground record, F = C·v + K·u + element and contact
forces with their tangents, and the small dense solver. Shared by every integration method
(:mod:`femoat.integration.methods`), the events and the recorder.

Units: kip, in, s.
"""

import numpy as np

from femoat.compilation.jit import njit
from femoat.contact.kernels import step_force
from femoat.structure.materials.kernels import material_trial


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



@njit(cache=True, inline="always")
def _internal_force(u, v, model, el_S, c_H, c_closed, el_f, el_d, c_f, c_d, F, KT, CT,
                    want_tangent, nd):
    """F = C·v + K·u + element and contact forces at (u, v); tangents KT, CT if asked.

    Element states ``el_S`` and contact histories ``c_H`` are the committed ones (read only); the
    element forces and deformations, contact forces and indentations are written to ``el_f``,
    ``el_d``, ``c_f``, ``c_d``. Rows and columns from ``nd`` on are treated as diagonal
    (uncoupled wall modes while no contact carries force); ``nd = n`` is the general dense case.
    Contacts act only while their episode is open (between a located closure and the located
    separation); a Kelvin-Voigt contact then acts at δ = 0⁺ too (its dashpot force c·δ̇ jumps on
    at closure), so that the step after a located closure starts from the right force.
    """
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
def internal_force(model, state, work):
    """The state's forces at its own (u, v), without tangents (the initial equilibrium): element
    and contact forces into ``state``, F = C·v + K·u + ... into ``state.F``."""
    _internal_force(state.u, state.v, model, state.el_S, state.c_H, state.c_closed, state.el_f,
                    state.el_d, state.c_f, state.c_d, state.F, work.KT, work.CT, False,
                    state.u.size)
