"""The impact table, kept inside the compiled loop as the samples are recorded.

The same episodes and the same values as :func:`femoat.results.base.impact_table` reads
from a recorded history, sample by sample, so that a run that keeps no history still has its
impact table. For each contact, an episode is a run of recorded samples with the contact closed;
its segment reaches to the first sample after the run (the located separation) or to the last
sample of the run. Of each episode:

* start [s]: the time of its first closed sample; approach velocity [in/s]: δ̇ there;
* peak force [kip]: the largest recorded force (its first sample k), refined by the parabola
  through samples k − 1, k, k + 1 (:func:`parabolic_peak`, the twin of
  :func:`femoat.dense_peaks.parabolic_peak`);
* duration [s]: from the start to the first sample at or after k whose force is ≤ 0 (a
  tension-free law's force has fallen to zero), else to the segment's end;
* max indentation [in] over the segment; impulse [kip·s]: the trapezoid rule over it.

A sample is taken in once the sample after it is recorded: an event at the committed state may
still change the contact flags and force of the last sample (``recorder.mark_last_sample``).
:func:`finish_episodes` takes in the last one after the loop and closes the open episodes.

``state.ep`` holds, per contact, the running episode (the ``EP_*`` columns); finished episodes
are appended to ``rec.episodes`` (the ``IMPACT_*`` columns, one row each, in the order they
end; ``state.stats[S_IMPACTS]`` counts them).
"""

import numpy as np

from femoat.compilation.jit import njit
from femoat.integration.recording.rows import row
from femoat.integration.codes import S_IMPACTS, S_NOUT

# state.ep columns: the running episode of one contact
(EP_PHASE, EP_START, EP_APPROACH, EP_MAX_INDENT, EP_IMPULSE, EP_FMAX, EP_T_ZERO, EP_T_END,
 EP_T_BEFORE, EP_F_BEFORE, EP_T_PEAK, EP_WAIT, EP_T_AFTER, EP_F_AFTER) = range(14)
N_EP = 14
# EP_PHASE: no episode, an episode open, an episode ended whose peak waits for sample k + 1
IDLE, OPEN, ENDED = 0.0, 1.0, 2.0

# rec.episodes columns: one finished episode
IMPACT_CONTACT, IMPACT_START, IMPACT_DURATION, IMPACT_APPROACH, IMPACT_PEAK, IMPACT_MAX_INDENT, \
    IMPACT_IMPULSE = range(7)
N_IMPACT = 7
IMPACT_FIELDS = ("contact", "start", "duration", "approach_velocity", "peak_force",
                 "max_indentation", "impulse")
"""Names of the ``IMPACT_*`` columns (units: -, s, s, in/s, kip, in, kip·s)."""


@njit(cache=True, inline="always")
def parabolic_peak(t0, f0, t1, f1, t2, f2):
    """The vertex of the parabola through (t0, f0), (t1, f1), (t2, f2) where it is a maximum
    inside [t0, t2] and both neighbours carry force, else f1 (the same operations as
    :func:`femoat.dense_peaks.parabolic_peak`)."""
    if f0 <= 0.0 or f2 <= 0.0:
        return f1
    d1, d2 = (f1 - f0) / (t1 - t0), (f2 - f1) / (t2 - t1)
    a = (d2 - d1) / (t2 - t0)
    if a >= 0:
        return f1
    b = d1 - a * (t0 + t1)
    tv = -b / (2 * a)
    if not (t0 <= tv <= t2):
        return f1
    return max(f1, f0 + (tv - t0) * (d1 + a * (tv - t1)))


@njit(cache=True, inline="always")
def _emit(c, row, has_after, stats, episodes):
    """Append contact ``c``'s episode (``row`` of state.ep) to the impact table ``episodes``
    (``rec.episodes``; ``stats``: ``state.stats``)."""
    j = stats[S_IMPACTS]
    out = episodes[j]
    fmax = row[EP_FMAX]
    out[IMPACT_CONTACT] = c
    out[IMPACT_START] = row[EP_START]
    t_last = row[EP_T_ZERO] if not np.isnan(row[EP_T_ZERO]) else row[EP_T_END]
    out[IMPACT_DURATION] = t_last - row[EP_START]
    out[IMPACT_APPROACH] = row[EP_APPROACH]
    out[IMPACT_PEAK] = (parabolic_peak(row[EP_T_BEFORE], row[EP_F_BEFORE], row[EP_T_PEAK], fmax,
                                       row[EP_T_AFTER], row[EP_F_AFTER]) if has_after else fmax)
    out[IMPACT_MAX_INDENT] = row[EP_MAX_INDENT]
    out[IMPACT_IMPULSE] = row[EP_IMPULSE]
    stats[S_IMPACTS] = j + 1
    row[EP_PHASE] = IDLE


@njit(cache=True, inline="always")
def _new_peak(row, t, f, t_prev, f_prev):
    """Sample (t, f) is the episode's largest force so far: k moves there ((t_prev, f_prev):
    the sample before it)."""
    row[EP_FMAX] = f
    row[EP_T_BEFORE] = t_prev
    row[EP_F_BEFORE] = f_prev
    row[EP_T_PEAK] = t
    row[EP_WAIT] = 1.0
    row[EP_T_ZERO] = t if f <= 0.0 else np.nan


@njit(cache=True)
def _take(c, t, f, d, dv, closed, t_prev, f_prev, row, stats, episodes):
    """Contact ``c``'s final values at one recorded sample: time t [s], force f [kip],
    indentation d [in], its rate dv [in/s], closed flag; (t_prev, f_prev) at the sample
    before; ``row`` its running episode (``state.ep[c]``). Its own compiled function, with
    arrays rather than the bundles: called only for a contact in an episode, it is compiled
    once, not again inside every kernel that records."""
    if row[EP_WAIT] == 1.0:  # the sample after the peak: the parabola's third point
        row[EP_T_AFTER] = t
        row[EP_F_AFTER] = f
        row[EP_WAIT] = 0.0
        if row[EP_PHASE] == ENDED:
            _emit(c, row, True, stats, episodes)
    if row[EP_PHASE] == OPEN:
        row[EP_IMPULSE] += (t - t_prev) * (f + f_prev) / 2.0
        if d > row[EP_MAX_INDENT]:
            row[EP_MAX_INDENT] = d
        if f > row[EP_FMAX]:
            _new_peak(row, t, f, t_prev, f_prev)
        elif np.isnan(row[EP_T_ZERO]) and f <= 0.0:
            row[EP_T_ZERO] = t
        row[EP_T_END] = t
        if not closed:  # the first sample after the closed run ends the segment
            if row[EP_WAIT] == 1.0:
                row[EP_PHASE] = ENDED
            else:
                _emit(c, row, True, stats, episodes)
    elif closed:
        row[EP_PHASE] = OPEN
        row[EP_START] = t
        row[EP_APPROACH] = dv
        row[EP_MAX_INDENT] = d
        row[EP_IMPULSE] = 0.0
        row[EP_T_END] = t
        _new_peak(row, t, f, t_prev, f_prev)


@njit(cache=True, inline="always")
def _take_sample(k, state, rec):
    """Take in recorder sample ``k`` for every contact that is in an episode, waits for the
    sample after its peak or closes at k (the others have nothing to do: most samples). The
    sample before k is still in the recorder (a ring holds k − 1, k and k + 1); before sample 0
    is the initial state (time 0, no force)."""
    rows = rec.t.shape[0]
    r = row(k, rows)
    ep = state.ep
    for c in range(ep.shape[0]):
        if ep[c, EP_PHASE] == IDLE and ep[c, EP_WAIT] == 0.0 and rec.closed[r, c] == 0:
            continue
        t_prev, f_prev = 0.0, 0.0
        if k >= 1:
            p = row(k - 1, rows)
            t_prev, f_prev = rec.t[p], rec.cf[p, c]
        _take(c, rec.t[r], rec.cf[r, c], rec.cd[r, c], rec.cv[r, c], rec.closed[r, c] != 0,
              t_prev, f_prev, ep[c], state.stats, rec.episodes)


@njit(cache=True, inline="always")
def push_episodes(k, state, rec):
    """Sample ``k`` was just recorded: take in sample k − 1 (final now)."""
    if k >= 1:
        _take_sample(k - 1, state, rec)


@njit(cache=True)
def start_episodes(state):
    """No episode yet."""
    ep = state.ep
    for c in range(ep.shape[0]):
        for j in range(N_EP):
            ep[c, j] = 0.0
        ep[c, EP_T_ZERO] = np.nan
    state.stats[S_IMPACTS] = 0


@njit(cache=True)
def finish_episodes(state, rec):
    """After the loop: take in the last sample and end every episode still open (its segment
    ends at the last sample; a peak there has no sample after it)."""
    m = state.stats[S_NOUT]
    if m >= 1:
        _take_sample(m - 1, state, rec)
    for c in range(state.ep.shape[0]):
        row = state.ep[c]
        if row[EP_PHASE] != IDLE:
            _emit(c, row, row[EP_WAIT] == 0.0, state.stats, rec.episodes)
