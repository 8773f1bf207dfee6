"""The results table in other shapes: an xarray Dataset of peaks, a pelicun demand file."""

from femoat.suite.columns import column_of

_ID = ["record", "im", "variation"]


def to_xarray(df):
    """Peaks as an ``xarray.Dataset`` with dims (record, intensity, variation).

    ``record`` is the record label (e.g. ``farfield/3b``), ``intensity`` the im [g] (kind in the
    ``im_kind`` attribute), ``variation`` the variation label; runs absent from the table
    (hunt-and-fill traces at other intensities) are NaN. Every numeric column of the intensity
    as applied, the outcome and the peaks (:mod:`femoat.suite.columns`) becomes a variable;
    ``status`` is kept as text.
    """
    import numpy as np

    keep = [c for c in df.columns if c not in _ID and _variable(column_of(c))]
    frame = df[_ID + keep].copy()
    for c in keep:
        if c != "status":  # nullable Int64 / boolean columns: NaN where missing
            frame[c] = frame[c].astype("float64")
    ds = frame.set_index(_ID).to_xarray().rename(im="intensity")
    ds.attrs.update(im_kind=str(df["im_kind"].iloc[0]) if len(df) else "",
                    units="forces kip, displacements in, accelerations and im g, times s")
    for c in ds.data_vars:
        if ds[c].dtype == object and c != "status":
            ds[c] = ds[c].astype(np.float64)
        if column_of(c).unit:
            ds[c].attrs["units"] = column_of(c).unit
    return ds


def _variable(col):
    """Whether a table column is a variable of :func:`to_xarray`."""
    return col is not None and col.section in ("intensity", "outcome", "peaks") and (
        col.dtype != "string" or col.name == "status")


def to_demand_csv(df, path, n_stories=None):
    """Write a pelicun demand sample (one row per run of ``df``) to ``path``; return ``path``.

    Columns ``type-location-direction`` with pelicun's (FEMA P-58) numbering, location 0 being
    the ground: ``PFA-0-1`` the PGA of the record as applied [g], ``PFA-1-1`` the base mat (the
    floor slab above the isolators) [g], ``PFA-{k+1}-1`` the floor on top of story k [g] and
    ``PID-k-1`` the peak drift ratio of story k [rad] (story k spans floors k and k+1); a plan
    suite's table gives direction 1 (x) and 2 (y) of each, its ground PFA the pair's
    geometric-mean PGA as applied in both (the table holds no PGA per direction). The
    second row holds the units (``Units,g,...,rad``); the index is the run_id. Filter ``df`` to
    one stripe (intensity, variation) and to the runs that did not collapse first
    (``df[~df.collapsed & (df.status == "ok")]``): pelicun reads one sample per hazard level and
    treats collapse through its own fragility, and a run stopped at collapse has peaks only up
    to that time.
    """
    import pandas as pd

    from femoat.atomic import atomic_path

    if n_stories is None:
        n_stories = max((int(c.rsplit("_", 1)[1]) for c in df.columns
                         if c.startswith("peak_drift_ratio_")), default=0)
    plan = "peak_drift_ratio_x_1" in df.columns or "peak_base_acceleration_x" in df.columns
    axes = {"1": "_x", "2": "_y"} if plan else {"1": ""}
    cols = {}
    for d, a in axes.items():  # the ground: the pair's geometric-mean PGA in both directions
        cols[f"PFA-0-{d}"] = df["pga"]
    for d, a in axes.items():
        cols[f"PFA-1-{d}"] = df[f"peak_base_acceleration{a}"]
    for k in range(1, n_stories + 1):
        for d, a in axes.items():
            cols[f"PFA-{k + 1}-{d}"] = df[f"peak_floor_acceleration{a}_{k}"]
    for k in range(1, n_stories + 1):
        for d, a in axes.items():
            cols[f"PID-{k}-{d}"] = df[f"peak_drift_ratio{a}_{k}"]
    units = {c: ("rad" if c.startswith("PID") else "g") for c in cols}
    demand = pd.DataFrame(cols)
    demand.index = df["run_id"].to_numpy()
    table = pd.concat([pd.DataFrame([units], index=["Units"]), demand.astype(object)])
    with atomic_path(path) as tmp:
        table.to_csv(tmp)
    return path
