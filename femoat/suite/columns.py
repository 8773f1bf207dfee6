"""The columns of a suite's run table, in one place: one row of :data:`COLUMNS` per column (or
per family of columns: one per story, per collapse criterion, per varied key) gives its name,
type, unit, what it holds and how a run's value is read. The rows (:mod:`femoat.suite.runs`),
the Parquet schema (:mod:`femoat.suite.table`), the exports (:mod:`femoat.suite.export`) and the
column list of ``docs/suite_table.md`` (:func:`markdown`, checked by a test) are all made from it;
a new column is one row here.

How a value is read depends on the column's section:

* ``identity``, ``intensity``, ``variation``: from the run's place in the suite, known before it
  runs (a :class:`Planned`: the suite, the :class:`~femoat.suite.runs.RunSpec`, the record and
  the scale factor);
* ``outcome``, ``peaks``: from the finished run's :class:`~femoat.results.RunResult` (its
  ``peaks`` and ``collapse``); a run that did not finish gets the column's ``failed`` value
  (None: missing), and the task sets its status and error. A column without an extractor is
  filled by the task itself (its CPU time).

Units: forces [kip], displacements [in], accelerations and intensities [g], times [s], drift
ratios and factors [-]; text, flags and counts have none.
"""

import math
from dataclasses import dataclass
from typing import Callable, NamedTuple

import numpy as np

from femoat.collapse import CRITERIA
from femoat.suite import variations as var
from femoat.suite.definition import code_version, wall_keys

DTYPES = ("string", "int64", "float64", "bool")
SECTIONS = {  # section: what its columns say (the headings of docs/suite_table.md)
    "identity": "which run: its id, the suite and the record",
    "intensity": "how the record was scaled, as applied",
    "variation": "the values of the varied keys",
    "outcome": "how the run ended",
    "peaks": "the peak responses and the run's cost",
}
PLANNED = ("identity", "intensity", "variation")  # read before the run

PER = {  # family: (placeholder in the name, the indices of a suite)
    "story": ("k", lambda suite: range(1, suite.n_stories + 1)),
    "wall": ("w", lambda suite: suite.walls),
    "criterion": ("c", lambda suite: CRITERIA),
    "key": ("key", lambda suite: suite.varied),
}


@dataclass(frozen=True)
class Column:
    """One column of the run table, or one family of them.

    name : str  the column's name; a family's holds its placeholder: ``{k}`` the story, 1 at
        the bottom; ``{c}`` the collapse criterion; ``{key}`` the varied key (dotted)
    dtype : str or None  "string" | "int64" | "float64" | "bool"; None: from the values
    unit : str  "kip", "in", "g", "s", "km", "-", or "" (text, flags, counts)
    extract : callable or None  the value of a run: ``extract(planned)`` for the sections
        read before the run, ``extract(result)`` after it (``(…, index)`` for a family); None:
        the task fills it
    description : str  what the column holds (docs/suite_table.md)
    section : str  one of :data:`SECTIONS`
    per : str or None  the family: "story" | "wall" | "criterion" | "key"
    failed : object  the value when the run did not finish (columns read from the result)
    models : str or None  "plan": a plan suite's column only; "1d": a 1D suite's only; None:
        every suite's (in a plan suite, a building-wide value over both axes: the larger)
    """

    name: str
    dtype: str | None
    unit: str
    extract: Callable | None
    description: str
    section: str
    per: str | None = None
    failed: object = None
    models: str | None = None

    def __post_init__(self):
        if self.models not in (None, "1d", "plan"):
            raise ValueError(f"column {self.name}: models = {self.models!r}, use None, '1d' or "
                             "'plan'")
        if self.dtype not in DTYPES and not (self.dtype is None and self.per == "key"):
            raise ValueError(f"column {self.name}: dtype = {self.dtype!r}, use one of {DTYPES}")
        if self.section not in SECTIONS:
            raise ValueError(f"column {self.name}: section = {self.section!r}, use one of "
                             f"{list(SECTIONS)}")
        if self.per is not None and f"{{{PER[self.per][0]}}}" not in self.name:
            raise ValueError(f"column {self.name}: a family per {self.per} names its "
                             f"{{{PER[self.per][0]}}}")


class Planned(NamedTuple):
    """What the sections read before a run see: its place in the suite."""

    suite: object  # Suite
    spec: object  # RunSpec
    record: object  # RecordRef
    factor: float  # [-] total amplitude factor on the unscaled record


def planned(suite, spec):
    """The :class:`Planned` view of run ``spec`` of ``suite``."""
    return Planned(suite, spec, suite.records[spec.rec], suite.scaling.factor(spec.rec, spec.im))


def _sa(p):
    sa = p.suite.scaling.sa[p.spec.rec]
    return None if sa is None else sa * p.factor


def _collapsed(result):
    """A criterion reached, or a runaway bound: a run whose criteria allow more than a story
    drift of one story height ended there all the same, and its building had collapsed."""
    return bool(result.collapse["collapsed"] or result.runaway is not None)


def _criterion_time(result, c):
    t = result.collapse.get(c)
    return math.nan if t is None else float(t)


def _per_story(peaks, name):
    """The per-story list ``name`` of a run's peaks; in a plan run, where the peaks hold it per
    axis (``name_x``, ``name_y``), the larger of the two story by story; None when not
    recorded."""
    if name in peaks:
        return peaks[name]
    x, y = peaks.get(f"{name}_x"), peaks.get(f"{name}_y")
    if x is None or y is None:
        return None
    return [max(a, b) for a, b in zip(x, y)]


def _story(peaks, name, k):
    """Story ``k``'s (1 at the bottom) value of the per-story peak ``name`` (:func:`_per_story`);
    NaN above the variation's own stories (a suite's variations may differ in height) or when
    not recorded."""
    values = _per_story(peaks, name)
    if values is None:
        return math.nan
    return float(np.asarray(values, dtype=float)[k - 1]) if k <= len(values) else math.nan


def _largest_over_axes(peaks, name):
    """A scalar peak ``name``, or in a plan run the larger of ``name_x`` and ``name_y``."""
    if name in peaks:
        return _optional(peaks[name])
    values = [peaks.get(f"{name}_{a}") for a in ("x", "y")]
    return math.nan if None in values else float(max(values))


def _impacts(peaks, w):
    value = peaks.get(f"impacts_{w}")
    return None if value is None else int(value)


def _pounding(peaks):
    """Any impact on any wall."""
    return any(v for k, v in peaks.items() if k.startswith("impacts_") and v)


def _optional(x):
    return math.nan if x is None else float(x)


COLUMNS = (
    # (name, dtype, unit, extract, description, section, [per], [failed]), in column order
    Column("run_id", "string", "", lambda p: p.spec.run_id,
           "the run's id: a hash of the suite hash, the record, the variation and the "
           "intensity, stable across processes and reruns", "identity"),
    Column("suite_hash", "string", "", lambda p: p.suite.hash,
           "the suite definition's hash", "identity"),
    Column("femoat_version", "string", "", lambda p: code_version(),
           "femoat's version and a fingerprint of the sources that compute a run", "identity"),
    Column("record", "string", "", lambda p: p.record.label,
           "the record's label, e.g. farfield/3b or the AT2 file's stem (a plan suite: the "
           "pair and its angle, e.g. farfield/3@30)", "identity"),
    Column("variation", "string", "", lambda p: var.label(p.suite.combos[p.spec.var]),
           "the variation's label, e.g. walls.law=E (base when nothing varies)", "identity"),
    Column("record_set", "string", "", lambda p: p.record.record_set,
           "the FEMA P695 set (empty for AT2 files)", "identity"),
    Column("record_id", "string", "", lambda p: p.record.record_id,
           "the ID in the set, or the file's stem", "identity"),
    Column("rsn", "int64", "", lambda p: p.record.rsn,
           "PEER record sequence number", "identity"),
    Column("record_name", "string", "", lambda p: p.record.record_name,
           "PEER component name", "identity"),
    Column("component", "string", "", lambda p: p.record.component,
           "'a' or 'b' of a FEMA P695 pair (empty in a plan suite: both)", "identity"),
    Column("earthquake", "string", "", lambda p: p.record.earthquake,
           "the earthquake's name", "identity"),
    Column("magnitude", "float64", "-", lambda p: p.record.magnitude,
           "moment magnitude", "identity"),
    Column("distance_km", "float64", "km", lambda p: p.record.distance_km,
           "closest distance to the rupture plane", "identity"),
    Column("pulse", "bool", "", lambda p: p.record.pulse,
           "a pulse-like record", "identity"),
    Column("angle", "float64", "deg", lambda p: p.record.angle,
           "the pair's orientation in plan, from +x toward +y", "identity", models="plan"),
    Column("scale_factor", "float64", "-", lambda p: p.factor,
           "total amplitude factor on the unscaled record", "intensity"),
    Column("im_kind", "string", "", lambda p: p.suite.scaling.im_kind,
           "the intensity measure: 'sa' (Sa(T), 5 %) or 'pga'", "intensity"),
    Column("im", "float64", "g", lambda p: p.spec.im,
           "the run's intensity", "intensity"),
    Column("sa_t", "float64", "g", _sa,
           "Sa(T) as applied (empty without a period; a pair: the geometric mean of its "
           "components')", "intensity"),
    Column("pga", "float64", "g", lambda p: p.suite.scaling.pga[p.spec.rec] * p.factor,
           "PGA as applied (a pair: the geometric mean of its components')", "intensity"),
    Column("{key}", None, "", lambda p, key: p.suite.combos[p.spec.var][key],
           "one column per varied key, named by its dotted key (e.g. walls.law), typed by its "
           "values", "variation", per="key"),
    Column("status", "string", "", lambda r: "collapsed" if _collapsed(r) else "ok",
           "'ok', 'collapsed', 'solver_failure' or 'error'", "outcome"),
    Column("error", "string", "", lambda r: None,
           "why the run failed, naming the run (empty when it finished)", "outcome"),
    Column("collapsed", "bool", "", _collapsed,
           "any collapse criterion reached, or a runaway bound (a story drifted by its height, "
           "the isolator by ten times its capacity: femoat.collapse) with criteria that allow "
           "more", "outcome", failed=False),
    Column("collapse_{c}", "bool", "", lambda r, c: r.collapse.get(c) is not None,
           f"criterion c ({', '.join(CRITERIA)}: femoat.collapse) reached", "outcome",
           per="criterion", failed=False),
    Column("collapse_{c}_time", "float64", "s", _criterion_time,
           "when criterion c was first reached (NaN if not)", "outcome", per="criterion",
           failed=math.nan),
    Column("peak_base_displacement", "float64", "in",
           lambda r: r.peaks.get("peak_base_displacement",
                                 r.peaks.get("peak_plan_base_displacement")),
           "peak isolator (base) displacement; in a plan suite its largest displacement in plan "
           "|u| (the vector sum, as ASCE 7 Chapter 17 measures it)", "peaks"),
    Column("peak_base_displacement_x", "float64", "in",
           lambda r: r.peaks["peak_base_displacement_x"],
           "peak base displacement along x", "peaks", models="plan"),
    Column("peak_base_displacement_y", "float64", "in",
           lambda r: r.peaks["peak_base_displacement_y"],
           "peak base displacement along y", "peaks", models="plan"),
    Column("peak_impact_force_{w}", "float64", "kip",
           lambda r, w: _optional(r.peaks.get(f"peak_impact_force_{w}")),
           "peak contact force on wall w: pos, neg (1D: the walls on the positive and negative "
           "side) or px, mx, py, my (plan: the +x, -x, +y, -y walls; NaN without that wall)",
           "peaks", per="wall"),
    Column("impacts_{w}", "int64", "", lambda r, w: _impacts(r.peaks, w),
           "impacts on wall w (empty without that wall)", "peaks", per="wall"),
    Column("peak_wall_displacement_{w}", "float64", "in",
           lambda r, w: _optional(r.peaks.get(f"peak_wall_displacement_{w}")),
           "peak displacement of wall w at the impact point (NaN without that wall)", "peaks",
           per="wall"),
    Column("peak_drift_{k}", "float64", "in", lambda r, k: _story(r.peaks, "peak_drift", k),
           "peak drift of story k (1 at the bottom; NaN above a shorter variation's top; plan: "
           "the larger of x and y)", "peaks", per="story"),
    Column("peak_drift_ratio_{k}", "float64", "-",
           lambda r, k: _story(r.peaks, "peak_drift_ratio", k),
           "peak drift of story k / its height", "peaks", per="story"),
    Column("peak_floor_acceleration_{k}", "float64", "g",
           lambda r, k: _story(r.peaks, "peak_floor_acceleration", k),
           "peak absolute acceleration of the floor on top of story k", "peaks", per="story"),
    Column("peak_drift_ratio_x_{k}", "float64", "-",
           lambda r, k: _story(r.peaks, "peak_drift_ratio_x", k),
           "peak drift ratio of story k along x", "peaks", per="story", models="plan"),
    Column("peak_drift_ratio_y_{k}", "float64", "-",
           lambda r, k: _story(r.peaks, "peak_drift_ratio_y", k),
           "peak drift ratio of story k along y", "peaks", per="story", models="plan"),
    Column("peak_floor_acceleration_x_{k}", "float64", "g",
           lambda r, k: _story(r.peaks, "peak_floor_acceleration_x", k),
           "peak absolute acceleration along x of the floor on top of story k", "peaks",
           per="story", models="plan"),
    Column("peak_floor_acceleration_y_{k}", "float64", "g",
           lambda r, k: _story(r.peaks, "peak_floor_acceleration_y", k),
           "the same along y", "peaks", per="story", models="plan"),
    Column("peak_drift_ratio", "float64", "-",
           lambda r: float(np.asarray(_per_story(r.peaks, "peak_drift_ratio"),
                                      dtype=float).max(initial=0.0)),
           "largest peak drift ratio over the stories (plan: and over x and y)", "peaks"),
    Column("peak_base_acceleration", "float64", "g",
           lambda r: _largest_over_axes(r.peaks, "peak_base_acceleration"),
           "peak absolute acceleration of the base mat (plan: the larger of x and y)", "peaks"),
    Column("peak_base_acceleration_x", "float64", "g",
           lambda r: _optional(r.peaks["peak_base_acceleration_x"]),
           "peak absolute acceleration of the base mat along x", "peaks", models="plan"),
    Column("peak_base_acceleration_y", "float64", "g",
           lambda r: _optional(r.peaks["peak_base_acceleration_y"]),
           "the same along y", "peaks", models="plan"),
    Column("pounding", "bool", "", lambda r: _pounding(r.peaks),
           "any impact on any wall", "peaks"),
    Column("t_reached", "float64", "s", lambda r: float(r.meta["stats"]["t_reached"]),
           "the run's last time (the collapse time when it stopped there)", "peaks"),
    Column("cpu_seconds", "float64", "s", None,
           "CPU of the whole run in its thread: model lookup, record scaling, solver, peaks "
           "(NaN when its task was lost)", "peaks"),
    Column("solver_seconds", "float64", "s", lambda r: float(r.peaks["cpu_seconds"]),
           "process CPU of the compiled loop, from the solver", "peaks"),
    Column("steps", "int64", "", lambda r: int(r.peaks["steps"]),
           "solver steps", "peaks"),
)


class Field(NamedTuple):
    """One column of a particular suite's table: a :class:`Column`, with its family index."""

    name: str
    dtype: str
    column: Column
    index: object  # story number, criterion or varied key; None for a single column

    def read(self, source):
        """The value of this column from a :class:`Planned` or a RunResult."""
        if self.index is None:
            return self.column.extract(source)
        return self.column.extract(source, self.index)


def fields(suite):
    """The :class:`Field` list of ``suite``'s table, in column order: the rows of
    :data:`COLUMNS`, a run of consecutive rows of one family repeated per index (per story:
    peak_drift_1, peak_drift_ratio_1, peak_floor_acceleration_1, peak_drift_2, ...); the rows
    of the other kind of model left out (:attr:`Column.models`)."""
    kind = "plan" if suite.plan else "1d"
    out, i = [], 0
    while i < len(COLUMNS):
        col = COLUMNS[i]
        if col.per is None:
            if col.models in (None, kind):
                out.append(Field(col.name, col.dtype, col, None))
            i += 1
            continue
        group = [c for c in _run_of(i) if c.models in (None, kind)]
        placeholder, indices = PER[col.per]
        for index in indices(suite):
            for c in group:
                dtype = c.dtype or _value_type([combo[index] for combo in suite.combos])
                out.append(Field(c.name.format(**{placeholder: index}), dtype, c, index))
        i += len(_run_of(i))
    return out


def _run_of(i):
    """The consecutive rows of one family from row ``i`` on."""
    per = COLUMNS[i].per
    j = i
    while j < len(COLUMNS) and COLUMNS[j].per == per:
        j += 1
    return COLUMNS[i:j]


def _value_type(values):
    if all(isinstance(v, bool) for v in values):
        return "bool"
    if all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        return "int64"
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return "float64"
    return "string"


def planned_values(fields_, p):
    """{column: value} of the sections known before the run (a :class:`Planned` ``p``)."""
    return {f.name: f.read(p) for f in fields_ if f.column.section in PLANNED}


def result_values(fields_, result):
    """{column: value} of the sections read from a finished run's ``result``."""
    return {f.name: f.read(result) for f in fields_
            if f.column.section not in PLANNED and f.column.extract is not None}


def failed_values(fields_):
    """{column: value} of the sections read from the result, for a run that did not finish."""
    return {f.name: f.column.failed for f in fields_
            if f.column.section not in PLANNED and f.column.extract is not None}


def column_of(name):
    """The :class:`Column` row a table column ``name`` comes from (a family's member, e.g.
    peak_drift_3, included); None for the varied keys and unknown names."""
    import re

    for col in COLUMNS:
        if col.per is None:
            if col.name == name:
                return col
        elif col.per != "key":
            holder = f"{{{PER[col.per][0]}}}"
            head, tail = col.name.split(holder)
            member = {"story": r"\d+", "criterion": "|".join(map(re.escape, CRITERIA)),
                      "wall": "|".join(wall_keys())}[col.per]
            if re.fullmatch(re.escape(head) + f"(?:{member})" + re.escape(tail), name):
                return col
    return None


def markdown():
    """The column list of docs/suite_table.md: a table per section, in column order."""
    lines = []
    for section, what in SECTIONS.items():
        lines += ["", f"### {section}: {what}", "", "| column | type | unit | holds |",
                  "|---|---|---|---|"]
        for col in COLUMNS:
            if col.section == section:
                name = col.name.replace("{", "<").replace("}", ">")
                unit = f"[{col.unit}]" if col.unit else ""
                only = {"plan": " (plan suites only)", "1d": " (1D suites only)"}.get(col.models,
                                                                                      "")
                lines.append(f"| `{name}` | {col.dtype or 'from the values'} | {unit} | "
                             f"{col.description}{only} |")
    return "\n".join(lines[1:]) + "\n"



DOCS_MARK = "<!-- the column list below is generated from femoat/suite/columns.py: " \
            "femoat.suite.columns.update_docs('docs/suite_table.md') -->"


def docs_text(current):
    """``current`` (the text of docs/suite_table.md) with everything after :data:`DOCS_MARK`
    replaced by :func:`markdown`."""
    head, mark, _ = current.partition(DOCS_MARK)
    if not mark:
        raise ValueError(f"the page has no line {DOCS_MARK!r} to put the column list after")
    return head + DOCS_MARK + "\n\n" + markdown()


def update_docs(path):
    """Rewrite the column list of the page ``path`` (docs/suite_table.md) from :data:`COLUMNS`."""
    from pathlib import Path

    page = Path(path)
    page.write_text(docs_text(page.read_text(encoding="utf-8")), encoding="utf-8")
