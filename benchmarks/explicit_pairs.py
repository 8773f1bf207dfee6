"""The 1D open phase's explicit pair: Dormand-Prince 5(4) (``dp5``) against Tsitouras 5(4)
(``tsit5``) side by side, each at its default rtol (issue 26 item 4).

    python benchmarks/explicit_pairs.py [--repeat 3] [--quick] [--no-paper] [--no-records]

Both pairs run through the same compiled step (only the tableau differs), so a step costs the
same and the CPU follows the steps. Printed for each run: steps and loop CPU (best of
``--repeat``) of each pair, and each pair's worst peak against the converged run (the named
peaks, and the peak force of every impact of at least 5 kip one by one).

Cases: the 20 paper runs (5 laws x 2 walls x 2 dampings, Erzincan N-S at 0.91 g, time x 0.5;
converged: Newmark at rtol 1e-8, steps of at most 1e-4 s), and the x components of the FEMA
P695 far-field pairs (normalized, at 0.5, 1 and 1.5 x the paper building's MCE as the
bidirectional study anchors it, time x 0.5) on the paper building in the concrete moat with
Hertzdamp: the headline suite's kind of run, pounding or not (converged: dp5 at rtol 1e-9,
itself checked against Newmark at rtol 1e-8 on the first record). Ends with the totals.
Prints; nothing is asserted.
"""

import argparse

from femoat.ground_motions import fema_p695_pair
from femoat.integration import Integrator
from femoat.run import run

PAIRS = ["dp5", "tsit5"]
"""The methods compared (``--methods``); the first is the baseline of the totals."""
RTOL = {}
"""{method: rtol} where not the method's default (``--rtol tsit5=1e-6``)."""
RECORDS = list(range(1, 23))
"""The far-field pairs whose x component runs (``--records``)."""
SMALL = 5.0
"""[kip] impacts at least this strong are compared one by one."""


def named(pk):
    """The named peaks of a 1D run ({name: value})."""
    out = {k.replace("peak_", ""): pk[k] for k in ("peak_impact_force", "peak_base_displacement",
                                                  "peak_wall_displacement",
                                                  "peak_base_acceleration")}
    for k, short in (("peak_drift", "d"), ("peak_floor_acceleration", "a")):
        for i, x in enumerate(pk[k]):
            out[f"{short}{i + 1}"] = x
    return out


def worst(res, ref):
    """(worst relative error of a named peak or of an impact >= SMALL kip, impacts compared,
    whether the impact counts differ)."""
    a, b = named(res.peaks), named(ref.peaks)
    e = max((abs(a[k] - b[k]) / abs(b[k]) for k in b if b[k]), default=0.0)
    if len(res.impacts) != len(ref.impacts):
        return e, 0, True
    n = 0
    for r, q in zip(res.impacts, ref.impacts):
        if q["peak_force"] >= SMALL:
            n += 1
            e = max(e, abs(r["peak_force"] - q["peak_force"]) / q["peak_force"])
    return e, n, False


def timed(model, gm, integ, repeat):
    """The run (no history) and its best loop CPU [s] over ``repeat`` runs."""
    res = run(model, gm, integ, history=False)
    cpu = res.peaks["cpu_seconds"]
    for _ in range(repeat - 1):
        cpu = min(cpu, run(model, gm, integ, history=False).peaks["cpu_seconds"])
    return res, cpu


def compare(cases, reference, repeat, totals):
    """One line per case: each pair's steps, CPU and worst peak against ``reference``."""
    head = "".join(f" {p + ' steps':>11s} {'ms':>6s} {'worst':>7s}" for p in PAIRS)
    print("rtol: " + ", ".join(f"{p} {Integrator(method=p, rtol=RTOL.get(p)).rtol:g}"
                               for p in PAIRS))
    print(f"{'case':>24s}{head} {'impacts':>7s}")
    for label, model, gm in cases:
        ref = run(model, gm, reference, history=False)
        cells, n_imp, counts = "", 0, ""
        for p in PAIRS:
            res, cpu = timed(model, gm, Integrator(method=p, rtol=RTOL.get(p)), repeat)
            e, n, mismatch = worst(res, ref)
            t = totals.setdefault(p, {"steps": 0, "cpu": 0.0, "worst": 0.0, "mismatch": []})
            t["steps"] += res.peaks["steps"]
            t["cpu"] += cpu
            t["worst"] = max(t["worst"], e)
            if mismatch:
                t["mismatch"].append(label)
                counts += f" COUNT({p})"
            n_imp = max(n_imp, n)
            cells += f" {res.peaks['steps']:11d} {cpu * 1e3:6.1f} {e:7.1e}"
        print(f"{label:>24s}{cells} {n_imp:7d}{counts}", flush=True)


def paper_cases(quick):
    from femoat.paper import LAWS, WALLS, paper_model, paper_motion

    gm = paper_motion()
    for damping in ("published",) if quick else ("published", "consistent"):
        for wall in WALLS[:1] if quick else WALLS:
            for law in LAWS[:2] if quick else LAWS:
                yield f"{damping[:4]}/{wall}/{law}", paper_model(wall, law, damping=damping), gm


def record_cases(quick):
    from femoat.paper import paper_model
    from femoat.studies.bidirectional import full_anchor

    sf = full_anchor()
    model = paper_model("concrete", "H")
    for k in (1, 5, 12) if quick else RECORDS:
        for scale in (1.0,) if quick else (0.5, 1.0, 1.5):
            p = fema_p695_pair("farfield", k, scale=sf * scale, normalized=True)
            yield f"FF{k}x@{scale:g}MCE", model, p.x.scaled(p.scale).time_scaled(0.5)


def report(title, totals):
    base = totals[PAIRS[0]]
    print(f"\n{title}:")
    for p in PAIRS:
        t = totals[p]
        print(f"  {p:6s} {t['steps']:9d} steps {t['cpu'] * 1e3:9.1f} ms of loop CPU "
              f"({t['cpu'] / base['cpu']:.3f} of {PAIRS[0]}'s), worst peak {t['worst']:.1e}, "
              f"impact counts differing: {t['mismatch'] or 'none'}")
    print()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="4 paper runs and 3 records")
    ap.add_argument("--no-paper", action="store_true")
    ap.add_argument("--no-records", action="store_true")
    ap.add_argument("--methods", default=",".join(PAIRS), help="e.g. dp5,tsit5,newmark")
    ap.add_argument("--rtol", nargs="*", default=[], help="method=rtol, e.g. tsit5=1e-6")
    ap.add_argument("--records", type=int, nargs="*", default=None,
                    help="far-field pair numbers (default: all 22)")
    args = ap.parse_args(argv)
    PAIRS[:] = args.methods.split(",")
    RTOL.update({k: float(v) for k, v in (x.split("=") for x in args.rtol)})
    RECORDS[:] = args.records or RECORDS
    for p in PAIRS:  # compile outside the timings
        run(*next(paper_cases(True))[1:], Integrator(method=p), history=False)
    if not args.no_paper:
        totals = {}
        print("paper runs, against Newmark at rtol 1e-8, max_step 1e-4 s")
        compare(paper_cases(args.quick), Integrator(method="newmark", rtol=1e-8, max_step=1e-4),
                args.repeat, totals)
        report("paper runs", totals)
    if not args.no_records:
        totals = {}
        first = next(record_cases(True))
        ref = run(first[1], first[2], Integrator(rtol=1e-9), history=False)
        check = run(first[1], first[2], Integrator(method="newmark", rtol=1e-8, max_step=1e-4),
                    history=False)
        print(f"far-field x components, against dp5 at rtol 1e-9 ({first[0]}: that reference "
              f"within {worst(ref, check)[0]:.1e} of Newmark at rtol 1e-8)")
        compare(record_cases(args.quick), Integrator(rtol=1e-9), args.repeat, totals)
        report("far-field x components", totals)


if __name__ == "__main__":
    main()
