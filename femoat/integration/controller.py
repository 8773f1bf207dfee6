"""The step controller's shared rules: where a step may end (never across a record sample),
and the controller's state kept in :class:`~femoat.integration.bundles.State` between calls of
the loop. Each method's own step-size rule is in its module (:mod:`femoat.integration.methods`)."""

import numpy as np

from femoat.compilation.jit import njit


@njit(cache=True, inline="always")
def _step_end(t, h, t_goal, shortened, settings, n_samples):
    """(hh, t1): the step from ``t`` of at most ``h``, never crossing a record sample nor the
    goal, landing exactly on the goal or a sample when within round-off of it (not after an
    event shortening, which the snap would undo)."""
    hmax, dt_rec = settings.h_max, settings.dt_record
    k_next = int(np.floor(t / dt_rec + 1e-9)) + 1
    hh = min(h, hmax, t_goal - t)
    if k_next <= n_samples - 1:
        t_sample = k_next * dt_rec
        if t_sample - t < hh:
            hh = t_sample - t
    t1 = t + hh
    if not shortened and t_goal - t1 < 1e-9 * hh:
        t1 = t_goal
    elif not shortened and k_next <= n_samples - 1 and abs(t1 - k_next * dt_rec) < 1e-9 * hh:
        t1 = k_next * dt_rec
    return t1 - t, t1


@njit(cache=True, inline="always")
def _stop(status, t, h, h_cruise, shortened, landing, since_record, state):
    """Leave the loop at time ``t`` with the controller's state kept for the next call (the
    next step ``h``, the cruising step, a pending landing and the samples since the last record),
    so that a run does not depend on where it was re-entered (a grown recorder, a progress
    display's chunks)."""
    state.t[0] = t
    state.h[0] = h
    state.h_cruise[0] = h_cruise
    state.shortened[0] = 1 if shortened else 0
    state.landing[0] = landing
    state.since_record[0] = since_record
    return status
