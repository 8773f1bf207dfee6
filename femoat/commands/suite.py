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
    g = p.add_argument_group(
        "FEMA P695 inputs of the report (default: the suite file's [p695] table, else SDC from "
        "[scaling] or Dmax, mu_T = 3, ratings B, B, B)")
    g.add_argument("--mu-t", type=float, default=None, metavar="MU",
                   help="period-based ductility du/dy,eff of a pushover (Eq. 6-6) [-], >= 1")
    g.add_argument("--sdc", default=None, help="seismic design category: Dmax, Dmin, Cmax, "
                   "Cmin, Bmax or Bmin (sets S_MT and the SSF)")
    for key, table in (("design-requirements", "3-1"), ("test-data", "3-2"),
                       ("modeling", "5-3")):
        g.add_argument(f"--{key}", default=None, metavar="RATING",
                       help=f"quality rating A (superior) .. D (poor), Table {table}")
    g.add_argument("--beta-total", type=float, default=None, metavar="BETA",
                   help="total collapse uncertainty beta_TOT [-] directly, instead of ratings")
    return p


def report_options(args):
    """The P695 options given on the command line (None: not given)."""
    return {k: v for k, v in dict(
        mu_t=args.mu_t, sdc=args.sdc, design_requirements=args.design_requirements,
        test_data=args.test_data, modeling=args.modeling,
        beta_total=args.beta_total).items() if v is not None}


def print_verdict(out, options, as_json=False, extra=None, write=True, force=False):
    """Write the report of the suite folder ``out`` (``write``) unless it is current and not
    ``force``d, then print the verdict for every stored run; returns the report paths (empty
    when not rewritten). Without ``write`` the verdict is computed, nothing is written."""
    import pandas as pd

    from femoat.suite import report as rp
    from femoat.suite.p695_inputs import margin_basis
    from femoat.suite.verdict import counts, verdict_text

    paths = []
    if write and not force and rp.is_current(out, options):  # only the status counts needed
        from femoat.suite.table import load_table

        table = load_table(out, columns=["run_id", "status"])
        meta = json.loads((Path(out) / "suite.json").read_text(encoding="utf-8"))
    else:
        table, meta = rp.load(out)
        if write:
            paths = rp.run_report(out, table, meta, **options)
    onsets = None
    if write:
        summary = pd.read_csv(Path(out) / "report" / "collapse_summary.csv")
        if (Path(out) / "report" / "pounding_fragility.csv").is_file():
            onsets = pd.read_csv(Path(out) / "report" / "pounding_fragility.csv")
    inputs = rp.p695_inputs(meta, **options)
    meta = {**meta, "im_kind": meta.get("im_kind") or "sa"}
    basis = margin_basis(meta, inputs)
    if not write:
        summary = rp.collapse_summary(table, meta, inputs)
        onsets = rp.pounding_summary(table, meta, inputs)
    if as_json:
        rows = [{k: (None if isinstance(v, float) and v != v else v) for k, v in r.items()}
                for r in summary.to_dict(orient="records")]
        units = {"elapsed": "s", "runs_per_second": "1/s", "stored": "runs",
                 "verdict": "units in each key, as in collapse_summary.csv",
                 "pounding": "units in each key, as in pounding_fragility.csv"}
        pound = [] if onsets is None else [
            {k: (None if isinstance(v, float) and v != v else v) for k, v in r.items()}
            for r in onsets.to_dict(orient="records")]
        print(json.dumps({**(extra or {}), "stored": counts(table),
                          "p695_inputs": inputs.statements(),
                          "S_MT [g]": basis.smt, "verdict": rows, "pounding": pound,
                          "units": units}, default=str))
    else:
        where = f"report in {Path(out) / 'report'}" if write else f"results in {out}"
        print(verdict_text(table, summary, inputs, basis, where, onsets), end="")
    return paths


def run(args):
    options = report_options(args)
    if args.suite == "report":
        if len(args.rest) != 1:
            raise ValueError("usage: femoat suite report DIR [--mu-t MU ...] (DIR: the --out "
                             "folder of a suite)")
        print_verdict(Path(args.rest[0]), options, args.json, force=True)
        return 0
    if args.rest:
        raise ValueError(f"unexpected arguments {args.rest}")
    from femoat.suite import finished, load_suite, run_suite
    from femoat.suite.execute import pending

    stem = Path(args.suite).stem if args.suite else "headline"
    out = args.out or Path("femoat_output") / "suite" / stem
    if not (args.check or args.overwrite) and finished.is_finished(args.suite, out):
        if not args.json:
            print(f"femoat suite: every run is stored in {out} (nothing changed since)")
        print_verdict(out, options, args.json, extra={"this_invocation": {"runs": 0}},
                      write=not args.no_report)
        return 0
    suite = load_suite(args.suite)
    if args.check:
        n = len(suite.records) * len(suite.combos)
        what = (f"{n} hunt-and-fill traces" if suite.scaling.hunt else
                f"{n * len(suite.scaling.levels)} runs")
        smt = "-" if suite.scaling.smt is None else f"{suite.scaling.smt:.4g} g"
        period = "-" if suite.scaling.period is None else f"{suite.scaling.period:g} s"
        records = (f"{len(suite.records)} records" if not suite.plan else
                   f"{len({r.pair_label for r in suite.records})} record pairs x "
                   f"{len({r.angle for r in suite.records})} angles (a building in plan)")
        print(f"suite {suite.hash}: {records} x {len(suite.combos)} "
              f"variations: {what}; S_MT = {smt}, period (prototype) = {period}, "
              f"time_scale = {suite.time_scale:g} [-]")
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
        print(f"\nfemoat suite: interrupted; {_stored(out)} in {out}: rerun the same command "
              "to resume", file=sys.stderr)
        return 130
    if summary["failed_tasks"] == 0 and not pending(suite, out)[0]:
        finished.mark(args.suite, out)
    this = (f"femoat suite: this invocation ran {summary['runs']} runs"
            + (f" in {summary['elapsed']:.0f} s" if "elapsed" in summary else ""))
    from femoat.suite.table import part_files

    if not part_files(out):
        print(json.dumps(summary) if args.json else f"{this}; nothing stored in {out}")
        return 0 if summary["failed_tasks"] == 0 else 1
    if not args.json:
        print(this)
    print_verdict(out, options, args.json, extra={"this_invocation": summary},
                  write=not args.no_report)
    return 0 if summary["failed_tasks"] == 0 else 1


def _stored(out):
    """'N runs stored' of the suite folder ``out`` (its part files), for the interrupt line."""
    try:
        from femoat.suite.table import load_table

        return f"{len(load_table(out, columns=['run_id']))} runs stored"
    except Exception:  # noqa: BLE001 - a line about an interrupted suite must not fail
        return "the finished batches are stored"
