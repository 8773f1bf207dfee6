"""Single impacts: the precise reference solver and exact-restitution calibration."""

from femoat.impact.single import ContactDidNotEndError, ImpactResult, simulate_impact

__all__ = ["ContactDidNotEndError", "ImpactResult", "simulate_impact"]
