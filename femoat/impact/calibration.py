"""Exact-restitution calibration: the damping parameter that makes a simulated impact reach e.

The paper's closed forms (docs/paper.md §2) are approximations: at e = 0.70, Hertzdamp achieves about
0.683 and Jankowski about 0.698. :func:`calibrate` solves, on the precise single-impact solver,
for the parameter that gives the target exactly at a stated impact speed (and, optionally,
against a stated wall rather than the rigid stop that defines e).

How is the law's own business: its :class:`~femoat.contact.spec.LawSpec` names a
``calibration``, a :class:`~femoat.contact.spec.Bracket` for a root search (Brent's method) of the
damping parameter, or a procedure of its own (the bilinear law's self-consistent one,
:func:`femoat.contact.muthukumar.calibrate_bilinear`), which is handed a :class:`Search`.
"""

import math

from scipy.optimize import brentq

from femoat.impact.single import simulate_impact


def achieved_restitution(law, v0, wall=None):
    """Restitution [-] reached by ``law`` at impact speed ``v0`` [in/s]."""
    return simulate_impact(law, v0, wall=wall, samples_per_phase=2).restitution


class Search:
    """What a law's calibration works with: the impact (``v0`` [in/s], ``wall``), the
    ``target`` restitution [-] and ``tol`` on it, and the solver's answers."""

    def __init__(self, v0, target, wall, tol):
        self.v0, self.target, self.wall, self.tol = v0, target, wall, tol

    def max_indentation(self, law):
        """Largest indentation [in] of ``law``'s impact."""
        return simulate_impact(law, self.v0, wall=self.wall, samples_per_phase=2).max_indentation

    def check(self, law):
        """``law``, if it reaches the target within ``tol``; else RuntimeError."""
        err = abs(achieved_restitution(law, self.v0, self.wall) - self.target)
        if err > self.tol:
            raise RuntimeError(f"Calibration of law {law.kind} missed the target by {err:.2e}.")
        return law

    def solve(self, law, lo, hi):
        """``law`` with the damping parameter in [lo, hi] that reaches the target (Brent)."""
        def miss(x):
            return achieved_restitution(law.with_damping(x), self.v0, self.wall) - self.target

        f_lo, f_hi = miss(lo), miss(hi)
        if f_lo * f_hi > 0:
            reach = sorted((f_lo + self.target, f_hi + self.target))
            raise ValueError(
                f"target = {self.target}: law {law.kind} reaches e between {reach[0]:.4f} and "
                f"{reach[1]:.4f} at v0 = {self.v0} in/s; choose a target in that range or "
                "another law."
            )
        x = brentq(miss, lo, hi, xtol=1e-12, rtol=1e-12, maxiter=200)
        return self.check(law.with_damping(x))


def calibrate(law, v0, target=None, wall=None, tol=1e-7):
    """Return a copy of ``law`` whose damping parameter reaches restitution ``target`` exactly.

    Parameters
    ----------
    law : ContactLaw
        A law that can be calibrated (``law.calibratable``: V, J, H or M built in).
    v0 : float
        Impact speed [in/s] at which e is matched (J, H and V are speed-independent; M is not).
    target : float or None
        Target restitution in (0, 1]; defaults to ``law.params.e``.
    wall : SdofWall or None
        Calibrate against this wall instead of a rigid stop (the definition of e).
    tol : float
        Tolerance on the achieved restitution [-].
    """
    if not law.calibratable:
        raise ValueError(f"law = {law.kind!r}: the {law.name} law has no damping to calibrate.")
    target = law.params.e if target is None else target
    if not (isinstance(target, (int, float)) and math.isfinite(target) and 0 < target <= 1):
        raise ValueError(f"target = {target!r} must be a restitution in (0, 1].")
    return law.spec.calibration(law, Search(v0, target, wall, tol))
