"""The records of a suite: which ones (``[records]``), their metadata, and loading them once.

A plan suite (``[building] plan = true``) runs record **pairs**: ``pairs = true`` with a FEMA
P695 ``set`` (component a along x, b along y), or ``pairs = [["x.AT2", "y.AT2"], ...]``, each at
every orientation of ``angles`` [deg] (default [0]; positive from +x toward +y,
:mod:`femoat.ground_motions.pair`). A :class:`PairRef` is one pair at one angle: the unit of
a run and of a hunt-and-fill trace (its label, e.g. ``farfield/3@30``, names both); the report
counts the pair as the record and each angle as one analysis of it
(:data:`femoat.suite.statistics.RECORD_RULE`).

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
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

SETS = {"farfield": ("farfield",), "nearfield_pulse": ("nearfield_pulse",),
        "nearfield_no_pulse": ("nearfield_no_pulse",),
        "nearfield": ("nearfield_pulse", "nearfield_no_pulse")}
"""``[records] set`` choices and the FEMA P695 sets each stands for (``nearfield``: 28 x 2)."""

KEYS = {"set", "ids", "components", "folder", "glob", "files", "time_scale", "duration", "pairs",
        "angles"}
PAIR_KEYS = {"pairs", "angles"}
"""The keys of a plan suite's records (``[building] plan = true``): its records are pairs."""


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


@dataclass(frozen=True)
class PairRef:
    """One record pair of a plan suite, at one orientation: its x and y components (each a
    :class:`RecordRef`) and the angle [deg] the pair is turned by in plan. It answers what a
    :class:`RecordRef` answers (the record's metadata are those of x: the two components of
    one recording share them), with no single component."""

    x: RecordRef
    y: RecordRef
    angle: float  # [deg]

    source = property(lambda self: self.x.source)
    record_set = property(lambda self: self.x.record_set)
    component = None
    path = None
    rsn = property(lambda self: self.x.rsn)
    earthquake = property(lambda self: self.x.earthquake)
    magnitude = property(lambda self: self.x.magnitude)
    distance_km = property(lambda self: self.x.distance_km)
    pulse = property(lambda self: self.x.pulse)
    normalization = property(lambda self: self.x.normalization)

    @property
    def record_id(self):
        """The set ID, or the two files' stems joined by '+'."""
        return self.x.record_id if self.source == "fema" else \
            f"{self.x.record_id}+{self.y.record_id}"

    @property
    def record_name(self):
        """The two PEER component names, x + y."""
        return f"{self.x.record_name} + {self.y.record_name}"

    @property
    def digest(self):
        """Both components' digests."""
        return f"{self.x.digest}{self.y.digest}"

    @property
    def pair_label(self):
        """The pair's label without the angle, e.g. ``farfield/3``."""
        return f"{self.record_set}/{self.record_id}" if self.source == "fema" else self.record_id

    @property
    def label(self):
        """Short unique label: the pair and its angle, e.g. ``farfield/3@30``."""
        return f"{self.pair_label}@{self.angle:g}"

    @property
    def components(self):
        """(x, y): the two :class:`RecordRef`."""
        return self.x, self.y


def records_from_dict(d, base_dir=Path("."), plan=False):
    """The :class:`RecordRef` list of the ``[records]`` table, each record loaded and checked;
    with ``plan`` (a plan suite) the :class:`PairRef` list, pair by pair and angle by angle."""
    from femoat.scenario import check_keys

    d = dict(d)
    check_keys(d, KEYS, "[records]")
    if not plan:
        stray = sorted(PAIR_KEYS & set(d))
        if stray:
            raise ValueError(f"[records] {', '.join(stray)}: record pairs run a building in plan; "
                             "add plan = true to [building] (or remove the key).")
    elif "pairs" not in d:
        raise ValueError("[records]: a plan suite ([building] plan = true) runs record pairs: add "
                         "pairs = true with set = '...' (FEMA P695, a along x, b along y) or pairs "
                         "= [['x.AT2', 'y.AT2'], ...].")
    sources = [k for k in ("set", "folder", "glob", "files") if k in d]
    if plan and not sources and isinstance(d["pairs"], list):
        sources = ["pairs"]
    if len(sources) != 1:
        raise ValueError("[records] needs exactly one of set = 'farfield' (FEMA P695), "
                         "folder = 'dir', glob = 'dir/*.AT2' or files = [...]"
                         + (" (a plan suite: set = '...' with pairs = true, or pairs = "
                            "[['x.AT2', 'y.AT2'], ...])" if plan else "")
                         + f"; got {sources or 'none'}.")
    for key, kind, example in (("ids", int, "[1, 2, 3]"), ("components", str, "['a', 'b']"),
                               ("files", str, "['a.AT2', 'b.AT2']")):
        if key in d and (not isinstance(d[key], list) or not all(
                isinstance(v, kind) and not isinstance(v, bool) for v in d[key])):
            raise ValueError(f"[records] {key} = {d[key]!r}: give a list like {example}.")
    for key in ("set", "folder", "glob"):
        if key in d and not isinstance(d[key], str):
            raise ValueError(f"[records] {key} = {d[key]!r}: give a string.")
    if plan:
        return _pair_refs(d, Path(base_dir), sources[0])
    if "set" in d:
        return _fema_refs(d)
    for key in ("ids", "components"):
        if key in d:
            raise ValueError(f"[records] {key} applies to set = '...' (FEMA P695) only.")
    refs = [_at2_ref(p) for p in _files(d, Path(base_dir))]
    _check_unique(refs)
    return refs


def _check_unique(refs):
    seen = {}
    for r in refs:  # the file stem names a record in the table and in run ids
        if r.label in seen:
            raise ValueError(f"[records] two files are named {r.label}: {seen[r.label]} and "
                             f"{r.path}; rename one (each record needs its own name).")
        seen[r.label] = r.path


def _pair_refs(d, base_dir, source):
    """The pairs of a plan suite, each at every angle of ``angles``."""
    angles = d.get("angles", [0.0])
    if not isinstance(angles, list) or not angles or not all(
            isinstance(a, (int, float)) and not isinstance(a, bool) and math.isfinite(a)
            for a in angles):
        raise ValueError(f"[records] angles = {angles!r}: give a non-empty list of orientations "
                         "[deg], e.g. [0, 45, 90, 135].")
    outside = [a for a in angles if not 0.0 <= a < 360.0]
    if outside:
        raise ValueError(f"[records] angles = {angles!r}: {outside[0]!r} is outside [0, 360) "
                         f"[deg]; write {float(outside[0]) % 360.0:g} for the same turn.")
    if len({float(a) for a in angles}) != len(angles):
        raise ValueError(f"[records] angles = {angles!r} lists an angle twice.")
    pairs = d["pairs"]
    if source == "set":
        if pairs is not True:
            raise ValueError(f"[records] pairs = {pairs!r}: with set = '...' give pairs = true "
                             "(component a along x, b along y).")
        if "components" in d:
            raise ValueError("[records] components: a plan suite applies both components of "
                             "each record (a along x, b along y); remove the key.")
        refs = _fema_refs({k: v for k, v in d.items() if k in ("set", "ids")})
        comps = [(refs[i], refs[i + 1]) for i in range(0, len(refs), 2)]
    elif source == "pairs":
        for key in ("ids", "components"):
            if key in d:
                raise ValueError(f"[records] {key} applies to set = '...' (FEMA P695) only.")
        if not pairs or not all(isinstance(p, list) and len(p) == 2 and all(
                isinstance(f, str) for f in p) for p in pairs):
            raise ValueError(f"[records] pairs = {pairs!r}: give a list of [x, y] file pairs, "
                             "e.g. [['RSN1_X.AT2', 'RSN1_Y.AT2']] (or pairs = true with set = "
                             "'...').")
        files = [_at2_ref(f) for f in _files({"pairs": pairs}, base_dir)]
        comps = list(zip(files[0::2], files[1::2]))
    else:
        raise ValueError(f"[records] {source} = ...: a plan suite's records are pairs; give "
                         "pairs = [['x.AT2', 'y.AT2'], ...] (or set = '...' with pairs = true).")
    out = [PairRef(x, y, float(a)) for x, y in comps for a in angles]
    for x, y in comps:
        _check_pair(x, y)
    seen = set()
    for r in out:
        if r.label in seen:
            raise ValueError(f"[records] the pair {r.pair_label} is listed twice.")
        seen.add(r.label)
    return out


def _check_pair(x, y):
    """Both components of a pair share one time step (one is extended with zeros to the
    other's length, as :func:`femoat.ground_motions.pair.fema_p695_pair` does)."""
    gx, gy = load_motion(x), load_motion(y)
    if gx.dt != gy.dt:
        raise ValueError(f"[records] pair {x.label} + {y.label}: the components' time steps "
                         f"differ ({gx.dt:g} s and {gy.dt:g} s); a pair needs one time step "
                         "(resample one of them, or pair the two components of one recording).")


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
    key = "files" if "files" in d else "pairs"  # a plan suite's pairs: x, y, x, y, ...
    given = d["files"] if key == "files" else [f for pair in d["pairs"] for f in pair]
    files = [_resolve(p, base_dir) for p in given]
    if not files:
        raise ValueError(f"[records] {key} = []: list at least one AT2 file.")
    for p, name in zip(files, given):
        if not p.is_file():
            raise ValueError(f"[records] {key}: {name!r} ({p}) does not exist.")
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



def applied(ref, factor, time_scale, duration=None):
    """What a run applies: :func:`applied_motion` of a component, or for a :class:`PairRef`
    its pair turned by its angle, both components cut, scaled and time-scaled alike (the
    shorter one extended with zeros to the longer one's length)."""
    if not isinstance(ref, PairRef):
        return applied_motion(ref, factor, time_scale, duration)
    from femoat.ground_motions.pair import RecordPair, zero_padded

    x, y = zero_padded(*(applied_motion(c, factor, time_scale, duration)
                         for c in ref.components))
    return RecordPair(x, y, angle=ref.angle, name=ref.label)
