"""The friendly entry point: run a pounding model under a ground motion."""

import functools
import math

import numpy as np

from femoat.collapse import (
    CollapseCriteria,
    collapse_summary,
    runaway_limits,
    runaway_summary,
)
from femoat.bearings import registry as bearing_registry
from femoat.integration.settings import Integrator
from femoat.integration.solve import solve
from femoat.ground_motions.pair import RecordPair
from femoat.plan.model import PlanModel
from femoat.results.plan import PlanRunResult
from femoat.results import RunResult, impact_rows
from femoat.structure.pounding import PoundingModel
from femoat.units import G


@functools.lru_cache(maxsize=64)
def packed_model(model):
    """``model.pack()``, once per model: a suite runs each model under many records, and the
    solver copies what it changes (element and contact states) before integrating."""
    return model.pack()


def run(model, motion, integrator=None, extra_time=2.0, duration=None, u0=None, v0=None,
        progress=None, channels=None, collapse=None, history=True):
    """Integrate ``model`` under ``motion`` and return a :class:`~femoat.results.RunResult`.

    Parameters
    ----------
    model : PoundingModel or PlanModel
        Building and moat walls: along one axis, or in plan (:mod:`femoat.plan`: the building
        in x and y, the coupled friction pendulum, a rectangular moat).
    motion : GroundMotion or RecordPair
        Ground acceleration record (femoat.ground_motions), in g at interval dt [s]; for a
        PlanModel a :class:`~femoat.ground_motions.pair.RecordPair` (two components, applied
        together, turned by its angle). A plan run returns a
        :class:`~femoat.results.plan.PlanRunResult`.
    integrator : Integrator or None
        Integration settings (default: ``Integrator()``, the fifth-order step at rtol = 1e-5, or
        Newmark's on a velocity-dependent triple pendulum, :func:`axis_method`; a plan run:
        :func:`plan_method`'s).
    extra_time : float
        Free vibration after the record [s] (default 2 s, as in the paper study).
    duration : float or None
        Total analysis time [s]; overrides ``extra_time``.
    u0, v0 : arrays or None
        Initial relative displacements [in] and velocities [in/s] per DOF (``model.dof_names()``).
    progress : callable or None
        progress(t, duration) is called as the run advances.
    channels : iterable of str or None
        Histories to record (see :data:`femoat.integration.solve.CHANNELS`); None records all.
        Decimate the open phase with ``Integrator(record_every=k)``.
    history : bool
        False keeps no history (what a suite does; a plan run too): the peaks, the impact
        table, the energy balance, collapse and runaway are all kept inside the compiled loop
        and are the same as with a history; the result's history arrays have no rows and its
        history accessors raise (``channels`` must then be None).
    collapse : CollapseCriteria or None
        Limit states to check after every step (:mod:`femoat.collapse`); their first times are
        in ``result.collapse``, and the run ends at the first one unless ``collapse.stop`` is
        False. None: no criteria (``result.collapse`` is then None).

    Every run, with criteria or not, ends at the runaway bounds of :mod:`femoat.collapse` (a
    story drift of one story height, 10 × the isolator capacity): ``result.runaway`` then names
    the bound and the time. A record that would outgrow ``integrator.record_budget`` raises
    :class:`~femoat.integration.solve.RecordBudgetError`.
    """
    if channels is not None and not history:
        raise ValueError("channels names the histories to record; with history=False none "
                         "is recorded: leave channels at None.")
    plan = isinstance(model, PlanModel)
    if not (plan or isinstance(model, PoundingModel)):
        raise ValueError("model must be a PoundingModel (femoat.structure.pounding) or a "
                         "PlanModel (femoat.plan).")
    if plan and not isinstance(motion, RecordPair):
        raise ValueError("a PlanModel runs under a RecordPair (femoat.ground_motions.pair: "
                         "fema_p695_pair, read_at2_pair or RecordPair(x, y, angle)); for one "
                         "component, RecordPair(x, zeros) or the 1D model model.along('x').")
    if not plan and isinstance(motion, RecordPair):
        raise ValueError("a PoundingModel runs along x under one GroundMotion: give one "
                         "component (pair.x), or run the pair on a femoat.plan.PlanModel "
                         "(PlanBuilding.from_building(model.building) and a rectangular_moat).")
    bearing_registry.check_compiled(model.building.isolator)  # in this process's loop?
    if duration is None:
        if not (math.isfinite(extra_time) and extra_time >= 0):
            raise ValueError(f"extra_time = {extra_time!r} must be a time >= 0 [s].")
        duration = motion.duration + extra_time
    integ = integrator or (Integrator(method=plan_method(model)) if plan else
                           Integrator(method=axis_method(model)))
    packed = packed_model(model)
    kw = {} if channels is None else dict(channels=tuple(channels))
    limits, stop = _limits(model, packed, collapse)
    # the ground: one component [g] along x, or a pair's (x, y) as columns [in/s²]
    accel = np.ascontiguousarray(motion.accel_g.T) * G if plan else motion.accel
    hist = solve(packed, accel, motion.dt, duration, integ, u0=u0, v0=v0, progress=progress,
                 limits=limits, history=history, stop_at_limit=stop, **kw)
    laws = [w.law.kind for w in model.walls]
    if plan:
        info = dict(motion=motion.name, angle=float(motion.angle), scale=float(motion.scale),
                    motion_dt=float(motion.dt), duration=float(duration), method=integ.method,
                    rtol=integ.rtol, alpha=integ.alpha, laws=laws)
        arrays = dict(hist.arrays)
        arrays["bearing_force"] = np.zeros((arrays["time"].size, 0))
        meta = dict(impacts=impact_rows(hist.impacts, packed.c_names), stats=hist.stats,
                    energy=hist.energy, info=info)
        meta.update(_limit_summaries(limits, hist, packed, collapse))
        return PlanRunResult.from_arrays(arrays, packed, meta,
                                         running_peaks=None if history else hist.peaks)
    info = dict(motion=motion.name, motion_pga_g=float(motion.pga), motion_dt=float(motion.dt),
                duration=float(duration), method=integ.method, rtol=integ.rtol, alpha=integ.alpha,
                laws=laws,
                wall_damping=[getattr(w.wall, "damping_source", "modal") for w in model.walls])
    result = RunResult.from_history(hist, packed, info)
    result.meta.update(_limit_summaries(limits, hist, packed, collapse))
    return result


PLAN_METHOD = "ark5"
"""The default method of a plan run: the fifth-order step that carries each sliding bearing's
friction state (:mod:`femoat.integration.methods.ark5`), where every bearing kind of the model
declares a rate form; else :data:`PLAN_METHOD_PATH` (:func:`plan_method`). Its accuracy at the
default rtol against a converged run is measured by ``benchmarks/plan_speed.py``."""

PLAN_METHOD_PATH = "newmark"
"""The default method of a plan run on a bearing kind without a rate form (its friction state
follows each step's path: first order in an explicit step's stages, so the implicit step)."""


def plan_method(model):
    """The default method of a plan run of ``model`` (a :class:`~femoat.plan.PlanModel`):
    :data:`PLAN_METHOD` if its isolator kind declares a rate form that covers it (not a
    triple pendulum whose velocity-dependent friction leaves some surface at μ_fast = μ), else
    :data:`PLAN_METHOD_PATH`."""
    from femoat.bearings import registry

    iso = model.building.isolator
    kind = registry.kind_of(iso)
    if kind is None:  # no plan bearing (an elastic isolator): ark5 is dp5 there
        return PLAN_METHOD
    covered = registry.rate_form_covers(registry.kinds()[kind], iso.params())
    return PLAN_METHOD if covered else PLAN_METHOD_PATH


def axis_method(model):
    """The default method of a 1D run of ``model`` (a
    :class:`~femoat.structure.pounding.PoundingModel`): the Integrator's own, or
    :data:`PLAN_METHOD_PATH` (Newmark) on an isolator that reads each step's duration (a triple
    pendulum's velocity-dependent friction, :func:`femoat.bearings.registry.reads_duration`)."""
    from femoat.bearings import registry

    iso = model.building.isolator
    kind = registry.kind_of(iso)
    if kind is not None and registry.reads_duration(registry.kinds()[kind], iso.params()):
        return PLAN_METHOD_PATH
    return Integrator().method


def _limits(model, packed, collapse):
    """(the limit rows of a run: the criteria's, then the runaway bounds; whether the run stops
    at its first criterion)."""
    limits = runaway_limits(model, packed)
    if collapse is None:
        return limits, False
    if not isinstance(collapse, CollapseCriteria):
        raise ValueError("collapse must be a CollapseCriteria (femoat.collapse) or None.")
    return collapse.limits(model, packed) + limits, collapse.stop


def _limit_summaries(limits, hist, packed, collapse):
    """{"runaway": ..., "collapse": ...}: what a result's meta says of its limit rows (each
    only when it applies)."""
    out = {}
    runaway = runaway_summary(limits, hist.limit_times, packed)
    if runaway is not None:
        out["runaway"] = runaway
    if collapse is not None:
        out["collapse"] = collapse_summary(limits, hist.limit_times, hist.stopped_at_limit,
                                           collapse.names)
    return out
