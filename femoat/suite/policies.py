"""How a suite's report counts the runs the solver could not finish (``[run] solver_failure``),
listed once: the suite file is checked against these names, :func:`femoat.suite.statistics.
usable_runs` applies them and the report's README.txt states the one used.

A run that raised an error (status 'error') is never counted, whatever the policy.
"""

SOLVER_FAILURE = {
    "separate": "solver failures are left out of the fragility and the statistics and reported "
                "apart (n_solver_failures)",
    "collapse": "solver failures count as collapses",
    "exclude": "solver failures are dropped (their count is still in n_solver_failures)",
}
DEFAULT = "separate"


def check(policy, where):
    """``policy`` if it is one of :data:`SOLVER_FAILURE`, else a ValueError naming ``where``."""
    if policy not in SOLVER_FAILURE:
        raise ValueError(f"{where} solver_failure = {policy!r}: use one of "
                         f"{list(SOLVER_FAILURE)}.")
    return policy
