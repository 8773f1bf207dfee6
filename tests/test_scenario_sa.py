"""Scenario files scaled to Sa(T) at a period the user gives (issue 27, item 8): ``[motion] sa``
[g] with ``period`` [s]; 1D the component's Sa(T), plan the geometric mean of the pair's two
components' Sa(T) (as suites scale); the factor echoed on the terminal and in README.txt; bad
keys exit 2 naming the key."""

import csv
import math
import tomllib

import numpy as np
import pytest

from femoat.cli import main
from femoat.ground_motions import fema_p695_pair, fema_p695_record, response_spectrum
from femoat.scenario import scenario_from_dict
from conftest import write_at2


def _sa(motion, period):
    """Sa(T) [g], 5 % damped, recomputed with the spectrum function itself."""
    return float(response_spectrum(motion, period, 0.05).psa)


def test_a_record_scaled_to_sa_has_that_sa_at_the_period():
    sc = scenario_from_dict({"motion": {"source": "fema", "sa": 0.5, "period": 2.0}})
    # the applied record's Sa(2 s) is the target: factor · Sa_record(2 s) = 0.5 g
    assert _sa(sc.motion, 2.0) == pytest.approx(0.5, rel=1e-10)
    # the factor is the target over the record's own Sa(2 s), far-field 1 component a as read
    own = _sa(fema_p695_record("farfield", 1, "a"), 2.0)
    assert sc.intensity.factor == pytest.approx(0.5 / own, rel=1e-12)
    assert sc.intensity.record == pytest.approx(own, rel=1e-12)


def test_a_time_scaled_record_is_scaled_at_the_prototype_period():
    # the paper's Erzincan default runs at time_scale 0.5: T = 2 s of the prototype is 1 s of
    # the applied record, whose Sa there is the record's as read at 2 s (time similitude), so
    # the applied record's Sa(1 s) is the target; and sa replaces the default PGA
    sc = scenario_from_dict({"motion": {"sa": 0.3, "period": 2.0}})
    assert sc.motion.dt == pytest.approx(0.5 * 0.005)
    assert _sa(sc.motion, 1.0) == pytest.approx(0.3, rel=1e-10)
    assert "T*time_scale = 1 s" in sc.intensity.describe()


def test_a_pair_scaled_to_sa_has_that_geometric_mean_whatever_its_angle():
    factors = []
    for angle in (0.0, 30.0):
        sc = scenario_from_dict({"building": {"plan": True},
                                 "motion": {"sa": 0.5, "period": 2.0, "angle": angle}})
        p = sc.motion
        # √(Sa(s·x) · Sa(s·y)) at 2 s, the two components as recorded times the one scale s
        mean = math.sqrt(_sa(p.x.scaled(p.scale), 2.0) * _sa(p.y.scaled(p.scale), 2.0))
        assert mean == pytest.approx(0.5, rel=1e-10)
        factors.append(p.scale)
    # the factor is found before the turn: the same at every angle
    assert factors[0] == factors[1]
    # and it is the target over the geometric mean of the pair as read (far-field 1, a and b)
    raw = fema_p695_pair("farfield", 1)
    assert factors[0] == pytest.approx(0.5 / math.sqrt(_sa(raw.x, 2.0) * _sa(raw.y, 2.0)),
                                       rel=1e-12)


@pytest.mark.parametrize("plan", [False, True])
def test_run_echoes_the_factor_on_the_terminal_and_in_the_readme(tmp_path, capsys, plan):
    # 2 s of a 1 Hz sine at 0.01 s, 0.2 g along x (and 0.1 g along y in plan)
    t = np.arange(201) * 0.01
    write_at2(tmp_path / "x.AT2", 0.2 * np.sin(2 * np.pi * t), 0.01)
    write_at2(tmp_path / "y.AT2", 0.1 * np.sin(2 * np.pi * t), 0.01)
    motion = 'sa = 0.3\nperiod = 1.0\nextra_time = 0.2\nsource = "at2"\n'
    motion += 'path_x = "x.AT2"\npath_y = "y.AT2"\n' if plan else 'path = "x.AT2"\n'
    text = ("[building]\nplan = true\n[moat]\ngap = 3.0\n" if plan else "") + \
        "[motion]\n" + motion
    path = tmp_path / "s.toml"
    path.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out), "--no-figures"]) == 0
    sc = scenario_from_dict(tomllib.loads(text), tmp_path)
    # the echo names the factor the scenario computed (6 significant digits) and the target
    said = f"factor {sc.intensity.factor:.6g} [-]"
    terminal = capsys.readouterr().out
    readme = (out / "README.txt").read_text(encoding="utf-8")
    for where in (terminal, readme):
        assert said in where and "Sa(1 s) = 0.3 g" in where, where
    if plan:  # the summary's scale is that factor, the one on both components
        row = dict(zip(*csv.reader((out / "summary.csv").open(encoding="utf-8"))))
        assert float(row["scale [-]"]) == pytest.approx(sc.intensity.factor, rel=1e-12)
        assert "on both components" in terminal


@pytest.mark.parametrize("plan, keys, named", [
    (False, "sa = 0.5\n", "[motion] sa = 0.5 needs period"),
    (False, "period = 2.0\n", "[motion] period = 2.0"),
    (False, "sa = -0.5\nperiod = 2.0\n", "[motion] sa = -0.5"),
    (False, "sa = 0.5\nperiod = 0.0\n", "[motion] period = 0.0"),
    (False, "sa = 0.5\nperiod = 2.0\npga = 0.4\n", "[motion] sa and pga"),
    (True, "sa = 0.5\nperiod = 2.0\nscale = 2.0\n", "[motion] sa and scale"),
    (True, "sa = 0.5\nperiod = 2.0\nnormalized = true\n", "[motion] sa and normalized"),
    (True, "sa = 0.5\n", "[motion] sa = 0.5 needs period"),
])
def test_bad_sa_keys_exit_2_naming_the_key(tmp_path, capsys, plan, keys, named):
    path = tmp_path / "s.toml"
    head = "[building]\nplan = true\n[moat]\ngap = 3.0\n" if plan else ""
    path.write_text(head + "[motion]\n" + keys, encoding="utf-8")
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-figures"]) == 2
    err = capsys.readouterr().err
    assert named in err, err
    assert not (tmp_path / "out").exists()
