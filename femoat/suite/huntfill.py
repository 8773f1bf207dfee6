"""Hunt-and-fill tracing of one IDA curve (Vamvatsikos & Cornell 2002, Earthq. Eng. Struct. Dyn.
31(3), §6), as a pure function of a ``collapsed(im) -> bool`` oracle.

1. **Hunt up**: im_1 = step0, im_{k+1} = im_k + step0 + k·step_increment (steps grow by
   ``step_increment`` each run) until the first collapse.
2. **Bracket**: bisect between the highest non-collapsing im below the lowest collapsing im and
   that collapsing im until their distance is at most ``resolution``.
3. **Fill**: with the runs left, halve the largest gap between the non-collapsing ims (from 0 up to
   the highest non-collapse) until every gap is at most ``resolution`` or the runs are used up.
   A fill run that collapses (the IDA curve is not monotone: the structure "resurrects" above
   it) lowers the collapse intensity; step 2 then refines the new bracket before filling on.

At most ``max_runs`` runs in all; a trace that never collapses ends after ``max_runs`` hunt runs.
A run that fails to converge is handed to the oracle's caller to classify; the suite counts it as
"did not survive" (see :mod:`femoat.suite.execute`) so that the trace brackets below it.
"""

import math


def hunt_fill(collapsed, step0, step_increment, resolution, max_runs):
    """Trace one IDA curve; return the runs as a list of ``(im, collapsed)`` in run order.

    collapsed : callable  im -> bool, the run at intensity im (any IM unit, e.g. g)
    step0 : float  first intensity and first step [IM], > 0
    step_increment : float  growth of the step per hunt run [IM], >= 0
    resolution : float  bracket width [IM] at which the collapse intensity is known, > 0
    max_runs : int  cap on the number of runs, >= 1
    """
    for name, value, low in (("step0", step0, 0.0), ("resolution", resolution, 0.0)):
        if not (math.isfinite(value) and value > low):
            raise ValueError(f"{name} = {value!r} must be a positive intensity.")
    if not (math.isfinite(step_increment) and step_increment >= 0):
        raise ValueError(f"step_increment = {step_increment!r} must be >= 0.")
    if int(max_runs) < 1:
        raise ValueError(f"max_runs = {max_runs!r} must be at least 1.")
    runs = []

    def trial(im):
        c = bool(collapsed(im))
        runs.append((im, c))
        return c

    # 1. hunt up
    im, step = 0.0, step0
    while len(runs) < max_runs:
        im = im + step
        if trial(im):
            break
        step += step_increment
    # 2. bracket the lowest collapse, 3. fill the largest gap below it; a fill run that
    # collapses (a non-monotone IDA curve, "resurrection" above it) moves the lowest collapse
    # down, and the bracket is refined again before any further fill
    while len(runs) < max_runs:
        low, high = _bracket(runs)
        if high is not None and high - low > resolution:
            trial(0.5 * (low + high))
            continue
        safe = sorted({0.0} | {im for im, c in runs if not c and im <= low})
        gaps = [(b - a, a, b) for a, b in zip(safe[:-1], safe[1:])]
        if not gaps:
            break
        width, a, b = max(gaps)
        if width <= resolution:
            break
        trial(0.5 * (a + b))
    return runs


def _bracket(runs):
    """(highest non-collapse below the lowest collapse, lowest collapse); None when none."""
    fails = [im for im, c in runs if c]
    high = min(fails) if fails else None
    safe = [im for im, c in runs if not c and (high is None or im < high)]
    return (max(safe) if safe else 0.0), high


def collapse_bracket(runs):
    """The bracket ``(low, high)`` [IM] of a finished trace (``high`` None: never collapsed)."""
    return _bracket(runs)
