"""Fingerprints of a 72-run suite's table: the suite machinery and the solver's exact output, to
hold a refactor to bit-identity (the suite twin of :mod:`fingerprints`, stored from the commit
before issue 24's compile work).

The suite: the three shipped PEER records (3 s each) x laws E, H x concrete and steel walls x
six Sa(1 s) stripes = 72 runs, serial. Each column of its run table (rows sorted by record,
variation and intensity) is hashed on its own, so that a column added later does not break
the comparison of the others; timings and identities are left out.

    PYTHONPATH=. python tests/suite_fingerprints.py            # compare with the stored ones
    PYTHONPATH=. python tests/suite_fingerprints.py --write    # store them
"""

import hashlib
import io
import json
import shutil
import sys
import tempfile
from pathlib import Path

import numpy as np
from fingerprints import write_or_compare

DATA = Path(__file__).resolve().parent / "data"
PATH = DATA / "fingerprints_suite.json"
RECORDS = ("Rinaldi228.AT2", "RSN77_SFERN_PUL164.AT2", "RSN181_IMPVALL.H_H-E06230.AT2")
LEFT_OUT = ("cpu_seconds", "solver_seconds", "femoat_version", "suite_hash", "run_id")
"""Columns that are timings or the code's and the definition's identity (they change with any
edit of femoat), not results."""

SUITE = """
[records]
folder = "{folder}"
duration = 3.0
extra_time = 0.5
[variations]
"walls.law" = ["E", "H"]
"walls.preset" = ["concrete", "steel"]
[scaling]
method = "ida"
period = 1.0
levels = [0.25, 0.5, 0.75, 1.0, 1.25, 1.5]
[run]
batch_size = 6
"""


def _column_hash(values):
    h = hashlib.sha256()
    if values.dtype.kind in "fiub":
        a = np.ascontiguousarray(values.astype(np.float64))
        a[np.isnan(a)] = np.nan  # one NaN bit pattern
        h.update(a.tobytes())
    else:
        h.update("\0".join(map(str, values.tolist())).encode())
    return h.hexdigest()


def compute():
    """{column: sha256} of the suite's run table (72 rows)."""
    from femoat.suite import load_suite, load_table, run_suite

    with tempfile.TemporaryDirectory(prefix="femoat-suite-fp-") as work:
        work = Path(work)
        folder = work / "peer"
        folder.mkdir()
        for name in RECORDS:
            shutil.copyfile(DATA / "peer" / name, folder / name)
        path = work / "suite.toml"
        path.write_text(SUITE.format(folder=folder.as_posix()), encoding="utf-8")
        run_suite(load_suite(path), work / "out", serial=True, stream=io.StringIO())
        table = load_table(work / "out")
    table = table.sort_values(["record", "variation", "im"], kind="stable")
    out = {"rows": int(len(table))}
    for column in table.columns:
        if column not in LEFT_OUT:
            out[column] = _column_hash(table[column].to_numpy())
    return out


def load():
    return json.loads(PATH.read_text())


def main(argv):
    return write_or_compare(PATH, compute(), argv)


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    raise SystemExit(main(sys.argv[1:]))
