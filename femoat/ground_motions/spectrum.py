"""Linear elastic response spectrum of a ground motion, exact for piecewise-linear excitation.

The single-degree-of-freedom oscillator, relative displacement u [in], is

    u'' + 2ζω u' + ω² u = -a_g(t),      ω = 2π/T,   u(0) = u'(0) = 0,

with a_g linear between samples. Over one step h = dt the exact solution is the Nigam-Jennings
recurrence

    [u, u']_{n+1} = Φ [u, u']_n + F_a a_n + F_b a_{n+1}.

We get Φ, F_a and F_b from the matrix exponential of the system augmented with the ramp
(state [u, u', a_g, a_g'], with a_g' constant over the step): this is the same exact recurrence as
the closed-form coefficients, without their cancellation at long periods (terms like 1/(ω³ h)) and
for any damping ratio ζ ≥ 0. The time loop is vectorised over periods.

Peaks are taken over the samples of the record, 0 <= t <= duration (the usual convention); a
peak between samples or in the free vibration after the record ends is not counted.
"""

from typing import NamedTuple

import numpy as np

from femoat.units import G

from .record import GroundMotion


class ResponseSpectrum(NamedTuple):
    """Peak responses of linear oscillators, one entry per period."""

    psa: np.ndarray
    """Pseudo-spectral acceleration [g], ω² · sd."""
    sd: np.ndarray
    """Spectral displacement [in], the peak absolute relative displacement."""


def response_spectrum(motion, periods, damping=0.05):
    """Pseudo-acceleration and displacement spectra of ``motion``.

    Parameters
    ----------
    motion : GroundMotion
        The excitation, linear between samples.
    periods : float or array_like  [s]
        Oscillator periods, each finite and >= 0. T = 0 is a rigid oscillator: psa = PGA, sd = 0.
    damping : float  [-]
        Damping ratio ζ (fraction of critical), finite and >= 0.

    Returns
    -------
    ResponseSpectrum
        ``psa`` [g] and ``sd`` [in], each shaped like ``periods``.
    """
    if not isinstance(motion, GroundMotion):
        raise TypeError(f"motion must be a GroundMotion; got {type(motion).__name__}.")
    periods = np.asarray(periods, dtype=float)
    if not np.all(np.isfinite(periods) & (periods >= 0.0)):
        raise ValueError(f"periods [s] must be finite and >= 0; got {periods!r}.")
    damping = float(damping)
    if not (np.isfinite(damping) and damping >= 0.0):
        raise ValueError(
            f"damping must be a damping ratio >= 0 (0.05 for 5 %); got {damping!r}."
        )

    flat = periods.ravel()
    sd = np.zeros(flat.shape)
    psa = np.full(flat.shape, motion.pga)  # T = 0: the mass moves with the ground
    positive = flat > 0.0
    if np.any(positive):
        omega = 2.0 * np.pi / flat[positive]
        peak = _peak_displacement(motion.accel_g, motion.dt, omega, damping)  # [g·s²]
        sd[positive] = peak * G
        psa[positive] = omega**2 * peak
    return ResponseSpectrum(psa.reshape(periods.shape), sd.reshape(periods.shape))


def _step_matrices(omega, damping, h):
    """Φ (n, 2, 2), F_a (n, 2), F_b (n, 2) of the exact step for a ramp excitation."""
    n = omega.size
    aug = np.zeros((n, 4, 4))
    aug[:, 0, 1] = 1.0
    aug[:, 1, 0] = -(omega**2)
    aug[:, 1, 1] = -2.0 * damping * omega
    aug[:, 1, 2] = -1.0  # u'' = ... - a_g
    aug[:, 2, 3] = 1.0  # a_g' = constant slope over the step
    from scipy.linalg import expm  # imported here: scipy.linalg costs ~0.3 s at start-up

    psi = expm(aug * h)
    phi = psi[:, :2, :2]
    f_slope = psi[:, :2, 3] / h  # response to the slope (a_{n+1} - a_n) / h
    f_a = psi[:, :2, 2] - f_slope
    f_b = f_slope
    return phi, f_a, f_b


SCALAR_PERIODS = 4
"""Up to this many periods the recurrence runs on Python floats, one period at a time (a suite's
intensity measure is one period: numpy's per-call cost on arrays of one element made that loop
~10x slower); more periods run vectorised. The same IEEE operations in the same order either
way: the same bits."""


def _peak_displacement(accel, dt, omega, damping):
    """Peak |u| over the samples, for each ω; u in the units of accel times s²."""
    phi, f_a, f_b = _step_matrices(omega, damping, dt)
    if omega.size <= SCALAR_PERIODS:
        samples = accel.tolist()
        return np.array([_peak_one(samples, *phi[k].ravel().tolist(), *f_a[k].tolist(),
                                   *f_b[k].tolist()) for k in range(omega.size)])
    p11, p12, p21, p22 = phi[:, 0, 0], phi[:, 0, 1], phi[:, 1, 0], phi[:, 1, 1]
    fa1, fa2, fb1, fb2 = f_a[:, 0], f_a[:, 1], f_b[:, 0], f_b[:, 1]
    u = np.zeros(omega.size)
    v = np.zeros(omega.size)
    peak = np.zeros(omega.size)
    for a0, a1 in zip(accel[:-1].tolist(), accel[1:].tolist()):
        u, v = p11 * u + p12 * v + fa1 * a0 + fb1 * a1, p21 * u + p22 * v + fa2 * a0 + fb2 * a1
        np.maximum(peak, np.abs(u), out=peak)
    return peak


def _peak_one(samples, p11, p12, p21, p22, fa1, fa2, fb1, fb2):
    """:func:`_peak_displacement` of one period on Python floats (``samples`` a list)."""
    u = v = peak = 0.0
    for a0, a1 in zip(samples[:-1], samples[1:]):
        u, v = p11 * u + p12 * v + fa1 * a0 + fb1 * a1, p21 * u + p22 * v + fa2 * a0 + fb2 * a1
        if abs(u) > peak:
            peak = abs(u)
    return peak
