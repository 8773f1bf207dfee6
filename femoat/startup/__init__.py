"""Starting the solver before it is timed: above the solver, so that nothing below imports it.

* :mod:`~femoat.startup.probe`: a tiny run that compiles (or loads from numba's on-disk cache)
  every entry point of the solver;
* :mod:`~femoat.startup.warmup`: that run once per process, and the start-up it cost (a run's
  ``meta["compile_seconds"]``), paid before any timing;
* :mod:`~femoat.startup.bearing_kinds`: which bearing kinds a command's loop is compiled for;
* :mod:`~femoat.startup.compile_helper`: the process that compiles the loop's callees beside a
  cold first run (:mod:`femoat.compilation.compile_plan`), and the recording of its plan.
"""
