"""The run table's one column table: it drives the rows, the Parquet schema and the docs."""

from dataclasses import replace
from pathlib import Path

import pytest

from conftest import three_records
from femoat.suite import columns as cols
from femoat.suite import load_suite

ROOT = Path(__file__).resolve().parents[1]

TINY = """
[records]
folder = "{folder}"
duration = 0.5
extra_time = 0.2
[variations]
"walls.law" = ["E", "H"]
"walls.gap" = [3, 4.5]
[scaling]
method = "pga"
targets = [0.3]
"""


@pytest.fixture(scope="module")
def suite(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("columns")
    folder = three_records(tmp / "peer")
    path = tmp / "suite.toml"
    path.write_text(TINY.format(folder=folder.as_posix()), encoding="utf-8")
    return load_suite(path)


def test_the_docs_page_lists_the_column_table():
    page = (ROOT / "docs" / "suite_table.md").read_text(encoding="utf-8")
    assert page == cols.docs_text(page), (
        "docs/suite_table.md is out of date with femoat/suite/columns.py: run "
        "python -c \"from femoat.suite.columns import update_docs; "
        "update_docs('docs/suite_table.md')\"")
    # every column row is on the page once, with its unit in brackets
    for col in cols.COLUMNS:
        name = col.name.replace("{", "<").replace("}", ">")
        assert page.count(f"| `{name}` |") == 1
        assert (f"[{col.unit}]" in page) or not col.unit


def test_column_order_and_types_follow_the_table(suite):
    fields = cols.fields(suite)
    names = [f.name for f in fields]
    # the paper building has 3 stories; 2 varied keys; 4 collapse criteria (femoat.collapse):
    # 19 identity and intensity columns, 2 varied keys, status/error/collapsed, 4 x 2 collapse
    # columns, 7 peaks, 3 x 3 per story and 7 at the end = 19 + 2 + 3 + 8 + 7 + 9 + 7 = 55
    assert len(names) == 55 and len(set(names)) == 55
    assert names[:3] == ["run_id", "suite_hash", "femoat_version"]
    assert names[19:21] == ["walls.law", "walls.gap"]
    assert names[24:28] == ["collapse_drift", "collapse_drift_time", "collapse_isolator",
                            "collapse_isolator_time"]
    # families repeat together, story by story
    assert names[39:45] == ["peak_drift_1", "peak_drift_ratio_1", "peak_floor_acceleration_1",
                            "peak_drift_2", "peak_drift_ratio_2", "peak_floor_acceleration_2"]
    assert names[-1] == "steps"
    types = dict((f.name, f.dtype) for f in fields)
    # a varied key is typed by its values: laws are text, gaps 3 and 4.5 mixed int and float
    assert (types["walls.law"], types["walls.gap"]) == ("string", "float64")
    assert (types["rsn"], types["pulse"], types["steps"]) == ("int64", "bool", "int64")
    from femoat.suite.table import schema

    assert schema(suite).names == names


def test_rows_fill_exactly_the_schema_finished_or_failed(suite):
    # the rows are made from the same table as the schema: a finished run, a run that fails
    # in the solver, one that raises and the row of a lost task each carry every column and
    # no other
    from femoat.suite import runs
    from femoat.suite.table import schema

    names = set(schema(suite).names)
    first, second = runs.plan(suite)[:2]  # records RSN181 and RSN77, law E, gap 3
    row = runs.run_one(suite, first)
    assert set(row) == names and row["status"] in ("ok", "collapsed")
    assert row["walls.law"] == "E" and row["walls.gap"] == 3 and row["im"] == 0.3
    # pga as applied = the target intensity, PGA being the intensity measure
    assert row["pga"] == pytest.approx(0.3, rel=1e-12)

    def solver(**keys):  # the same suite with other [solver] keys (its own variation cache)
        return replace(suite, tables={**suite.tables, "solver": keys}, hash=repr(keys))

    # two Newton iterations and a 4 ms floor on the step: RSN77 at 0.3 g stalls at ~0.1 s
    stalled = runs.run_one(solver(max_newton=2, min_step=0.004), second)
    assert set(stalled) == names and stalled["status"] == "solver_failure"
    assert stalled["peak_base_displacement"] is None and stalled["collapsed"] is False
    raised = runs.run_one(solver(max_newton=1), first)  # refused when the model is built
    assert set(raised) == names and raised["status"] == "error"
    assert "max_newton = 1" in raised["error"] and raised["steps"] is None
    lost = runs.failed_row(suite, first, RuntimeError("worker lost"))
    assert set(lost) == names and lost["status"] == "error" and "worker lost" in lost["error"]


def test_column_of_finds_every_member_of_a_family():
    assert cols.column_of("peak_drift_12").name == "peak_drift_{k}"
    assert cols.column_of("peak_drift_ratio_2").name == "peak_drift_ratio_{k}"
    assert cols.column_of("collapse_wall_force_time").name == "collapse_{c}_time"
    assert cols.column_of("collapse_isolator").name == "collapse_{c}"
    assert cols.column_of("peak_drift_ratio").name == "peak_drift_ratio"
    assert cols.column_of("walls.law") is None and cols.column_of("collapse_roof") is None


@pytest.mark.parametrize("kwargs, message", [
    (dict(dtype="float32"), "dtype = 'float32'"), (dict(section="result"), "section"),
    (dict(per="story"), "names its {k}")])
def test_a_bad_column_row_is_refused_by_name(kwargs, message):
    base = dict(name="peak_roof", dtype="float64", unit="in", extract=lambda r: 0.0,
                description="x", section="peaks")
    with pytest.raises(ValueError, match="column peak_roof") as err:
        cols.Column(**{**base, **kwargs})
    assert message in str(err.value)


def test_a_run_ended_by_a_runaway_bound_is_a_collapse():
    # A suite whose criteria allow more than the runaway bounds (e.g. drift_ratio = 2) has runs
    # that end at a runaway bound with no criterion reached (RunResult.runaway set, collapse
    # "collapsed" False): the building had collapsed all the same, and its row says so.
    from types import SimpleNamespace

    status, collapsed = cols.column_of("status"), cols.column_of("collapsed")
    quiet = SimpleNamespace(collapse={"collapsed": False}, runaway=None)
    ran_away = SimpleNamespace(collapse={"collapsed": False},
                               runaway=dict(time=20.78, element="story1", bound=156.0,
                                            reason="drift of one story height"))
    reached = SimpleNamespace(collapse={"collapsed": True}, runaway=None)
    assert (status.extract(quiet), collapsed.extract(quiet)) == ("ok", False)
    assert (status.extract(ran_away), collapsed.extract(ran_away)) == ("collapsed", True)
    assert (status.extract(reached), collapsed.extract(reached)) == ("collapsed", True)
