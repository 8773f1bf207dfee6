"""The results table: one row per run, Parquet part files in ``DIR/runs/``, one per batch.

Each part is written atomically (:mod:`femoat.atomic`), so a part on disk is always complete;
an interrupted suite loses at most the batches in flight. The columns, their types and units
come from :data:`femoat.suite.columns.COLUMNS` (listed in docs/suite_table.md).
:func:`load_table` is the only reader of the parts: everything else (the resume, the report,
the exports) reads the table through it, with its de-duplication and its run_id order.
"""

import hashlib
from pathlib import Path
from typing import NamedTuple

from femoat.suite import columns as cols


def schema(suite):
    """The Parquet schema of ``suite``'s table (:func:`femoat.suite.columns.fields`)."""
    return _schema(cols.fields(suite))


def _schema(fields):
    import pyarrow as pa

    types = dict(bool=pa.bool_(), int64=pa.int64(), float64=pa.float64(), string=pa.string())
    return pa.schema([(f.name, types[f.dtype]) for f in fields])


def write_part(rows, suite, out):
    """Write ``rows`` as one Parquet part in ``out/runs/`` (atomically); return its path."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from femoat.atomic import atomic_path

    fields = cols.fields(suite)
    text = {f.name for f in fields if f.dtype == "string"}
    clean = [{k: (str(v) if k in text and v is not None else v) for k, v in row.items()}
             for row in rows]
    table = pa.Table.from_pylist(clean, schema=_schema(fields))
    name = hashlib.sha256("|".join(r["run_id"] for r in rows).encode()).hexdigest()[:16]
    path = Path(out) / "runs" / f"part-{name}.parquet"
    with atomic_path(path) as tmp:
        pq.write_table(table, tmp)
    return path


def part_files(out):
    """The part files of the suite folder ``out``, sorted (what a report or a finished mark
    depends on; read them with :func:`load_table`)."""
    folder = Path(out) / "runs"
    return sorted(folder.glob("part-*.parquet")) if folder.is_dir() else []


def load_table(out, columns=None):
    """The results table of the suite folder ``out`` as a pandas DataFrame (one row per run)."""
    import pandas as pd
    import pyarrow.parquet as pq

    parts = part_files(out)
    if not parts:
        if not (Path(out) / "suite.json").is_file():
            raise FileNotFoundError(f"{out} is not a suite folder (no suite.json, no runs/).")
        return pd.DataFrame(columns=columns or [])
    import pyarrow as pa

    tables = [pq.read_table(p, columns=columns) for p in parts]
    # integers and booleans that may be missing (rsn, pulse, pounding of a failed run) keep
    # their type as pandas' nullable Int64 / boolean
    nullable = {pa.int64(): pd.Int64Dtype(), pa.bool_(): pd.BooleanDtype()}
    df = pa.concat_tables(tables, promote_options="default").to_pandas(types_mapper=nullable.get)
    # one order whatever order the batches finished in (a fit over the rows is then the same
    # to the last digit on every rerun)
    df = df.drop_duplicates("run_id", keep="first")
    return df.sort_values("run_id", kind="stable").reset_index(drop=True)


class StoredRun(NamedTuple):
    """A run already in the table: its record and variation labels, whether it survived
    (status 'ok'; a collapse, a solver failure or an error did not) and the walls it pounded
    on (the ``walls`` asked for whose ``impacts_<wall>`` > 0)."""

    record: str
    variation: str
    survived: bool
    hits: frozenset = frozenset()


def stored_runs(out, walls=()):
    """{run_id: :class:`StoredRun`} of the runs already stored in ``out``; ``walls``: the wall
    keys whose impacts are read (a hunt-and-fill trace that brackets its onsets needs them)."""
    impacts = [f"impacts_{w}" for w in walls]
    df = load_table(out, columns=["run_id", "record", "variation", "status", *impacts])
    if df.empty:
        return {}
    hit = {w: (df[c].fillna(0).to_numpy(int) > 0) for w, c in zip(walls, impacts)}
    return {rid: StoredRun(rec, v, st == "ok", frozenset(w for w in walls if hit[w][i]))
            for i, (rid, rec, v, st) in enumerate(zip(df["run_id"], df["record"],
                                                      df["variation"], df["status"]))}
