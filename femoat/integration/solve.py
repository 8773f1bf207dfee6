"""Run the compiled loop on a packed model: validation, buffers, status → exceptions."""

import functools
import math
import os
import time as _time
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from femoat.bearings import registry as bearing_registry
from femoat.integration import codes, methods
from femoat.integration.bundles import FSAL_ROWS, Model, Recorder, Settings, State, Work
from femoat.integration.limits import pack_limits
from femoat.integration.methods import N_STAGES
from femoat.integration.recording import channels as registry
from femoat.integration.recording.episodes import N_EP, N_IMPACT
from femoat.integration.recording.peaks import size as pk_size
from femoat.integration.recording.recorder import RING_ROWS
from femoat.integration.settings import Integrator
from femoat.structure.materials.codes import BEARING
from femoat.structure.roles import ISOLATOR, STORY
from femoat.units import G


class SolverError(RuntimeError):
    """The time stepping could not continue; the message says where and what to change."""


class RecordBudgetError(SolverError):
    """The recorded histories would outgrow ``Integrator.record_budget``: the run was ended
    before it could exhaust the machine's memory."""


@dataclass
class History:
    """What the loop kept: the histories trimmed to the samples recorded, and what it kept
    without a history (peaks, impacts, energies, counters, limit times)."""

    arrays: dict
    """{channel: array}, one row per recorded sample (t = 0 first), the channels of
    :mod:`femoat.integration.recording.channels` (no rows when the run kept no history);
    units there."""
    stats: dict
    energy: dict
    limit_times: np.ndarray
    """First time [s] each row of ``limits`` was exceeded (NaN: never), in their order."""
    stopped_at_limit: bool
    """The run ended at a limit: a runaway row, or a criterion row with ``stop_at_limit``."""
    peaks: np.ndarray
    """The running peaks of the continuous solution
    (:mod:`femoat.integration.recording.peaks`)."""
    impacts: np.ndarray
    """The impact episodes kept in the loop (:mod:`femoat.integration.recording.episodes`),
    one row each in the order they ended, columns ``episodes.IMPACT_FIELDS``."""


CHANNELS = registry.GROUPS


def solve(packed, ag, dt_rec, duration, integrator=None, u0=None, v0=None, progress=None,
          chunks=None, lazy=True, channels=CHANNELS, limits=None,
          stop_at_limit=False, history=True):
    """Integrate ``packed`` under ground acceleration ``ag`` [in/s²] sampled at ``dt_rec`` [s].

    Parameters
    ----------
    packed : PackedModel
        A model's arrays (:meth:`PoundingModel.pack <femoat.structure.pounding.PoundingModel.pack>`
        on one axis, :meth:`PlanModel.pack <femoat.plan.model.PlanModel.pack>` in plan).
    ag : array
        Ground acceleration samples [in/s²] at t = k·dt_rec: (samples,) on one axis (or
        (samples, 1)), (samples, 2) in plan (x, y).
    dt_rec : float
        Sample interval of ``ag`` [s].
    duration : float
        Length of the analysis [s] (may exceed the record; a_g = 0 afterwards).
    integrator : Integrator
    u0, v0 : arrays or None
        Initial relative displacements [in] and velocities [in/s].
    progress : callable or None
        Called as progress(t, duration) after each chunk.
    channels : iterable of str
        Which histories to record, among :data:`CHANNELS` (the groups of
        :mod:`femoat.integration.recording.channels`); displacements and contacts are always
        recorded. Unrequested channels are not written at all (their arrays come back with zero
        columns).
    history : bool
        False keeps no history: the recorder is a ring of the last few samples that the running
        peaks and the impact episodes read (both kept inside the loop), every history array
        comes back with no rows, and ``channels`` is not read.
    lazy : bool
        Skip the wall DOFs in the Newton elimination while no contact carries force (exact: the
        walls are then uncoupled linear oscillators). False solves the full system every step
        (for measuring what the lazy path saves).
    limits : sequence of Limit or None
        Limit states checked after every accepted step (:mod:`femoat.integration.limits`):
        the first time each row is exceeded is recorded, and a runaway row ends the run. None
        checks nothing (:func:`femoat.run.run` always gives the runaway bounds of
        :mod:`femoat.collapse`).
    stop_at_limit : bool
        End the run at the first step beyond a criterion row too (``History.stopped_at_limit``
        is then True, as after a runaway row).

    Returns the :class:`History`: :func:`integrate` without its status, raising instead.

    Raises
    ------
    SolverError
        The stepping cannot continue (the message says where and what to change);
        :class:`RecordBudgetError` when the recorded histories would outgrow
        ``integrator.record_budget``.
    """
    hist, status = integrate(packed, ag, dt_rec, duration, integrator, u0=u0, v0=v0,
                             progress=progress, chunks=chunks, lazy=lazy, channels=channels,
                             limits=limits, stop_at_limit=stop_at_limit,
                             history=history)
    if status.error is not None:
        raise status.error(status.message)
    return hist


class Status(NamedTuple):
    """How a run ended (:func:`integrate`)."""

    code: str
    """"done" (the whole duration), "limit" (a runaway row, or a criterion row with
    ``stop_at_limit``), "failed" (no step converged at the smallest step), "stalled" (no step
    accepted while locating an event) or "budget" (the record outgrew its budget)."""
    t: float
    """The time reached [s]."""
    message: str
    """What happened and what to change ("" when the run ended normally)."""
    error: type | None
    """The exception :func:`solve` raises for it (None when the run ended normally)."""


def integrate(packed, ag, dt_rec, duration, integrator=None, u0=None, v0=None, progress=None,
              chunks=None, lazy=True, channels=CHANNELS, limits=None,
              stop_at_limit=False, history=True):
    """(:class:`History`, :class:`Status`): :func:`solve` (the same parameters) without
    raising when the stepping cannot continue: the history, peaks, impacts and energies up
    to the time reached, and the status saying why it stopped. Bad input still raises
    ``ValueError``."""
    from femoat.bearings import registry
    from femoat.compilation.compile_plan import helper_while_compiling
    from femoat.compilation.numba_cache import first_compile_lock

    # this process's first run: compile or load alone, a helper compiling beside it if cold
    loop_kinds = ",".join(registry.keys()[k] for k in registry.compiled_kinds())
    with (first_compile_lock(_DRIVER_FILE),
          helper_while_compiling(loop_kinds, lambda: kernels().run_chunk)):
        return _integrate(packed, ag, dt_rec, duration, integrator, u0, v0, progress, chunks,
                          lazy, channels, limits, stop_at_limit, history)


_DRIVER_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "driver.py")
"""The compiled loop's module: numba's cache beside it holds the compile lock."""


def _integrate(packed, ag, dt_rec, duration, integrator, u0, v0, progress, chunks, lazy, channels,
               limits, stop_at_limit, history):
    kern = kernels()
    integ = integrator or Integrator()
    packed, ag, u, v = _inputs(packed, ag, dt_rec, duration, u0, v0)
    settings = _settings(packed, integ, ag, dt_rec, duration, limits, lazy, stop_at_limit,
                         history)
    model, state, work = _bundles(packed, ag, u, v, settings)
    start = _start(kern, packed, model, state, settings, work, channels, history, integ,
                   duration, u0, v0)
    cpu0 = _time.process_time()
    status, rec = _advance(kern, model, state, settings, work, start.rec, integ, duration,
                           progress, chunks, packed, history)
    kern.finish_peaks(model, state, settings, rec)
    kern.finish_episodes(state, rec)
    cpu = _time.process_time() - cpu0
    return _history(kern, packed, model, state, rec, start, history, status,
                    cpu), status


class _Start(NamedTuple):
    """What the loop starts from besides the bundles: the initial row of each channel that the
    recorder does not hold (the ``initial`` fields of
    :mod:`~femoat.integration.recording.channels`), the initial energy, the recorder."""

    t: float
    u: np.ndarray
    v: np.ndarray
    a: np.ndarray
    ag: float
    el_f: np.ndarray
    el_d: np.ndarray
    indentation: np.ndarray
    energy: float
    rec: Recorder
    sizes: dict


def _inputs(packed, ag, dt_rec, duration, u0, v0):
    """The validated inputs: (packed in the kernels' layout, ag as float array, u, v)."""
    packed = _canonical(packed)
    components = packed.R.shape[1]
    ag = np.array(ag, dtype=float)
    if components == 1 and ag.ndim == 1:
        ag = ag[:, None]
    if (ag.ndim != 2 or ag.shape[0] < 2 or ag.shape[1] != components
            or not np.all(np.isfinite(ag))):
        raise ValueError(
            "ag must be a 1-D array of at least 2 finite accelerations [in/s²]" if components == 1
            else f"ag must be an array (samples, {components}) of finite accelerations [in/s²], "
                 "one column per ground component (x, y), at least 2 samples.")
    ag = np.ascontiguousarray(ag)
    if not (math.isfinite(dt_rec) and dt_rec > 0):
        raise ValueError(f"dt_rec = {dt_rec!r} must be a positive sample interval [s].")
    if not (math.isfinite(duration) and duration > 0):
        raise ValueError(f"duration = {duration!r} must be a positive time [s].")
    n = packed.n
    u = np.zeros(n) if u0 is None else np.array(u0, dtype=float)
    v = np.zeros(n) if v0 is None else np.array(v0, dtype=float)
    if u.shape != (n,) or v.shape != (n,) or not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
        raise ValueError(f"u0 and v0 must be finite arrays of length {n} ({packed.dof_names}).")
    return packed, ag, u, v


def _settings(packed, integ, ag, dt_rec, duration, limits, lazy, stop_at_limit, history):
    """The :class:`Settings` bundle: the method and its options by name, error scales, limit
    rows."""
    n = packed.n
    scale_open, scale_contact, err_ref, scale_accel = error_scales(packed, np.abs(ag).max())
    d_me = float(scale_contact[0])
    episode_dofs, episode_floor, episode_tighten = episode_scaling(integ, scale_open,
                                                                   scale_contact)
    # first step after closure: a fraction of the local contact half-period π·√(m/k_eff)
    h_contact = math.inf
    for c, w in enumerate(packed.walls):
        m_local = min(packed.M[0, 0], min(packed.M[i, i] for i in range(packed.n_struct, n)
                                          if packed.c_B[c, i] != 0.0))
        h_contact = min(h_contact, math.pi * math.sqrt(m_local / w.law.params.k_eff))
    h_contact = h_contact / integ.contact_steps if math.isfinite(h_contact) else dt_rec

    n_explicit = _uncoupled_size(packed)  # the walls apart while the gaps are open (if they can be)
    method = methods.module(integ.method)
    if packed.bearing_dofs.size:
        _check_plan_method(integ.method, packed)
    _check_axis_method(integ.method, packed)
    return Settings(
        method=methods.CODES[integ.method], quintic_peaks=bool(method.QUINTIC_DENSE),
        beta=float(integ.beta), gamma=float(integ.gamma), alpha=float(integ.alpha),
        newton_tol=float(integ.newton_tol), max_newton=int(integ.max_newton),
        n_coupled=int(n_explicit if lazy else n), n_explicit=int(n_explicit),
        n_struct=int(packed.n_struct),
        rtol=float(integ.rtol),
        h_max=float(integ.max_step if integ.max_step is not None else dt_rec),
        h_min=float(integ.min_step), t_end=float(duration), dt_record=float(dt_rec),
        scale_open=scale_open, scale_contact=scale_contact, err_ref=err_ref,
        scale_accel=scale_accel,
        episode_dofs=episode_dofs, episode_floor=float(episode_floor),
        episode_tighten=float(episode_tighten),
        h_contact=float(h_contact), gap_tol=float(1e-3 * integ.rtol * d_me),
        record_every=int(integ.record_every), ring=not history,
        stop_at_limit=bool(stop_at_limit),
        limits=pack_limits(() if limits is None else tuple(limits), packed))


def _check_plan_method(name, packed):
    """Refuse an open-phase method that is first order on the plan bearings of ``packed``."""
    rated = [bearing_registry.has_rate_form(bearing_registry.kinds()[k])
             for k in np.unique(packed.bearing_kind)]
    if name in methods.EXPLICIT_PAIRS:
        raise ValueError(
            f"method = {name!r} on plan bearings: its explicit stages read a bearing's friction "
            "direction from a path guessed between stage values, which on a curved orbit is "
            "only first order in the step (a 1 % error in the peak base displacement at rtol "
            "1e-8). Use Integrator(method='ark5') (the fifth-order step that carries the "
            "friction state, the default of a plan run) or method='newmark'.")
    if name == "ark5" and not all(rated):
        kinds = ", ".join(bearing_registry.kinds()[k] for k, r in
                          zip(np.unique(packed.bearing_kind), rated) if not r)
        raise ValueError(
            f"method = 'ark5' on plan bearings without a rate form ({kinds}): their friction "
            "state would follow a path guessed between stage values (first order in the step). "
            "Use Integrator(method='newmark'), the default of a plan run on these bearings.")
    if name == "ark5":
        for k, p in zip(packed.bearing_kind, packed.bearing_P):
            kind = bearing_registry.kinds()[k]
            if not bearing_registry.rate_form_covers(kind, p):
                raise ValueError(
                    f"method = 'ark5' on a bearing its kind's rate form does not cover ({kind}: "
                    "a triple pendulum whose velocity-dependent friction leaves some surface at "
                    "μ_fast = μ): its friction would be a backward-Euler return over each stage "
                    "(first order in the step). Use Integrator(method='newmark'), the default "
                    "of a plan run on this bearing, or give every surface μ_fast > μ.")


def _check_axis_method(name, packed):
    """Refuse any method but Newmark's on a one-axis bearing that reads each step's duration
    (:func:`femoat.bearings.registry.reads_duration`; the loop gives it on Newmark's step)."""
    if name == "newmark":
        return
    for code, p in zip(packed.el_code, packed.el_P):
        if code < BEARING:
            continue
        kind = bearing_registry.kinds()[code - BEARING]
        if bearing_registry.reads_duration(kind, p):
            raise ValueError(
                f"method = {name!r} on a 1D isolator with velocity-dependent friction ({kind}): "
                "its friction is a backward-Euler return over each step, which a stage would "
                "take over the stage's offset (first order in the step), and only Newmark's "
                "solve gives it the step's duration. Use Integrator(method='newmark') (what "
                "femoat.run.run chooses for this bearing by default).")


def _bundles(packed, ag, u, v, settings):
    """(:class:`Model`, :class:`State`, :class:`Work`): the model read by the loop, working
    copies of the states it advances (the packed model stays reusable), its scratch."""
    n, n_explicit = packed.n, settings.n_explicit
    nel, ncon = packed.el_code.size, packed.c_code.size
    nb, nk = packed.bearing_dofs.shape[0], ag.shape[1]
    nq = bearing_registry.rate_width()
    model = Model(M=packed.M, C=packed.C, K=packed.K, r=packed.R, ag=ag,
                  dof_axis=packed.dof_axis, base_xy=_base_xy(packed), el_i=packed.el_i,
                  el_j=packed.el_j, el_code=packed.el_code, el_P=packed.el_P,
                  b_kind=packed.bearing_kind, b_dofs=packed.bearing_dofs, b_P=packed.bearing_P,
                  c_B=packed.c_B, c_gap=packed.c_gap, c_code=packed.c_code, c_P=packed.c_P,
                  c_T=packed.c_T, c_mu=packed.c_friction,
                  Minv=np.ascontiguousarray(np.linalg.inv(packed.M[:n_explicit, :n_explicit])))
    h0 = settings.h_max
    state = State(t=np.zeros(1), ag_now=np.zeros(nk),
                  u=u, v=v, a=np.zeros(n), F=np.zeros(n), el_S=packed.el_S.copy(),
                  el_f=np.zeros(nel), el_d=np.zeros(nel), el_W=np.zeros(nel),
                  b_S=packed.bearing_S.copy(), b_f=np.zeros((nb, 2)), b_W=np.zeros(nb),
                  c_H=packed.c_H.copy(), c_f=np.zeros(ncon), c_d=np.zeros(ncon),
                  c_W=np.zeros(ncon), c_ft=np.zeros(ncon), c_Wt=np.zeros(ncon),
                  c_closed=np.zeros(ncon, dtype=np.int64),
                  energy=np.zeros(codes.N_ENERGY), stats=np.zeros(codes.N_STATS, dtype=np.int64),
                  first_exceed=np.full(settings.limits.shape[0], -1.0),
                  pk=np.zeros(pk_size(packed.n_struct, ncon)), pk_ring=np.zeros((2, 3 * n + 1 + nk)),
                  pk_n=np.zeros(1, dtype=np.int64), ep=np.zeros((ncon, N_EP)),
                  h=np.array([h0]), h_cruise=np.array([h0]),
                  shortened=np.zeros(1, dtype=np.int64), landing=np.full(1, -1, dtype=np.int64),
                  since_record=np.zeros(1, dtype=np.int64))
    work = Work(u=np.zeros(n), v=np.zeros(n), a=np.zeros(n), F=np.zeros(n), KT=np.zeros((n, n)),
                CT=np.zeros((n, n)), A=np.zeros((n, n)), b=np.zeros(n), ef=np.zeros(nel),
                ed=np.zeros(nel), bf=np.zeros((nb, 2)), cf=np.zeros(ncon), cd=np.zeros(ncon),
                cft=np.zeros(ncon), ag1=np.zeros(nk), ag_stage=np.zeros(nk),
                k22=np.zeros((3, 2, 2)),
                kv=np.zeros((N_STAGES, n)), ka=np.zeros((N_STAGES, n)), eu=np.zeros(n),
                ev=np.zeros(n), de=np.zeros(codes.N_ENERGY),
                wexp=np.zeros((n, 4)), wexp_h=np.zeros(n), wscratch=np.zeros((4, 2, 2)),
                s_tmp=np.zeros(packed.el_S.shape[1]), b_rate=np.zeros(nb, dtype=np.int64),
                bz=np.zeros((nb, nq)), kz=_stage_rates_array(nb, nq),
                rq=np.zeros((4 + 2 * nq, nq + 1)))
    return model, state, work


def _stage_rates_array(nb, nq):
    """The work bundle's ``kz``: the stages' rates, then :data:`~femoat.integration.bundles.
    FSAL_ROWS` rows of NaN."""
    kz = np.zeros((N_STAGES + FSAL_ROWS, nb, nq))
    kz[N_STAGES:] = np.nan
    return kz


def _start(kern, packed, model, state, settings, work, channels_asked, history, integ,
           duration, u0, v0):
    """The initial equilibrium M·a0 = p0 − F(u0, v0), the running peaks and episodes started,
    the recorder: a :class:`_Start`."""
    n, nel, ncon = packed.n, packed.el_code.size, packed.c_code.size
    kern.ground_accel(model.ag, settings.dt_record, 0.0, state.ag_now)
    ag0 = state.ag_now.copy()
    kern.internal_force(model, state, work)
    state.a[:] = np.linalg.solve(packed.M, -(model.r * ag0[None, :]).sum(axis=1) - state.F)
    a_initial, el_f_initial, el_d_initial = (state.a.copy(), state.el_f.copy(),
                                             state.el_d.copy())
    kern.start_peaks(model, state, settings)
    for c in range(ncon):
        if state.c_d[c] > 0:
            raise ValueError(
                f"u0 puts the {packed.c_names[c]} wall in contact at t = 0 (indentation "
                f"{state.c_d[c]:.3g} in); start the base mat inside the gap.")

    e_initial = _initial_energy(kern, packed, model, state.u, state.v)
    sizes = dict(dofs=n, elements=nel, contacts=ncon, ground=ag0.size,
                 bearings=state.b_f.shape[0])
    cols = registry.columns(sizes, channels_asked, history)
    if history:
        # room for every record sample plus contact steps (grown by doubling when short, up to
        # the record budget); the fifth-order open phase takes 1-1.6 steps per sample, turning
        # points included
        per_sample = 2.0 if methods.module(integ.method).EXPLICIT else 1.2
        cap = min(int(per_sample * duration / settings.dt_record / integ.record_every)
                  + 1024, _max_rows(integ, cols))
    else:  # what the peaks and the episodes read: the last samples' contact channels
        cap = RING_ROWS
    rec = Recorder(*registry.buffers(cap, cols), np.zeros((IMPACT_ROWS + 3 * ncon, N_IMPACT)))
    kern.start_episodes(state)
    u_start, v_start = _initial_u(u0, n), _initial_u(v0, n)
    return _Start(t=0.0, u=u_start, v=v_start, a=a_initial, ag=ag0, el_f=el_f_initial,
                  el_d=el_d_initial, indentation=packed.c_B @ u_start - packed.c_gap,
                  energy=e_initial, rec=rec, sizes=sizes)


def _max_rows(integ, cols):
    """The most samples the record budget holds (buffer columns ``cols``)."""
    return int(integ.record_budget // registry.row_bytes(cols))


def _advance(kern, model, state, settings, work, rec, integ, duration, progress, chunks, packed,
             history):
    """Run the loop to the end, in chunks when there is a progress display, growing the
    recorder when it is short: (:class:`Status`, the recorder)."""
    # with a progress display the loop returns 20 times to report; without, it runs through
    if chunks is None:
        chunks = 20 if progress is not None else 1
    targets = np.linspace(0, duration, chunks + 1)[1:]
    k = 0
    while True:
        code = kern.run_chunk(targets[k], model, state, settings, work, rec)
        t = float(state.t[0])
        if code == codes.BUFFER_FULL:
            cap = rec.t.shape[0]
            if history and state.stats[codes.S_NOUT] >= cap:
                max_cap = _max_rows(integ, _columns(rec))
                if cap >= max_cap:
                    return Status("budget", t, _budget_message(t, duration, cap, integ),
                                  RecordBudgetError), rec
                rec = Recorder(*(registry.grown(arr, min(2 * cap, max_cap))
                                 for arr in rec[:-1]), rec.episodes)
            else:  # the impact table is short
                rec = rec._replace(episodes=registry.grown(rec.episodes,
                                                           2 * rec.episodes.shape[0]))
            continue
        if code in (codes.NEWTON_FAILED, codes.STEP_TOO_SMALL):
            stalled = code == codes.STEP_TOO_SMALL
            return Status("stalled" if stalled else "failed", t,
                          _failure_message(packed, t, state.u, state.v, state.c_closed, integ,
                                           stalled=stalled), SolverError), rec
        if progress is not None:
            progress(t, duration)
        if code == codes.DONE:
            return Status("done", t, "", None), rec
        if code == codes.LIMIT_REACHED:
            return Status("limit", t, "", None), rec
        k = min(k + 1, chunks - 1)


def _columns(rec):
    """{buffer: columns (None: one value per sample)} of the recorder ``rec``."""
    return {name: (None if arr.ndim == 1 else arr.shape[1])
            for name, arr in zip(registry.BUFFERS, rec)}


def _history(kern, packed, model, state, rec, start, history, status, cpu):
    """The :class:`History` of the run (its rows trimmed to the samples recorded)."""
    stats = state.stats
    m = stats[codes.S_NOUT]
    arrays = (registry.histories(rec, m, start) if history
              else registry.no_histories(start.sizes))
    return History(
        arrays=arrays,
        stats=dict(steps=int(stats[codes.S_STEPS]),
                   rejected_error=int(stats[codes.S_REJECT_ERR]),
                   rejected_newton=int(stats[codes.S_REJECT_NEWTON]),
                   newton_iterations=int(stats[codes.S_NEWTON]),
                   events=int(stats[codes.S_EVENTS]),
                   cpu_seconds=cpu, recorded=int(m) if history else 0, kernels="jit",
                   t_reached=float(state.t[0])),
        energy=_energy(kern, packed, model, state, start.energy),
        limit_times=np.where(state.first_exceed >= 0.0, state.first_exceed, np.nan),
        stopped_at_limit=status.code == "limit",
        peaks=state.pk.copy(),
        impacts=rec.episodes[:stats[codes.S_IMPACTS]].copy(),
    )


def _initial_u(u0, n):
    """The initial displacements [in] (zeros when not given)."""
    return np.zeros(n) if u0 is None else np.asarray(u0, dtype=float)


IMPACT_ROWS = 64
"""The impact table's first room [episodes] (doubled when short)."""


ACCELERATION_FRACTION = 0.15
"""While all gaps are open, a building DOF's acceleration error is measured against rtol times
this fraction of the record's peak ground acceleration (at least ACCELERATION_FLOOR): the
floors' higher modes carry little drift but much of the floor acceleration, and a drift scale
alone lets them run with too large steps. Proportional to the record, so that a weak record's
accelerations are as accurate, relative to their peaks, as a strong one's."""
ACCELERATION_FLOOR = 0.1 * G
"""[in/s²] The smallest PGA the acceleration scale is taken from: a record of zeros or a tiny
one (a run driven by its initial conditions) would otherwise ask for steps without bound
(they grow as PGA^(-1/3))."""


def error_scales(packed, pga):
    """(scale while all gaps are open, scale while a contact is closed, reference DOF) of each
    DOF's local error [in], and the scale of each building DOF's acceleration error [in/s²]
    (``inf`` for the walls), for a record of peak ground acceleration ``pga`` [in/s²].

    The error of a floor is measured on its story's drift (against the floor below,
    ``err_ref``), scaled by the story's yield drift: a story's response is judged on its own
    scale, not on the base's. The base mat and the walls are measured on their own coordinates,
    scaled by the gap while all gaps are open (a wall's ground-driven motion while open is small
    against its impact response and does not reach the building) and by δ_me, the contact's
    expected indentation, while a contact is closed.

    While all gaps are open, each building DOF's acceleration error, estimated from its
    displacement error e as (K_T·e)_i / m_i, is also held below rtol·ACCELERATION_FRACTION·pga.
    """
    n, ns = packed.n, packed.n_struct
    gaps = packed.c_gap
    gap_scale = float(np.max(gaps)) if gaps.size and np.max(gaps) > 0 else 1.0
    d_me = min((w.law.params.delta_me for w in packed.walls), default=gap_scale)
    scale_open = np.full(n, gap_scale)
    scale_contact = scale_open.copy()
    scale_contact[0] = d_me
    scale_contact[np.flatnonzero(np.any(packed.c_B[:, :ns] != 0.0, axis=0))] = d_me  # (in plan)
    scale_contact[ns:] = d_me
    err_ref = np.full(n, -1, dtype=np.int64)
    for role, i, j, mat in zip(packed.el_roles, packed.el_i, packed.el_j, packed.el_materials):
        if role.kind == STORY and j >= 0:
            err_ref[i] = j
            drift = mat.yield_deformation
            scale_open[i] = scale_contact[i] = min(gap_scale, drift) if drift else gap_scale
    scale_accel = np.full(n, np.inf)
    scale_accel[:ns] = ACCELERATION_FRACTION * max(pga, ACCELERATION_FLOOR)
    return scale_open, scale_contact, err_ref, scale_accel


EPISODE_FLOOR = 0.1
"""[-] The smallest episode scale, as a fraction of δ_me: an impact whose indentation stays below
it (a tenth of δ_me: a force of about 3 % of the law's reference impact for a Hertz law) is
held to that absolute error, so that a touch does not ask for ever smaller steps."""
EPISODE_TIGHTEN = 0.5
"""[-] The factor on the episode scale (measured: benchmarks/README.md, issue 26 item 2)."""


def episode_scaling(integ, scale_open, scale_contact):
    """(DOF flags, floor, factor) of the contact phase's episode scale: with an explicit open
    method, the local error of each DOF measured against δ_me while a contact is closed (the
    base mat and the walls) is measured instead against ``factor`` × the size of the smallest
    episode under way (its largest indentation so far, at least ``floor`` × δ_me, at most
    δ_me): a small impact's peak force is then controlled relative to itself, as a large one's
    (issue 26). Newmark keeps its scales (flags zero: bit for bit as before)."""
    flags = np.zeros(scale_open.size, dtype=np.int64)
    if not methods.module(integ.method).EXPLICIT:
        return flags, 1.0, 1.0
    flags[scale_contact < scale_open] = 1
    return flags, EPISODE_FLOOR, EPISODE_TIGHTEN


_INT_ARRAYS = ("el_i", "el_j", "el_code", "c_code", "bearing_kind", "bearing_dofs")
_FLOAT_ARRAYS = ("M", "C", "K", "R", "el_P", "el_S", "c_B", "c_gap", "c_P", "c_H",
                 "bearing_P", "bearing_S", "c_T", "c_friction")


def _canonical(packed):
    """``packed`` with its arrays as the compiled kernels take them: C-contiguous float64, int64
    codes and indices: one type per argument, so one compiled signature (a strided or read-only
    array would be another type to numba, compiled and cached again)."""
    changes = {}
    for names, dtype in ((_INT_ARRAYS, np.int64), (_FLOAT_ARRAYS, np.float64)):
        for name in names:
            a = getattr(packed, name)
            if a.dtype != dtype or not a.flags.c_contiguous:
                changes[name] = np.ascontiguousarray(a, dtype=dtype)
    return replace(packed, **changes) if changes else packed


def _base_xy(packed):
    """The base mat's x and y DOFs (2,) in plan, (−1, −1) on one axis (the kernels then keep no
    displacement in plan). A writable copy: a read-only array is another type to numba, another
    compiled signature."""
    base = packed.layout.floor_dofs[0, :2]
    return np.array(base if np.all(base >= 0) else (-1, -1), dtype=np.int64)


def kernels():
    """The namespace of the solver's compiled entry points
    (:data:`femoat.compilation.exports.EXPORTS`): numba's JIT kernels, compiled on first call
    or loaded from numba's on-disk cache."""
    return _jit_kernels()


@functools.lru_cache(maxsize=1)
def _jit_kernels():
    """The entry points (:data:`femoat.compilation.exports.EXPORTS`) as numba's JIT kernels."""
    from importlib import import_module
    from types import SimpleNamespace

    from femoat.compilation.exports import EXPORTS

    return SimpleNamespace(**{name: getattr(import_module(module), name)
                              for name, module in EXPORTS.items()})


def _uncoupled_size(packed):
    """Size of the block solved densely (Newmark) or stepped explicitly (dp5) while all
    contacts are open: the structural DOFs, if every wall DOF has a diagonal row and column in
    M, C and K; otherwise all DOFs."""
    n, ns = packed.n, packed.n_struct
    if ns == n:
        return n
    for A in (packed.M, packed.C, packed.K):
        W = A[ns:, ns:]
        if np.any(A[:ns, ns:]) or np.any(A[ns:, :ns]) or np.any(W - np.diag(np.diag(W))):
            return n
    return ns


def _quadratic(x, A):
    """xᵀ·A·x, correctly rounded sum of its terms x_i·A_ij·x_j (A_ij ≠ 0): the same bits on
    every machine (numpy's matrix products take machine-dependent SIMD paths and differ in the
    last bit; an exactly rounded sum does not depend on the order of its terms)."""
    x = np.asarray(x, dtype=float)
    return math.fsum(((x[:, None] * A) * x[None, :])[A != 0.0].tolist())


def _initial_energy(kern, packed, model, u, v):
    """Kinetic plus strain energy of the initial state [kip·in] (elements and plan bearings
    start virgin at u)."""
    e = 0.5 * _quadratic(v, packed.M) + 0.5 * _quadratic(u, packed.K)
    el, bearing = np.zeros(packed.el_code.size), np.zeros(model.b_kind.size)
    kern.initial_element_energies(packed.el_i, packed.el_j, packed.el_code, packed.el_P,
                                  packed.el_S, u, np.zeros(packed.el_S.shape[1]), el,
                                  model.b_kind, model.b_dofs, model.b_P, packed.bearing_S, v,
                                  np.zeros(packed.bearing_S.shape[1]), bearing)
    for x in el.tolist():
        e += x
    for x in bearing.tolist():
        e += x
    return float(e)


def _energy(kern, packed, model, state, e_initial):
    """The energy balance [kip·in] at the end of the run and its relative residual: the plan
    bearings' friction counts with the isolator's, the walls' friction with the contacts'."""
    u, v, el_S, el_W = state.u, state.v, state.el_S, state.el_W
    c_H, c_d, c_W, c_closed, energy = state.c_H, state.c_d, state.c_W, state.c_closed, state.energy
    kinetic = 0.5 * _quadratic(v, packed.M)
    linear_strain = 0.5 * _quadratic(u, packed.K)
    el_rec, c_rec = np.zeros(packed.el_code.size), np.zeros(packed.c_code.size)
    b_rec = np.zeros(model.b_kind.size)
    kern.stored_energies(packed.el_code, packed.el_P, el_S, packed.c_code, packed.c_P, c_H, c_d,
                         c_closed, el_rec, c_rec, model.b_kind, model.b_P, state.b_S, b_rec)
    el_diss = el_W - el_rec
    b_diss = state.b_W - b_rec
    iso = [e for e, role in enumerate(packed.el_roles) if role.kind == ISOLATOR]
    sto = [e for e, role in enumerate(packed.el_roles) if role.kind != ISOLATOR]
    out = dict(
        initial=e_initial,
        input=float(energy[codes.E_INPUT]),
        kinetic=float(kinetic),
        recoverable=math.fsum([linear_strain, *el_rec, *b_rec, *c_rec]),
        hysteretic=math.fsum(el_diss[sto]),
        friction=math.fsum([*el_diss[iso], *b_diss]),
        viscous=float(energy[codes.E_VISCOUS]),
        contact=math.fsum([*(c_W - c_rec), *state.c_Wt]),
    )
    accounted = sum(out[k] for k in ("kinetic", "recoverable", "hysteretic", "friction",
                                     "viscous", "contact"))
    supplied = out["initial"] + out["input"]
    scale = max(abs(supplied), abs(accounted))
    out["residual"] = float(abs(supplied - accounted) / scale) if scale > 0 else 0.0
    return out


def _budget_message(t, duration, cap, integ):
    return (
        f"The recorded histories reached Integrator(record_budget={integ.record_budget:g}) "
        f"bytes ({cap} samples) at t = {t:.6g} s of {duration:.6g} s: the run was ended there "
        "rather than exhausting the memory. The run needs more samples than that (very small "
        "steps: contact chattering, a structure running away below the runaway bounds? or a "
        "long duration): record fewer channels or Integrator(record_every=...), or raise "
        "record_budget if the machine has the memory."
    )


def _failure_message(packed, t, u, v, closed, integ, stalled=False):
    where = ", ".join(f"{packed.c_names[c]} wall in contact" for c in range(closed.size)
                      if closed[c]) or "all gaps open"
    if stalled:
        return (
            f"The solver stalled at t = {t:.6g} s ({where}; base displacement {u[0]:.4g} in, "
            f"velocity {v[0]:.4g} in/s): 100000 step attempts without accepting one, while "
            "locating a contact event. This is a solver defect; please report the scenario. "
            "A looser Integrator(rtol=...) usually steps past it."
        )
    if methods.module(integ.method).EXPLICIT and not closed.any():
        return (
            f"The explicit step of the open phase (method {integ.method!r}) gave no finite "
            f"state at "
            f"t = {t:.6g} s (all gaps open; base displacement {u[0]:.4g} in, velocity "
            f"{v[0]:.4g} in/s) even at the smallest step {integ.min_step:g} s: the building "
            "runs away faster than the runaway bounds of femoat.collapse end it (a negative "
            "story stiffness?)"
            + (", or the step's Newton solve of a plan bearing's friction state found no "
               "solution" if integ.method == "ark5" else "")
            + ". Check the element parameters, or try Integrator(method='newmark')."
        )
    return (
        f"The solver could not converge at t = {t:.6g} s ({where}; base displacement "
        f"{u[0]:.4g} in, velocity {v[0]:.4g} in/s) even at the smallest step "
        f"{integ.min_step:g} s. Check the contact and element parameters for extreme values, "
        "or relax Integrator(newton_tol=...) / raise max_newton."
    )
