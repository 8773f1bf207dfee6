"""Damping parameters of the contact laws from a coefficient of restitution (docs/paper.md §2).

These are the published closed forms. They are approximations: the achieved restitution of a
simulated impact differs slightly (see :mod:`femoat.impact.calibration` for exact values).
"""

import math


def _check_e(e):
    if not (isinstance(e, (int, float)) and math.isfinite(e) and 0 < e <= 1):
        raise ValueError(f"e = {e!r} is invalid: the coefficient of restitution must be in (0, 1].")


def xi_kelvin_voigt(e):
    """Kelvin-Voigt damping ratio ξ_KV solving ln(1/e) = 2ξ/√(1−ξ²)·arctan(√(1−ξ²)/ξ).

    The relation assumes that contact ends when the force returns to zero (no tension). The
    right-hand side grows monotonically from 0 (ξ→0) to 2 (ξ→1), so a root exists for
    e > exp(−2) ≈ 0.135; below that a tension-free Kelvin-Voigt contact cannot dissipate enough.
    """
    from scipy.optimize import brentq

    _check_e(e)
    if e == 1.0:
        return 0.0
    target = math.log(1.0 / e)
    if target >= 2.0:
        raise ValueError(
            f"e = {e} is too small for the Kelvin-Voigt law: a tension-free Kelvin-Voigt contact "
            f"reaches at least e = exp(-2) = {math.exp(-2):.4f}; use another law or a larger e."
        )

    def g(xi):
        s = math.sqrt(1.0 - xi * xi)
        return 2.0 * xi / s * math.atan(s / xi) - target

    return brentq(g, 1e-12, 1.0 - 1e-15, xtol=1e-15, rtol=1e-14)


def xi_jankowski(e):
    """Jankowski damping ratio ξ_J = (9√5/2)·(1−e²)/(e·(e(9π−16)+16))."""
    _check_e(e)
    return 9.0 * math.sqrt(5.0) / 2.0 * (1.0 - e * e) / (e * (e * (9.0 * math.pi - 16.0) + 16.0))


def xi_hertzdamp(e):
    """Hertzdamp damping factor ξ_h = (8/5)·(1−e)/e."""
    _check_e(e)
    return 1.6 * (1.0 - e) / e


def muthukumar_loss_factor(e):
    """Loss factor λ = 0.4·(1−e²) of the Muthukumar bilinear law [-]."""
    _check_e(e)
    return 0.4 * (1.0 - e * e)


def muthukumar_stiffnesses(k_eff, e, a, loss=None):
    """Loading stiffnesses (k1, k2) [kip/in] of the Muthukumar bilinear law.

    k1 = (1 + λ/a)·k_eff and k2 = (1 − λ/(1−a))·k_eff with λ = 0.4(1−e²) unless ``loss`` gives λ.
    With these, the loop dissipates λ·k_eff·δ_me² when the indentation reaches δ_me, while the
    backbone stores ½(1+λ)·k_eff·δ_me² (so that, at δ_max = δ_me, e² = (1−λ)/(1+λ) exactly).
    """
    lam = muthukumar_loss_factor(e) if loss is None else loss
    k1 = (1.0 + lam / a) * k_eff
    k2 = (1.0 - lam / (1.0 - a)) * k_eff
    if k2 <= 0.0:
        raise ValueError(
            f"The Muthukumar law with loss factor {lam:.4g} (e = {e}) and a = {a} has a "
            f"non-positive second stiffness k2 = {k2:.4g} kip/in: choose a smaller a "
            "(a < 1 - loss factor) or a larger e."
        )
    return k1, k2
