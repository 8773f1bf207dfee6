"""Compiled contact-law kernels called from the time-stepping loops.

Conventions (PAPER.md §2): indentation ``d`` = δ [in] > 0 in contact; ``v`` = δ̇ [in/s] > 0 while
approaching. Forces are compressive-positive [kip]. Every kernel returns
``(f, df/dδ, df/dδ̇)`` evaluated from the *committed* history ``h`` (never modified here), so a
Newton iteration may call it any number of times; :func:`contact_commit` advances the history once
a step has converged.

Packed parameters ``p`` (see :meth:`femoat.contact.laws.ContactLaw.packed`):

====  ==========  ==========================================================
idx   name        meaning
====  ==========  ==========================================================
0     k_h         Hertz stiffness [kip/in^1.5]
1     k_eff       effective linear stiffness [kip/in]
2     c_eff       Kelvin-Voigt dashpot [kip·s/in]
3     xi_J        Jankowski damping ratio [-]
4     xi_h        Hertzdamp damping factor [-]
5     k1          Muthukumar first loading stiffness [kip/in]
6     k2          Muthukumar second loading stiffness [kip/in]
7     delta_y     Muthukumar yield indentation [in]
8     m_eff       effective mass [kip·s²/in]
9     tension     1.0 if the Kelvin-Voigt law may pull (tension), else 0.0
10    v0_min      smallest approach velocity used by Hertzdamp [in/s]
====  ==========  ==========================================================

History ``h``: ``h[0]`` approach velocity δ̇₀ captured at gap closure [in/s] (Hertzdamp);
``h[1]`` largest indentation reached so far δ_m [in] (Muthukumar); for the implicit time
stepping only (:func:`step_force`, :func:`step_commit`): ``h[2]`` the indentation δ_n at the last
committed step [in] and ``h[3]`` the elastic force f̃_n the step used there [kip].
"""

import numpy as np
from femoat.jit import njit

LINEAR, KELVIN_VOIGT, JANKOWSKI, HERTZDAMP, MUTHUKUMAR = 0, 1, 2, 3, 4
N_PARAMS = 11
N_HISTORY = 4

_KH, _KEFF, _CEFF, _XIJ, _XIH, _K1, _K2, _DY, _MEFF, _TENSION, _V0MIN = range(N_PARAMS)


@njit(cache=True)
def bilinear_backbone(p, d):
    """Loading branch of the Muthukumar law: k1 up to δ_y, then k2. Returns (f, df/dδ)."""
    k1, k2, dy = p[_K1], p[_K2], p[_DY]
    if d <= dy:
        return k1 * d, k1
    return k1 * dy + k2 * (d - dy), k2


@njit(cache=True)
def _muthukumar(p, dm, d):
    # Below the largest past indentation δ_m the force follows the unloading path from
    # (δ_m, f_m): slope k1 over δ_y, then the continuous k2 branch (PAPER.md §5.2), which is the
    # line f = k2·δ through the origin. Reloading after a partial unloading retraces that same
    # path (no dissipation in inner cycles) until it meets the backbone again at δ_m.
    if d >= dm:
        return bilinear_backbone(p, d)
    k1, k2, dy = p[_K1], p[_K2], p[_DY]
    if dm <= dy:  # never yielded: elastic on k1
        return k1 * d, k1
    fm = k1 * dy + k2 * (dm - dy)
    upper = fm - k1 * (dm - d)
    lower = k2 * d
    if upper >= lower:
        return upper, k1
    return lower, k2


@njit(cache=True)
def contact_force(code, p, h, d, v):
    """Force [kip] and tangents (df/dδ [kip/in], df/dδ̇ [kip·s/in]) of law ``code``."""
    if d <= 0.0:
        return 0.0, 0.0, 0.0
    if code == LINEAR:
        return p[_KEFF] * d, p[_KEFF], 0.0
    if code == KELVIN_VOIGT:
        f = p[_KEFF] * d + p[_CEFF] * v
        if f < 0.0 and p[_TENSION] == 0.0:
            return 0.0, 0.0, 0.0
        return f, p[_KEFF], p[_CEFF]
    if code == JANKOWSKI:
        sd = np.sqrt(d)
        f = p[_KH] * d * sd
        dfd = 1.5 * p[_KH] * sd
        if v > 0.0:
            # c_J = 2 ξ_J √(m k_h √δ); ∂c_J/∂δ = c_J / (4δ)
            cj = 2.0 * p[_XIJ] * np.sqrt(p[_MEFF] * p[_KH] * sd)
            return f + cj * v, dfd + 0.25 * cj * v / d, cj
        return f, dfd, 0.0
    if code == HERTZDAMP:
        v0 = max(h[0], p[_V0MIN])
        sd = np.sqrt(d)
        fh = p[_KH] * d * sd
        r = 1.0 + p[_XIH] * v / v0
        if r <= 0.0:
            return 0.0, 0.0, 0.0
        return fh * r, 1.5 * p[_KH] * sd * r, fh * p[_XIH] / v0
    if code == MUTHUKUMAR:
        f, k = _muthukumar(p, h[1], d)
        return f, k, 0.0
    return np.nan, np.nan, np.nan


@njit(cache=True)
def contact_closure(h, v):
    """Start a new contact episode at gap closure with approach velocity δ̇₀ = ``v`` [in/s].

    Each impact is a new loading of the contact surface: the bilinear law's largest indentation
    starts again from zero.
    """
    h[0] = v
    h[1] = 0.0
    h[3] = 0.0  # the Hertz spring starts unloaded; h[2] keeps the committed δ (≤ 0 here)


@njit(cache=True)
def contact_commit(h, d):
    """Advance the history after a converged step ending at indentation ``d`` [in]."""
    if d > h[1]:
        h[1] = d


@njit(cache=True)
def contact_stored_energy(code, p, h, d):
    """Elastic energy [kip·in] the contact would return if unloaded now from indentation ``d``.

    Used by energy balances while a contact is open. Zero at separation for every law.
    """
    if d <= 0.0:
        return 0.0
    if code == LINEAR or code == KELVIN_VOIGT:
        return 0.5 * p[_KEFF] * d * d
    if code == JANKOWSKI or code == HERTZDAMP:
        return 0.4 * p[_KH] * d * d * np.sqrt(d)
    # Muthukumar: area under the unloading path from d down to 0 (unloading from max(d, δ_m)).
    dm = max(h[1], d)
    k1, k2, dy = p[_K1], p[_K2], p[_DY]
    if dm <= dy:
        return 0.5 * k1 * d * d
    dk = dm - dy  # the unloading path has its corner at δ = δ_m − δ_y
    if d <= dk:
        return 0.5 * k2 * d * d
    f_corner = k2 * dk
    f_d, _ = _muthukumar(p, dm, d)
    return 0.5 * k2 * dk * dk + 0.5 * (f_corner + f_d) * (d - dk)


# ---- implicit time stepping: an energy-consistent Hertz spring --------------------------------
#
# The trapezoidal rule (Newmark average acceleration) conserves the energy of a linear spring
# exactly, but not of the hardening Hertz spring k_h·δ^1.5 of the Jankowski and Hertzdamp laws:
# over a step it does the work ½(f₀ + f₁)·Δδ instead of ΔΦ, Φ = 0.4·k_h·δ^2.5, and over many
# impacts of a lossless (e = 1) law the difference accumulates into an energy gain (5 % after 60
# impacts at rtol = 1e-4, measured). In the time-stepping loops the elastic part therefore uses
# the discrete gradient: the end-of-step force f̃₁ is chosen so that ½(f̃₀ + f̃₁)·Δδ = ΔΦ
# exactly, f̃₁ = 2·ΔΦ/Δδ − f̃₀, with f̃₀ the value the previous step ended with (h[3]); f̃ differs
# from k_h·δ^1.5 by the trapezoidal defect, O(Δδ²·f''), alternating in sign. The damping part
# of the law is unchanged. The single-impact solver (an ODE solver, not the trapezoidal rule)
# keeps using contact_force.


@njit(cache=True)
def _hertz_gradient(kh, d0, f0, d):
    """(f̃₁, df̃₁/dδ₁) of the discrete gradient from (δ₀, f̃₀) to δ₁ = d (Φ = 0 for δ ≤ 0)."""
    d1p = max(d, 0.0)
    d0p = max(d0, 0.0)
    dd = d - d0
    if abs(dd) > 1e-6 * max(d1p, d0p):
        phi1 = 0.4 * kh * d1p * d1p * np.sqrt(d1p)
        phi0 = 0.4 * kh * d0p * d0p * np.sqrt(d0p)
        fe = kh * d1p * np.sqrt(d1p)
        dphi = phi1 - phi0
        return 2.0 * dphi / dd - f0, 2.0 * (fe * dd - dphi) / (dd * dd)
    # ΔΦ/Δδ = f(δ_mid) + O(Δδ²·f''): no cancellation for tiny steps
    dm = max(0.5 * (d + d0), 0.0)
    sm = np.sqrt(dm)
    return 2.0 * kh * dm * sm - f0, 1.5 * kh * sm


@njit(cache=True)
def step_force(code, p, h, d, v):
    """contact_force for an implicit trapezoidal step from the committed state (h[2], h[3]).

    Identical to :func:`contact_force` except for the elastic part k_h·δ^1.5 of the Jankowski
    and Hertzdamp laws, which is replaced by its discrete gradient (see above); the step that
    ends a contact (δ₁ ≤ 0, from δ₀ > 0) returns the energy stored at δ₀ too.
    """
    f, kf, cf = contact_force(code, p, h, d, v)
    if code != JANKOWSKI and code != HERTZDAMP:
        return f, kf, cf
    if d <= 0.0 and h[2] <= 0.0:
        return f, kf, cf
    fe, kfe = 0.0, 0.0
    if d > 0.0:
        sd = np.sqrt(d)
        fe = p[_KH] * d * sd
        kfe = 1.5 * p[_KH] * sd
    g, kg = _hertz_gradient(p[_KH], h[2], h[3], d)
    if d == h[2]:
        g = h[3]  # at the committed state itself (a restart): the force the last step ended with
    return f - fe + g, kf - kfe + kg, cf


@njit(cache=True)
def step_commit(code, p, h, d):
    """contact_commit, plus the state (δ_n, f̃_n) the next step's discrete gradient starts from."""
    contact_commit(h, d)
    g = 0.0
    if (code == JANKOWSKI or code == HERTZDAMP) and (d > 0.0 or h[2] > 0.0):
        g = _hertz_gradient(p[_KH], h[2], h[3], d)[0]
    h[2] = d
    h[3] = g if d > 0.0 else 0.0
