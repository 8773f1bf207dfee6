"""Isolators designed for one MCE displacement: ASCE 7-16 Chapter 17's equivalent lateral force
procedure, with each bearing's effective properties computed from its own hysteresis.

ASCE 7-16 §17.5.3.1 (Eq. 17.5-1) gives the maximum displacement of the isolation system at the
MCE_R:

    D_M = g·S_M1·T_M / (4π²·B_M),   T_M = 2π·sqrt(W / (k_M·g))   (Eq. 17.5-2)

with S_M1 [g·s] the MCE_R spectral acceleration at 1 s, W [kip] the weight on the isolators, k_M
[kip/in] the effective stiffness at D_M and B_M [-] the damping coefficient of the effective
damping β_M (Table 17.5-1: 0.8 at 2 %, 1.0 at 5 %, 1.2 at 10 %, 1.5 at 20 %, 1.7 at 30 %, 1.9
at 40 %, 2.0 at 50 % and above, linear between). The effective properties at an amplitude D
(§17.8.4's, Eqs. 17.8-1 and 17.8-2 with the test loops replaced by the bearing's own):

    k_eff = F(D) / D,   β_eff = E_loop / (2π·k_eff·D²)

where F(D) is the force at the loop's tip and E_loop the energy of one steady cycle ±D, here
computed by cycling the bearing's one-axis kernels (:mod:`femoat.bearings`): every bearing kind,
whatever its hysteresis, is designed the same way. D_M is then the fixed point
D = D_M(k_eff(D), β_eff(D)) (:func:`mce_displacement`), and :func:`match_displacement` tunes one
parameter of a bearing until its D_M equals a target: the three isolators of the isolators study
(:mod:`femoat.studies.isolators`) carry the same building to the same MCE displacement.

Scaled models: a model at length scale λ and time scale √λ (the paper's quarter-scale building
at time scale 0.5) sees the prototype's spectrum at its own periods T/√λ; for the constant-
velocity branch S_a = S_M1/T this is S_M1 times the time scale at the model's periods, which is
what ``s_m1`` should be given (0.9 × 0.5 = 0.45 for SDC Dmax at time scale 0.5).

Units: kip, in, s; g = 386.09 in/s² (:data:`femoat.units.G`).
"""

import math

import numpy as np
from scipy.optimize import brentq

from femoat.bearings import registry
from femoat.units import G

DAMPING_TABLE = ((0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9),
                 (0.50, 2.0))
"""ASCE 7-16 Table 17.5-1: (effective damping β [-], damping coefficient B_M [-])."""

POINTS_PER_CYCLE = 2000
"""Displacement increments of one imposed cycle ±D. The loop is piecewise smooth, its corners
(a friction bearing's reversals) cut within one increment: on the friction pendulum the
damping is within 1e-4 of its closed form at D = 0.5-5 in (tests/test_isolation_design.py)."""


def damping_coefficient(beta):
    """B_M [-] of ASCE 7-16 Table 17.5-1 for the effective damping ``beta`` [-] (linear between
    its rows, 0.8 below 2 %, 2.0 above 50 %)."""
    if not (isinstance(beta, (int, float)) and math.isfinite(beta) and beta >= 0):
        raise ValueError(f"beta = {beta!r} [-]: expected a non-negative damping ratio.")
    b, coef = zip(*DAMPING_TABLE)
    return float(np.interp(beta, b, coef))


def effective_properties(bearing, amplitude, cycles=2):
    """(k_eff [kip/in], β_eff [-]) of ``bearing`` (a one-axis bearing of any registered kind)
    cycled at ±``amplitude`` [in] at 1 in/s (what rate-dependent friction reads): the force at
    the tip over the amplitude, and the last cycle's loop energy over 2π·k_eff·D² (module
    docstring)."""
    if not (isinstance(amplitude, (int, float)) and math.isfinite(amplitude) and amplitude > 0):
        raise ValueError(f"amplitude = {amplitude!r} [in]: expected a positive displacement.")
    kind = registry.kind_of(bearing)
    if kind is None:
        raise ValueError(f"bearing: a {type(bearing).__name__} is not a registered bearing "
                         f"kind ({', '.join(registry.keys())}).")
    mod = registry.module(kind)
    p, s = bearing.params(), bearing.initial_state_axis()
    n = POINTS_PER_CYCLE
    quarter = np.linspace(0.0, amplitude, n // 4 + 1)
    down = np.linspace(amplitude, -amplitude, n // 2 + 1)[1:]
    up = np.linspace(-amplitude, amplitude, n // 2 + 1)[1:]
    path = np.concatenate([quarter, *([down, up] * cycles)])
    speed = 1.0  # [in/s] a nominal sliding speed for rate-dependent friction (its sign matters)
    # a bearing whose one-axis state ends with the step's duration reads it there
    # (femoat.structure.materials.kernels.DURATION): each step taken at that speed
    timed = registry.reads_duration(registry.kinds()[kind], p)
    # numba's dispatchers called straight, without the lookup a femoat kernel's own call
    # makes every time (thousands of calls a cycle)
    trial, commit = (getattr(k, "python_dispatcher", k) for k in (mod.axis_trial,
                                                                   mod.axis_commit))
    force = np.empty(path.size)
    prev = 0.0
    for i, u in enumerate(path):
        v = math.copysign(speed, u - prev) if u != prev else 0.0
        if timed:
            s[-1] = abs(u - prev) / speed
        force[i] = trial(p, s, u, v)[0]
        commit(p, s, u, v)
        prev = u
    last = slice(path.size - down.size - up.size - 1, path.size)
    loop = float(np.trapezoid(force[last], path[last]))  # the cycle encloses its loop once
    k_eff = force[-1] / amplitude
    return k_eff, loop / (2.0 * math.pi * k_eff * amplitude ** 2)


def mce_displacement(bearing, weight, s_m1, bracket=(0.05, 100.0)):
    """(D_M [in], T_M [s], β_M [-]) of ``bearing`` carrying ``weight`` [kip] under an MCE_R
    spectrum of ``s_m1`` [g·s] (module docstring: the fixed point of ASCE 7-16 Eq. 17.5-1 with
    the bearing's effective properties at D_M). ValueError when no displacement in ``bracket``
    [in] is a fixed point (an isolator too soft or too stiff for the spectrum)."""
    if not (weight > 0 and s_m1 > 0):
        raise ValueError(f"weight = {weight!r} [kip] and s_m1 = {s_m1!r} [g·s] must be positive.")

    def period_damping(d):
        k, beta = effective_properties(bearing, d)
        return 2.0 * math.pi * math.sqrt(weight / (k * G)), beta

    def excess(d):
        t, beta = period_damping(d)
        return G * s_m1 * t / (4.0 * math.pi ** 2 * damping_coefficient(beta)) - d

    lo, hi = bracket
    if excess(lo) * excess(hi) > 0:
        raise ValueError(f"bearing {bearing!r}: no MCE displacement between {lo} and {hi} in "
                         f"for s_m1 = {s_m1} g·s and W = {weight} kip; check its stiffness.")
    d = brentq(excess, lo, hi, xtol=1e-9, rtol=1e-12)
    t, beta = period_damping(d)
    return d, t, beta


def match_displacement(make, target, weight, s_m1, bracket):
    """The bearing ``make(x)`` whose D_M (:func:`mce_displacement`) is ``target`` [in], x
    searched in ``bracket`` (e.g. a post-yield stiffness or a radius); returns (bearing, x)."""
    lo, hi = bracket

    def miss(x):
        return mce_displacement(make(x), weight, s_m1)[0] - target

    if miss(lo) * miss(hi) > 0:
        raise ValueError(f"no parameter in {bracket} gives D_M = {target} in; widen the bracket.")
    x = brentq(miss, lo, hi, xtol=1e-10, rtol=1e-12)
    return make(x), x
