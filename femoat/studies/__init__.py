"""Studies built on suites (:mod:`femoat.suite`): each module holds its suite definitions, runs
them through :func:`femoat.suite.run_suite` (resumable, in a folder, on Dask) and reduces their
run tables to the study's own table. ``femoat study NAME`` runs one.

* ``bidirectional``: one record's components run alone (1D) against the pair applied together
  in plan (2D), at the MCE (issue 18, item 6);
* ``isolators``: three isolators (single and triple friction pendulum, lead-rubber) designed for
  the same MCE displacement, in the moat, 1D and in plan (issue 28, item 6).

Nothing heavy is imported here.
"""
