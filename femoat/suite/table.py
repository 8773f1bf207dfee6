"""The results table: one row per run, Parquet part files in ``DIR/runs/``, one per batch.

Each part is written atomically (:mod:`femoat.atomic`), so a part on disk is always complete;
an interrupted suite loses at most the batches in flight. Units: forces [kip], displacements
[in], accelerations and intensities [g], times [s], drift ratios [-]. Columns, in order:

* identity: run_id, suite_hash, femoat_version, record (label), variation (label), record_set,
  record_id, rsn, record_name (PEER component name), component, earthquake, magnitude,
  distance_km (closest to the rupture plane), pulse;
* intensity: scale_factor (total factor on the unscaled record), im_kind ('sa' | 'pga'), im,
  sa_t and pga as applied; then one column per varied key, named by its dotted key;
* outcome: status ('ok' | 'collapsed' | 'solver_failure' | 'error'), error (naming the run),
  collapsed, collapse_<c> and collapse_<c>_time (NaN if not reached) for c in drift, isolator,
  wall_displacement, wall_force;
* peaks: peak_impact_force_pos/neg, impacts_pos/neg, peak_base_displacement,
  peak_wall_displacement_pos/neg, peak_drift_<k>, peak_drift_ratio_<k>, peak_drift_ratio (max
  over stories), peak_floor_acceleration_<k>, peak_base_acceleration, pounding (any impact),
  t_reached (the run's last time: the collapse time when it stopped there), cpu_seconds (CPU
  of the whole run in its thread: model lookup, record scaling, solver, peaks), solver_seconds
  (process CPU of the compiled loop, from the solver), steps.
"""

import hashlib
from pathlib import Path

from femoat.collapse import CRITERIA

IDENTITY = [("run_id", "string"), ("suite_hash", "string"), ("femoat_version", "string"),
            ("record", "string"), ("variation", "string"), ("record_set", "string"),
            ("record_id", "string"), ("rsn", "int64"), ("record_name", "string"),
            ("component", "string"), ("earthquake", "string"), ("magnitude", "float64"),
            ("distance_km", "float64"), ("pulse", "bool"), ("scale_factor", "float64"),
            ("im_kind", "string"), ("im", "float64"), ("sa_t", "float64"), ("pga", "float64")]
PEAKS = [("peak_impact_force_pos", "float64"), ("peak_impact_force_neg", "float64"),
         ("impacts_pos", "int64"), ("impacts_neg", "int64"),
         ("peak_base_displacement", "float64"), ("peak_wall_displacement_pos", "float64"),
         ("peak_wall_displacement_neg", "float64")]
TAIL = [("peak_drift_ratio", "float64"), ("peak_base_acceleration", "float64"),
        ("pounding", "bool"), ("t_reached", "float64"), ("cpu_seconds", "float64"),
        ("solver_seconds", "float64"), ("steps", "int64")]


def columns(suite):
    """[(name, arrow type name)] of ``suite``'s table."""
    cols = list(IDENTITY)
    for key in suite.varied:
        cols.append((key, _value_type([c[key] for c in suite.combos])))
    cols += [("status", "string"), ("error", "string"), ("collapsed", "bool")]
    for c in CRITERIA:
        cols += [(f"collapse_{c}", "bool"), (f"collapse_{c}_time", "float64")]
    cols += PEAKS
    for k in range(1, suite.n_stories + 1):
        cols += [(f"peak_drift_{k}", "float64"), (f"peak_drift_ratio_{k}", "float64"),
                 (f"peak_floor_acceleration_{k}", "float64")]
    return cols + TAIL


def _value_type(values):
    if all(isinstance(v, bool) for v in values):
        return "bool"
    if all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        return "int64"
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return "float64"
    return "string"


def schema(suite):
    import pyarrow as pa

    types = dict(bool=pa.bool_(), int64=pa.int64(), float64=pa.float64(), string=pa.string())
    return pa.schema([(name, types[kind]) for name, kind in columns(suite)])


def write_part(rows, suite, out):
    """Write ``rows`` as one Parquet part in ``out/runs/`` (atomically); return its path."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from femoat.atomic import atomic_path

    types = dict(columns(suite))
    clean = []
    for row in rows:
        r = {k: (str(v) if types.get(k) == "string" and v is not None else v)
             for k, v in row.items()}
        clean.append(r)
    table = pa.Table.from_pylist(clean, schema=schema(suite))
    name = hashlib.sha256("|".join(r["run_id"] for r in rows).encode()).hexdigest()[:16]
    path = Path(out) / "runs" / f"part-{name}.parquet"
    with atomic_path(path) as tmp:
        pq.write_table(table, tmp)
    return path


def _parts(out):
    folder = Path(out) / "runs"
    return sorted(folder.glob("part-*.parquet")) if folder.is_dir() else []


def load_table(out, columns=None):
    """The results table of the suite folder ``out`` as a pandas DataFrame (one row per run)."""
    import pandas as pd
    import pyarrow.parquet as pq

    parts = _parts(out)
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


def stored_runs(out):
    """{run_id: (record, variation, did-not-survive)} of the runs already stored in ``out``."""
    df = load_table(out, columns=["run_id", "record", "variation", "status"])
    return {rid: (rec, v, st != "ok")
            for rid, rec, v, st in zip(df["run_id"], df["record"], df["variation"], df["status"])}
