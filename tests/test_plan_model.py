"""The plan model description (femoat.plan.model, building, moat): defaults, validation, the DOF
layout and the packed arrays, checked against the 1D PoundingModel they must reduce to."""

import math

import numpy as np
import pytest

from femoat.contact import make_law
from femoat.plan import (
    SIDES,
    BidirectionalFrictionPendulum,
    PlanBuilding,
    PlanModel,
    PlanWall,
    rectangular_moat,
)
from femoat.structure.building import Building
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.structure.materials import Bilinear, Elastic, FrictionPendulum, IMKBilinear
from femoat.structure.materials.codes import BEARING
from femoat.structure.roles import ISOLATOR, STORY
from femoat.units import G
from femoat.walls import ModalWall, wall_preset

CONCRETE = wall_preset("concrete")
HERTZDAMP = make_law("H", CONCRETE.contact)


def two_mode_wall():
    return ModalWall(modal_masses=(1e-3, 2e-3), modal_stiffnesses=(10.0, 300.0),
                     modal_dampings=(0.1, 0.2), impact_shape=(1.0, 0.4),
                     ground_participation=(1.2e-3, 0.5e-3))


# ------------------------------------------------------------------------------------ defaults


def test_default_is_the_paper_building_in_both_directions_in_a_four_wall_moat():
    model = PlanModel()
    b = model.building
    # the paper's building (femoat.structure.building): the same 1D Building along x and y
    assert b.along("x") == Building() == b.along("y")
    assert b.isolator == BidirectionalFrictionPendulum()
    assert b.isolator.uniaxial() == Building().isolator
    # the paper's concrete wall (Table 3), the scenario files' Hertzdamp law, 4 in on all sides
    assert [w.side for w in model.walls] == list(SIDES) == ["+x", "-x", "+y", "-y"]
    for w in model.walls:
        assert w.gap == 4.0 and w.friction == 0.0
        assert w.wall == CONCRETE.wall and w.law == HERTZDAMP


def test_walls_are_kept_in_side_order_and_found_by_side():
    law, wall = HERTZDAMP, CONCRETE.wall
    given = (PlanWall(law, wall, 1.0, "-y"), PlanWall(law, wall, 2.0, "+x"),
             PlanWall(law, wall, 3.0, "\u2212x"))  # a typographic minus reads as "-x"
    model = PlanModel(walls=given)
    assert [w.side for w in model.walls] == ["+x", "-x", "-y"]
    assert [w.gap for w in model.walls] == [2.0, 3.0, 1.0]
    assert model.wall("-x").gap == 3.0 and model.wall("+y") is None


def test_wall_geometry():
    # outward normals from the base mat; the tangent is the normal turned by +90°
    expected = {"+x": ((1, 0), (0, 1), 0, 1), "-x": ((-1, 0), (0, -1), 0, -1),
                "+y": ((0, 1), (-1, 0), 1, 1), "-y": ((0, -1), (1, 0), 1, -1)}
    for w in rectangular_moat():
        n, t, axis, sign = expected[w.side]
        assert w.normal == n and w.tangent == t and w.axis == axis and w.sign == sign
        assert np.dot(w.normal, w.tangent) == 0.0
        one_d = w.uniaxial()  # the wall on its own axis, a 1D model's: "+x" or "-x" by sign
        assert (one_d.sign, one_d.axis, one_d.gap, one_d.law, one_d.wall) == \
            (sign, 0, 4.0, w.law, w.wall)
        assert one_d == MoatWall(w.law, w.wall, 4.0, sign)  # ±1 still names a 1D wall


def test_from_building_round_trips_and_takes_other_stories_in_y():
    b = Building(floor_weights=(5.0, 4.0), stories=(Elastic(30.0), Bilinear()), p_delta=True,
                 story_heights=(40.0, 36.0), isolator=FrictionPendulum(mu=0.05, mu_fast=0.09,
                                                                       a=0.7))
    plan = PlanBuilding.from_building(b)
    assert plan.along("x") == b == plan.along("y")
    assert isinstance(plan.isolator, BidirectionalFrictionPendulum)
    y = (IMKBilinear(theta_p=0.6, theta_pc=2.0, Lambda=40.0), Elastic(12.0))
    other = PlanBuilding.from_building(b, stories_y=y)
    assert other.along("x") == b and other.along("y").stories == y


# ------------------------------------------------------------------------------------ bad input


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"gap": -1.0}, r"wall \+x: gap = -1.0 must be a clearance >= 0 \[in\]"),
    ({"gap": math.nan}, r"wall \+x: gap = nan must be a clearance"),
    ({"friction": -0.1}, r"wall \+x: friction = -0.1 must be a Coulomb coefficient >= 0"),
    ({"side": "x"}, r"side = 'x' is not a moat wall: use one of '\+x', '-x', '\+y', '-y'"),
    ({"side": "+z"}, r"side = '\+z' is not a moat wall"),
    ({"side": 2}, r"side = 2 is not a moat wall: .*\+1 and -1 are '\+x' and '-x'"),
    ({"side": True}, r"side = True is not a moat wall"),
    ({"wall": "steel"}, r"wall \+x: wall must be an SdofWall or a modal wall"),
])
def test_bad_walls_are_named(kwargs, message):
    args = dict(law=HERTZDAMP, wall=CONCRETE.wall, gap=4.0, side="+x") | kwargs
    with pytest.raises(ValueError, match=message):
        PlanWall(**args)


def test_bad_moats_are_named():
    walls = rectangular_moat()
    with pytest.raises(ValueError, match=r"more than one wall on side \+y"):
        PlanModel(walls=(walls[2], walls[2]))
    with pytest.raises(ValueError, match="walls must be PlanWall entries"):
        PlanModel(walls=("+x",))
    with pytest.raises(ValueError, match="building must be a PlanBuilding"):
        PlanModel(Building())
    with pytest.raises(ValueError, match="side = 'north'"):
        rectangular_moat(sides=("+x", "north"))


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"isolator": FrictionPendulum()},
     "FrictionPendulum is the 1D bearing; in plan use femoat.plan.BidirectionalFrictionPendulum"),
    ({"isolator": Bilinear()}, "isolator must be a BidirectionalFrictionPendulum"),
    ({"stories_y": (Bilinear(),) * 2}, "stories_y: 2 story springs for 3 floors"),
    ({"stories_x": (Bilinear(), Bilinear(), FrictionPendulum())}, "stories_x: FrictionPendulum"),
    ({"stories_x": [Bilinear()] * 3}, "stories_x must be a tuple"),
    ({"base_weight": -1.0}, "base_weight = -1.0 must be a positive weight"),
    ({"story_heights": (39.0, 0.0, 39.0)}, r"story_heights\[1\] = 0.0"),
    ({"p_delta": 1}, "p_delta = 1 must be true or false"),
])
def test_bad_buildings_are_named(kwargs, message):
    with pytest.raises(ValueError, match=message):
        PlanBuilding(**kwargs)


@pytest.mark.parametrize("kwargs", [
    {"base_weight": 0.0}, {"floor_weights": (8.0, -1.0, 7.0)}, {"story_damping_ratio": -0.01},
    {"story_damping_period": 0.0}, {"story_heights": (39.0, 39.0)}, {"p_delta": "yes"},
    {"isolator_capacity": float("nan")},
])
def test_one_building_checks_the_shared_parameters_once(kwargs):
    # the parameters both buildings have are checked by one code (StoryBuilding): the same
    # sentence from the 1D and the plan building
    messages = []
    for cls in (Building, PlanBuilding):
        with pytest.raises(ValueError) as err:
            cls(**kwargs)
        messages.append(str(err.value))
    assert messages[0] == messages[1]
    # and what follows from them is one code too: the plan building along x is the 1D one,
    # its stories per axis where the 1D building has its one axis
    plan = PlanBuilding(p_delta=True, stories_y=(Elastic(k=30.0),) * 3)
    one = plan.along("y")
    assert plan.stories_along("y") == one.stories_along("x") == one.stories
    assert plan.geometric_stiffnesses() == one.geometric_stiffnesses()
    assert (plan.heights, plan.total_weight, plan.story_damping_beta) == (
        one.heights, one.total_weight, one.story_damping_beta)
    with pytest.raises(ValueError, match="axis = 'y': use 'x'"):
        one.stories_along("y")


# ------------------------------------------------------------------------------------- layout


def test_layout_is_node_major_with_an_empty_rotation_column():
    walls = rectangular_moat(sides=("+x", "-y"))
    model = PlanModel(walls=(walls[0], PlanWall(HERTZDAMP, two_mode_wall(), 4.0, "+y"),
                             walls[1]))
    lay = model.layout()
    # 4 levels × (x, y) = 8, then +x (1 mode), +y (2 modes), −y (1 mode): n = 12
    assert lay.n == 12 and lay.n_struct == 8
    np.testing.assert_array_equal(lay.floor_dofs, [[0, 1, -1], [2, 3, -1], [4, 5, -1],
                                                   [6, 7, -1]])
    assert lay.wall_dofs == ((8,), (9, 10), (11,))
    assert lay.names == ("base_x", "base_y", "floor1_x", "floor1_y", "floor2_x", "floor2_y",
                         "floor3_x", "floor3_y", "wall_+x", "wall_+y_mode1", "wall_+y_mode2",
                         "wall_-y")
    assert model.dof_names() == list(lay.names)


# --------------------------------------------------------------------------------------- pack


def restricted(packed, model, axis):
    """The plan pack's rows and columns of one axis: the floors' DOFs on it and the modes of
    the walls normal to it, in the 1D order (floors, then the + wall, then the − wall)."""
    lay = model.layout()
    walls = [d for w, d in zip(model.walls, lay.wall_dofs) if w.axis == axis]
    return list(lay.floor_dofs[:, axis]) + [i for d in walls for i in d]


@pytest.mark.parametrize("axis", [0, 1], ids=["x", "y"])
@pytest.mark.parametrize("variant", ["paper", "p-delta, elastic isolator, modal wall"])
def test_pack_along_an_axis_is_the_1d_pack(axis, variant):
    # Along one axis the plan model is the 1D PoundingModel of model.along(axis): its mass,
    # damping and stiffness matrices, ground load, story elements and contacts are the plan
    # pack's rows and columns of that axis, to the bit (the same numbers, assembled the same
    # way), and nothing couples the axis to the other (the off-axis blocks are zero).
    if variant == "paper":
        model = PlanModel()
    else:
        y = (Elastic(20.0), IMKBilinear(theta_p=0.6, theta_pc=2.0, Lambda=40.0), Bilinear(k0=30.0, Fy=8.0, b=0.05))
        building = PlanBuilding(isolator=Elastic(2.5), stories_y=y, p_delta=True,
                                story_heights=(40.0, 38.0, 36.0))
        steel = wall_preset("steel")
        walls = (PlanWall(make_law("J", steel.contact), steel.wall, 2.0, "+x"),
                 PlanWall(HERTZDAMP, two_mode_wall(), 3.0, "-x"),
                 PlanWall(make_law("E", steel.contact), steel.wall, 1.0, "+y", friction=0.2),
                 PlanWall(HERTZDAMP, two_mode_wall(), 5.0, "-y"))
        model = PlanModel(building, walls)
    plan, one = model.pack(), model.along("xy"[axis]).pack()
    idx = restricted(plan, model, axis)
    other = [i for i in range(plan.n) if i not in idx]
    for name in ("M", "C", "K"):
        block = getattr(plan, name)
        np.testing.assert_array_equal(block[np.ix_(idx, idx)], getattr(one, name))
        assert not block[np.ix_(idx, other)].any()
    np.testing.assert_array_equal(plan.R[idx, axis], one.r)
    assert not plan.R[other, axis].any()
    # uniaxial elements on this axis (an Elastic isolator is one per axis; the bidirectional
    # bearing is separate and carries the 1D bearing's params)
    on_axis = np.flatnonzero(plan.el_axis == axis)
    one_els = range(len(one.el_code))
    if isinstance(model.building.isolator, BidirectionalFrictionPendulum):
        assert one.el_roles[0].kind == ISOLATOR
        # one bearing row: kind 0 (the friction pendulum), the 1D isolator's params and code
        width = plan.bearing_P.shape[1]
        np.testing.assert_array_equal(plan.bearing_P[0], one.el_P[0, :width])
        assert one.el_code[0] == BEARING + plan.bearing_kind[0] and plan.bearing_kind[0] == 0
        np.testing.assert_array_equal(plan.bearing_dofs[0], model.layout().floor_dofs[0, :2])
        one_els = range(1, len(one.el_code))
    else:
        assert plan.bearing_dofs.size == 0
    assert len(on_axis) == len(one_els)
    to_plan = np.array(idx)
    for e, f in zip(on_axis, one_els):
        assert plan.el_i[e] == to_plan[one.el_i[f]]
        assert plan.el_j[e] == (-1 if one.el_j[f] < 0 else to_plan[one.el_j[f]])
        assert plan.el_code[e] == one.el_code[f] and plan.el_roles[e] == one.el_roles[f]
        width = min(plan.el_P.shape[1], one.el_P.shape[1])  # the rest is padding (zeros)
        np.testing.assert_array_equal(plan.el_P[e, :width], one.el_P[f, :width])
        assert not plan.el_P[e, width:].any() and not one.el_P[f, width:].any()
    # contacts of the walls normal to this axis: δ = b·u − gap, the same rows
    rows = [c for c, w in enumerate(model.walls) if w.axis == axis]
    np.testing.assert_array_equal(plan.c_B[np.ix_(rows, idx)], one.c_B)
    assert not plan.c_B[np.ix_(rows, other)].any()
    np.testing.assert_array_equal(plan.c_gap[rows], one.c_gap)
    np.testing.assert_array_equal(plan.c_code[rows], one.c_code)
    np.testing.assert_array_equal(plan.c_P[rows], one.c_P)


def test_pack_physics():
    model = PlanModel()
    p = model.pack()
    lay = model.layout()
    # a rigid translation of the building and walls by (dx, dy): the ground load −R·a_g is
    # −M·ι·a_g, so ι_x·R_x (x rows) sums the masses: (10 + 8 + 8 + 7) kip/g plus the x walls'
    # participation L = M1 with opposite signs (the +x wall's mode points to +x, the −x wall's
    # to −x): they cancel in the sum and appear with |L| = M1 = 0.29/g on their own rows.
    assert p.R[lay.floor_dofs[:, 0], 0].sum() == pytest.approx(33.0 / G, rel=1e-15)
    m1 = CONCRETE.wall.mass
    np.testing.assert_array_equal(p.R[8:, 0], [m1, -m1, 0.0, 0.0])
    np.testing.assert_array_equal(p.R[8:, 1], [0.0, 0.0, m1, -m1])
    # the base mat at (1, 2) in with the walls at rest: δ = n·u − gap on every wall
    u = np.zeros(p.n)
    u[lay.floor_dofs[0, :2]] = (1.0, 2.0)
    np.testing.assert_array_equal(p.c_B @ u - p.c_gap, [1 - 4, -1 - 4, 2 - 4, -2 - 4])
    # its slip along each wall, t·u with t = (−n_y, n_x): +x: 2, −x: −2, +y: −1, −y: 1
    np.testing.assert_array_equal(p.c_T @ u, [2.0, -2.0, -1.0, 1.0])
    # a +x wall pushed 0.5 in away from the building closes its gap by as much
    u[8] = 0.5
    assert (p.c_B @ u)[0] == 1.0 - 0.5
    # the story dashpots c = β·k0 in both directions, β = 2·0.02·0.30/2π: the x block between
    # base and floor 1 holds −c, the cross-direction block nothing
    c = 2 * 0.02 * 0.30 / (2 * math.pi) * 42.799
    assert p.C[lay.floor_dofs[1, 0], lay.floor_dofs[0, 0]] == pytest.approx(-c, rel=1e-15)
    assert p.C[lay.floor_dofs[1, 1], lay.floor_dofs[0, 1]] == pytest.approx(-c, rel=1e-15)
    assert p.C[lay.floor_dofs[1, 0], lay.floor_dofs[0, 1]] == 0.0
    assert [r.kind for r in p.el_roles] == [STORY] * 6
    np.testing.assert_array_equal(p.c_friction, [0.0] * 4)
    assert p.c_names == list(SIDES)


def test_run_names_the_motion_each_model_takes():
    # run() is one path for both models; the motion must match the model's axes (checked before
    # any packing or solving, so these cost nothing)
    from femoat.ground_motions import GroundMotion, RecordPair
    from femoat.run import run
    from femoat.structure.pounding import PoundingModel

    gm = GroundMotion(np.zeros(11), 0.01, name="rest")
    pair = RecordPair(gm, gm)
    with pytest.raises(ValueError, match="a PlanModel runs under a RecordPair"):
        run(PlanModel(), gm)
    with pytest.raises(ValueError, match="a PoundingModel runs along x under one GroundMotion"):
        run(PoundingModel(Building()), pair)
    with pytest.raises(ValueError, match="model must be a PoundingModel"):
        run(Building(), gm)


def test_one_wall_class_for_both_models():
    # a 1D model's wall is the plan wall on the +x or -x side: ±1 still names it, the plan
    # wall's side names it too, and both are the same wall (equal and hashed alike: the suite
    # and packed_model's cache key models by them)
    law, wall = HERTZDAMP, CONCRETE.wall
    assert MoatWall(law, wall, 4.0, 1) == PlanWall(law, wall, 4.0, "+x")
    assert hash(MoatWall(law, wall, 4.0, -1)) == hash(PlanWall(law, wall, 4.0, "\u2212x"))
    assert MoatWall(law, wall, 4.0, -1).side == "-x" and MoatWall(law, wall, 4.0, -1).sign == -1
    # a 1D model holds only walls along its axis, without friction: others say where they go
    with pytest.raises(ValueError, match=r"wall \+y: a 1D model's walls stand at ±gap"):
        PoundingModel(Building(), (PlanWall(law, wall, 4.0, "+y"),))
    with pytest.raises(ValueError, match="need a plan model"):
        PoundingModel(Building(), (PlanWall(law, wall, 4.0, "+x", friction=0.3),))
    with pytest.raises(ValueError, match="walls must be MoatWall entries"):
        PoundingModel(Building(), ("+x",))
    # the plan model along x holds the 1D walls (the same class, friction dropped)
    plan = PlanModel(walls=rectangular_moat(friction=0.2))
    assert plan.along("x").walls == (MoatWall(HERTZDAMP, wall, 4.0, 1),
                                     MoatWall(HERTZDAMP, wall, 4.0, -1))
