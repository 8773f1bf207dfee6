"""Work-precision of femoat against OpenSees on the paper runs. A script, not a test.

    python benchmarks/work_precision.py            # 20 runs, full record: ~40 min on 2 cores
    python benchmarks/work_precision.py --quick    # 2 runs, first 4 s of the record: ~1 min
    python benchmarks/work_precision.py --reuse-opensees benchmarks/results/work_precision.csv
                                                   # 20 runs, OpenSees reused: ~1 min
    python benchmarks/work_precision.py --methods dp5   # one femoat method only

For each paper run (5 laws × concrete/steel wall × published/consistent C_imp) femoat runs with
each of its integration methods (--methods, default both: "newmark", implicit Newmark/HHT
throughout, and "dp5", Dormand-Prince 5(4) for the building while every gap is open) at several
accuracy settings (rtol: RTOLS plus the method's default), and its OpenSees twin
(femoat.opensees.building) at several fixed time steps. Each run's error is measured against one
converged reference for all tools and methods, femoat-newmark at rtol = 1e-8 (tool "femoat-ref"),
itself cross-checked against OpenSees at the finest step (dt = 1e-5 s, column "ref vs OS" of each
table), for six quantities: peak impact force, peak base displacement, peak wall displacement, the
largest impact impulse, the peak story drifts and the peak floor accelerations. The last two are
one value per story (floor k atop story k), and a run's error is the worst over the stories,
max_k |x_k − ref_k|/|ref_k| (relative to each story's own reference peak, so a small drift counts
as much as a large one); the other errors are |x − ref|/|ref|. femoat's drifts are peaks of the
continuous solution, its accelerations peaks at the step ends (dp5: also of its quintic interpolant
within the smooth open-phase steps); OpenSees' both at its samples.

Same problem for both tools: law V runs with ``allow_tension=True`` in both (OpenSees'
ViscoelasticGap pulls in tension; femoat's default V does not). CPU time is ``time.process_time``
of femoat's whole ``run()`` call (packing, compiled loop, impact table and peaks), measured after
a warm-up run of each method (numba compiled), and of OpenSees' ``analyze`` call with binary
recorders; runs under 1 s are repeated 3 times and the best is kept, for both tools alike.
--reuse-opensees takes OpenSees' points from an earlier CSV of the same record and runs (keyed by
run and dt only: not with --quick and a full-record CSV).

Speed ratio at equal error: OpenSees' CPU time at femoat's error, interpolated log-log along
OpenSees' work-precision front (the points no cheaper point beats: the most favourable reading for
OpenSees, whose error is not monotone in dt). Outside OpenSees' range the ratio is a bound (≥ when
femoat is more accurate than OpenSees' finest step, ≤ when OpenSees' coarsest converged step is
already more accurate than femoat).

Writes benchmarks/results/work_precision.csv (every point, tool "femoat-ref", "femoat-newmark",
"femoat-dp5" or "opensees", method "newmark", "dp5" or empty for OpenSees; the drifts and floor
accelerations as peak_drift_k and peak_floor_acceleration_k, k = 1…3, their errors as err_drift
and err_a_fl, the worst over the stories) and work_precision.png (CPU time against error, one
panel per quantity and wall/C_imp, one line per tool and run: colour the tool, marker the law),
atomically (--quick: work_precision_quick.*); prints one table per quantity (a line per run and
femoat method), the targets of issue 15 per method (CPU per paper run at the method's default rtol
≤ 5 ms; OpenSees' CPU at equal error ≥ 100x femoat's on every quantity and run) and, last, one line
per quantity and method with the range over the runs of femoat's error at the method's default
rtol and of the ratio.
"""

import argparse
import csv
import io
import math
import os
import sys
import time
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

from femoat.atomic import atomic_path, write_text  # noqa: E402
from femoat.contact.laws import make_law  # noqa: E402
from femoat.ground_motions import GroundMotion  # noqa: E402
from femoat.integration import Integrator  # noqa: E402
from femoat.integration.settings import DEFAULT_RTOL as METHOD_RTOL, METHODS  # noqa: E402
from femoat.paper import LAWS, WALLS, paper_motion  # noqa: E402
from femoat.run import run  # noqa: E402
from femoat.structure.building import Building  # noqa: E402
from femoat.structure.pounding import MoatWall, PoundingModel  # noqa: E402
from femoat.walls.presets import DAMPING_CHOICES, wall_preset  # noqa: E402

RTOLS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)  # each method runs at these and at its own default
REF_RTOL = 1e-8
REF_METHOD = "newmark"  # the reference of every tool and method: femoat-newmark at REF_RTOL
DTS = (1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5)
QUANTITIES = ("peak_impact_force", "peak_base_displacement", "peak_wall_displacement",
              "peak_impulse", "peak_drift", "peak_floor_acceleration")
PER_STORY = ("peak_drift", "peak_floor_acceleration")  # lists, one value per story (floor)
N_STORIES = len(Building().stories)
SHORT = {"peak_impact_force": "F", "peak_base_displacement": "u_b",
         "peak_wall_displacement": "w", "peak_impulse": "I", "peak_drift": "drift",
         "peak_floor_acceleration": "a_fl"}
LABEL = {"peak_impact_force": "peak-force", "peak_drift": "worst story drift",
         "peak_floor_acceleration": "worst floor acceleration"}
TARGET_ERROR = 5e-3      # 0.5 %: column "worst ≤0.5%", the worst ratio over settings within it
TARGET_RATIO = 100.0     # issue 15: OpenSees' CPU at equal error ≥ 100x femoat's, every quantity
TARGET_CPU = 0.005       # [s] per paper run after compilation (issue 15)
REPEAT_BELOW = 1.0       # [s]: runs cheaper than this are timed best of 3
OUT = Path(__file__).resolve().parent / "results"


def benchmark_model(wall, law, damping):
    """The paper model with the law OpenSees has too (V with tension allowed)."""
    preset = wall_preset(wall, damping=damping)
    options = {"allow_tension": True} if law == "V" else {}
    contact = make_law(law, preset.contact, **options)
    walls = tuple(MoatWall(contact, preset.wall, 4.0, side) for side in (1, -1))
    return PoundingModel(Building(), walls)


def _timed(fn):
    """(result, CPU seconds): best of 3 when one call takes less than REPEAT_BELOW."""
    t0 = time.process_time()
    out = fn()
    best = time.process_time() - t0
    if best < REPEAT_BELOW:
        for _ in range(2):
            t0 = time.process_time()
            out = fn()
            best = min(best, time.process_time() - t0)
    return out, best


def method_rtols(method):
    """The rtols ``method`` runs at: RTOLS and its default, loosest first."""
    return tuple(sorted({*RTOLS, METHOD_RTOL[method]}, reverse=True))


def femoat_point(model, motion, duration, rtol, method=REF_METHOD):
    from femoat.integration import SolverError

    integrator = Integrator(method=method, rtol=rtol)
    try:
        res, cpu = _timed(lambda: run(model, motion, integrator, duration=duration))
    except SolverError as exc:  # a result too: recorded, not fatal
        return dict(status=f"SolverError: {exc}"[:120], cpu=math.nan, steps=0, impacts=0,
                    energy_residual=math.nan, **{q: math.nan for q in QUANTITIES})
    p = res.peaks
    return dict(status="ok", cpu=cpu, steps=p["steps"], impacts=p["impacts_pos"] + p["impacts_neg"],
                energy_residual=p["energy_residual"], **{q: p[q] for q in QUANTITIES})


def opensees_point(model, motion, duration, dt):
    from femoat.opensees import OpenSeesFailure, opensees_run

    try:
        res, _ = _timed(lambda: opensees_run(model, motion, dt, duration=duration))
    except OpenSeesFailure as exc:
        return dict(status=f"{exc.kind} at t = {exc.time:.4g} s", cpu=math.nan, steps=exc.step,
                    impacts=0, energy_residual=math.nan, **{q: math.nan for q in QUANTITIES})
    p = res["peaks"]
    return dict(status="ok", cpu=res["cpu_seconds"], steps=p["steps"],
                impacts=p["impacts_pos"] + p["impacts_neg"], energy_residual=math.nan,
                **{q: p[q] for q in QUANTITIES})


def _front(points):
    """Work-precision front of [(cpu, err, setting)]: the points no cheaper point beats."""
    front = []
    for c, e, s in sorted(p for p in points if math.isfinite(p[0]) and p[1] > 0):
        if not front or e < front[-1][1]:
            front.append((c, e, s))
    return front


def cpu_at_error(points, err):
    """(CPU [s], setting, bound) to reach ``err`` on the front of ``points``, interpolated
    log-log; bound is "=", ">=" (err below the front) or "<=" (the cheapest point is enough)."""
    front = _front(points)
    if not front or not err > 0:
        return math.nan, math.nan, "?"
    if err >= front[0][1]:
        return front[0][0], front[0][2], "<="
    if err < front[-1][1]:
        return front[-1][0], front[-1][2], ">="
    for (c0, e0, s0), (c1, e1, s1) in zip(front, front[1:]):
        if e0 >= err >= e1:
            w = math.log(err / e0) / math.log(e1 / e0)
            return (math.exp(math.log(c0) + w * math.log(c1 / c0)),
                    math.exp(math.log(s0) + w * math.log(s1 / s0)), "=")
    return math.nan, math.nan, "?"


def label(quantity):
    """The quantity's name in the tables: "peak-force", "worst story drift", ..."""
    return LABEL.get(quantity, quantity.replace("_", " "))


def rel_error(x, ref):
    """|x − ref|/|ref|; for a per-story quantity (lists) the worst over the stories,
    max_k |x_k − ref_k|/|ref_k|. nan without a usable reference (missing, nan or 0)."""
    if ref is None:
        return math.nan
    x, ref = np.atleast_1d(np.asarray(x, dtype=float)), np.atleast_1d(np.asarray(ref, dtype=float))
    if x.shape != ref.shape or not np.all(np.isfinite(ref) & (ref != 0)):
        return math.nan
    return float(np.max(np.abs(x / ref - 1.0)))


def run_case(wall, law, damping, motion, duration, methods, dts, log, cached=None):
    """All points of one paper run, femoat with each of ``methods`` at its rtols
    (:func:`method_rtols`); OpenSees points found in ``cached`` ({(run, dt): row}, from an
    earlier CSV) are reused: they do not depend on femoat's code."""
    model = benchmark_model(wall, law, damping)
    name = f"{wall}/{law}/{damping}"
    cached = cached or {}
    ref = femoat_point(model, motion, duration, REF_RTOL, REF_METHOD)
    rows = [dict(run=name, tool="femoat-ref", method=REF_METHOD, setting=REF_RTOL, **ref)]
    for method in methods:
        for rtol in method_rtols(method):
            rows.append(dict(run=name, tool=f"femoat-{method}", method=method, setting=rtol,
                             **femoat_point(model, motion, duration, rtol, method)))
            log(f"  {name} femoat-{method} rtol {rtol:g}: {rows[-1]['cpu'] * 1e3:.1f} ms, "
                f"{rows[-1]['steps']} steps, {rows[-1]['status']}")
    for dt in dts:
        point = cached.get((name, dt)) or opensees_point(model, motion, duration, dt)
        rows.append(dict(run=name, tool="opensees", method="", setting=dt, **point))
        log(f"  {name} OpenSees dt {dt:g}: {rows[-1]['status']}, {rows[-1]['cpu']:.2f} s"
            + (" (reused)" if (name, dt) in cached else ""))
    # OpenSees against its own finest step too: where its material is not femoat's law (M's
    # inner cycles, see README) this separates its discretisation error from the law difference
    finest = min((r for r in rows if r["tool"] == "opensees" and r["status"] == "ok"),
                 key=lambda r: r["setting"], default=None)
    for r in rows:
        own = finest if r["tool"] == "opensees" else ref
        for q in QUANTITIES:
            r[f"err_{SHORT[q]}"] = rel_error(r[q], ref[q])
            r[f"self_{SHORT[q]}"] = rel_error(r[q], own[q]) if own is not None else math.nan
    return rows


def value_columns(quantity):
    """The CSV columns of a quantity: itself, or q_1 … q_n for a per-story one."""
    if quantity in PER_STORY:
        return [f"{quantity}_{k}" for k in range(1, N_STORIES + 1)]
    return [quantity]


COLUMNS = (["run", "tool", "method", "setting", "status", "cpu", "steps", "impacts",
            "energy_residual"]
           + [c for q in QUANTITIES for c in value_columns(q)]
           + [f"err_{SHORT[q]}" for q in QUANTITIES] + [f"self_{SHORT[q]}" for q in QUANTITIES])


def flatten(row):
    """``row`` with each per-story list spread over its columns (nan in each for a failed
    point, whose value is a single nan)."""
    out = dict(row)
    for q in PER_STORY:
        value = out.pop(q)
        values = value if isinstance(value, (list, tuple)) else [value] * N_STORIES
        out.update(zip(value_columns(q), values))
    return out


def _number(raw):
    return float(raw) if raw not in ("", "nan") else math.nan


def read_opensees_points(path):
    """{(run, dt): point} of the OpenSees rows of an earlier CSV of this script; a CSV without
    some quantity's columns (written before it was added) gives no points: they are re-run."""
    out = {}
    with open(path, newline="", encoding="utf-8") as fh:
        reader = csv.DictReader(fh)
        if not all(c in reader.fieldnames for q in QUANTITIES for c in value_columns(q)):
            return out
        for r in reader:
            if r["tool"] != "opensees":
                continue
            point = {"status": r["status"], "cpu": _number(r["cpu [s]"])}
            for key in ("steps", "impacts", "energy_residual"):
                point[key] = _number(r[key])
            for q in QUANTITIES:
                values = [_number(r[c]) for c in value_columns(q)]
                point[q] = values if q in PER_STORY else values[0]
            out[(r["run"], float(r["setting"]))] = point
    return out


def read_rows(path):
    """All points of an earlier CSV of this script, numbers as floats. A CSV from before the
    method column (one method, tool "femoat") reads as femoat-newmark."""
    rows = []
    with open(path, newline="", encoding="utf-8") as fh:
        for r in csv.DictReader(fh):
            row = {k.replace(" [s]", ""): v for k, v in r.items()}
            for k in row:
                if k not in ("run", "tool", "method", "status"):
                    row[k] = _number(row[k])
            if "method" not in row:
                row["method"] = "" if row["tool"] == "opensees" else "newmark"
                if row["tool"] == "femoat":
                    row["tool"] = "femoat-newmark"
            rows.append(row)
    return rows


def methods_in(rows):
    """The femoat methods with points in ``rows``, in METHODS' order."""
    tools = {r["tool"] for r in rows}
    return [m for m in METHODS if f"femoat-{m}" in tools]


def write_csv(rows, path):
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow([c + (" [s]" if c == "cpu" else "") for c in COLUMNS])
    for r in map(flatten, rows):
        w.writerow([r[c] for c in COLUMNS])
    write_text(path, buf.getvalue())


def finest_row(rows):
    """OpenSees' finest converged point among ``rows`` (or None)."""
    return min((r for r in rows if r["tool"] == "opensees" and r["status"] == "ok"),
               key=lambda r: r["setting"], default=None)


def summarise(rows, quantity="peak_impact_force", method=REF_METHOD, at_rtol=None):
    """One dict per run: femoat's ``method`` at ``at_rtol`` (default: the method's default),
    OpenSees at the same error, the ratio, the worst ratio over the method's settings within
    TARGET_ERROR, and the reference cross-check (the quantity's error of OpenSees' finest step
    against the reference)."""
    key = f"err_{SHORT[quantity]}"
    tool = f"femoat-{method}"
    at_rtol = METHOD_RTOL[method] if at_rtol is None else at_rtol
    out = []
    for name in dict.fromkeys(r["run"] for r in rows):
        mine = [r for r in rows if r["run"] == name]
        fm = {r["setting"]: r for r in mine if r["tool"] == tool and r["status"] == "ok"}
        os_pts = [(r["cpu"], r[key], r["setting"]) for r in mine
                  if r["tool"] == "opensees" and r["status"] == "ok"]
        finest = finest_row(mine)
        row = dict(run=name, tool=tool, method=method, at_rtol=at_rtol)
        f = fm.get(at_rtol)
        if f is not None:
            c_os, dt_os, bound = cpu_at_error(os_pts, f[key])
            row.update(cpu_femoat=f["cpu"], err_femoat=f[key], dt_opensees=dt_os,
                       cpu_opensees=c_os, bound=bound, ratio=c_os / f["cpu"])
        worst, worst_bound = math.inf, "="
        for r in fm.values():
            if r[key] <= TARGET_ERROR:
                c_os, _, bound = cpu_at_error(os_pts, r[key])
                if c_os / r["cpu"] < worst:
                    worst, worst_bound = c_os / r["cpu"], bound
        row["worst_ratio_within_target"] = worst
        row["worst_bound"] = worst_bound
        # the same ratio with OpenSees' errors against its own finest step (optimistic for
        # OpenSees: near that step its error is underestimated)
        own_pts = [(r["cpu"], r[f"self_{SHORT[quantity]}"], r["setting"]) for r in mine
                   if r["tool"] == "opensees" and r["status"] == "ok"
                   and r is not finest_row(mine)]
        if f is not None:
            c_own, _, b_own = cpu_at_error(own_pts, f[key])
            row.update(ratio_self=c_own / f["cpu"], bound_self=b_own)
        row["ref_vs_opensees_finest"] = finest[key] if finest else math.nan
        row["opensees_finest_dt"] = finest["setting"] if finest else math.nan
        out.append(row)
    return out


_BOUND = {"=": " ", ">=": "≥", "<=": "≤", "?": "?"}


def format_summary(summaries, quantity="peak_impact_force"):
    """The table of ``{method: summarise(rows, quantity, method)}``, a line per run and method
    (each method at its own default rtol)."""
    err = f"err {SHORT[quantity]}"
    at = ", ".join(f"{m} {next(iter(sm), {}).get('at_rtol', METHOD_RTOL[m]):g}"
                   for m, sm in summaries.items())
    head = (f"{'run':26s}{'tool':16s}{'CPU ms':>8s}{err:>10s}{'OpenSees dt':>13s}"
            f"{'OpenSees s':>11s}{'ratio':>9s}{'worst ≤0.5%':>12s}{'ref vs OS':>10s}{'ratio*':>9s}")
    lines = [f"{label(quantity)}: femoat at rtol = {at}; OpenSees at the same {label(quantity)} "
             "error (ratio*: OpenSees' error against its own finest step)", head]
    by_run = {}
    for sm in summaries.values():
        for s in sm:
            by_run.setdefault(s["run"], []).append(s)
    for name, lines_of_run in by_run.items():
        for s in lines_of_run:
            b = _BOUND[s.get("bound", "?")]
            dt = b + format(s.get("dt_opensees", math.nan), ".2g")
            ratio = b + format(s.get("ratio", math.nan), ".0f")
            worst = _BOUND[s["worst_bound"]] + format(s["worst_ratio_within_target"], ".0f")
            ratio_self = (_BOUND[s.get("bound_self", "?")]
                          + format(s.get("ratio_self", math.nan), ".0f"))
            lines.append(
                f"{name:26s}{s['tool']:16s}{s.get('cpu_femoat', math.nan) * 1e3:8.1f}"
                f"{s.get('err_femoat', math.nan):10.1e}{dt:>13s}"
                f"{s.get('cpu_opensees', math.nan):11.2f}{ratio:>9s}{worst:>12s}"
                f"{s['ref_vs_opensees_finest']:10.1e}{ratio_self:>9s}")
    return "\n".join(lines)


def _ratios(summary):
    """[(ratio, bound, run)] of ``summary`` with a finite ratio, smallest first."""
    return sorted((s["ratio"], s["bound"], s["run"]) for s in summary
                  if math.isfinite(s.get("ratio", math.nan)))


def format_range(summary, quantity="peak_impact_force"):
    """One line: the range over the runs of femoat's error at its rtol and of the speed ratio
    at that error (≥/≤ on an end that is a bound)."""
    tool = summary[0]["tool"] if summary else "femoat"
    errs = [s["err_femoat"] for s in summary if math.isfinite(s.get("err_femoat", math.nan))]
    ratios = _ratios(summary)
    if not errs or not ratios:
        return f"{label(quantity):26s} {tool:16s} no runs"
    (lo, b_lo, _), (hi, b_hi, _) = ratios[0], ratios[-1]
    n_bound = sum(b != "=" for _, b, _ in ratios)
    return (f"{label(quantity):26s} {tool:16s} err {min(errs):.1e}–{max(errs):.1e}   ratio "
            f"{_BOUND[b_lo].strip()}{lo:.0f}–{_BOUND[b_hi].strip()}{hi:.0f}"
            f"   ({n_bound} of {len(ratios)} ratios are bounds)")


def format_targets(summaries, quantities):
    """Issue 15's targets for one method (``summaries``: {quantity: summarise(...)}): CPU per
    run at its rtol ≤ TARGET_CPU, and the smallest ratio over the runs of every quantity
    ≥ TARGET_RATIO."""
    first = summaries[quantities[0]]
    tool, at_rtol = first[0]["tool"], first[0]["at_rtol"]
    cpus = sorted((s.get("cpu_femoat", math.nan), s["run"]) for s in first)
    finite = [c for c, _ in cpus if math.isfinite(c)]
    slow = [name for c, name in cpus if not c <= TARGET_CPU]
    lines = [f"{tool} at rtol {at_rtol:g}: CPU per run {min(finite, default=math.nan) * 1e3:.1f}"
             f"–{max(finite, default=math.nan) * 1e3:.1f} ms (median "
             f"{np.median(finite) * 1e3 if finite else math.nan:.1f} ms); "
             f"≤ {TARGET_CPU * 1e3:g} ms: "
             + ("all runs" if not slow else f"missed by {len(slow)} of {len(cpus)} runs")]
    parts, missed, unsure = [], [], []
    for q in quantities:
        summary = summaries[q]
        ratios = _ratios(summary)
        if not ratios:
            parts.append(f"{SHORT[q]} ?")
            unsure.append(f"{SHORT[q]} on {len(summary)} of {len(summary)} runs")
            continue
        lo, bound, name = ratios[0]
        parts.append(f"{SHORT[q]} {_BOUND[bound].strip()}{lo:.0f} ({name})")
        # a bound decides only on its own side of the target: "≤ 150" or "≥ 50" leave it open
        n_low = sum(r < TARGET_RATIO and b != ">=" for r, b, _ in ratios)
        n_open = (sum((r < TARGET_RATIO and b == ">=") or (r >= TARGET_RATIO and b == "<=")
                      for r, b, _ in ratios) + len(summary) - len(ratios))
        if n_low:
            missed.append(f"{SHORT[q]} on {n_low} of {len(summary)} runs")
        if n_open:
            unsure.append(f"{SHORT[q]} on {n_open}")
    lines.append(f"    smallest ratio over the {len(first)} runs: " + ", ".join(parts))
    verdict = "met" if not missed and not unsure else ("missed, " + ", ".join(missed)
                                                         if missed else "not missed")
    if unsure:
        verdict += "; undecided (a bound on the other side of the target, or no ratio): " + \
            ", ".join(unsure)
    lines.append(f"    ratio ≥ {TARGET_RATIO:.0f} on every quantity and run: {verdict}")
    clear = [s["run"] for s in first
             if all(t.get("ratio", 0.0) >= TARGET_RATIO and t.get("bound") != "<="
                    for q in quantities for t in summaries[q] if t["run"] == s["run"])]
    lines.append(f"    runs with ratio ≥ {TARGET_RATIO:.0f} on every quantity: {len(clear)} of "
                 f"{len(first)}" + (f" ({', '.join(clear)})" if clear else ""))
    return "\n".join(lines)


TOOL_STYLE = {"femoat-newmark": dict(color="#1f77b4", ls="-", lw=1.2, mfc="#1f77b4"),
              "femoat-dp5": dict(color="#d62728", ls="-", lw=1.2, mfc="#d62728"),
              "opensees": dict(color="0.45", ls="--", lw=1.0, mfc="none")}
LAW_MARKER = {"E": "o", "V": "s", "J": "^", "H": "D", "M": "v"}


def plot(rows, path, quantities=QUANTITIES):
    from matplotlib.lines import Line2D

    from femoat.plotting.style import pyplot

    plt = pyplot()
    tools = [f"femoat-{m}" for m in methods_in(rows)] + ["opensees"]
    groups = [(w, d) for d in DAMPING_CHOICES for w in WALLS]
    fig, axes = plt.subplots(len(quantities), len(groups), figsize=(4.2 * len(groups),
                             3.4 * len(quantities)), sharey=True, squeeze=False)
    for j, (wall, damping) in enumerate(groups):
        for i, q in enumerate(quantities):
            ax = axes[i, j]
            key = f"err_{SHORT[q]}"
            for tool in tools:
                for law in LAWS:
                    name = f"{wall}/{law}/{damping}"
                    # in the order of the accuracy knob (rtol or dt), loosest first
                    pts = sorted(((r["setting"], r[key], r["cpu"]) for r in rows
                                  if r["run"] == name and r["tool"] == tool
                                  and r["status"] == "ok"), reverse=True)
                    if pts:
                        _, e, c = zip(*pts)
                        ax.loglog(np.maximum(e, 1e-12), c, marker=LAW_MARKER[law], ms=3.5,
                                  alpha=0.85, **TOOL_STYLE[tool])
            if q == "peak_impact_force":
                ax.axvline(TARGET_ERROR, color="0.5", lw=0.8, ls=":")
            ax.axhline(TARGET_CPU, color="#d62728", lw=0.7, ls=":")
            ax.set_xlabel(f"relative error, {label(q) if q in PER_STORY else q.replace('_', ' ')}")
            if j == 0:
                ax.set_ylabel("CPU time [s]")
            if i == 0:
                ax.set_title(f"{wall} wall, C_imp {damping}")
            ax.grid(True, which="major", alpha=0.3)
    handles = [Line2D([], [], label=tool, **TOOL_STYLE[tool]) for tool in tools]
    handles += [Line2D([], [], color="k", ls="none", marker=LAW_MARKER[law], ms=4,
                       mfc="none", label=f"law {law}") for law in LAWS]
    handles.append(Line2D([], [], color="#d62728", lw=0.7, ls=":",
                          label=f"{TARGET_CPU * 1e3:g} ms per run (target)"))
    fig.legend(handles=handles, fontsize=9, ncol=len(handles), loc="upper center",
               bbox_to_anchor=(0.5, 1 - 0.5 / fig.get_figheight()), frameon=False)
    fig.suptitle("Work-precision on the paper runs: femoat (solid, rtol) against OpenSees (grey, "
                 f"dashed, fixed dt); errors against femoat-{REF_METHOD} at rtol {REF_RTOL:g}")
    # room for the suptitle and the legend under it
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.8 / fig.get_figheight()))
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true",
                    help="2 runs on the first 4 s of the record, fewer OpenSees steps")
    ap.add_argument("--runs", nargs="*", default=None,
                    help="subset as wall/law/damping, e.g. concrete/H/published")
    ap.add_argument("--out", type=Path, default=OUT, help="output folder")
    ap.add_argument("--from-csv", type=Path, default=None,
                    help="no runs: summarise and plot an earlier CSV")
    ap.add_argument("--reuse-opensees", type=Path, default=None,
                    help="reuse the OpenSees points of an earlier CSV (femoat re-measured)")
    ap.add_argument("--methods", default=",".join(METHODS),
                    help=f"femoat's methods, comma-separated (default {','.join(METHODS)})")
    args = ap.parse_args(argv)
    methods = [m.strip() for m in args.methods.split(",") if m.strip()]
    if not methods or any(m not in METHODS for m in methods):
        ap.error(f"--methods {args.methods!r}: a comma-separated subset of {','.join(METHODS)}")

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    motion = paper_motion()
    duration = motion.duration + 2.0
    cases = [(w, law, d) for d in DAMPING_CHOICES for w in WALLS for law in LAWS]
    dts = DTS
    suffix = ""
    if args.quick:
        n = int(round(4.0 / motion.dt)) + 1
        motion = GroundMotion(motion.accel_g[:n], motion.dt, name=motion.name + " (first 4 s)")
        duration = 5.0
        cases = [("concrete", "H", "published"), ("steel", "M", "published")]
        dts = (5e-4, 2e-4, 1e-4, 5e-5)
        suffix = "_quick"
    if args.runs:
        cases = [tuple(c.split("/")) for c in args.runs]
    if args.from_csv:
        report(read_rows(args.from_csv), motion.name, duration,
               args.from_csv.with_suffix(".png"))
        return 0
    # warm-up: numba compilation (or cache load) is not part of a run's CPU time
    for method in dict.fromkeys([REF_METHOD, *methods]):
        for law in LAWS:
            run(benchmark_model("concrete", law, "published"), motion,
                Integrator(method=method, rtol=1e-3), duration=1.0)
    rows = []
    csv_path = args.out / f"work_precision{suffix}.csv"
    cached = read_opensees_points(args.reuse_opensees) if args.reuse_opensees else {}
    if args.reuse_opensees and not cached:
        log(f"{args.reuse_opensees}: no reusable OpenSees points (a CSV without the drift and "
            "floor acceleration columns?): OpenSees is run")
    for k, (wall, law, damping) in enumerate(cases):
        log(f"[{k + 1}/{len(cases)}] {wall}/{law}/{damping}")
        rows += run_case(wall, law, damping, motion, duration, methods, dts, log, cached)
        write_csv(rows, csv_path)
    report(rows, motion.name, duration, args.out / f"work_precision{suffix}.png")
    log(f"wrote {csv_path} and {args.out / f'work_precision{suffix}.png'}")
    return 0


def report(rows, motion_name, duration, png):
    """Print the summary tables, targets and ranges (per femoat method), write them beside
    ``png`` (.txt), plot. Quantities without error columns in ``rows`` (a CSV from before they
    were added) are left out."""
    quantities = [q for q in QUANTITIES if rows and f"err_{SHORT[q]}" in rows[0]]
    methods = methods_in(rows)
    summaries = {q: {m: summarise(rows, q, m) for m in methods} for q in quantities}
    n_runs = len(dict.fromkeys(r["run"] for r in rows))
    parts = [f"{motion_name}, {duration:g} s; CPU = process time of a whole run() (best of 3 "
             "below 1 s); errors against femoat-newmark at rtol "
             f"{REF_RTOL:g}; each femoat method at its default rtol (" + ", ".join(
                 f"{m} {METHOD_RTOL[m]:g}" for m in methods) + ")",
             "",
             f"targets (issue 15): CPU per paper run ≤ {TARGET_CPU * 1e3:g} ms; OpenSees' CPU at "
             f"equal error ≥ {TARGET_RATIO:.0f}x femoat's on every quantity and run"]
    parts += [format_targets({q: summaries[q][m] for q in quantities}, quantities)
              for m in methods]
    for q in quantities:
        parts += ["", format_summary(summaries[q], q)]
    parts += ["", f"ranges over the {n_runs} runs, each femoat method at its default rtol (err: "
              "its error; ratio: OpenSees' CPU / femoat's at that error)"]
    parts += [format_range(summaries[q][m], q) for q in quantities for m in methods]
    text = "\n".join(parts)
    print(text)
    write_text(png.with_suffix(".txt"), text + "\n")
    plot(rows, png, quantities)


if __name__ == "__main__":
    sys.exit(main())
