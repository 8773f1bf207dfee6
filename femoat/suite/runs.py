"""Runs of a suite: their identity, one run as a table row, and the tasks workers run.

A run is (record, variation, intensity); in a plan suite the record is a pair at one angle. Its
``run_id`` is a hash of the suite hash, the record, the variation and the intensity (``repr`` of
the float, exact), so it is stable across processes and reruns: resuming skips every stored
run_id. A task is a :class:`Batch` of runs at fixed intensities or a :class:`Trace` (one IDA
curve by hunt-and-fill); ``task.run(suite, out_dir)`` returns its rows. Worker processes keep
each variation (:func:`femoat.suite.model.build_variation`) and each record
(:func:`femoat.suite.records.load_motion`) in a per-process cache and return only scalars, one
dict per run: a row of the table, its columns read by :mod:`femoat.suite.columns`.
"""

import hashlib
import math
import time
from pathlib import Path
from typing import NamedTuple

from femoat.suite import columns as cols
from femoat.suite import variations as var
from femoat.suite.huntfill import Outcome, hunt_fill
from femoat.suite.model import build_variation, run_variation
from femoat.suite.records import applied


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


def hunt_settings(suite):
    """The keyword arguments of :func:`~femoat.suite.huntfill.hunt_fill` for a trace of
    ``suite``: ``[scaling]``'s, with the suite's walls when it brackets the onsets of pounding
    (``pounding_onsets``, default false; 1D: pos, neg; plan: px, mx, py, my)."""
    hunt = dict(suite.scaling.hunt)
    onsets = hunt.pop("pounding_onsets", False)
    return {**hunt, "walls": tuple(suite.walls) if onsets else ()}


def outcome(suite, row):
    """The :class:`~femoat.suite.huntfill.Outcome` of a run's row (:func:`run_one`): whether
    it did not survive (status not 'ok': a collapse, a solver failure, an error) and the walls
    it pounded on (``impacts_<wall>`` > 0; None, a run that did not finish, counts as none)."""
    return Outcome(row["status"] != "ok",
                   frozenset(w for w in suite.walls if (row.get(f"impacts_{w}") or 0) > 0))


def trace_key(suite, rec, var_index):
    """(record label, variation label) of a trace: how its stored runs are found."""
    return suite.records[rec].label, var.label(suite.combos[var_index])


class Batch(NamedTuple):
    """A task: runs at fixed intensities, one after the other."""

    specs: tuple  # RunSpec

    @property
    def units(self):
        """Units of work for the progress: runs."""
        return len(self.specs)

    def run(self, suite, out_dir=None):
        """Run every spec; return their rows. ``out_dir`` receives requested histories."""
        return [run_one(suite, s, out_dir) for s in self.specs]


class Trace(NamedTuple):
    """A task: one IDA curve, of record ``rec`` and variation ``var``, by hunt-and-fill."""

    rec: int
    var: int
    stored: dict  # run_id -> Outcome: its runs already in the table

    @property
    def units(self):
        """Units of work for the progress: one trace."""
        return 1

    def run(self, suite, out_dir=None):
        """Trace the curve; return the rows of the runs it made. A run that collapsed, failed
        to converge or raised counts as "did not survive"."""
        rows = []

        def run(im):
            s = spec(suite, self.rec, self.var, im)
            if s.run_id in self.stored:
                return self.stored[s.run_id]
            row = run_one(suite, s, out_dir)
            rows.append(row)
            return outcome(suite, row)

        hunt_fill(run, **hunt_settings(suite))
        return rows


# ---- worker side ------------------------------------------------------------------------------
_VARIATIONS = {}
_FIELDS = {}


def _fields(suite):
    """The table's columns (:func:`femoat.suite.columns.fields`), once per suite and process."""
    if suite.hash not in _FIELDS:
        _FIELDS[suite.hash] = cols.fields(suite)
    return _FIELDS[suite.hash]


def models(suite):
    """Every variation's model (1D or plan), in variation order, built once per process."""
    return [_variation(suite, v).pounding for v in range(len(suite.combos))]


def _variation(suite, var_index):
    key = (suite.hash, var_index)
    if key not in _VARIATIONS:
        tables = var.apply(suite.tables, suite.combos[var_index])
        _VARIATIONS[key] = build_variation(tables, suite.stop_on_collapse, Path(suite.base_dir))
    return _VARIATIONS[key]


def warm(suite):
    """Build every variation and load the first record (for a FEMA P695 suite, its whole set)
    in this process, so that the first runs do not pay for it."""
    from femoat.suite.definition import code_version
    from femoat.suite.records import load_motion

    if code_version() != suite.code:
        raise RuntimeError(f"this worker runs femoat {code_version()}, the suite was defined "
                           f"with {suite.code}: install the same femoat on every worker.")
    for v in range(len(suite.combos)):
        _variation(suite, v)
    for component in getattr(suite.records[0], "components", suite.records[:1]):
        load_motion(component)


def run_one(suite, s, out_dir=None):
    """Run ``s``; return its row. Failures become rows (status, error), never exceptions."""
    from femoat.integration.solve import SolverError

    clock = time.thread_time()
    fields = _fields(suite)
    at = cols.planned(suite, s)
    row = {**cols.planned_values(fields, at), **cols.failed_values(fields)}
    try:
        variation = _variation(suite, s.var)
        motion = applied(at.record, at.factor, suite.time_scale, suite.duration)
        keep = out_dir is not None and s.run_id in suite.histories
        result = run_variation(variation, motion, suite.extra_time, history=keep)
        row.update(cols.result_values(fields, result))
        if keep:
            result.save(Path(out_dir) / "histories" / f"{s.run_id}.npz")
    except SolverError as exc:
        row.update(status="solver_failure", error=f"run {s.run_id} ({_describe(at)}): {exc}")
    except Exception as exc:  # noqa: BLE001 - a failing run is stored, the suite goes on
        row.update(status="error",
                   error=f"run {s.run_id} ({_describe(at)}): {type(exc).__name__}: {exc}")
    row["cpu_seconds"] = time.thread_time() - clock
    return row


def failed_row(suite, s, exc):
    """The row of a run whose task failed outside :func:`run_one` (e.g. its worker died)."""
    fields = _fields(suite)
    at = cols.planned(suite, s)
    return {**cols.planned_values(fields, at), **cols.failed_values(fields), "status": "error",
            "error": f"run {s.run_id} ({_describe(at)}): its task failed on the cluster "
            f"({type(exc).__name__}: {exc}), e.g. the run kills its worker",
            "cpu_seconds": math.nan}


def _describe(at):
    sc = at.suite.scaling
    return (f"{at.record.record_name} ({at.record.label}) x {at.factor:.6g}, "
            f"{sc.im_kind} {at.spec.im:.6g} g, {var.label(at.suite.combos[at.spec.var])}")
