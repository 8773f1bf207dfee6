"""Hunt-and-fill tracing of one IDA curve (Vamvatsikos & Cornell 2002, Earthq. Eng. Struct. Dyn.
31(3), §6), as a pure function of a run oracle ``run(im)``: whether the run at ``im`` collapsed,
and (to bracket the onset of pounding) which walls it pounded on.

1. **Hunt up**: im_1 = step0, im_{k+1} = im_k + step0 + k·step_increment (steps grow by
   ``step_increment`` each run) until the first collapse.
2. **Bracket** the collapse: bisect between the highest non-collapsing im below the lowest
   collapsing im and that collapsing im until their distance is at most ``resolution``.
3. **Bracket the onsets of pounding** (``walls`` given): for "any" wall and each wall, bisect
   between the highest run below the lowest collapse that pounded on neither that wall nor
   collapsed and the lowest run up to the collapse that pounded on it (the bracket
   :func:`onset_bracket`, the one :mod:`femoat.suite.pounding` reads), until it is at most
   ``resolution`` wide; the widest bracket first, so that a budget that runs out leaves the
   walls' brackets alike. A trace that collapsed before it pounded on a wall has no onset there
   and no run for it.
4. **Fill**: with the runs left, halve the largest gap between the non-collapsing ims (from 0 up
   to the highest non-collapse) until every gap is at most ``resolution`` or the runs are used
   up.

Every step re-reads the runs made so far: a later run that collapses below the lowest collapse
(the IDA curve is not monotone: the structure "resurrects" above it) lowers the collapse
intensity, one that pounds below an onset lowers the onset, and the brackets are refined again
before anything else.

At most ``max_runs`` runs in all: when they run out a bracket stays as wide as it is (the report
reads each record's onset bracket, :func:`femoat.suite.pounding.traces`); a trace that never
collapses ends after ``max_runs`` hunt runs. A run that fails to converge is handed to the
oracle's caller to classify; the suite counts it as "did not survive"
(see :mod:`femoat.suite.execute`) so that the trace brackets below it.
"""

import math
from typing import NamedTuple

ANY = "any"
"""The wall key of the first impact on any wall."""


class Outcome(NamedTuple):
    """What the oracle says of one run: whether it collapsed (or did not survive) and the keys
    of the walls it pounded on."""

    collapsed: bool
    hits: frozenset = frozenset()


class Run(NamedTuple):
    """One run of a trace: its intensity [IM], whether it collapsed, the walls it pounded on."""

    im: float
    collapsed: bool
    hits: frozenset = frozenset()


def hunt_fill(run, step0, step_increment, resolution, max_runs, walls=()):
    """Trace one IDA curve; return its runs (:class:`Run`) in run order.

    run : callable  im -> bool (collapsed) or :class:`Outcome`, the run at intensity im (any
        IM unit, e.g. g)
    step0 : float  first intensity and first step [IM], > 0
    step_increment : float  growth of the step per hunt run [IM], >= 0
    resolution : float  bracket width [IM] at which the collapse (and each onset) is known, > 0
    max_runs : int  cap on the number of runs, >= 1
    walls : sequence of str  the wall keys whose onset of pounding is bracketed, with "any"
        wall (empty: the collapse only)
    """
    for name, value, low in (("step0", step0, 0.0), ("resolution", resolution, 0.0)):
        if not (math.isfinite(value) and value > low):
            raise ValueError(f"{name} = {value!r} must be a positive intensity.")
    if not (math.isfinite(step_increment) and step_increment >= 0):
        raise ValueError(f"step_increment = {step_increment!r} must be >= 0.")
    if int(max_runs) < 1:
        raise ValueError(f"max_runs = {max_runs!r} must be at least 1.")
    keys = (ANY, *walls) if walls else ()
    runs = []

    def trial(im):
        r = run(im)
        r = r if isinstance(r, Outcome) else Outcome(bool(r))
        runs.append(Run(im, bool(r.collapsed), frozenset(r.hits)))
        return runs[-1].collapsed

    # 1. hunt up
    im, step = 0.0, step0
    while len(runs) < max_runs:
        im = im + step
        if trial(im):
            break
        step += step_increment
    # 2.-4. the brackets, then the fill, re-read after every run
    while len(runs) < max_runs:
        im = _next(runs, keys, resolution)
        if im is None:
            break
        trial(im)
    return runs


def _next(runs, keys, resolution):
    """The intensity of the next run after the hunt (None: the trace is done)."""
    # 2. the collapse bracket
    low, high = _bracket(runs)
    if high is not None and high - low > resolution:
        return 0.5 * (low + high)
    # 3. the widest onset bracket
    wide = [(b - a, a, b) for a, b in filter(None, (onset_bracket(runs, k) for k in keys))
            if b - a > resolution]
    if wide:
        _, a, b = max(wide)
        return 0.5 * (a + b)
    # 4. the largest gap between non-collapsing runs below the collapse
    safe = sorted({0.0} | {r[0] for r in runs if not r[1] and r[0] <= low})
    gaps = [(b - a, a, b) for a, b in zip(safe[:-1], safe[1:]) if b - a > resolution]
    if gaps:
        _, a, b = max(gaps)
        return 0.5 * (a + b)
    return None


def _bracket(runs):
    """(highest non-collapse below the lowest collapse, lowest collapse); None when none."""
    fails = [r[0] for r in runs if r[1]]
    high = min(fails) if fails else None
    safe = [r[0] for r in runs if not r[1] and (high is None or r[0] < high)]
    return (max(safe) if safe else 0.0), high


def collapse_bracket(runs):
    """The bracket ``(low, high)`` [IM] of a finished trace (``high`` None: never collapsed);
    ``runs`` are :class:`Run` or ``(im, collapsed)`` pairs."""
    return _bracket(runs)


def onset_bracket(runs, wall=ANY):
    """The bracket ``(clear, onset)`` [IM] of the onset of pounding on ``wall`` ("any": on any
    wall) of a trace's ``runs`` (:class:`Run`): ``onset`` the lowest run up to the lowest collapse (the
    collapse run included: it may have pounded) that pounded on the wall, ``clear`` the highest
    run below it (0 when none: every run below it neither pounded there nor collapsed). None
    when no run up to the collapse pounded there (it collapsed first, or never pounded)."""
    top = min((r.im for r in runs if r.collapsed), default=math.inf)
    hit = [r.im for r in runs if r.im <= top and (r.hits if wall == ANY else wall in r.hits)]
    if not hit:
        return None
    onset = min(hit)
    return max((r.im for r in runs if r.im < onset), default=0.0), onset
