"""``[motion]``: the ground motion, scaled and time-scaled, and the free vibration after it.

Amplitude: ``pga`` [g], the record scaled to this PGA, or ``sa`` [g] with ``period`` [s], the
record scaled to this Sa(T) (:mod:`femoat.scenario.intensity`, as suites scale); not both.

Defaults: the paper's record (Erzincan N-S at :data:`~femoat.ground_motions.PAPER_PGA`,
time-scaled as :func:`~femoat.ground_motions.erzincan_paper`), :func:`femoat.run.run`'s
``extra_time``, :func:`~femoat.ground_motions.read_text`'s units and column; other records
keep their own amplitude and time axis. The FEMA record picked when the table names none is the
scenario's own (:data:`OWN_DEFAULTS`).
"""

from pathlib import Path

from femoat.scenario import intensity
from femoat.scenario.reading import (check_keys, integer, naming, number, one_of,
                                     parameter_default, resolve, text)

KEYS = ("source", "path", "dt", "units", "record_set", "record_id", "component", "pga",
        *intensity.KEYS, "time_scale", "extra_time", "column", "skip_rows")
SOURCES = ("erzincan", "at2", "text", "fema")

OWN_DEFAULTS = dict(source="erzincan", record_set="farfield", record_id=1, component="a")
"""The paper's record; a ``fema`` source without a choice: far-field record 1, component a."""


def defaults():
    """The ``[motion]`` table of an empty scenario: the paper's record and the run's free
    vibration after it."""
    from femoat import ground_motions as gmod
    from femoat.run import run

    return dict(source=OWN_DEFAULTS["source"], pga=gmod.PAPER_PGA,
                time_scale=parameter_default(gmod.erzincan_paper, "time_scale"),
                extra_time=parameter_default(run, "extra_time"))


def motion_from_dict(d, base_dir=Path(".")):
    """The ground motion from the ``[motion]`` table (scaled and time-scaled)."""
    return motion_and_scaling_from_dict(d, base_dir)[0]


def motion_and_scaling_from_dict(d, base_dir=Path(".")):
    """(the ground motion, its :class:`~femoat.scenario.intensity.SaScaling` or None): the
    ``[motion]`` table's record and, with ``sa``, how it was scaled to Sa(T) (echoed)."""
    d = dict(d)
    where = "[motion]"
    check_keys(d, KEYS, where)
    with naming(where):
        return _motion(d, base_dir, where)


def extra_time_from_dict(d):
    """``extra_time`` [s] of the ``[motion]`` table: free vibration after the record."""
    extra_time = number(d, "extra_time", defaults()["extra_time"], "[motion]", "s")
    if extra_time < 0.0:
        raise ValueError(f"[motion] extra_time = {extra_time!r}: expected a time >= 0 [s].")
    return extra_time


def _motion(d, base_dir, where):
    from femoat import ground_motions as gmod

    source = text(d, "source", OWN_DEFAULTS["source"], where)
    erzincan = source == "erzincan"
    if erzincan:
        gm = gmod.erzincan_ns()
    elif source == "at2":
        gm = gmod.read_at2(_path(d, base_dir))
    elif source == "text":
        if "dt" not in d:
            raise ValueError("[motion] source = 'text' needs dt [s] (the sample interval).")
        skip = integer(d, "skip_rows", 0, where) if "skip_rows" in d else None
        gm = gmod.read_text(_path(d, base_dir), number(d, "dt", 0.01, where, "s"),
                            units=text(d, "units", parameter_default(gmod.read_text, "units"),
                                       where),
                            column=integer(d, "column",
                                           parameter_default(gmod.read_text, "column"), where),
                            skip_rows=skip)
    elif source == "fema":
        gm = gmod.fema_p695_record(text(d, "record_set", OWN_DEFAULTS["record_set"], where),
                                   integer(d, "record_id", OWN_DEFAULTS["record_id"], where),
                                   text(d, "component", OWN_DEFAULTS["component"], where))
    else:
        raise ValueError(f"[motion] source = {source!r}: use {one_of(SOURCES)}.")
    default = defaults() if erzincan else dict(pga=None, time_scale=1.0)
    ts = number(d, "time_scale", default["time_scale"], where)
    scaling = intensity.sa_scaling(d, (gm.time_scaled(ts) if ts != 1.0 else gm,), ts, where,
                                   replaces=("pga",))
    if scaling is not None:
        gm = gm.scaled(scaling.factor)
    pga = number(d, "pga", default["pga"], where, "g") \
        if scaling is None and (erzincan or "pga" in d) else None
    if pga is not None:
        if pga <= 0.0:
            raise ValueError(f"[motion] pga = {d['pga']!r}: expected a positive target PGA "
                             f"[g], e.g. pga = {gmod.PAPER_PGA} (omit it to keep the record's "
                             "own amplitude).")
        gm = gm.scaled_to_pga(pga)
    if ts != 1.0:
        gm = gm.time_scaled(ts)
    return gm, scaling


def _path(d, base_dir):
    if "path" not in d:
        raise ValueError("[motion] needs path = '...' for this source.")
    path = resolve(text(d, "path", "record.AT2", "[motion]"), base_dir)
    if not path.is_file():
        raise FileNotFoundError(f"[motion] path = {d['path']!r}: no such file ({path}).")
    return path
