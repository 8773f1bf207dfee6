"""What a plan ``femoat run`` writes (issue 27, item 4): summary.csv with units in the
headings and README.txt with the echo of the model (moat sides, gaps, laws, walls, the pair,
its angle and scale), figure titles with the angle and the law; a default moat said loudly."""

import csv

import numpy as np
import pytest

from femoat.cli import main
from conftest import write_at2


def _scenario(tmp_path, moat=True):
    # 2 s of a 1 Hz sine of 0.5 g along x, 0.3 g along y, at 0.01 s
    t = np.arange(201) * 0.01
    write_at2(tmp_path / "x.AT2", 0.5 * np.sin(2 * np.pi * t), 0.01)
    write_at2(tmp_path / "y.AT2", 0.3 * np.sin(2 * np.pi * t), 0.01)
    text = "[building]\nplan = true\n"
    if moat:
        text += ('[moat]\nlaw = "H"\ngap = 3.0\n[moat."+x"]\npreset = "steel"\nlaw = "E"\n'
                 '[moat."+y"]\ngap = 5.0\n[moat."-y"]\ngap = 5.0\n')
    text += ('[motion]\nsource = "at2"\npath_x = "x.AT2"\npath_y = "y.AT2"\nangle = 30\n'
             'scale = 1.5\nextra_time = 0.5\n')
    path = tmp_path / "plan.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def plan_run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("plan_run")
    out = tmp / "out"
    assert main(["run", str(_scenario(tmp)), "--out", str(out)]) == 0
    return out


def test_a_plan_run_writes_summary_csv_with_units_and_the_peaks(plan_run):
    import json

    rows = list(csv.reader((plan_run / "summary.csv").open(encoding="utf-8")))
    head, row = rows[0], dict(zip(rows[0], rows[1]))
    # every heading but the record's carries its unit in brackets
    assert all(h.endswith("]") for h in head if h != "record")
    assert float(row["angle [deg]"]) == 30.0 and float(row["scale [-]"]) == 1.5
    # the summary is run.npz's peaks: the same plan displacement and wall forces
    from femoat.results.plan import PlanRunResult

    r = PlanRunResult.load(plan_run / "run.npz")
    assert float(row["peak_plan_base_displacement [in]"]) == pytest.approx(
        r.peaks["peak_plan_base_displacement"], rel=1e-12)
    for w in ("px", "mx", "py", "my"):
        assert int(row[f"impacts_{w} [-]"]) == r.peaks[f"impacts_{w}"]
    assert json.loads(json.dumps(r.peaks))  # (JSON-ready, as the summary's source)


def test_a_plan_runs_readme_echoes_the_moat_and_the_pair(plan_run):
    text = (plan_run / "README.txt").read_text(encoding="utf-8")
    # the +x wall's own table: steel (K1 = 100 kip/in, Table 3), law E, the default 3 in gap;
    # +y and -y at 5 in; -x the [moat] default: law H, 3 in, concrete (K1 = 2.4 kip/in)
    assert "wall +x: law E, gap 3 in, SdofWall K1 = 100 kip/in" in text
    assert "wall -x: law H, gap 3 in, SdofWall K1 = 2.4 kip/in" in text
    assert "wall +y: law H, gap 5 in" in text and "wall -y: law H, gap 5 in" in text
    assert "angle 30 deg (from +x toward +y), scale 1.5 [-]" in text
    assert "units: kip, in, s" in text and "summary.csv" in text
    for name in ("plan_orbit.png", "plan_impact_forces.png", "impacts.csv"):
        assert (plan_run / name).stat().st_size > 0


def test_plan_figure_titles_carry_the_angle_and_the_laws():
    from femoat.plan import PlanModel, PlanWall, rectangular_moat
    from femoat.plan_report import figure_title
    from femoat.ground_motions.pair import fema_p695_pair

    pair = fema_p695_pair("farfield", 5, angle=30.0)
    assert figure_title(PlanModel(), pair) == "farfield/5 at 30 deg, x1; law H"
    walls = rectangular_moat(law="E", sides=("+x",)) + rectangular_moat(sides=("-x",))
    assert figure_title(PlanModel(walls=walls), pair).endswith("law E/H")
    assert isinstance(walls[0], PlanWall)


def test_a_plan_file_without_a_moat_says_so_loudly(tmp_path, capsys):
    path = _scenario(tmp_path, moat=False)
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-figures"]) == 0
    printed = capsys.readouterr().out
    # the default moat: four concrete walls, law H, 4 in (rectangular_moat())
    assert "moat: NOT IN THE FILE ([moat] left out)" in printed
    assert "wall +x: law H, gap 4 in" in printed and "wall -y: law H, gap 4 in" in printed
    assert "NOT IN THE FILE" in (tmp_path / "out" / "README.txt").read_text(encoding="utf-8")
