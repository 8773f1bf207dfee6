"""The recorder: the committed state appended as a sample (:func:`record`, the one kernel that
writes the channels of :mod:`femoat.integration.recording.channels`), and the samples an event
at the committed state needs (:func:`sample_before_event`, :func:`mark_last_sample`)."""

from femoat.compilation.jit import njit
from femoat.contact.kernels import contact_force, recorded_force
from femoat.integration.codes import S_NOUT
from femoat.integration.forces import contact_rate
from femoat.integration.recording.episodes import push_episodes
from femoat.integration.recording.peaks import push_sample
from femoat.integration.recording.rows import row

RING_ROWS = 3
"""The rows of the recorder of a run that keeps no history: a ring of the last samples, which
the running peaks and the impact episodes read (row k modulo its length)."""


@njit(cache=True, inline="always")
def mark_last_sample(c, t, model, state, rec):
    """An episode opened or closed at the committed state: if that state (time ``t``) is the
    last recorded sample, record the contact's new flag there, and for an opened episode the
    law's force at that state (recorded before, with the episode not yet open, as zero; within
    gap_tol of the wall it is tiny but not zero)."""
    k = state.stats[S_NOUT]
    last = row(k - 1, rec.t.shape[0])
    if k > 0 and rec.t[last] == t:
        rec.closed[last, c] = state.c_closed[c]
        if state.c_closed[c] and rec.cf[last, c] == 0.0 and state.c_d[c] > 0.0:
            rec.cf[last, c] = contact_force(model.c_code[c], model.c_P[c], state.c_H[c],
                                             state.c_d[c], contact_rate(model.c_B, c, state.v))[0]


@njit(cache=True, python=False)
def sample_before_event(t, model, state, settings, rec):
    """Before an episode opens or closes at the committed state (time ``t`` > 0): record that
    state if it was skipped (``record_every`` > 1), so that the event has its sample."""
    k = state.stats[S_NOUT]
    if t > 0.0 and (k == 0 or rec.t[row(k - 1, rec.t.shape[0])] != t):
        record_sample(t, model, state, settings, rec)


@njit(cache=True, python=False)
def record_sample(t, model, state, settings, rec):
    """:func:`record` as a compiled function of its own: the loop and the events call one
    copy (inlined, each of its call sites compiled the recorder and the running peaks again)."""
    record(t, model, state, settings, rec)


@njit(cache=True, inline="always")
def record(t, model, state, settings, rec):
    """Append the committed state at time ``t`` as sample ``k`` to the recorder, in its row
    ``k`` modulo its length (a ring without history; a channel whose buffer has no columns was
    not requested: nothing is written), and pass it to the running peaks and episodes."""
    u, v, a = state.u, state.v, state.a
    n_out = state.stats[S_NOUT]
    k = row(n_out, rec.t.shape[0])
    rec.t[k] = t
    for j in range(rec.ag.shape[1]):
        rec.ag[k, j] = state.ag_now[j]
    for i in range(rec.u.shape[1]):
        rec.u[k, i] = u[i]
    for i in range(rec.v.shape[1]):
        rec.v[k, i] = v[i]
    for i in range(rec.a.shape[1]):
        rec.a[k, i] = a[i]
    for e in range(rec.ef.shape[1]):
        rec.ef[k, e] = state.el_f[e]
        rec.ed[k, e] = state.el_d[e]
    c_f, c_d, c_closed = state.c_f, state.c_d, state.c_closed
    for c in range(c_f.size):
        dd1 = contact_rate(model.c_B, c, v)
        # the law's force at the recorded state; the Hertz laws' step force differs
        # from it by the discrete gradient's O(Δδ²) trapezoidal defect
        rec.cf[k, c] = c_f[c]
        if c_closed[c]:
            rec.cf[k, c] = recorded_force(model.c_code[c], model.c_P[c], state.c_H[c], c_d[c],
                                          dd1, c_f[c])
        rec.cd[k, c] = c_d[c]
        rec.cv[k, c] = dd1
        rec.closed[k, c] = c_closed[c]
    state.stats[S_NOUT] = n_out + 1
    push_sample(t, n_out, model, state, settings, rec)
    push_episodes(n_out, state, rec)
