"""Modal (finite-element) walls in the OpenSees twins: the chain of rescaled modes with
inerters (femoat.opensees.wall_chain.wall_chain_commands), in 1D against femoat's solver and in
3D against the 1D twin."""

from pathlib import Path

import numpy as np
import pytest
from conftest import ahead, opensees_or_skip

from femoat.contact import make_law
from femoat.ground_motions import GroundMotion, RecordPair
from femoat.integration import Integrator
from femoat.opensees import opensees_commands, opensees_run
from femoat.opensees.plan import opensees_plan_commands, opensees_plan_run
from femoat.paper import paper_model, paper_motion
from femoat.plan import PlanBuilding, PlanModel, PlanWall, rectangular_moat
from femoat.run import run
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.walls import ModalWall, wall_preset
from femoat.walls.fe import beam_model, load_geometry, modal_analysis

MESHES = Path(__file__).resolve().parents[1] / "meshes"


def _fe_wall():
    res = modal_analysis(beam_model(load_geometry(MESHES / "concrete_wall.toml")), 40)
    return ModalWall.from_fe(res, n_modes=3, damping_ratio=0.05, residual=False)


@pytest.fixture(scope="module")
def fe_wall():
    """The concrete wall's first three impact modes (5 % damping): φ = 1 at the impact point,
    L_i ≠ m_i (L = 1.1e-3, −6.9e-4, 4.4e-4 against m = 7.5e-4, 9.0e-4, 1.1e-3 kip·s²/in), so
    the twin needs the chain's inerters and its ground-load corrections."""
    return _fe_wall()


def rescaled(wall, phi):
    """The same wall with mode i scaled by 1/φ_i (q_i' = φ_i·q_i): m, k, c × φ², L × φ, and
    impact shape φ. Physically the same wall."""
    phi = np.asarray(phi, dtype=float)
    return ModalWall(wall.modal_masses * phi**2, wall.modal_stiffnesses * phi**2,
                     wall.modal_dampings * phi**2, phi, wall.ground_participation * phi)


def first_seconds(gm, seconds):
    n = int(round(seconds / gm.dt)) + 1
    return GroundMotion(gm.accel_g[:n], gm.dt, name=gm.name)


def fe_model(wall):
    law = make_law("H", wall_preset("concrete").contact)
    return PoundingModel(paper_model("concrete", "H").building,
                         (MoatWall(law, wall, 3.0, 1), MoatWall(law, wall, 3.0, -1)))


def opensees_modal_1d_twin():
    """The peaks of the twin of the test below (OpenSees alone: a parallel session computes
    it ahead, conftest.py, AHEAD)."""
    gm = first_seconds(paper_motion(quick=True), 4.0)
    return opensees_run(fe_model(_fe_wall()), gm, 1e-4, duration=4.5)["peaks"]


@pytest.mark.opensees
def test_1d_twin_of_a_modal_wall_matches_femoat(fe_wall):
    opensees_or_skip()
    # The paper's building between two three-mode concrete walls at 3 in (Hertzdamp), the
    # first 4 s of the paper motion: 8 + 9 impacts. Both tools solve the same modal equations
    # (femoat: q_i with m_i, k_i, c_i, −L_i·a_g, φ_i·F; the twin: the chain of s_i = φ_i·q_i).
    # The fastest time scale is the third mode (156 Hz, ω·dt = 0.1 at dt = 1e-4 s: Newmark's
    # period error (ω·dt)²/12 = 8e-4 on that mode) and the Hertz contact (τ ≈ 1 ms): impact
    # forces within 5e-3 (measured 3e-3 and 1.5e-3), while the slow isolation mode carries the
    # base and wall displacements and the drifts: 2e-5 (measured 1e-6, 8e-7, 4e-6). A twin
    # that dropped the inerters or the ground-load corrections moves the wall displacement by
    # its modes' share: the participation differs from the mass by 50-140 %.
    model = fe_model(fe_wall)
    gm = first_seconds(paper_motion(quick=True), 4.0)
    ours = run(model, gm, Integrator(rtol=1e-8), duration=4.5)
    p, q = ahead(opensees_modal_1d_twin), ours.peaks
    assert (p["impacts_pos"], p["impacts_neg"]) == (q["impacts_pos"], q["impacts_neg"]) == (8, 9)
    for key in ("peak_impact_force_pos", "peak_impact_force_neg"):
        assert p[key] == pytest.approx(q[key], rel=5e-3), key
    for key in ("peak_base_displacement", "peak_wall_displacement"):
        assert p[key] == pytest.approx(q[key], rel=2e-5), key
    np.testing.assert_allclose(p["peak_drift"], q["peak_drift"], rtol=2e-5)


@pytest.mark.opensees
def test_rescaled_modes_are_the_same_wall(fe_wall):
    opensees_or_skip()
    # Scaling mode i by 1/φ_i is a change of coordinates, not of the wall: the chain's s_i =
    # φ_i·q_i, masses m_i/φ_i², stiffnesses k_i/φ_i² and loads L_i/φ_i are the same numbers up
    # to rounding. So the twin's run is the φ = 1 run to round-off (1e-9), with a negative φ
    # among them (the mode's sign flips, the wall does not). 2 s, dt = 2e-4 s: 3 + 3 impacts.
    gm = first_seconds(paper_motion(quick=True), 2.0)
    one = opensees_run(fe_model(fe_wall), gm, 2e-4, duration=2.0)
    other = opensees_run(fe_model(rescaled(fe_wall, (1.0, 0.5, -0.8))), gm, 2e-4, duration=2.0)
    assert one["peaks"]["impacts_pos"] + one["peaks"]["impacts_neg"] >= 2
    for key in ("base_displacement", "wall_displacement", "contact_force"):
        scale = np.abs(one[key]).max()
        assert np.abs(other[key] - one[key]).max() <= 1e-9 * scale, key


@pytest.mark.opensees
def test_plan_twin_with_modal_walls_along_x_is_the_1d_twin(fe_wall):
    opensees_or_skip()
    # As tests/test_opensees_plan.py's y = 0 test, with the three-mode wall on ±x (and the
    # paper's concrete SDOF wall on ±y): under (a_x, 0) the 3D chain along x is the 1D chain
    # (the same springs, masses, inerters and load corrections on x DOFs), the slider is the
    # 1D ElasticPP, so the x response equals the 1D twin's run of model.along("x") to
    # round-off and nothing moves in y: displacements to 1e-8 (as the SDOF test), contact
    # forces to 1e-7 of the peak: each step's Newton remainder (NormDispIncr 1e-10 in) reaches
    # the force through the Hertz tangent 1.5·F/δ = 1.5·34/0.028 ≈ 1,900 kip/in, 2e-7 kip a
    # step, against a 34 kip peak (measured 4e-8).
    law = make_law("H", wall_preset("concrete").contact)
    walls = (PlanWall(law, fe_wall, 3.0, "+x"), PlanWall(law, fe_wall, 3.0, "-x"),
             *rectangular_moat("concrete", "H", gap=3.0, sides=("+y", "-y")))
    plan = PlanModel(PlanBuilding.from_building(paper_model("concrete", "H").building), walls)
    gm = first_seconds(paper_motion(quick=True), 3.0)
    zero = GroundMotion(np.zeros(gm.npts), gm.dt, name="zero")
    ours = opensees_plan_run(plan, RecordPair(gm, zero), 2e-4, duration=3.0)
    theirs = opensees_run(plan.along("x"), gm, 2e-4, duration=3.0)
    assert theirs["peaks"]["impacts_pos"] + theirs["peaks"]["impacts_neg"] >= 4
    scale = np.abs(theirs["base_displacement"]).max()
    assert np.abs(ours["base_displacement"][:, 0] - theirs["base_displacement"]).max() \
        <= 1e-8 * scale
    assert np.abs(ours["floor_displacement"][:, :, 0] - theirs["floor_displacement"]).max() \
        <= 1e-8 * scale
    force = theirs["contact_force"]
    assert np.abs(ours["contact_force"][:, :2] - force).max() <= 1e-7 * force.max()
    walls_1d = theirs["wall_displacement"]
    assert np.abs(ours["wall_displacement"][:, :2] - walls_1d).max() \
        <= 1e-8 * np.abs(walls_1d).max()
    assert np.all(ours["base_displacement"][:, 1] == 0.0)
    assert np.all(ours["contact_force"][:, 2:] == 0.0)


def test_a_modal_wall_is_a_chain_with_inerters_and_load_corrections(fe_wall):
    # No OpenSees needed. Wall +x, three modes of φ = 1: chain nodes 100, 1001, 1002 (the
    # impact point, where the contact ends), mode 1's mass m_1 lumped on node 100, inerters m_2,
    # m_3 between nodes; the load corrections (in/s² × kip·s²/in) on the x excitation:
    # node j gets L_{j+1} − L_j (+ m_1 on the first node, whose mass the excitation loads).
    gm = paper_motion(quick=True)
    law = make_law("H", wall_preset("concrete").contact)
    plan = PlanModel(walls=(PlanWall(law, fe_wall, 3.0, "+x"),))
    cmds = opensees_plan_commands(plan, RecordPair(gm, gm))
    m, L = fe_wall.modal_masses, fe_wall.ground_participation
    inerters = [c for c in cmds if c[:2] == ("element", "InertiaTruss")]
    assert [c[3:] for c in inerters] == [(100, 1001, m[1]), (1001, 1002, m[2])]
    contact = next(c for c in cmds if c[:3] == ("element", "zeroLength", 200))
    assert contact[3:5] == (2, 1002)
    assert ("mass", 100, m[0], 0.0, 0.0, 0.0, 0.0, 0.0) in cmds
    loads = [c for c in cmds if c[0] == "load" and c[1] != 2]  # 2: the slider's gravity
    expected = [L[1] - L[0] + m[0], L[2] - L[1], -L[2]]
    assert [c[1] for c in loads] == [100, 1001, 1002]
    np.testing.assert_allclose([c[2] for c in loads], expected, rtol=1e-12)
    assert ("pattern", "Plain", 100, 100) in cmds


def test_a_wall_of_more_than_99_modes_is_refused(fe_wall):
    # Chain tags are 1000 + 100·wall + mode: a 100th mode would take the next wall's first
    # tag, so both twins refuse it with the fix (no OpenSees needed).
    many = ModalWall(*(np.repeat(getattr(fe_wall, name)[:1], 100) for name in (
        "modal_masses", "modal_stiffnesses", "modal_dampings", "impact_shape",
        "ground_participation")))
    law = make_law("H", wall_preset("concrete").contact)
    gm = paper_motion(quick=True)
    with pytest.raises(ValueError, match="at most 99"):
        opensees_plan_commands(PlanModel(walls=(PlanWall(law, many, 3.0, "-y"),)),
                               RecordPair(gm, gm))
    with pytest.raises(ValueError, match="at most 99"):
        opensees_commands(fe_model(many), gm)
