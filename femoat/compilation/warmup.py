"""Pay the solver's start-up cost before anything is timed, and say how much it was.

The first building run of a process loads the solver's compiled kernels: from the
ahead-of-time module (:mod:`femoat.compilation.aot`, milliseconds), from numba's on-disk cache
(about a second: numba's own import), or by compiling them with numba (ten seconds or more).
Timed inside that first run, this start-up would be reported as solver time, a thousand times
the solver's real cost. :func:`warm_up` pays it with one tiny run and returns it, so that the
commands report compile / start-up time apart from solver time.
"""

import time

_done = set()


def warm_up(backend="auto"):
    """Load or compile the building solver's kernels with a tiny run; return the CPU time it
    took [s] (process time, like the solver's ``cpu_seconds``).

    Only the first call of a process (per backend) does anything; later calls return 0.0. The
    returned time is the start-up the first run of this process would otherwise have paid:
    numba's import and compilation (or its cache load), or loading the ahead-of-time module.
    """
    if backend in _done:
        return 0.0
    from femoat.compilation.probe import run_probe

    t0 = time.process_time()
    run_probe(backend)  # the walls are 4 in away: no contact needed
    _done.add(backend)
    return time.process_time() - t0
