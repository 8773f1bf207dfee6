"""Time integration: settings, the compiled loop, and the validated entry point."""

from femoat.integration.limits import Limit
from femoat.integration.settings import Integrator
from femoat.integration.solve import (
    RawHistory,
    RecordBudgetError,
    SolverError,
    Status,
    integrate,
    solve,
)

__all__ = ["Integrator", "Limit", "RawHistory", "RecordBudgetError", "SolverError", "Status",
           "integrate", "solve"]
