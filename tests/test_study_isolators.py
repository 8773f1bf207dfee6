"""``femoat study isolators --quick`` end to end (femoat.studies.isolators): three isolators of
equal MCE displacement, their suites, the table recomputed from the run tables, and the figure."""

import contextlib
import io

import numpy as np
import pandas as pd
import pytest

from femoat.cli import main
from femoat.studies import isolators as iso
from femoat.structure.isolation_design import mce_displacement


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """The quick study run once through the command line: (folder, printed table)."""
    out = tmp_path_factory.mktemp("study") / "isolators"
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(io.StringIO()):
        code = main(["study", "isolators", "--quick", "--serial", "--out", str(out)])
    assert code == 0
    return out, printed.getvalue()


def test_the_isolators_share_one_mce_displacement():
    bearings, design = iso.isolators()
    assert list(bearings) == list(iso.ISOLATORS)
    target = design["fp"][0]
    for key, bearing in bearings.items():
        # ASCE 7-16 Eq. 17.5-1 at each bearing's own effective period and damping
        assert mce_displacement(bearing, iso.WEIGHT, iso.S_M1)[0] == pytest.approx(target,
                                                                                  rel=1e-8)
        assert bearing.yield_deformation < target < bearing.capacity  # it yields, it holds
    # the tuned parameters stay what the docstring says: TFP outer radii equal, LRB K_u = 10 K_d
    assert bearings["tfp"].L2 == bearings["tfp"].L3 and bearings["lrb"].K_u == pytest.approx(
        10 * bearings["lrb"].K_d, rel=1e-14)


def test_the_command_prints_and_writes_the_table(study):
    out, printed = study
    table = pd.read_csv(out / "table.csv")
    assert len(table) == len(iso.ISOLATORS) * len(iso.CASES)
    n = len(iso.QUICK["ids"])
    assert set(table["records"]) == {n} and table["failed runs"].sum() == 0
    # runs behind a case: 1D two components per record, 2D one pair per record per angle
    runs = table.groupby("case")["runs"].unique().to_dict()
    assert {k: list(v) for k, v in runs.items()} == {"1d": [2 * n], "2d": [n * len(iso.ANGLES)]}
    assert (out / "table.markdown").read_text(encoding="utf-8") in printed
    assert (out / "isolators.png").stat().st_size > 10_000


def test_the_table_is_the_run_tables_reduced_by_hand(study):
    out, _ = study
    table = pd.read_csv(out / "table.csv").set_index(["isolator", "case"])
    runs = pd.concat([pd.read_parquet(p) for p in sorted((out / "2d" / "runs").glob("*.parquet"))])
    runs = runs.drop_duplicates("run_id")
    lrb = runs[runs["building.isolator"].astype(str).str.contains("'type': 'lrb'")]
    # per record, the largest peak plan displacement over its two angles; then the median
    per_record = lrb.groupby("record_id")["peak_base_displacement"].max()
    assert table.at[("lrb", "2d"), "median peak base displacement [in]"] == pytest.approx(
        float(np.median(per_record)), rel=1e-12)
    pounded = lrb.groupby("record_id")["pounding"].any()
    assert table.at[("lrb", "2d"), "pounding probability [-]"] == pytest.approx(
        float(pounded.mean()), rel=1e-12)
