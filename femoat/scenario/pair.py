"""``[motion]`` of a plan scenario: a record pair (:class:`~femoat.ground_motions.RecordPair`),
its orientation and its one scale factor, and the free vibration after it.

Sources: ``"fema"``, a FEMA P695 record as a pair (:func:`~femoat.ground_motions.fema_p695_pair`:
component a along x, b along y, the shorter extended with zeros), or ``"at2"``, two PEER files
``path_x`` and ``path_y`` (:func:`~femoat.ground_motions.read_at2_pair`; ``pad = true`` extends
the shorter with zeros). ``angle`` [deg] turns the pair in plan (positive from +x toward +y).

Amplitude, one factor for both components (FEMA P695 practice, docs/plan.md §2): ``scale`` [-],
times the record's normalization factor NF when ``normalized = true`` (fema); or ``pga`` [g],
which sets the factor so that the **geometric mean of the two components' PGAs**, as recorded
(before any rotation), is ``pga``: √(PGA_x·PGA_y)·scale = pga, the geometric mean P695 uses for
a record's intensity (its NF is PGV-based on the same mean), and independent of the angle, so a
pair is scaled once and applied at any orientation. ``pga`` replaces ``scale`` and
``normalized``. Or ``sa`` [g] with ``period`` [s]: the factor that brings the **geometric mean
of the two components' Sa(T)**, as recorded, to ``sa``, as a suite of pairs scales its records
(:mod:`femoat.scenario.intensity`); it replaces ``scale``, ``normalized`` and ``pga``.

Defaults: the pair's own (:class:`RecordPair`'s angle and scale, :func:`fema_p695_pair`'s
``normalized``, :func:`read_at2_pair`'s ``pad``), the 1D ``[motion]``'s FEMA record choice and
free vibration, and the scenario's own source (:data:`OWN_DEFAULTS`).
"""

import math
from pathlib import Path

from femoat.scenario import intensity, motion
from femoat.scenario.reading import (check_keys, field_default, flag, integer, naming, number,
                                     one_of, parameter_default, resolve, text)

KEYS = ("source", "record_set", "record_id", "normalized", "path_x", "path_y", "pad", "angle",
        "scale", "pga", *intensity.KEYS, "time_scale", "extra_time")
SOURCES = ("fema", "at2")

OWN_DEFAULTS = dict(source="fema", time_scale=1.0)
"""A pair without a source: the 1D file's FEMA record (far-field 1), as recorded in time."""


def defaults():
    """The ``[motion]`` table of a plan scenario without one (TOML-shaped): the default source's
    keys (a FEMA pair; ``pad``, of an AT2 pair, is :func:`read_at2_pair`'s), no ``pga`` (the
    record's own amplitude times ``scale``)."""
    from femoat.ground_motions import RecordPair, fema_p695_pair

    one_d = motion.OWN_DEFAULTS
    return dict(source=OWN_DEFAULTS["source"], record_set=one_d["record_set"],
                record_id=one_d["record_id"],
                normalized=parameter_default(fema_p695_pair, "normalized"),
                angle=field_default(RecordPair, "angle"), scale=field_default(RecordPair, "scale"),
                time_scale=OWN_DEFAULTS["time_scale"],
                extra_time=motion.defaults()["extra_time"])


def pair_from_dict(d, base_dir=Path(".")):
    """The :class:`~femoat.ground_motions.RecordPair` of a plan scenario's ``[motion]`` table
    (turned, scaled and time-scaled)."""
    return pair_and_scaling_from_dict(d, base_dir)[0]


def pair_and_scaling_from_dict(d, base_dir=Path(".")):
    """(the pair, its :class:`~femoat.scenario.intensity.SaScaling` or None): the plan
    ``[motion]`` table's pair and, with ``sa``, how it was scaled to Sa(T) (echoed)."""
    from femoat import ground_motions as gmod

    d = dict(d)
    where = "[motion]"
    single = sorted(set(d) & set(motion.KEYS) - set(KEYS))
    if single:
        raise ValueError(f"{where} {', '.join(single)}: a single record's key; a plan scenario's "
                         "motion is a pair: source = 'fema' with record_set and record_id, or "
                         "source = 'at2' with path_x and path_y.")
    check_keys(d, KEYS, where)
    default = defaults()
    angle = number(d, "angle", default["angle"], where, "deg")
    if not 0.0 <= angle < 360.0:
        raise ValueError(f"{where} angle = {angle:g}: an orientation in [0, 360) [deg] "
                         f"(positive from +x toward +y); write angle = {angle % 360.0:g} for "
                         "the same turn.")
    source = text(d, "source", default["source"], where)
    if source not in SOURCES:
        raise ValueError(f"{where} source = {source!r}: a pair's source is {one_of(SOURCES)}.")
    other = {"fema": ("path_x", "path_y", "pad"), "at2": ("record_set", "record_id", "normalized")}
    stray = [key for key in other[source] if key in d]
    if stray:
        raise ValueError(f"{where} {', '.join(stray)}: not a key of source = {source!r} (fema: "
                         "record_set, record_id, normalized; at2: path_x, path_y, pad).")
    if source == "fema":
        with naming(where):
            pair = gmod.fema_p695_pair(
                text(d, "record_set", default["record_set"], where),
                integer(d, "record_id", default["record_id"], where),
                normalized=flag(d, "normalized", default["normalized"], where))
    else:
        pad = flag(d, "pad", parameter_default(gmod.read_at2_pair, "pad"), where)
        paths = [_path(d, key, base_dir) for key in ("path_x", "path_y")]
        with naming(f"{where} path_x, path_y (pad = {str(pad).lower()}):"):
            pair = gmod.read_at2_pair(*paths, pad=pad)
    x, y = pair.x, pair.y
    ts = number(d, "time_scale", default["time_scale"], where)
    with naming(where):
        if ts != 1.0:
            x, y = x.time_scaled(ts), y.time_scaled(ts)
        scaling = intensity.sa_scaling(d, (x, y), ts, where,
                                       replaces=("scale", "normalized", "pga"))
        scale = scaling.factor if scaling is not None else _scale(d, pair, default, where)
        return gmod.RecordPair(x, y, angle, scale, pair.name), scaling


def _scale(d, pair, default, where):
    """The pair's one amplitude factor [-]: ``scale`` (times NF when normalized, already in
    ``pair.scale``), or the factor that brings the geometric-mean PGA to ``pga`` [g]."""
    if "pga" not in d:
        scale = number(d, "scale", default["scale"], where)
        if scale <= 0.0:
            raise ValueError(f"{where} scale = {scale!r}: expected a positive amplitude factor "
                             "[-] for both components, e.g. scale = 1.5.")
        return pair.scale * scale
    given = [key for key in ("scale", "normalized") if key in d]
    if given:
        raise ValueError(f"{where} pga and {', '.join(given)}: pga sets the pair's amplitude "
                         "alone; give pga or scale (and normalized), not both.")
    pga = number(d, "pga", 1.0, where, "g")
    if pga <= 0.0:
        raise ValueError(f"{where} pga = {pga!r}: expected a positive target [g] for the geometric "
                         "mean of the two components' PGAs, e.g. pga = 0.5 (omit it to keep the "
                         "records' own amplitude).")
    mean = math.sqrt(pair.x.pga * pair.y.pga)
    if mean == 0.0:
        raise ValueError(f"{where} pga = {pga!r}: a component of {pair.name} is zero, so its "
                         "geometric-mean PGA is 0 g and cannot be scaled; use scale.")
    return pga / mean


def _path(d, key, base_dir):
    """The AT2 file of ``key`` (path_x or path_y), relative to the scenario's folder."""
    if key not in d:
        raise ValueError(f"[motion] source = 'at2' needs path_x and path_y (the x and y "
                         f"component files); {key} is missing.")
    path = resolve(text(d, key, f"{key[-1]}.AT2", "[motion]"), base_dir)
    if not path.is_file():
        raise FileNotFoundError(f"[motion] {key} = {d[key]!r}: no such file ({path}).")
    return path
