"""Every peak at the default against converged femoat (issue 26's accuracy target): the named
peaks of each run and the peak force of every impact of at least 5 kip, one by one; the 20 paper
runs in 1D (both wall dampings) and plan runs under far-field pairs.

    python benchmarks/impact_accuracy.py [--pairs 1 2 4 6 8 10 12 15 17 21]
                                         [--scales 0.5 1 1.5] [--angles 0 30]
                                         [--rtol DEFAULT] [--method ark5]
                                         [--reference-rtol 1e-9] [--quick] [--no-paper] [--no-plan]

Paper runs: the 5 laws x 2 walls x 2 dampings (published, consistent C_imp) under Erzincan N-S
(0.91 g, time x 0.5), at the 1D default against Newmark at rtol 1e-8 with steps of at most
1e-4 s.

Each FEMA P695 far-field pair (normalized, at ``scale`` x the paper building's MCE as the
bidirectional study anchors it, time x 0.5, rotated by ``angle``) drives the paper building in
plan in the paper's concrete moat (Hertzdamp, 4 in gaps on all four sides). The run at the
default is compared with the same run converged (ark5 at ``--reference-rtol``; the first pair
also against Newmark at rtol 1e-8 with steps of at most 1e-4 s, an independent check of the
reference). Impacts are matched wall by wall in the order they happen; a differing count is
printed and counts as a miss. Prints; nothing is asserted.
"""

import argparse
import time

from femoat.ground_motions import RecordPair, fema_p695_pair
from femoat.integration import Integrator
from femoat.plan import PlanModel, rectangular_moat
from femoat.run import run

SMALL = 5.0
"""[kip] impacts at least this strong are compared one by one (issue 26)."""


def named(pk):
    """The named peaks of a plan run's peak summary ({name: value}; walls never hit are 0)."""
    out = {"plan": pk["peak_plan_base_displacement"]}
    for key in ("px", "mx", "py", "my"):
        out[f"F{key}"] = pk[f"peak_impact_force_{key}"] or 0.0
        out[f"w{key}"] = pk[f"peak_wall_displacement_{key}"] or 0.0
    for axis in "xy":
        out[f"base_{axis}"] = pk[f"peak_base_displacement_{axis}"]
        for k, d in enumerate(pk[f"peak_drift_{axis}"]):
            out[f"d{k + 1}{axis}"] = d
        for k, a in enumerate(pk[f"peak_floor_acceleration_{axis}"]):
            out[f"a{k + 1}{axis}"] = a
        out[f"a0{axis}"] = pk[f"peak_base_acceleration_{axis}"]
    return out


def compare(res, ref):
    """(worst relative error of a named peak and its name, worst relative error of an impact
    >= SMALL kip and its description, impacts compared, count mismatch message or '')."""
    a, b = named(res.peaks), named(ref.peaks)
    errs = {k: abs(a[k] - b[k]) / abs(b[k]) for k in b if b[k]}
    name = max(errs, key=errs.get)
    worst_imp, where, n, mismatch = 0.0, "-", 0, ""
    for side in sorted({r["side"] for r in ref.impacts} | {r["side"] for r in res.impacts}):
        mine = [r for r in res.impacts if r["side"] == side]
        theirs = [r for r in ref.impacts if r["side"] == side]
        if len(mine) != len(theirs):
            mismatch += f" {side}: {len(mine)} vs {len(theirs)}"
            continue
        for r, q in zip(mine, theirs):
            if q["peak_force"] < SMALL:
                continue
            n += 1
            e = abs(r["peak_force"] - q["peak_force"]) / q["peak_force"]
            if e > worst_imp:
                worst_imp, where = e, f"{side}@{q['start']:.2f}s {q['peak_force']:.1f}kip"
    return errs[name], name, worst_imp, where, n, mismatch


def paper_runs(args):
    """The 20 paper runs in 1D at the default against Newmark converged: (worst named, worst
    impact, impacts compared, count mismatches, loop CPU [s], steps)."""
    from femoat.paper import LAWS, WALLS, paper_model, paper_motion

    ref_int = Integrator(method="newmark", rtol=1e-8, max_step=1e-4)
    gm = paper_motion()
    print(f"paper runs in 1D at {Integrator().method} rtol {Integrator().rtol:g} against Newmark "
          f"rtol 1e-8, max_step 1e-4 s")
    print(f"{'case':>22s} {'steps':>7s} {'ms':>6s} {'impacts':>7s} {'worst named':>11s} "
          f"{'which':>10s} {'worst impact':>12s} {'which':>22s}")
    worst, worst_imp, total, misses, cpu, steps = 0.0, 0.0, 0, [], 0.0, 0
    for damping in ("published", "consistent"):
        for wall in WALLS:
            for law in LAWS:
                model = paper_model(wall, law, damping=damping)
                run(model, gm)  # (caches)
                res, ref = run(model, gm), run(model, gm, ref_int)
                a, b = res.peaks, ref.peaks
                errs = {}
                for k in ("peak_impact_force", "peak_base_displacement",
                          "peak_wall_displacement", "peak_base_acceleration"):
                    if b[k]:
                        errs[k.replace("peak_", "")] = abs(a[k] - b[k]) / abs(b[k])
                for k, short in (("peak_drift", "d"), ("peak_floor_acceleration", "a")):
                    for i, (x, y) in enumerate(zip(a[k], b[k])):
                        errs[f"{short}{i + 1}"] = abs(x - y) / abs(y)
                name = max(errs, key=errs.get)
                ei, where, n = 0.0, "-", 0
                if len(res.impacts) == len(ref.impacts):
                    for r, q in zip(res.impacts, ref.impacts):
                        if q["peak_force"] >= SMALL:
                            n += 1
                            e = abs(r["peak_force"] - q["peak_force"]) / q["peak_force"]
                            if e > ei:
                                ei, where = e, f"@{q['start']:.2f}s {q['peak_force']:.1f}kip"
                else:
                    misses.append(f"{damping}/{wall}/{law}")
                worst, worst_imp, total = max(worst, errs[name]), max(worst_imp, ei), total + n
                cpu, steps = cpu + a["cpu_seconds"], steps + a["steps"]
                label = f"{damping[:4]}/{wall}/{law}"
                print(f"{label:>22s} {a['steps']:7d} {a['cpu_seconds'] * 1e3:6.1f} {n:7d} "
                      f"{errs[name]:11.1e} {name:>10s} {ei:12.1e} {where:>22s}", flush=True)
    print(f"paper runs: worst named peak {worst:.1e}; worst impact >= {SMALL:g} kip "
          f"{worst_imp:.1e} ({total} impacts); count mismatches: {misses or 'none'}; "
          f"{steps} steps, {cpu * 1e3:.0f} ms of loop CPU in all\n")


def pairs(args):
    from femoat.studies.bidirectional import full_anchor

    sf = full_anchor()
    for k in args.pairs:
        for scale in args.scales:
            p = fema_p695_pair("farfield", k, scale=sf * scale, normalized=True)
            base = RecordPair(p.x.time_scaled(0.5), p.y.time_scaled(0.5), scale=p.scale)
            for angle in args.angles:
                yield f"{k}x{scale:g}@{angle:g}", base.rotated(angle)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, nargs="+", default=[1, 2, 4, 6, 8, 10, 12, 15, 17, 21])
    ap.add_argument("--scales", type=float, nargs="+", default=[0.5, 1.0, 1.5])
    ap.add_argument("--angles", type=float, nargs="+", default=[0.0, 30.0])
    ap.add_argument("--method", default=None, help="default: the plan default (ark5)")
    ap.add_argument("--rtol", type=float, default=None, help="default: the method's default")
    ap.add_argument("--reference-rtol", type=float, default=1e-9)
    ap.add_argument("--quick", action="store_true", help="pairs 1 and 6 at the MCE only")
    ap.add_argument("--no-paper", action="store_true", help="skip the 20 paper runs")
    ap.add_argument("--no-plan", action="store_true", help="skip the plan runs")
    args = ap.parse_args(argv)
    if not args.no_paper:
        paper_runs(args)
    if args.no_plan:
        return
    if args.quick:
        args.pairs, args.scales = [1, 6], [1.0]
    model = PlanModel(walls=rectangular_moat("concrete", "H", gap=4.0))
    kw = {} if args.method is None else {"method": args.method}
    integ = Integrator(**kw) if args.rtol is None else Integrator(**kw, rtol=args.rtol)
    method = integ.method if args.method else "ark5"
    refint = Integrator(method="ark5", rtol=args.reference_rtol)
    check = Integrator(method="newmark", rtol=1e-8, max_step=1e-4)
    print(f"plan runs at {method} rtol {integ.rtol:g} against ark5 rtol {args.reference_rtol:g}; "
          f"impacts >= {SMALL:g} kip one by one")
    print(f"{'case':>12s} {'steps':>7s} {'ms':>6s} {'impacts':>7s} {'worst named':>11s} "
          f"{'which':>7s} {'worst impact':>12s} {'which':>26s} {'ref vs Newmark 1e-8':>20s}")
    worst, worst_imp, total, misses, first = 0.0, 0.0, 0, [], True
    for label, pair in pairs(args):
        duration = pair.duration + 1.0
        t0 = time.process_time()
        res = run(model, pair, integ if args.method or args.rtol else None, duration=duration,
                  history=False)
        ms = (time.process_time() - t0) * 1e3
        ref = run(model, pair, refint, duration=duration, history=False)
        e, name, ei, where, n, mismatch = compare(res, ref)
        cross = ""
        if first:
            nm = run(model, pair, check, duration=duration, history=False)
            ce, cname, cei, _, cn, cmis = compare(ref, nm)
            cross = f"{max(ce, cei):.1e} ({cname}, {cn} imp){cmis}"
            first = False
        worst, worst_imp, total = max(worst, e), max(worst_imp, ei), total + n
        if mismatch:
            misses.append(f"{label}:{mismatch}")
        print(f"{label:>12s} {res.peaks['steps']:7d} {ms:6.0f} {n:7d} {e:11.1e} {name:>7s} "
              f"{ei:12.1e} {where:>26s} {cross:>20s}{'  COUNT' + mismatch if mismatch else ''}",
              flush=True)
    print(f"\nworst named peak {worst:.1e}; worst impact >= {SMALL:g} kip {worst_imp:.1e} "
          f"({total} impacts); count mismatches: {misses or 'none'}")


if __name__ == "__main__":
    main()
