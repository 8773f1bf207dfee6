"""Scenario defaults come from the objects the tables build (femoat.scenario, issue 16 item 6):
an empty file is the paper's model, ``defaults()`` reads back to the same scenario, a changed
field default changes the scenario's, and the package lists every key it reads."""

import dataclasses
import re

import numpy as np
import pytest

import femoat.scenario as scenario
from femoat.integration.settings import Integrator
from femoat.scenario import defaults, scenario_from_dict
from femoat.structure.building import Building
from femoat.structure.materials import Bilinear
from femoat.structure.pounding import MoatWall


def _field(cls, name):
    return next(f for f in dataclasses.fields(cls) if f.name == name)


def test_an_empty_scenario_is_the_papers_concrete_hertzdamp_model_under_erzincan():
    from femoat.paper import paper_model, paper_motion

    s = scenario_from_dict({})
    # docs/paper.md §4: the default building between two concrete walls 4 in away, Hertzdamp
    # law, published C_imp; Erzincan N-S at 0.91 g on a half time axis; 2 s of free vibration
    assert s.model == paper_model("concrete", "H")
    assert s.model.building == Building() and s.integrator == Integrator()
    paper = paper_motion()
    assert s.motion.dt == paper.dt and np.array_equal(s.motion.accel_g, paper.accel_g)
    assert s.extra_time == 2.0 and s.collapse is None and s.wall_label == "concrete"


def test_the_defaults_read_back_to_the_same_scenario():
    d = defaults()
    assert set(d) == {"building", "walls", "motion", "solver", "output"}  # no [collapse] table
    a, b = scenario_from_dict({}), scenario_from_dict(d)
    assert a.model == b.model and a.integrator == b.integrator and a.extra_time == b.extra_time
    assert (a.output_folder, a.figures, a.wall_label) == (b.output_folder, b.figures,
                                                          b.wall_label)
    assert np.array_equal(a.motion.accel_g, b.motion.accel_g) and a.motion.dt == b.motion.dt
    # TOML-shaped: no None (TOML has no null), lists not tuples
    assert d["building"]["floor_weights"] == [8.0, 8.0, 7.0] and "rtol" not in d["solver"]
    assert "W" not in d["building"]["isolator"]  # the building's weight, computed


@pytest.mark.parametrize("cls, name, value, read", [
    (Building, "base_weight", 12.5, lambda s: s.model.building.base_weight),
    (Building, "story_damping_ratio", 0.05, lambda s: s.model.building.story_damping_ratio),
    (Building, "p_delta", True, lambda s: s.model.building.p_delta),
    (MoatWall, "gap", 2.75, lambda s: s.model.walls[0].gap),
])
def test_a_field_default_is_read_not_copied(monkeypatch, cls, name, value, read):
    # Change the dataclass's own field default: an empty scenario follows it. A second copy of
    # the value in femoat.scenario would keep the old one.
    monkeypatch.setattr(_field(cls, name), "default", value)
    s = scenario_from_dict({"motion": {"source": "at2", "path": _at2()}})
    assert read(s) == value


def test_an_elastic_story_defaults_to_the_bilinear_storys_initial_stiffness(monkeypatch):
    monkeypatch.setattr(_field(Bilinear, "k0"), "default", 50.0)
    s = scenario_from_dict({"building": {"story_model": "elastic"},
                            "motion": {"source": "at2", "path": _at2()}})
    assert {m.k for m in s.model.building.stories} == {50.0}


def test_the_package_lists_every_key_it_reads():
    # the README sends users to femoat.scenario for every key: each table and key of KEYS is
    # named in the package's docstring, and every table reader accepts exactly its keys
    doc = scenario.__doc__
    for table, keys in scenario.KEYS.items():
        assert f"``[{table}]``" in doc, table
        for key in keys:
            if key not in ("story", "isolator", "fe"):  # the sub-tables, listed as tables
                assert re.search(rf"\b{key}\b", doc), f"[{table}] {key}"
    for table, keys in scenario.KEYS.items():
        if table == "output":
            continue
        with pytest.raises(ValueError, match=rf"allowed: {re.escape(str(sorted(keys)))}"):
            _read_table(table, {"no_such_key": 1})


def _read_table(table, d):
    readers = {"building": scenario.building_from_dict, "walls": scenario.walls_from_dict,
               "motion": scenario.motion_from_dict, "solver": lambda d: scenario.solver_from_dict(
                   {"method": "dp5", **d}), "collapse": scenario.collapse_from_dict,
               "walls.fe": lambda d: scenario.fe_wall_from_dict({"geometry": "x", **d}, None, 0.0)}
    return readers[table](d)


def _at2():
    from pathlib import Path

    return str(Path(__file__).resolve().parent / "data" / "peer" / "Rinaldi228.AT2")
