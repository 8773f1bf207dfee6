"""``femoat suite [suite.toml]``: run a suite of records (IDA, FEMA P695) locally or on Dask.

``femoat suite report DIR`` is handed to the report half (:mod:`femoat.suite.report`).
"""

import argparse
import json
import sys
from pathlib import Path


def add_parser(sub):
    p = sub.add_parser(
        "suite",
        help="run a suite of records: IDA or FEMA P695 collapse assessment, resumable, on Dask",
        description="Run every (record, variation, intensity) of a suite file (see "
        "femoat.suite.definition for every key; no file: the headline suite, FEMA P695 "
        "far-field IDA of the paper building for 5 laws x 2 walls) into OUT/runs/*.parquet. "
        "Rerunning the same command resumes. 'femoat suite report DIR' writes the report.",
    )
    p.add_argument("suite", nargs="?", default=None,
                   help="suite TOML file (default: the headline suite), or 'report'")
    p.add_argument("rest", nargs="*", help=argparse.SUPPRESS)
    p.add_argument("--out", type=Path, default=None,
                   help="output folder (default: femoat_output/suite/<suite file stem>)")
    p.add_argument("--workers", type=int, default=None,
                   help="local worker processes, one thread each (default: one per core)")
    p.add_argument("--scheduler", default=None, help="address of a running Dask scheduler")
    p.add_argument("--scheduler-file", type=Path, default=None,
                   help="scheduler file of a running Dask scheduler")
    p.add_argument("--serial", action="store_true", help="run in this process, without Dask")
    p.add_argument("--overwrite", action="store_true",
                   help="delete the results of a different suite in --out")
    p.add_argument("--check", action="store_true",
                   help="only validate the suite file and print what would run")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.add_argument("--no-report", action="store_true",
                   help="do not write the report (OUT/report/) after the runs")
    return p


def run(args):
    if args.suite == "report":
        from femoat.suite import report  # the report half (femoat/suite/report.py)

        if hasattr(report, "main"):
            return report.main(args.rest)
        if len(args.rest) != 1:
            raise ValueError("usage: femoat suite report DIR (the --out folder of a suite)")
        for path in report.run_report(args.rest[0]):
            print(f"wrote {path}")
        return 0
    if args.rest:
        raise ValueError(f"unexpected arguments {args.rest}")
    from femoat.suite import load_suite, run_suite
    from femoat.suite.execute import pending

    suite = load_suite(args.suite)
    stem = Path(args.suite).stem if args.suite else "headline"
    out = args.out or Path("femoat_output") / "suite" / stem
    if args.check:
        n = len(suite.records) * len(suite.combos)
        what = (f"{n} hunt-and-fill traces" if suite.scaling.hunt else
                f"{n * len(suite.scaling.levels)} runs")
        print(f"suite {suite.hash}: {len(suite.records)} records x {len(suite.combos)} "
              f"variations: {what}; S_MT = {suite.scaling.smt}, period (prototype) = "
              f"{suite.scaling.period} s, time_scale = {suite.time_scale}")
        if (out / "suite.json").is_file():
            print(f"{len(pending(suite, out)[0])} tasks left in {out}")
        return 0
    if args.scheduler and args.scheduler_file:
        raise ValueError("give --scheduler or --scheduler-file, not both")
    try:
        summary = run_suite(suite, out, workers=args.workers, scheduler=args.scheduler,
                            scheduler_file=args.scheduler_file, serial=args.serial,
                            overwrite=args.overwrite)
    except KeyboardInterrupt:
        print(f"\nfemoat suite: interrupted; finished batches are stored in {out}: rerun the "
              "same command to resume", file=sys.stderr)
        return 130
    if not args.no_report and any((Path(out) / "runs").glob("*.parquet")):
        from femoat.suite.report import run_report

        summary["report"] = [str(p) for p in run_report(out)]
    if args.json:
        print(json.dumps(summary))
    else:
        print(f"suite {suite.hash} (period {suite.scaling.period} s prototype, time_scale "
              f"{suite.time_scale}): {summary['runs']} runs, {summary['collapses']} collapses, "
              f"{summary['failures']} failures; results in {out}/runs"
              + (f", report in {out}/report" if "report" in summary else ""))
    return 0 if summary["failed_tasks"] == 0 else 1
