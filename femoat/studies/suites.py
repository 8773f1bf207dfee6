"""Running a study's suites: each definition into its own folder (resumable), its run table read
back, and the study's table written beside them."""

import contextlib
import sys
from pathlib import Path


def run_suites(name, definitions, out, workers=None, serial=False, overwrite=False,
               stream=None):
    """Run (or resume) each suite of ``definitions`` ({key: parsed-TOML dict}) into
    ``out/<key>``; return {key: its run table} (:func:`femoat.suite.load_table`)."""
    from femoat.suite import load_table, run_suite, suite_from_dict
    from femoat.suite.execute import local_cluster

    from femoat.startup.bearing_kinds import select_for
    from femoat.suite.runs import models

    stream = stream or sys.stderr
    out = Path(out)
    suites = {key: suite_from_dict(d) for key, d in definitions.items()}
    # one loop for every suite of the study (their bearing kinds together), and one local
    # cluster: its workers start and load that loop once for all the suites
    select_for([m for suite in suites.values() for m in models(suite)])
    tables = {}
    with contextlib.ExitStack() as stack:
        scheduler = None if serial else stack.enter_context(local_cluster(workers))
        for key, suite in suites.items():
            stream.write(f"femoat study {name}: the {key.upper()} suite\n")
            run_suite(suite, out / key, scheduler=scheduler, serial=serial, overwrite=overwrite,
                      stream=stream)
            tables[key] = load_table(out / key)
    return tables


def write_table(out, table, markdown):
    """``out/table.csv`` and ``out/table.markdown``, each written atomically."""
    from femoat.atomic import write_text

    write_text(Path(out) / "table.csv", table.to_csv(index=False))
    write_text(Path(out) / "table.markdown", markdown)
