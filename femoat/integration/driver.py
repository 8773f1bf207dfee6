"""The compiled time-stepping loop: adaptive steps by the open phase's method (Newmark/HHT-α
or the fifth-order explicit step, :mod:`femoat.integration.methods`; every contact phase by
Newmark/HHT-α), contact events located inside the step, element kinks landed on.

Everything here works on plain arrays grouped by role (:mod:`femoat.integration.bundles`:
model, state, settings, workspace, recorder) prepared by :func:`femoat.integration.solve.integrate`,
the friendly, validated API; nothing is allocated per step.

:func:`run_chunk` is the driver. Each step: choose the step's end (the controller,
:func:`~femoat.integration.controller._step_end`: never across a record sample), take the
trial step by the phase's method (``methods.step``; a step it cannot solve goes to
``methods.retry``), reject it when its error is above the tolerance, look for contact events
inside it (:func:`~femoat.integration.events.find_events`: a crossing shortens the step onto
it; one at the committed state opens or closes the episode there) and for element kinks
(:mod:`femoat.integration.kinks`), then accept it (:func:`~femoat.integration.commit.accept`),
choose the next step (``methods.next_step``, and the cruising step of an explicit method),
record (:func:`~femoat.integration.recording.recorder.record`) and check the limit states. The
helpers are inlined by numba (``inline="always"``): the bundles cost nothing at run time.

Model (relative to the ground, n DOFs)::

    M·ü + C·u̇ + K·u + Σ_e f_e(u_i − u_j, u̇_i − u̇_j)·(e_i − e_j) + Σ_c f_c(δ_c, δ̇_c)·b_c = −r·a_g(t)

with nonlinear two-node elements e (node j = −1 is the ground) and contacts c of indentation
δ_c = b_c·u − gap_c (compressive force f_c ≥ 0 pushes the bodies apart).
"""

from femoat.compilation.jit import njit
from femoat.integration import methods
from femoat.integration.codes import (
    BUFFER_FULL,
    DONE,
    LIMIT_REACHED,
    NEWTON_FAILED,
    S_IMPACTS,
    S_NOUT,
    S_REJECT_ERR,
    S_STEPS,
    STEP_TOO_SMALL,
    STOPPED,
)
from femoat.integration.commit import accept
from femoat.integration.controller import _step_end, _stop
from femoat.integration.events import (
    H_START,
    any_closed,
    declare_event,
    find_events,
    first_contact_step,
    restart,
)
from femoat.integration.forces import ground_accel
from femoat.integration.kinks import find_kink, find_turn
from femoat.integration.limits import CRITERION_EXCEEDED, RUNAWAY_EXCEEDED, check_limits
from femoat.integration.recording.recorder import record, record_sample
from femoat.integration.recording.rows import row


@njit(cache=True, inline="always")
def _limit_reached(t, model, state, settings):
    """Check the limit states (:mod:`femoat.integration.limits`) after an accepted step: does
    the run end here?"""
    hit = check_limits(t, settings.n_struct, model, state, settings.limits, state.first_exceed)
    return hit == RUNAWAY_EXCEEDED or (hit == CRITERION_EXCEEDED and settings.stop_at_limit)


@njit(cache=True, inline="always")
def _record_ends(state):
    """Whether the ground acceleration jumps to zero here (at the record's last sample, not
    zero: ``forces.ground_accel`` is zero after the record)."""
    for k in range(state.ag_now.size):
        if state.ag_now[k] != 0.0:
            return True
    return False


@njit(cache=True, inline="always")
def _recorded_at(t, state, rec):
    """Whether the last recorded sample is at time ``t``."""
    k = state.stats[S_NOUT]
    return k > 0 and rec.t[row(k - 1, rec.t.shape[0])] == t


@njit(cache=True, python=False)
def _record_end(t, model, state, work, settings, rec):
    """At the record's last sample (time ``t``), where the ground acceleration drops to zero:
    record that sample if a decimated record skipped it (the left limits), else restart from
    the drop and record the right limits (:func:`_after_the_record`). One sample per call (the
    loop checks the room before each). Its own compiled function: the recorder is inlined here
    once, not again into the loop."""
    if _recorded_at(t, state, rec):
        _after_the_record(t, model, state, work, settings, rec)
    else:
        record_sample(t, model, state, settings, rec)


@njit(cache=True, inline="always")
def _after_the_record(t, model, state, work, settings, rec):
    """At the record's last sample (time ``t``, recorded with the ground's left limit): the
    ground acceleration drops to zero, so the accelerations restart from it and the state is
    recorded again at ``t`` with these right limits (a second sample at one instant, as at an
    event). Without it the next step would ramp the ground from its last value to zero: a
    velocity error of a_g·h/2, which an explicit step's error estimate does not see (the
    ramp is linear inside the step) and which a fifth-order step's long steps make large. A
    Newmark open phase keeps the ramp (its runs stay bit for bit; its steps are short)."""
    for k in range(state.ag_now.size):
        state.ag_now[k] = 0.0
    restart(model, state, work)
    record_sample(t, model, state, settings, rec)


@njit(cache=True)
def run_chunk(t_stop, model, state, settings, work, rec):
    """Advance ``state`` from state.t[0] to min(t_stop, t_end), recording into ``rec``; return a
    status code (:mod:`femoat.integration.codes`)."""
    hmin, t_end = settings.h_min, settings.t_end
    h_contact, gap_tol = settings.h_contact, settings.gap_tol
    rec_every, open_method, ring = settings.record_every, settings.method, settings.ring
    # room for the episodes one loop pass can end and finish_episodes after the last
    impacts_room = rec.episodes.shape[0] - 3 * model.c_gap.size
    c_closed, stats = state.c_closed, state.stats
    t, h = state.t[0], state.h[0]
    t_goal = min(t_stop, t_end)  # this call returns after the first step reaching it
    stalls = 0
    h_cruise = state.h_cruise[0]  # an explicit method's step before landings and sample cuts
    shortened = state.shortened[0] == 1
    landing = state.landing[0]  # the contact whose located separation the shortened step lands on
    since_record = state.since_record[0]
    explicit_open = methods.EXPLICIT[open_method]
    t_record = (model.ag.shape[0] - 1) * settings.dt_record  # the record's last sample
    while t < t_goal * (1.0 - 1e-15) and t_goal - t > 1e-14:
        stalls += 1
        if stalls > 100000:  # no step accepted after 100000 attempts: report, don't spin
            return _stop(STEP_TOO_SMALL, t, h, h_cruise, shortened, landing, since_record, state)
        if (stats[S_NOUT] >= rec.t.size and not ring) or stats[S_IMPACTS] > impacts_room:
            return _stop(BUFFER_FULL, t, h, h_cruise, shortened, landing, since_record, state)
        if explicit_open and t == t_record and t < t_end and _record_ends(state):
            # the record's end: its sample (left limits) if a decimated record skipped it,
            # then the restart and its sample (right limits), each after the room check above
            _record_end(t, model, state, work, settings, rec)
            since_record = 0
            continue
        h_asked = h
        hh, t1 = _step_end(t, h, t_end, shortened, settings, model.ag.shape[0])
        ag1 = work.ag1
        ground_accel(model.ag, settings.dt_record, t1, ag1)
        closed_now = any_closed(c_closed)
        phase = methods.CONTACT if closed_now else open_method
        explicit_now = methods.EXPLICIT[phase]
        for e in range(work.b_rate.size):  # no bearing carries a friction state until a step
            work.b_rate[e] = 0             # of the coupled-friction method says so
        solved, err = methods.step(phase, hh, ag1, closed_now, model, state, settings, work)
        if not solved:
            h, failed = methods.retry(phase, t, hh, h, model, state, settings, work, rec)
            if failed:
                return _stop(NEWTON_FAILED, t, h, h_cruise, shortened, landing, since_record,
                             state)
            continue
        if err > 1.0 and hh > hmin:
            stats[S_REJECT_ERR] += 1
            h = max(hh * methods.shrink_factor(phase, err), hmin)
            continue
        theta, c_min, event_now = find_events(hh, explicit_now, model, state, settings, work)
        if event_now >= 0:  # closure at the committed state: start there, redo the step small
            h = declare_event(event_now, t, hh, h, model, state, settings, work, rec)
            continue
        if theta > 1.0 and not shortened:
            fine = methods.FINE_LANDING[phase]
            theta_k = find_kink(hh, model, state, work, fine)
            if explicit_now:
                theta_k = min(theta_k, find_turn(hh, model, state, work, fine))
            if theta_k < 1.0 and hh * theta_k >= hmin:
                stats[S_REJECT_ERR] += 1
                h = hh * theta_k
                shortened = True
                landing = -1
                continue
        if theta <= 1.0:
            # shorten by more than the time round-off, or the same step would repeat forever
            h_new = min(hh * theta, hh - 64.0 * 2.3e-16 * abs(t1))
            if h_new >= hmin:
                stats[S_REJECT_ERR] += 1
                h = h_new
                shortened = True
                landing = c_min if c_closed[c_min] else -1
            else:  # the crossing is closer than the smallest step: declare it where we are
                h = declare_event(c_min, t, hh, h, model, state, settings, work, rec)
            continue

        toggled, v_close = accept(hh, ag1, landing, explicit_now, model, state, settings, work)
        t = t1
        stalls = 0
        cut_short = shortened or hh < h_asked * (1.0 - 1e-12)
        shortened = False
        landing = -1
        if toggled:
            restart(model, state, work)
        stats[S_STEPS] += 1
        now_closed = any_closed(c_closed)
        h = methods.next_step(phase, hh, err, hmin)
        if explicit_now:
            # a step cut short (landed on a kink, a turning point or an event, or ending on a
            # sample) says nothing about the step the solution allows: resume the cruising
            # step (the error control rejects it once if it has become too long)
            if cut_short:
                h = max(h, h_cruise)
            else:
                h_cruise = h
        elif methods.EXPLICIT[open_method] and toggled and not now_closed:
            h = max(h, h_cruise)  # back to the open phase: its cruising step
        if toggled and now_closed:
            h = min(h, first_contact_step(v_close, H_START * h_contact, h_contact, gap_tol))
        since_record += 1
        if since_record >= rec_every or now_closed or closed_now or toggled or t >= t_end:
            since_record = 0
            record(t, model, state, settings, rec)
        if _limit_reached(t, model, state, settings):
            return _stop(LIMIT_REACHED, t, h, h_cruise, shortened, landing, since_record, state)
    return _stop(DONE if t >= t_end * (1.0 - 1e-15) or t_end - t <= 1e-14 else STOPPED, t, h,
                 h_cruise, shortened, landing, since_record, state)
