"""The records of a suite: which ones (``[records]``), their metadata, and loading them once.

A :class:`RecordRef` names one component by identity (a FEMA P695 set, ID and component, or an AT2
file) and carries what the results table reports about it. :func:`load_motion` turns a reference
into the **unscaled** :class:`~femoat.ground_motions.GroundMotion`, cached per process so that a
worker reads each record once however many runs use it. Each reference holds a hash of the
record's samples: a worker whose file differs from the one the suite was defined with refuses to
run it (an AT2 folder must be the same on every machine of a cluster).
"""

import functools
import glob as globmod
import hashlib
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

SETS = {"farfield": ("farfield",), "nearfield_pulse": ("nearfield_pulse",),
        "nearfield_no_pulse": ("nearfield_no_pulse",),
        "nearfield": ("nearfield_pulse", "nearfield_no_pulse")}
"""``[records] set`` choices and the FEMA P695 sets each stands for (``nearfield``: 28 x 2)."""

KEYS = {"set", "ids", "components", "folder", "glob", "files", "time_scale", "duration"}


@dataclass(frozen=True)
class RecordRef:
    """One ground-motion component, by identity, with its metadata (None where unknown)."""

    source: str  # "fema" | "at2"
    record_set: str | None  # the FEMA P695 set, or None for files
    record_id: str  # set ID ("1".."28") or the file stem
    component: str | None  # "a" | "b" for FEMA P695, None for files
    path: str | None  # AT2 file (absolute), None for FEMA P695
    record_name: str  # PEER component name, e.g. "NORTHR/MUL009", or the file stem
    rsn: int | None
    earthquake: str | None
    magnitude: float | None
    distance_km: float | None  # closest distance to the rupture plane
    pulse: bool | None
    normalization: float | None  # FEMA P695 normalization factor (PGV-based) [-]
    digest: str  # sha256 of dt and the samples, first 16 hex digits

    @property
    def label(self):
        """Short unique label, e.g. ``farfield/3b`` or ``Rinaldi228``."""
        if self.source == "fema":
            return f"{self.record_set}/{self.record_id}{self.component}"
        return self.record_id


def records_from_dict(d, base_dir=Path(".")):
    """The :class:`RecordRef` list of the ``[records]`` table, each record loaded and checked."""
    from femoat.scenario import check_keys

    d = dict(d)
    check_keys(d, KEYS, "[records]")
    sources = [k for k in ("set", "folder", "glob", "files") if k in d]
    if len(sources) != 1:
        raise ValueError("[records] needs exactly one of set = 'farfield' (FEMA P695), "
                         "folder = 'dir', glob = 'dir/*.AT2' or files = [...]; got "
                         f"{sources or 'none'}.")
    for key, kind, example in (("ids", int, "[1, 2, 3]"), ("components", str, "['a', 'b']"),
                               ("files", str, "['a.AT2', 'b.AT2']")):
        if key in d and (not isinstance(d[key], list) or not all(
                isinstance(v, kind) and not isinstance(v, bool) for v in d[key])):
            raise ValueError(f"[records] {key} = {d[key]!r}: give a list like {example}.")
    for key in ("set", "folder", "glob"):
        if key in d and not isinstance(d[key], str):
            raise ValueError(f"[records] {key} = {d[key]!r}: give a string.")
    if "set" in d:
        return _fema_refs(d)
    for key in ("ids", "components"):
        if key in d:
            raise ValueError(f"[records] {key} applies to set = '...' (FEMA P695) only.")
    refs = [_at2_ref(p) for p in _files(d, Path(base_dir))]
    seen = {}
    for r in refs:  # the file stem names a record in the table and in run ids
        if r.label in seen:
            raise ValueError(f"[records] two files are named {r.label}: {seen[r.label]} and "
                             f"{r.path}; rename one (each record needs its own name).")
        seen[r.label] = r.path
    return refs


def _fema_refs(d):
    from femoat.ground_motions.fema import _load

    name = d["set"]
    if name not in SETS:
        raise ValueError(f"[records] set = {name!r}: use one of {sorted(SETS)}.")
    comps = d.get("components", ["a", "b"])
    if not comps or any(c not in ("a", "b") for c in comps) or len(set(comps)) != len(comps):
        raise ValueError(f"[records] components = {comps!r}: use ['a', 'b'], ['a'] or ['b'].")
    refs, known = [], []
    for sub in SETS[name]:
        data = _load(sub)
        for rid, row in data.records.sort_index().iterrows():
            known.append(int(rid))
            if "ids" in d and int(rid) not in d["ids"]:
                continue
            for c in comps:
                gm = data.ground_motions.loc[(int(rid), c)]
                accel = np.asarray(gm["RecordedAcceleration"], dtype=float)
                refs.append(RecordRef(
                    source="fema", record_set=sub, record_id=str(int(rid)), component=c,
                    path=None, record_name=str(gm["ComponentName"]),
                    rsn=int(row["RecordSequenceNumber"]), earthquake=str(row["EarthquakeName"]),
                    magnitude=float(row["EarthquakeMagnitude"]),
                    distance_km=float(row["SiteDistanceClosestToPlane"]),
                    pulse=None if sub == "farfield" else sub == "nearfield_pulse",
                    normalization=float(row["NormalizationFactor"]),
                    digest=_digest(accel, float(gm["DT"]))))
    missing = sorted(set(d.get("ids", [])) - set(known))
    if missing:
        raise ValueError(f"[records] ids {missing} are not in FEMA P695 set {name!r} "
                         f"(IDs {min(known)}..{max(known)}).")
    if not refs:
        raise ValueError("[records] ids = [] selects no record.")
    return refs


def _files(d, base_dir):
    if "folder" in d:
        folder = _resolve(d["folder"], base_dir)
        if not folder.is_dir():
            raise ValueError(f"[records] folder = {d['folder']!r}: {folder} is not a folder.")
        files = sorted(p for p in folder.iterdir() if p.suffix.lower() == ".at2")
        if not files:
            raise ValueError(f"[records] folder = {d['folder']!r}: no .AT2 file in {folder}.")
        return files
    if "glob" in d:
        pattern = str(_resolve(d["glob"], base_dir))
        files = sorted(Path(p) for p in globmod.glob(pattern))
        if not files:
            raise ValueError(f"[records] glob = {d['glob']!r}: no file matches {pattern}.")
        return files
    files = [_resolve(p, base_dir) for p in d["files"]]
    if not files:
        raise ValueError("[records] files = []: list at least one AT2 file.")
    for p, given in zip(files, d["files"]):
        if not p.is_file():
            raise ValueError(f"[records] files: {given!r} ({p}) does not exist.")
    return files


def _resolve(path, base_dir):
    p = Path(path)
    return (p if p.is_absolute() else base_dir / p).resolve()


def _at2_ref(path):
    from femoat.ground_motions import read_at2

    gm = read_at2(path)  # RecordFormatError names the file and the line
    with open(path, encoding="latin-1") as f:
        f.readline()
        event = f.readline().strip()
    rsn = re.match(r"RSN(\d+)", path.stem, re.IGNORECASE)
    return RecordRef(source="at2", record_set=None, record_id=path.stem, component=None,
                     path=str(path), record_name=path.stem,
                     rsn=int(rsn.group(1)) if rsn else None,
                     earthquake=event.split(",")[0].strip() or None, magnitude=None,
                     distance_km=None, pulse=None, normalization=None,
                     digest=_digest(gm.accel_g, gm.dt))


def _digest(accel, dt):
    h = hashlib.sha256(np.float64(dt).tobytes())
    h.update(np.ascontiguousarray(accel, dtype=np.float64).tobytes())
    return h.hexdigest()[:16]


@functools.lru_cache(maxsize=256)
def load_motion(ref):
    """The unscaled record of ``ref`` (cached per process); checked against ``ref.digest``."""
    from femoat.ground_motions import fema_p695_record, read_at2

    if ref.source == "fema":
        gm = fema_p695_record(ref.record_set, int(ref.record_id), ref.component)
    else:
        gm = read_at2(ref.path)
    if _digest(gm.accel_g, gm.dt) != ref.digest:
        raise ValueError(f"record {ref.label}: its samples differ from those the suite was "
                         "defined with (a changed file, or another file on this machine).")
    return gm


def applied_motion(ref, factor, time_scale, duration=None):
    """The record as a run applies it: first ``duration`` [s] of the published record (all when
    None), amplitude x ``factor``, time x ``time_scale``."""
    gm = load_motion(ref)
    if duration is not None and duration < gm.duration:
        from femoat.ground_motions import GroundMotion

        n = int(round(duration / gm.dt)) + 1
        gm = GroundMotion(gm.accel_g[:n], gm.dt, gm.name, f"{gm.source}; first {duration:g} s")
    gm = gm.scaled(factor)
    return gm.time_scaled(time_scale) if time_scale != 1.0 else gm
