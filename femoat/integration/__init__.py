"""Time integration: settings, the compiled loop, and the validated entry point."""

from femoat.integration.limits import Limit
from femoat.integration.settings import Integrator
from femoat.integration.solve import (
    History,
    RecordBudgetError,
    SolverError,
    Status,
    integrate,
    solve,
)

__all__ = ["Integrator", "Limit", "History", "RecordBudgetError", "SolverError", "Status",
           "integrate", "solve"]
