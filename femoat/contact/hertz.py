"""The Hertz spring k_h·δ^1.5 of the Jankowski and Hertzdamp laws, and its discrete gradient.

Both laws store k_h [kip/in^1.5] at index :data:`K_H` of their params array and declare
``hertz_spring`` in their :class:`~femoat.contact.spec.KernelFamily`, so the time-stepping
variant of the force (:func:`femoat.contact.kernels.step_force`) can replace their elastic part
without knowing the law.

The trapezoidal rule (Newmark average acceleration) conserves the energy of a linear spring
exactly, but not of the hardening Hertz spring: over a step it does the work ½(f₀ + f₁)·Δδ instead
of ΔΦ, Φ = 0.4·k_h·δ^2.5, and over many impacts of a lossless (e = 1) law the difference
accumulates into an energy gain (5 % after 60 impacts at rtol = 1e-4, measured). In the
time-stepping loops the elastic part therefore uses the discrete gradient: the end-of-step force
f̃₁ is chosen so that
½(f̃₀ + f̃₁)·Δδ = ΔΦ exactly, f̃₁ = 2·ΔΦ/Δδ − f̃₀, with f̃₀ the value the previous step ended with
(``h[H_F_LAST]``); f̃ differs from k_h·δ^1.5 by the trapezoidal defect, O(Δδ²·f''), alternating
in sign. The damping part of the law is unchanged. The single-impact solvers (ODE solvers, not
the trapezoidal rule) keep using the law's own force.
"""

import numpy as np

from femoat.compilation.jit import njit

K_H = 0
"""Index of k_h [kip/in^1.5] in the params of every law built on the Hertz spring."""


@njit(cache=True)
def hertz_energy(p, h, d):
    """Elastic energy 0.4·k_h·δ^2.5 [kip·in] at indentation ``d`` > 0 [in] (the energy kernel
    of every law built on the Hertz spring)."""
    return 0.4 * p[K_H] * d * d * np.sqrt(d)


@njit(cache=True)
def hertz_gradient(kh, d0, f0, d):
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
