"""Contact events: a gap closing or opening located inside the step, the contact episode
opened or closed there, and the equilibrium restarted after it.

A gap closing or opening inside a step shortens the step until it ends within gap_tol of
δ = 0 (:func:`find_events` on the cubic Hermite interpolant of δ), where the episode starts
(capturing δ̇₀) or ends (:func:`~femoat.integration.commit.accept`); an event at the committed
state is declared there (:func:`declare_event`).
"""

from femoat.compilation.jit import njit
from femoat.contact.kernels import contact_closure
from femoat.integration.codes import S_EVENTS
from femoat.integration.forces import (
    Outputs,
    _internal_force,
    _solve_dense,
    contact_rate,
    ground_load,
)
from femoat.integration.interpolants import crossing, quintic
from femoat.integration.kinks import KINK_RESOLUTION
from femoat.integration.recording.recorder import mark_last_sample, sample_before_event
from femoat.structure.materials.kernels import stamp_duration


H_START = 1e-3
"""After a closure the force law is not smooth (Kelvin-Voigt jumps, Jankowski rises as
δ^(1/4)): restart at this fraction of the contact step and let the controller grow the step."""


@njit(cache=True, python=False)
def restart(model, state, work):
    """Re-establish equilibrium accelerations after a contact event changed the forces.

    A located closure or separation is a discontinuity of the force law; the trapezoidal rule
    must restart from a = M⁻¹·(p − F) at the event instead of the pre-event acceleration.
    """
    u, v, a, Fn = state.u, state.v, state.a, state.F
    M, r = model.M, model.r
    w_A, w_b = work.A, work.b
    ag_now = state.ag_now
    n = u.size
    out = Outputs(work.ef, work.ed, state.c_f, state.c_d, Fn, state.b_f, state.c_ft)
    stamp_duration(state.el_S, 0.0)  # (the committed state itself: no step)
    _internal_force(u, v, model, state, work, out, False, n, u, v, 0.0)
    for i in range(n):
        w_b[i] = ground_load(r, i, ag_now) - Fn[i]
        for j in range(n):
            w_A[i, j] = M[i, j]
    _solve_dense(w_A, w_b, n)
    for i in range(n):
        a[i] = w_b[i]


@njit(cache=True, inline="always")
def open_episode(c, v_close, state):
    """Open contact ``c``'s episode (gap closure at approach velocity ``v_close`` [in/s])."""
    state.c_closed[c] = 1
    contact_closure(state.c_H[c], v_close)
    state.stats[S_EVENTS] += 1


@njit(cache=True, inline="always")
def close_episode(c, state):
    """End contact ``c``'s episode (the located separation)."""
    state.c_closed[c] = 0
    state.stats[S_EVENTS] += 1


@njit(cache=True)
def first_contact_step(v_close, h_start, h_contact, gap_tol):
    """Step after a closure: small (h_start) for a real impact, whose force law may rise
    steeply from δ = 0; the ordinary contact step for a grazing closure that would not even
    indent gap_tol in h_start (a body settling on the wall must not restart tiny every time)."""
    return h_start if v_close * h_start > gap_tol else h_contact


@njit(cache=True, inline="always")
def find_events(hh, look_inside, model, state, settings, work):
    """(θ, c, c_now): the earliest crossing of δ = 0 inside the trial step at fraction θ of it
    (θ = 2: none) by contact c (a closure, or the separation of an open episode), and c_now ≥ 0
    a contact whose gap closes in the step while it was already touching at its start.

    ``look_inside`` (the long steps of the explicit method): a gap open at both ends of the
    step may still close inside it, near a turning point of δ; where δ approaches at the start,
    recedes at the end and its quintic interpolant (δ, δ̇ and δ̈ at the ends) crests above
    gap_tol, the step is shortened to end at the crest, where the ordinary crossing search
    takes over."""
    gap_tol = settings.gap_tol
    c_B, c_closed = model.c_B, state.c_closed
    theta = 2.0
    c_min = -1
    event_now = -1
    for c in range(c_closed.size):
        d0, d1 = state.c_d[c], work.cd[c]
        dd0 = 0.0
        dd1 = 0.0
        for i in range(state.v.size):
            dd0 += c_B[c, i] * state.v[i]
            dd1 += c_B[c, i] * work.v[i]
        if not c_closed[c] and d1 > 0.0:
            if d0 >= -gap_tol:
                event_now = c  # already touching at the start of the step
            else:
                th = crossing(d0, dd0, d1, dd1, hh)
                if th < theta:
                    theta = th
                    c_min = c
        elif c_closed[c] and d1 < -gap_tol:
            th = crossing(d0, dd0, d1, dd1, hh)
            if th < theta:
                theta = th
                c_min = c
        elif look_inside and not c_closed[c] and dd0 > 0.0 and dd1 < 0.0:
            dda0 = 0.0
            dda1 = 0.0
            for i in range(state.a.size):
                dda0 += c_B[c, i] * state.a[i]
                dda1 += c_B[c, i] * work.a[i]
            th = crossing(dd0, dda0, dd1, dda1, hh)
            crest = quintic(th, hh, d0, dd0, dda0, d1, dd1, dda1)
            # (a crest within gap_tol of the wall is a touch, not an impact; a crest at the
            # step's very end is the one the step was already shortened to; one closer than the
            # smallest step to the start is left to the next step, never declared here)
            if crest > gap_tol and 0.0 < th < min(theta, 1.0 - KINK_RESOLUTION) \
                    and th * hh >= settings.h_min:
                theta = th
                c_min = c
    return theta, c_min, event_now


@njit(cache=True, inline="always")
def any_closed(c_closed):
    for c in range(c_closed.size):
        if c_closed[c]:
            return True
    return False


@njit(cache=True, inline="always")
def declare_event(c, t, hh, h, model, state, settings, work, rec):
    """An event at the committed state (time ``t``): contact ``c``'s gap closed while it was
    already touching, or its crossing is closer than the smallest step. Open (or close) the
    episode there, restart, and return the step to redo (``h`` unless an episode opened)."""
    sample_before_event(t, model, state, settings, rec)
    if state.c_closed[c]:
        close_episode(c, state)
    else:
        dd0 = contact_rate(model.c_B, c, state.v)
        open_episode(c, max(dd0, 0.0), state)
        h_contact, gap_tol = settings.h_contact, settings.gap_tol
        h = min(hh, first_contact_step(dd0, H_START * h_contact, h_contact, gap_tol))
    mark_last_sample(c, t, model, state, rec)
    restart(model, state, work)
    return h
