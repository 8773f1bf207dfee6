"""One packed type and one pack path (issue 25): a 1D model's pack is the plan model's pack on
one axis (femoat.structure.packing, femoat.structure.packed, femoat.structure.layout)."""

import dataclasses

import numpy as np
import pytest

from femoat.bearings import registry as bearing_registry
from femoat.paper import paper_model
from femoat.plan import PackedPlanModel, PlanBuilding, PlanLayout, PlanModel, rectangular_moat
from femoat.structure.building import Building
from femoat.structure.layout import Layout, dof_layout
from femoat.structure.materials import Elastic
from femoat.structure.packed import PackedModel
from femoat.structure.pounding import PackedModel as PoundingPackedModel
from femoat.units import G


def test_one_type_under_every_name():
    # the public names stay importable and name the one class, whichever model packed it
    assert PackedPlanModel is PackedModel is PoundingPackedModel
    assert PlanLayout is Layout
    assert type(paper_model("concrete", "H").pack()) is type(PlanModel().pack()) is PackedModel


def test_a_1d_pack_has_one_axis_and_no_y_dofs():
    model = paper_model("concrete", "H")  # base mat + 3 floors, two SDOF walls (+x, -x)
    p = model.pack()
    # one axis: x only; the y and θ columns of the layout are empty (−1)
    assert p.layout.axes == ("x",)
    np.testing.assert_array_equal(p.layout.floor_dofs, [[0, -1, -1], [1, -1, -1],
                                                        [2, -1, -1], [3, -1, -1]])
    # n = (base + 3 floors) on x + one mode per wall = 4 + 2: no y DOF is carried (the plan
    # model of the same building has 2·4 + 4 = 12)
    assert (p.n, p.n_struct, p.layout.wall_dofs) == (6, 4, ((4,), (5,)))
    assert p.M.shape == p.C.shape == p.K.shape == (6, 6)
    # the ground load: one column, the 1D influence vector r; the masses w/g on the floors
    # (10, 8, 8, 7 kip) and the wall's participation L = its mass, + for the +x wall (its mode
    # points to +x, away from the building) and − for the −x wall
    m_wall = model.walls[0].wall.mass
    assert p.R.shape == (6, 1)
    np.testing.assert_array_equal(p.r, p.R[:, 0])
    np.testing.assert_array_equal(p.r, [10.0 / G, 8.0 / G, 8.0 / G, 7.0 / G, m_wall, -m_wall])
    # every element acts along x; the friction pendulum stays the 1D isolator element (no plan
    # bearing rows, whose widths are still the registry's, as the loop takes them)
    np.testing.assert_array_equal(p.el_axis, [0, 0, 0, 0])
    assert p.el_names == ["isolator", "story1", "story2", "story3"]
    wp, _, ws = bearing_registry.widths()
    assert p.bearing_kind.shape == (0,) and p.bearing_dofs.shape == (0, 2)
    assert p.bearing_P.shape == (0, wp) and p.bearing_S.shape == (0, ws)
    # the walls: δ = ±u_base − gap − q; no slip along a wall on one axis (t = (0, ±1) has no
    # x component) and no friction: zeros to the bit (no negative zero)
    np.testing.assert_array_equal(p.c_B, [[1, 0, 0, 0, -1, 0], [-1, 0, 0, 0, 0, -1]])
    assert p.c_T.shape == (2, 6) and p.c_T.tobytes() == np.zeros((2, 6)).tobytes()
    assert p.c_friction.tobytes() == np.zeros(2).tobytes()
    assert p.c_names == ["pos", "neg"]
    # the names a 1D run has always had
    assert p.dof_names == ["base", "floor1", "floor2", "floor3", "wall_pos", "wall_neg"]
    assert model.dof_names() == p.dof_names == list(model.layout().names)
    np.testing.assert_array_equal(p.dof_axis, np.zeros(6))


def _rows(plan, model, axis):
    """The plan pack's DOFs of ``axis`` in the 1D order: the floors on it, then the modes of the
    walls normal to it (+ wall, then − wall)."""
    lay = plan.layout
    walls = [d for w, d in zip(model.walls, lay.wall_dofs) if w.axis == axis]
    return list(lay.floor_dofs[:, axis]) + [i for d in walls for i in d]


@pytest.mark.parametrize("axis", [0, 1], ids=["x", "y"])
def test_the_1d_pack_is_the_plan_pack_on_one_axis_field_by_field(axis):
    # An Elastic isolator is one element per axis in plan and the isolator element in 1D, so
    # every field of the one type compares: the plan pack's rows, columns and elements of one
    # axis are the 1D pack of model.along(axis), to the bit. Every field of PackedModel is
    # named below: a new field must say how it reduces to one axis.
    model = PlanModel(PlanBuilding(isolator=Elastic(2.5), p_delta=True),
                      rectangular_moat(gap=3.0))
    plan, one = model.pack(), model.along("xy"[axis]).pack()
    idx = _rows(plan, model, axis)
    els = list(np.flatnonzero(plan.el_axis == axis))  # isolator on the axis, then its stories
    walls = [c for c, w in enumerate(model.walls) if w.axis == axis]
    to_plan = np.array(idx)

    def el_dof(j):  # a 1D element's DOF in the plan layout (−1 the ground stays −1)
        return np.where(j < 0, -1, to_plan[np.maximum(j, 0)])

    expected = {
        # the matrices' block of the axis's DOFs
        "M": lambda: plan.M[np.ix_(idx, idx)], "C": lambda: plan.C[np.ix_(idx, idx)],
        "K": lambda: plan.K[np.ix_(idx, idx)],
        # the ground load: the plan's column of the axis, on its rows
        "R": lambda: plan.R[np.ix_(idx, [axis])],
        # the layout: one axis, the axis's floors renumbered 0.., the walls after them
        "layout": None,
        "story_heights": lambda: plan.story_heights,
        # the axis's elements, their DOFs mapped back; on one axis every element acts along x
        "el_i": None, "el_j": None,
        "el_axis": lambda: np.zeros(len(els), dtype=np.int64),
        "el_code": lambda: plan.el_code[els], "el_P": lambda: plan.el_P[els],
        "el_S": lambda: plan.el_S[els], "el_roles": lambda: tuple(plan.el_roles[e] for e in els),
        "el_materials": lambda: [plan.el_materials[e] for e in els],
        # no plan bearing in either (the Elastic isolator is an element)
        "bearing_kind": lambda: plan.bearing_kind, "bearing_dofs": lambda: plan.bearing_dofs,
        "bearing_P": lambda: plan.bearing_P, "bearing_S": lambda: plan.bearing_S,
        # the walls normal to the axis: their rows on the axis's DOFs; the slip along such a
        # wall has no component on its own axis, so the 1D slip rows are zeros
        "c_B": lambda: plan.c_B[np.ix_(walls, idx)],
        "c_T": lambda: np.zeros((len(walls), len(idx))),
        "c_gap": lambda: plan.c_gap[walls], "c_code": lambda: plan.c_code[walls],
        "c_P": lambda: plan.c_P[walls], "c_H": lambda: plan.c_H[walls],
        "c_friction": lambda: plan.c_friction[walls],  # 0 here; along() drops friction
        # 1D names: "pos" and "neg" for the + and − walls
        "c_names": lambda: ["pos", "neg"],
        "walls": lambda: tuple(model.walls[c].uniaxial() for c in walls),
    }
    assert set(expected) == {f.name for f in dataclasses.fields(PackedModel)}
    for name, value in expected.items():
        if value is None:
            continue
        got, want = getattr(one, name), value()
        if isinstance(want, np.ndarray):
            assert got.dtype == want.dtype and got.shape == want.shape, name
            assert got.tobytes() == want.tobytes(), name
        else:
            assert got == want, name
    np.testing.assert_array_equal(plan.el_i[els], el_dof(one.el_i))
    np.testing.assert_array_equal(plan.el_j[els], el_dof(one.el_j))
    lay = one.layout
    assert lay.axes == ("x",) and lay.n == len(idx) and lay.n_struct == 4
    assert lay.wall_names == ("pos", "neg") and lay.wall_dofs == ((4,), (5,))
    # the plan layout of the same model: both axes, walls by side
    assert plan.layout.axes == ("x", "y") and plan.layout.n_struct == 8
    assert plan.layout.wall_names == ("+x", "-x", "+y", "-y")


def test_dof_layout_names_and_numbers():
    walls = rectangular_moat(sides=("+x", "-x"))
    one, two = dof_layout(2, 1, tuple(w.uniaxial() for w in walls)), dof_layout(2, 2, walls)
    # one axis: floor k at k; the walls after the 3 floor DOFs
    assert one.names == ("base", "floor1", "floor2", "wall_pos", "wall_neg")
    np.testing.assert_array_equal(one.floor_dofs[:, 0], [0, 1, 2])
    # two axes, node-major: floor k at (2k, 2k + 1); the walls after the 6 floor DOFs
    assert two.names == ("base_x", "base_y", "floor1_x", "floor1_y", "floor2_x", "floor2_y",
                         "wall_+x", "wall_-x")
    np.testing.assert_array_equal(two.floor_dofs[:, :2], [[0, 1], [2, 3], [4, 5]])
    with pytest.raises(ValueError, match="one axis or two"):
        dof_layout(2, 3, ())


def test_a_plan_bearing_needs_both_axes():
    # the pack path refuses a plan bearing on a layout with one axis (the 1D isolator is an
    # element: PoundingModel.pack never asks for one)
    from femoat.structure.packing import pack

    b = Building()
    with pytest.raises(ValueError, match="a plan bearing acts on the base mat's x and y"):
        pack(b, (b.stories,), dof_layout(3, 1, ()), (), bearing=0)
