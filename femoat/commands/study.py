"""``femoat study NAME``: a study built on suites (:mod:`femoat.studies`), run or resumed into a
folder, its table printed (markdown) and written as CSV and markdown."""

import sys
from pathlib import Path

STUDIES = {
    "bidirectional": "the paper building under the FEMA P695 far-field pairs at the MCE: each "
    "record's components alone (1D) against the pair in plan (2D, at 0 deg and the worst of six "
    "angles), for the 5 contact laws x 2 walls",
    "isolators": "the paper building on a single friction pendulum, a triple friction pendulum "
    "and a lead-rubber bearing designed for the same MCE displacement (ASCE 7-16 Ch. 17), in the "
    "concrete moat (law H) under the FEMA P695 far-field pairs at the MCE, 1D and in plan",
}


def add_parser(sub):
    p = sub.add_parser(
        "study",
        help="run a study built on suites (bidirectional: 1D against 2D pounding at the MCE; "
        "isolators: FP, TFP and LRB of equal MCE displacement)",
        description="Run (or resume) a study's suites into OUT and print its table; the table "
        "is also written to OUT/table.csv and OUT/table.markdown. Studies: "
        + "; ".join(f"{k}: {v}" for k, v in STUDIES.items()) + ".",
    )
    p.add_argument("name", choices=sorted(STUDIES), help="the study")
    p.add_argument("--out", type=Path, default=None,
                   help="output folder (default: femoat_output/study/<name>, "
                   "femoat_output/study/<name>-quick with --quick)")
    p.add_argument("--workers", type=int, default=None,
                   help="local Dask worker processes, one thread each (default: one per core)")
    p.add_argument("--serial", action="store_true", help="run in this process, without Dask")
    p.add_argument("--quick", action="store_true",
                   help="a small variant: three pairs (bidirectional: two laws)")
    p.add_argument("--overwrite", action="store_true",
                   help="delete the results of a different definition in --out (e.g. after "
                   "femoat changed)")
    return p


def run(args):
    import importlib

    run_study = importlib.import_module(f"femoat.studies.{args.name}").run_study

    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers {args.workers}: give a number of processes >= 1.")
    out = args.out or Path("femoat_output") / "study" / (
        args.name + ("-quick" if args.quick else ""))
    try:
        _, markdown = run_study(out, quick=args.quick, workers=args.workers, serial=args.serial,
                                overwrite=args.overwrite)
    except KeyboardInterrupt:
        print(f"\nfemoat study: interrupted; the finished runs are stored in {out}: rerun the "
              "same command to resume", file=sys.stderr)
        return 130
    print(markdown, end="")
    figure = " and the figure isolators.png" if args.name == "isolators" else ""
    print(f"femoat study {args.name}: the table in {out / 'table.markdown'} and "
          f"{out / 'table.csv'}{figure}; the run tables in {out / '1d'} and {out / '2d'} "
          "(femoat.suite.load_table)")
    return 0
