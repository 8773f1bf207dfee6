"""The OpenSees twin in 3D of the plan model (femoat.opensees.plan) against the 1D twin and
against itself under the symmetries of plan motion.

Every comparison is between OpenSees runs at the same fixed step, so the tolerances are
round-off, not discretisation: the two models solve the same equations with the DOFs numbered
differently (the 1D twin's one DOF per node against six per node here), so the Newton iterates
differ in the last bits and the differences stay near 1e-10 of the response (the NormDispIncr
tolerance 1e-10 in bounds each step's unconverged remainder).
"""

import math

import numpy as np
import pytest
from conftest import opensees_or_skip

from femoat.ground_motions import GroundMotion, RecordPair, fema_p695_pair
from femoat.opensees import opensees_run
from femoat.opensees.plan import opensees_plan_commands, opensees_plan_run
from femoat.paper import paper_model, paper_motion
from femoat.plan import PlanBuilding, PlanModel, PlanWall, rectangular_moat
from femoat.structure.building import Building
from femoat.structure.materials import Elastic
from femoat.structure.pounding import PoundingModel
from femoat.walls import wall_preset


def first_seconds(gm, seconds, factor=1.0):
    n = int(round(seconds / gm.dt)) + 1
    return GroundMotion(factor * gm.accel_g[:n], gm.dt, name=gm.name)


def zero_like(gm):
    return GroundMotion(np.zeros(gm.npts), gm.dt, name="zero")


def p695_pair(seconds, **kwargs):
    """The first seconds of FEMA P695 far-field record 1 (Northridge, Beverly Hills), a real pair
    whose components differ."""
    p = fema_p695_pair("farfield", 1)
    return RecordPair(first_seconds(p.x, seconds), first_seconds(p.y, seconds), **kwargs)


@pytest.mark.opensees
def test_along_x_it_is_the_1d_twin():
    opensees_or_skip()
    # The paper's building between steel walls (Jankowski law) under the first 4 s of the paper
    # motion along x, nothing along y, the same walls at ±y. Along x the 3D model is the 1D
    # twin's: the flat slider under N = W with Coulomb friction and kInit = μW/u_y returns
    # q = k0·(u − u_p) to |q| = μW, which on one axis is ElasticPP(μW/u_y, u_y) (the 1D twin's
    # friction spring) step for step; the stories, dashpots and Masroor chains are the same
    # materials. Nothing loads y (no excitation, no coupling: the slider's z stays on the x
    # axis), so the y DOFs stay exactly zero and the ±y walls are never touched.
    gm = paper_motion(quick=True)
    model_1d = paper_model("steel", "J")
    plan = PlanModel(PlanBuilding.from_building(model_1d.building),
                     rectangular_moat("steel", "J"))
    # (a step of 5e-4 s: the claim is step for step, at any step both converge at)
    ours = opensees_plan_run(plan, RecordPair(gm, zero_like(gm)), 5e-4, duration=4.5)
    theirs = opensees_run(model_1d, gm, 5e-4, duration=4.5)
    assert ours["bearing_normal_force"] == pytest.approx(33.0, rel=1e-12)  # N = W
    assert theirs["peaks"]["impacts_pos"] + theirs["peaks"]["impacts_neg"] == 3  # real impacts
    base = theirs["base_displacement"]
    scale = np.abs(base).max()
    assert np.abs(ours["base_displacement"][:, 0] - base).max() <= 1e-8 * scale
    floors = theirs["floor_displacement"]
    assert np.abs(ours["floor_displacement"][:, :, 0] - floors).max() <= 1e-8 * scale
    force = theirs["contact_force"]  # the 1D walls are (pos, neg): our +x, −x
    assert np.abs(ours["contact_force"][:, :2] - force).max() <= 1e-8 * force.max()
    walls = theirs["wall_displacement"]
    assert np.abs(ours["wall_displacement"][:, :2] - walls).max() <= 1e-8 * np.abs(walls).max()
    assert np.all(ours["base_displacement"][:, 1] == 0.0)
    assert np.all(ours["floor_displacement"][:, :, 1] == 0.0)
    assert np.all(ours["contact_force"][:, 2:] == 0.0)
    assert np.all(ours["wall_displacement"][:, 2:] == 0.0)


@pytest.mark.opensees
def test_a_pair_turned_by_90_degrees_gives_the_mirrored_response():
    opensees_or_skip()
    # Turning the pair by +90° applies (−a_y, a_x) (docs/plan.md §2). The building (the same
    # stories in x and y, an isotropic bearing) and the moat (the same wall at 3 in on all four
    # sides) are invariant under the plan rotation R(90°): (x, y) → (−y, x), so the response is
    # the original turned by 90°: u' = (−u_y, u_x), and the wall of outward normal n takes the
    # force of the wall of normal R(−90°)·n: +y' ← +x, −x' ← +y, −y' ← −x, +x' ← −y.
    pair = p695_pair(6.0, scale=2.0)
    model = PlanModel(walls=rectangular_moat("steel", "J", gap=3.0))
    run = opensees_plan_run(model, pair, 5e-4, duration=7.0)
    turned = opensees_plan_run(model, pair.rotated(90.0), 5e-4, duration=7.0)
    assert run["peaks"]["impacts"].min() >= 2  # every wall is hit
    u, v = run["base_displacement"], turned["base_displacement"]
    scale = np.hypot(*u.T).max()
    assert np.abs(v[:, 0] + u[:, 1]).max() <= 1e-8 * scale
    assert np.abs(v[:, 1] - u[:, 0]).max() <= 1e-8 * scale
    uf, vf = run["floor_displacement"], turned["floor_displacement"]
    assert np.abs(vf[:, :, 0] + uf[:, :, 1]).max() <= 1e-8 * scale
    assert np.abs(vf[:, :, 1] - uf[:, :, 0]).max() <= 1e-8 * scale
    f, g = run["contact_force"], turned["contact_force"]  # columns +x, −x, +y, −y
    assert np.abs(g[:, [2, 3, 1, 0]] - f).max() <= 1e-8 * f.max()


@pytest.mark.opensees
def test_diagonal_excitation_in_a_square_moat_hits_two_walls_at_once():
    opensees_or_skip()
    # The same component on x and y (a_x = a_y): the ground moves along the diagonal x = y.
    # The model is symmetric about that line (the same stories in x and y, an isotropic
    # bearing, the same wall at 2.5 in on all sides), so u_x = u_y at all times (to rounding:
    # x and y are different equations of one system), the base mat moves along the diagonal
    # and reaches the corner: it closes the +x and +y gaps at the same instant, and both
    # contacts carry the same force throughout (likewise −x and −y).
    gm = first_seconds(paper_motion(), 4.0)
    model = PlanModel(walls=rectangular_moat("steel", "J", gap=2.5))
    run = opensees_plan_run(model, RecordPair(gm, gm), 5e-4, duration=4.5)  # (any step)
    u = run["base_displacement"]
    assert np.abs(u[:, 0] - u[:, 1]).max() <= 1e-9 * np.abs(u).max()
    floors = run["floor_displacement"]
    assert np.abs(floors[:, :, 0] - floors[:, :, 1]).max() <= 1e-9 * np.abs(u).max()
    f = run["contact_force"]
    hits = run["peaks"]["impacts"]
    assert hits[0] == hits[2] >= 1 and hits[1] == hits[3]
    assert np.abs(f[:, 0] - f[:, 2]).max() <= 1e-9 * f.max()
    assert np.abs(f[:, 1] - f[:, 3]).max() <= 1e-9 * f.max()
    # a corner impact: the two walls are in contact on the same steps
    np.testing.assert_array_equal(f[:, 0] > 0, f[:, 2] > 0)
    assert np.any((f[:, 0] > 0) & (f[:, 2] > 0))


@pytest.mark.opensees
def test_coupled_friction_differs_from_two_independent_1d_runs():
    opensees_or_skip()
    # Elastic stories (so that every element is isotropic in plan: a bilinear story per axis
    # would yield at √2·Fy along the diagonal) on the paper's friction pendulum, no walls,
    # the paper motion on x and on y. Along the diagonal d = (1, 1)/√2 the ground moves
    # √2·a(t), and the whole model is the 1D model along d: restoring (W/R)·s, friction μW on
    # the line (coupled: |F| ≤ μW whatever the direction), the story springs and dashpots. So
    # u_x = u_y = s/√2 with s the 1D twin's response to √2·a: step for step (round-off).
    # Two independent 1D runs (one per axis, each with friction μW: √2·μW in all along d) give
    # u_x = u_y = the 1D response to a, which is the diagonal model with friction √2·μW: equal
    # to the coupled run only while the bearing sticks.
    gm = first_seconds(paper_motion(), 4.0)
    building = Building(stories=(Elastic(42.799),) * 3)
    plan = PlanModel(PlanBuilding.from_building(building), walls=())
    coupled = opensees_plan_run(plan, RecordPair(gm, gm), 5e-4, duration=4.0)
    along_d = opensees_run(PoundingModel(building), first_seconds(gm, 4.0, math.sqrt(2.0)),
                           5e-4, duration=4.0)
    independent = opensees_run(PoundingModel(building), gm, 5e-4, duration=4.0)
    u = coupled["base_displacement"]
    s = along_d["base_displacement"] / math.sqrt(2.0)
    assert np.abs(u[:, 0] - s).max() <= 1e-8 * np.abs(s).max()
    assert np.abs(u[:, 1] - s).max() <= 1e-8 * np.abs(s).max()
    # The independent runs keep friction μW on each axis: they slide less. Friction is a small
    # share of the bearing force here (μW = 2.0 kip against (W/R)·u = 11 kip at 10 in), so the
    # difference is that share, not round-off: measured peaks 10.47 and 9.78 in (7 %) and
    # histories apart by 1.66 in (17 % of the peak).
    peak_coupled = np.abs(u[:, 0]).max()
    peak_independent = np.abs(independent["base_displacement"]).max()
    assert peak_coupled > 1.03 * peak_independent
    assert np.abs(u[:, 0] - independent["base_displacement"]).max() > 0.1 * peak_independent


@pytest.mark.opensees
def test_p_delta_is_a_negative_story_spring_in_both_directions():
    opensees_or_skip()
    # An elastic building with P-Delta under a pair: the 3D twin adds Elastic(−P_k/h_k) to every
    # story in x and y (femoat's linear P-Delta: K gains −P/h per story), so it must equal the
    # same building without P-Delta whose stories are softened to k − P_k/h_k, with P_k the
    # weight of floor k and above (23, 15, 7 kip) and h = 39 in. Undamped on both sides (the
    # dashpots β·k0 would differ). The P-Delta terms are large here (stories of 2 kip/in, P/h
    # up to 23/39 = 0.59 kip/in), so a wrong sign or a missing direction shows at O(1).
    gm = first_seconds(paper_motion(), 3.0)
    pair = RecordPair(gm, first_seconds(paper_motion(), 3.0, 0.5))
    stories = (Elastic(2.0),) * 3
    softened = tuple(Elastic(2.0 - p / 39.0) for p in (23.0, 15.0, 7.0))

    def floors(stories, p_delta):
        b = PlanBuilding(stories_x=stories, stories_y=stories, p_delta=p_delta,
                         isolator=Elastic(2.0), story_damping_ratio=0.0)
        return opensees_plan_run(PlanModel(b, walls=()), pair, 1e-3,
                                 duration=3.0)["floor_displacement"]

    ours, theirs = floors(stories, True), floors(softened, False)
    scale = np.abs(theirs).max()
    assert np.abs(ours - theirs).max() <= 1e-9 * scale
    assert np.abs(floors(stories, False) - theirs).max() > 0.05 * scale


def test_commands_refuse_what_has_no_twin():
    # No OpenSees needed: the refusals come before any openseespy call.
    gm = paper_motion(quick=True)
    pair = RecordPair(gm, zero_like(gm))
    preset = wall_preset("concrete")
    walls = rectangular_moat()
    rubbing = (PlanWall(walls[0].law, preset.wall, 4.0, "+x", friction=0.3),)
    with pytest.raises(ValueError, match=r"wall \+x: friction = 0.3"):
        opensees_plan_commands(PlanModel(walls=rubbing), pair)
    with pytest.raises(ValueError, match="RecordPair"):
        opensees_plan_commands(PlanModel(), gm)
