"""Time integration: settings, the compiled loop, and the validated entry point."""

from femoat.integration.settings import Integrator
from femoat.integration.solve import RawHistory, SolverError, solve

__all__ = ["Integrator", "RawHistory", "SolverError", "solve"]
