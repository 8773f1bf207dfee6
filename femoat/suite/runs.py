"""Runs of a suite: their identity, one run as a table row, and the task functions workers call.

A run is (record, variation, intensity). Its ``run_id`` is a hash of the suite hash, the record,
the variation and the intensity (``repr`` of the float, exact), so it is stable across processes
and reruns: resuming skips every stored run_id. Worker processes keep each variation's model
and each record (:func:`femoat.suite.records.load_motion`) in a per-process cache and return
only scalars, one dict per run (a row of the table, :mod:`femoat.suite.table`).
"""

import hashlib
import math
import time
from pathlib import Path
from typing import NamedTuple

import numpy as np

from femoat.suite import variations as var
from femoat.suite.huntfill import hunt_fill
from femoat.collapse import CRITERIA
from femoat.suite.model import build_model, run_model
from femoat.suite.records import applied_motion


class RunSpec(NamedTuple):
    """One run: record index, variation index and intensity [g] within a suite."""

    run_id: str
    rec: int
    var: int
    im: float


def run_id(suite, rec, var_index, im):
    """Stable id (16 hex digits) of a run of ``suite``."""
    key = f"{suite.hash}|{suite.records[rec].label}|{var.label(suite.combos[var_index])}|" \
          f"{suite.scaling.im_kind}|{float(im)!r}"
    return hashlib.sha256(key.encode()).hexdigest()[:16]


def spec(suite, rec, var_index, im):
    return RunSpec(run_id(suite, rec, var_index, im), rec, var_index, float(im))


def plan(suite):
    """Every run of a fixed-intensity suite (variation, record, intensity order)."""
    return [spec(suite, r, v, im) for v in range(len(suite.combos))
            for r in range(len(suite.records)) for im in suite.scaling.levels]


def traces(suite):
    """(record, variation) pairs of a hunt-and-fill suite, one IDA curve each."""
    return [(r, v) for v in range(len(suite.combos)) for r in range(len(suite.records))]


def trace_label(suite, rec, var_index):
    return f"{suite.records[rec].label}|{var.label(suite.combos[var_index])}"


# ---- worker side ------------------------------------------------------------------------------
_MODELS = {}


def _model(suite, var_index):
    key = (suite.hash, var_index)
    if key not in _MODELS:
        tables = var.apply(suite.tables, suite.combos[var_index])
        _MODELS[key] = build_model(tables, suite.stop_on_collapse, Path(suite.base_dir))
    return _MODELS[key]


def warm(suite):
    """Build every variation's model and load the first record (for a FEMA P695 suite, its
    whole set) in this process, so that the first runs do not pay for it."""
    from femoat.suite.definition import code_version
    from femoat.suite.records import load_motion

    if code_version() != suite.code:
        raise RuntimeError(f"this worker runs femoat {code_version()}, the suite was defined "
                           f"with {suite.code}: install the same femoat on every worker.")
    for v in range(len(suite.combos)):
        _model(suite, v)
    load_motion(suite.records[0])


def run_batch(suite, specs, out_dir=None):
    """Task: run ``specs``; return their rows. ``out_dir`` receives requested histories."""
    return [run_one(suite, s, out_dir) for s in specs]


def run_trace(suite, rec, var_index, stored, out_dir=None):
    """Task: trace one IDA curve by hunt-and-fill; return the rows of the runs it made.

    stored : dict run_id -> bool  runs already in the table (True: did not survive)
    A run that collapsed, failed to converge or raised counts as "did not survive".
    """
    rows = []

    def collapsed(im):
        s = spec(suite, rec, var_index, im)
        if s.run_id in stored:
            return stored[s.run_id]
        row = run_one(suite, s, out_dir)
        rows.append(row)
        return row["status"] != "ok"

    hunt_fill(collapsed, **suite.scaling.hunt)
    return rows


def run_one(suite, s, out_dir=None):
    """Run ``s``; return its row. Failures become rows (status, error), never exceptions."""
    from femoat.integration.solve import SolverError

    clock = time.thread_time()
    row = _identity(suite, s)
    try:
        model = _model(suite, s.var)
        motion = applied_motion(suite.records[s.rec], row["scale_factor"], suite.time_scale,
                                suite.duration)
        keep = out_dir is not None and s.run_id in suite.histories
        result, collapse = run_model(model, motion, suite.extra_time, history=keep)
        row.update(_outcome(suite, result, collapse, model))
        if keep:
            result.save(Path(out_dir) / "histories" / f"{s.run_id}.npz")
    except SolverError as exc:
        row.update(status="solver_failure", error=f"run {s.run_id} ({_describe(suite, s)}): {exc}")
    except Exception as exc:  # noqa: BLE001 - a failing run is stored, the suite goes on
        row.update(status="error",
                   error=f"run {s.run_id} ({_describe(suite, s)}): {type(exc).__name__}: {exc}")
    row["cpu_seconds"] = time.thread_time() - clock
    return row


def failed_row(suite, s, exc):
    """The row of a run whose task failed outside :func:`run_one` (e.g. its worker died)."""
    row = _identity(suite, s)
    row.update(status="error", error=f"run {s.run_id} ({_describe(suite, s)}): its task failed "
               f"on the cluster ({type(exc).__name__}: {exc}), e.g. the run kills its worker",
               cpu_seconds=math.nan)
    return row


def _describe(suite, s):
    r = suite.records[s.rec]
    return (f"{r.record_name} ({r.label}) x {suite.scaling.factor(s.rec, s.im):.6g}, "
            f"{suite.scaling.im_kind} {s.im:.6g} g, {var.label(suite.combos[s.var])}")


def _identity(suite, s):
    from femoat.suite.definition import code_version

    r, sc = suite.records[s.rec], suite.scaling
    factor = sc.factor(s.rec, s.im)
    row = dict(run_id=s.run_id, suite_hash=suite.hash, femoat_version=code_version(),
               record=r.label, variation=var.label(suite.combos[s.var]),
               record_set=r.record_set, record_id=r.record_id, rsn=r.rsn,
               record_name=r.record_name, component=r.component, earthquake=r.earthquake,
               magnitude=r.magnitude, distance_km=r.distance_km, pulse=r.pulse,
               scale_factor=factor, im_kind=sc.im_kind, im=s.im,
               sa_t=None if sc.sa[s.rec] is None else sc.sa[s.rec] * factor,
               pga=sc.pga[s.rec] * factor)
    row.update(suite.combos[s.var])
    row.update(status=None, error=None, collapsed=False)
    for c in CRITERIA:
        row[f"collapse_{c}"] = False
        row[f"collapse_{c}_time"] = math.nan
    return row


def _outcome(suite, result, collapse, model):
    p = result.peaks
    n = len(model.story_heights)
    drift = np.asarray(p["peak_drift"], dtype=float)
    ratio = np.asarray(p["peak_drift_ratio"], dtype=float)
    floor = p.get("peak_floor_acceleration")
    floor = [math.nan] * n if floor is None else floor
    out = dict(status="collapsed" if collapse["collapsed"] else "ok",
               collapsed=bool(collapse["collapsed"]))
    for c in CRITERIA:
        t = collapse.get(c)
        out[f"collapse_{c}"] = t is not None
        out[f"collapse_{c}_time"] = math.nan if t is None else float(t)
    out.update(peak_impact_force_pos=p["peak_impact_force_pos"],
               peak_impact_force_neg=p["peak_impact_force_neg"],
               impacts_pos=int(p["impacts_pos"]), impacts_neg=int(p["impacts_neg"]),
               peak_base_displacement=p["peak_base_displacement"])
    for side in ("pos", "neg"):  # NaN where there is no wall on that side
        out[f"peak_wall_displacement_{side}"] = p.get(f"peak_wall_displacement_{side}", math.nan)
    for k in range(suite.n_stories):
        inside = k < n
        out[f"peak_drift_{k + 1}"] = float(drift[k]) if inside else math.nan
        out[f"peak_drift_ratio_{k + 1}"] = float(ratio[k]) if inside else math.nan
        out[f"peak_floor_acceleration_{k + 1}"] = float(floor[k]) if inside else math.nan
    out.update(peak_drift_ratio=float(ratio.max(initial=0.0)),
               peak_base_acceleration=_nan_if_none(p.get("peak_base_acceleration")),
               pounding=bool(p["impacts_pos"] + p["impacts_neg"] > 0),
               t_reached=float(result.time[-1]),
               solver_seconds=float(result.meta["stats"]["cpu_seconds"]),
               steps=int(p["steps"]))
    return out


def _nan_if_none(x):
    return math.nan if x is None else float(x)
