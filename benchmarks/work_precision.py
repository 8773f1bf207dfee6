"""Work-precision of femoat against OpenSees on the paper runs. A script, not a test.

    python benchmarks/work_precision.py            # 20 runs, full record: ~40 min on 2 cores
    python benchmarks/work_precision.py --quick    # 2 runs, first 4 s of the record: ~1 min

For each paper run (5 laws × concrete/steel wall × published/consistent C_imp) femoat runs at
several accuracy settings (rtol) and its OpenSees twin (femoat.opensees.building) at several fixed
time steps. Each run's error is measured against a converged reference, femoat at rtol = 1e-8,
itself cross-checked against OpenSees at the finest step (dt = 1e-5 s, column "ref vs OS" of each
table), for six quantities: peak impact force, peak base displacement, peak wall displacement, the
largest impact impulse, the peak story drifts and the peak floor accelerations. The last two are
one value per story (floor k atop story k), and a run's error is the worst over the stories,
max_k |x_k − ref_k|/|ref_k| (relative to each story's own reference peak, so a small drift counts
as much as a large one); the other errors are |x − ref|/|ref|. femoat's drifts are peaks of the
continuous solution, its accelerations peaks at the step ends; OpenSees' both at its samples.

Same problem for both tools: law V runs with ``allow_tension=True`` in both (OpenSees'
ViscoelasticGap pulls in tension; femoat's default V does not). CPU time is ``time.process_time``
of femoat's whole ``run()`` call (packing, compiled loop, impact table and peaks), measured after
a warm-up run (numba compiled), and of OpenSees' ``analyze`` call with binary recorders; runs
under 1 s are repeated 3 times and the best is kept, for both tools alike.

Speed ratio at equal error: OpenSees' CPU time at femoat's error, interpolated log-log along
OpenSees' work-precision front (the points no cheaper point beats: the most favourable reading for
OpenSees, whose error is not monotone in dt). Outside OpenSees' range the ratio is a bound (≥ when
femoat is more accurate than OpenSees' finest step, ≤ when OpenSees' coarsest converged step is
already more accurate than femoat).

Writes benchmarks/results/work_precision.csv (every point; the drifts and floor accelerations as
peak_drift_k and peak_floor_acceleration_k, k = 1…3, their errors as err_drift and err_a_fl, the
worst over the stories) and work_precision.png (CPU time against error, one line per tool and
run), atomically (--quick: work_precision_quick.*); prints one table per quantity and, last, one
line per quantity with the range over the runs of femoat's error at its default rtol and of the ratio.
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
from femoat.paper import LAWS, WALLS, paper_motion  # noqa: E402
from femoat.run import run  # noqa: E402
from femoat.structure.building import Building  # noqa: E402
from femoat.structure.pounding import MoatWall, PoundingModel  # noqa: E402
from femoat.walls.presets import DAMPING_CHOICES, wall_preset  # noqa: E402

DEFAULT_RTOL = Integrator().rtol
RTOLS = tuple(sorted({1e-2, 1e-3, 1e-4, 1e-5, DEFAULT_RTOL, 1e-6}, reverse=True))
REF_RTOL = 1e-8
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
TARGET_ERROR = 5e-3      # 0.5 % in peak impact force
TARGET_RATIO = 30.0      # femoat at most 1/30 of OpenSees' CPU time at equal error
TARGET_CPU = 0.050       # [s] per run after compilation
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


def femoat_point(model, motion, duration, rtol):
    from femoat.integration import SolverError

    try:
        res, cpu = _timed(lambda: run(model, motion, Integrator(rtol=rtol), duration=duration))
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


def run_case(wall, law, damping, motion, duration, rtols, dts, log, cached=None):
    """All points of one paper run; OpenSees points found in ``cached`` ({(run, dt): row}, from
    an earlier CSV) are reused: they do not depend on femoat's code."""
    model = benchmark_model(wall, law, damping)
    name = f"{wall}/{law}/{damping}"
    cached = cached or {}
    ref = femoat_point(model, motion, duration, REF_RTOL)
    rows = [dict(run=name, tool="femoat-ref", setting=REF_RTOL, **ref)]
    for rtol in rtols:
        rows.append(dict(run=name, tool="femoat", setting=rtol,
                         **femoat_point(model, motion, duration, rtol)))
        log(f"  {name} femoat rtol {rtol:g}: {rows[-1]['cpu'] * 1e3:.1f} ms")
    for dt in dts:
        point = cached.get((name, dt)) or opensees_point(model, motion, duration, dt)
        rows.append(dict(run=name, tool="opensees", setting=dt, **point))
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


COLUMNS = (["run", "tool", "setting", "status", "cpu", "steps", "impacts", "energy_residual"]
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
    """All points of an earlier CSV of this script, numbers as floats."""
    rows = []
    with open(path, newline="", encoding="utf-8") as fh:
        for r in csv.DictReader(fh):
            row = {k.replace(" [s]", ""): v for k, v in r.items()}
            for k in row:
                if k not in ("run", "tool", "status"):
                    row[k] = _number(row[k])
            rows.append(row)
    return rows


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


def summarise(rows, quantity="peak_impact_force", at_rtol=DEFAULT_RTOL):
    """One dict per run: femoat at ``at_rtol``, OpenSees at the same error, the ratio, the worst
    ratio over femoat's settings within TARGET_ERROR, and the reference cross-check (the
    quantity's error of OpenSees' finest step against the reference)."""
    key = f"err_{SHORT[quantity]}"
    out = []
    for name in dict.fromkeys(r["run"] for r in rows):
        mine = [r for r in rows if r["run"] == name]
        fm = {r["setting"]: r for r in mine if r["tool"] == "femoat" and r["status"] == "ok"}
        os_pts = [(r["cpu"], r[key], r["setting"]) for r in mine
                  if r["tool"] == "opensees" and r["status"] == "ok"]
        finest = finest_row(mine)
        row = dict(run=name)
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


def format_summary(summary, quantity="peak_impact_force", at_rtol=DEFAULT_RTOL):
    """The table of ``summarise(rows, quantity, at_rtol)``, one line per run."""
    err = f"err {SHORT[quantity]}"
    head = (f"{'run':26s}{'femoat ms':>10s}{err:>10s}{'OpenSees dt':>13s}{'OpenSees s':>11s}"
            f"{'ratio':>9s}{'worst ≤0.5%':>12s}{'ref vs OS':>10s}{'ratio*':>9s}")
    lines = [f"femoat at rtol = {at_rtol:g}; OpenSees at the same {label(quantity)} error "
             "(ratio*: OpenSees' error against its own finest step)", head]
    for s in summary:
        b = _BOUND[s.get("bound", "?")]
        dt = b + format(s.get("dt_opensees", math.nan), ".2g")
        ratio = b + format(s.get("ratio", math.nan), ".0f")
        worst = _BOUND[s["worst_bound"]] + format(s["worst_ratio_within_target"], ".0f")
        ratio_self = _BOUND[s.get("bound_self", "?")] + format(s.get("ratio_self", math.nan), ".0f")
        lines.append(
            f"{s['run']:26s}{s.get('cpu_femoat', math.nan) * 1e3:10.1f}"
            f"{s.get('err_femoat', math.nan):10.1e}{dt:>13s}{s.get('cpu_opensees', math.nan):11.2f}"
            f"{ratio:>9s}{worst:>12s}{s['ref_vs_opensees_finest']:10.1e}{ratio_self:>9s}")
    return "\n".join(lines)


def format_range(summary, quantity="peak_impact_force", at_rtol=DEFAULT_RTOL):
    """One line: the range over the runs of femoat's error at ``at_rtol`` and of the speed ratio
    at that error (≥/≤ on an end that is a bound)."""
    errs = [s["err_femoat"] for s in summary if math.isfinite(s.get("err_femoat", math.nan))]
    ratios = sorted((s["ratio"], s["bound"]) for s in summary
                    if math.isfinite(s.get("ratio", math.nan)))
    if not errs or not ratios:
        return f"{label(quantity):26s} no runs at rtol {at_rtol:g}"
    (lo, b_lo), (hi, b_hi) = ratios[0], ratios[-1]
    n_bound = sum(b != "=" for _, b in ratios)
    return (f"{label(quantity):26s} err {min(errs):.1e}–{max(errs):.1e}   ratio "
            f"{_BOUND[b_lo].strip()}{lo:.0f}–{_BOUND[b_hi].strip()}{hi:.0f}"
            f"   ({n_bound} of {len(ratios)} ratios are bounds)")


def plot(rows, path, quantities=QUANTITIES):
    from femoat.plotting.style import LAW_STYLE, pyplot

    plt = pyplot()
    groups = [(w, d) for d in DAMPING_CHOICES for w in WALLS]
    fig, axes = plt.subplots(len(quantities), len(groups), figsize=(4.2 * len(groups),
                             3.4 * len(quantities)), sharey=True, squeeze=False)
    for j, (wall, damping) in enumerate(groups):
        for i, q in enumerate(quantities):
            ax = axes[i, j]
            key = f"err_{SHORT[q]}"
            for law in LAWS:
                name = f"{wall}/{law}/{damping}"
                color = LAW_STYLE[law]["color"]
                for tool, style in (("femoat", dict(ls="-", marker="o")),
                                    ("opensees", dict(ls="--", marker="s", mfc="none"))):
                    # in the order of the accuracy knob (rtol or dt), loosest first
                    pts = sorted(((r["setting"], r[key], r["cpu"]) for r in rows
                                  if r["run"] == name and r["tool"] == tool
                                  and r["status"] == "ok"), reverse=True)
                    if pts:
                        _, e, c = zip(*pts)
                        ax.loglog(np.maximum(e, 1e-12), c, color=color, ms=4, lw=1.2,
                                  label=f"{law} {tool}", **style)
            if q == "peak_impact_force":
                ax.axvline(TARGET_ERROR, color="0.5", lw=0.8, ls=":")
            ax.set_xlabel(f"relative error, {label(q) if q in PER_STORY else q.replace('_', ' ')}")
            if j == 0:
                ax.set_ylabel("CPU time [s]")
            if i == 0:
                ax.set_title(f"{wall} wall, C_imp {damping}")
            ax.grid(True, which="major", alpha=0.3)
    axes[0, 0].legend(fontsize=7, ncol=2)
    fig.suptitle("Work-precision: femoat (solid, rtol) vs OpenSees (dashed, fixed dt), "
                 "paper runs")
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.4 / fig.get_figheight()))  # room for the suptitle
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
    args = ap.parse_args(argv)

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    motion = paper_motion()
    duration = motion.duration + 2.0
    cases = [(w, law, d) for d in DAMPING_CHOICES for w in WALLS for law in LAWS]
    rtols, dts = RTOLS, DTS
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
    for law in LAWS:
        run(benchmark_model("concrete", law, "published"), motion, Integrator(rtol=1e-3),
            duration=1.0)
    rows = []
    csv_path = args.out / f"work_precision{suffix}.csv"
    cached = read_opensees_points(args.reuse_opensees) if args.reuse_opensees else {}
    if args.reuse_opensees and not cached:
        log(f"{args.reuse_opensees}: no reusable OpenSees points (a CSV without the drift and "
            "floor acceleration columns?): OpenSees is run")
    for k, (wall, law, damping) in enumerate(cases):
        log(f"[{k + 1}/{len(cases)}] {wall}/{law}/{damping}")
        rows += run_case(wall, law, damping, motion, duration, rtols, dts, log, cached)
        write_csv(rows, csv_path)
    report(rows, motion.name, duration, args.out / f"work_precision{suffix}.png")
    log(f"wrote {csv_path} and {args.out / f'work_precision{suffix}.png'}")
    return 0


def report(rows, motion_name, duration, png):
    """Print the summary tables, targets and ranges, write them beside ``png`` (.txt), plot.
    Quantities without error columns in ``rows`` (a CSV from before they were added) are left
    out."""
    quantities = [q for q in QUANTITIES if rows and f"err_{SHORT[q]}" in rows[0]]
    summaries = {q: summarise(rows, q) for q in quantities}
    summary = summaries["peak_impact_force"]

    def missed(flags):
        return "all runs" if not flags else "missed by " + ", ".join(flags)

    slow = [s["run"] for s in summary if not s.get("cpu_femoat", math.inf) < TARGET_CPU]
    at_default = [s["run"] for s in summary if not s.get("ratio", 0.0) >= TARGET_RATIO]
    worst = [s["run"] for s in summary if not s["worst_ratio_within_target"] >= TARGET_RATIO]
    parts = [f"{motion_name}, {duration:g} s; CPU = process time (best of 3 below 1 s)",
             format_summary(summary),
             f"targets: femoat CPU at rtol {DEFAULT_RTOL:g} < {TARGET_CPU * 1e3:.0f} ms: {missed(slow)}",
             f"         ratio ≥ {TARGET_RATIO:.0f} at rtol {DEFAULT_RTOL:g}: {missed(at_default)}",
             f"         ratio ≥ {TARGET_RATIO:.0f} at every femoat setting within 0.5 %: "
             f"{missed(worst)}"]
    for q in quantities[1:]:
        parts += ["", format_summary(summaries[q], q)]
    parts += ["", f"ranges over the {len(summary)} runs, femoat at rtol {DEFAULT_RTOL:g} (err: its "
              "error; ratio: OpenSees' CPU / femoat's at that error)"]
    parts += [format_range(summaries[q], q) for q in quantities]
    text = "\n".join(parts)
    print(text)
    write_text(png.with_suffix(".txt"), text + "\n")
    plot(rows, png, quantities)


if __name__ == "__main__":
    sys.exit(main())
