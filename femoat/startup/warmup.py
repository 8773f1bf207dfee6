"""Pay the solver's start-up cost before anything is timed, and say how much it was.

The first building run of a process loads the solver's compiled kernels: from numba's on-disk
cache (about a second: numba's own import and the cache's load) or by compiling them with
numba (minutes on a fresh install, once). Timed inside that first run, this start-up would be
reported as solver time, a thousand times the solver's real cost. :func:`warm_up` pays it with
one tiny run and returns it, so that the commands report compile / start-up time apart from
solver time.
"""

import time

_done = []


def warm_up():
    """Load or compile the building solver's kernels with a tiny run; return the CPU time it
    took [s] (process time, like the solver's ``cpu_seconds``).

    Only the first call of a process does anything; later calls return 0.0. The returned time
    is the start-up the first run of this process would otherwise have paid: numba's import
    and compilation, or its cache load.
    """
    if _done:
        return 0.0
    from femoat.startup.probe import run_probe

    t0 = time.process_time()
    run_probe()  # the walls are 4 in away: no contact needed
    from femoat.compilation import call_types
    from femoat.compilation.inlining import forget

    forget()  # the inliner's kept IRs and the memoized call types served the compile: a
    call_types.clear()  # process keeps none
    _done.append(True)
    return time.process_time() - t0
