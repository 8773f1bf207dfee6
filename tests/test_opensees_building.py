"""femoat's building solver against its OpenSees twin (femoat.opensees.building).

The OpenSees side integrates with Newmark's average-acceleration rule at a fixed step; femoat's
reference runs at rtol = 1e-8, far below the differences asserted, so every tolerance below is an
estimate of OpenSees' own discretisation error at its step, derived next to the assert.
"""

import argparse
import json
import math

import numpy as np
import pytest
from conftest import opensees_missing

from femoat.ground_motions import GroundMotion
from femoat.integration import Integrator
from femoat.opensees import opensees_commands
from femoat.paper import paper_model, paper_motion
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.materials import Elastic, FrictionPendulum, IMKBilinear
from femoat.structure.pounding import PoundingModel

# the suite's one OpenSees probe (conftest): its reason names the packages and the apt-get command
needs_opensees = pytest.mark.skipif(opensees_missing() is not None,
                                    reason=str(opensees_missing()))


def _first_seconds(gm, seconds):
    n = int(round(seconds / gm.dt)) + 1
    return GroundMotion(gm.accel_g[:n], gm.dt, name=gm.name)


@pytest.mark.opensees
@needs_opensees
def test_linear_building_without_walls_matches_femoat():
    from femoat.opensees import opensees_run

    # Elastic isolator (T ≈ 1.3 s) under three elastic stories, no walls, the first 4 s of the
    # paper record. Both tools integrate the same linear ODE with the same piecewise-linear a_g
    # (dt = 5e-4 s divides the record's 2.5e-3 s). Newmark's only error is the period
    # elongation (ω·dt)²/12 per cycle: ≤ 1.7e-5 for the highest mode (ω ≈ 91 rad/s), 2e-8 for
    # the isolation mode that carries the base displacement; over the ≈ 60 cycles of the
    # highest mode in 4 s the phase error stays ≤ 1e-3 rad, weighted by that mode's share of
    # the response (< 1 %): histories and peaks agree to ~1e-5 (measured 3e-6).
    b = Building(isolator=Elastic(2.0), stories=(Elastic(42.799),) * 3)
    model = PoundingModel(b)
    gm = _first_seconds(paper_motion(), 4.0)
    os_run = opensees_run(model, gm, 5e-4, duration=4.0)
    fm = run(model, gm, Integrator(rtol=1e-8), duration=4.0)
    ub = np.interp(os_run["time"], fm.time, fm.base_displacement)
    peak = np.abs(ub).max()
    assert peak > 10.0  # the isolator swings far: a meaningful comparison
    assert np.abs(os_run["base_displacement"] - ub).max() < 2e-5 * peak
    for key in ("peak_base_displacement", "peak_base_acceleration"):
        assert os_run["peaks"][key] == pytest.approx(fm.peaks[key], rel=2e-5)
    for key in ("peak_drift", "peak_floor_acceleration"):
        assert os_run["peaks"][key] == pytest.approx(fm.peaks[key], rel=2e-5)
    assert os_run["peaks"]["impacts_pos"] == os_run["peaks"]["impacts_neg"] == 0


@pytest.mark.opensees
@needs_opensees
def test_paper_run_matches_femoat():
    from femoat.opensees import opensees_run

    # The paper's building between two steel walls, Jankowski law (JankowskiImpact evaluates
    # the same force), first 4 s of the record plus 1 s: three impacts (1 + 2).
    # In contact the fastest time scale is the contact spring against the wall dashpot,
    # τ = C_imp/k_eff = 5.1/1739 = 2.9 ms (the wall-mass oscillation is overdamped:
    # C_imp/(2√(k_eff·M1)) = 1.9). Newmark's relative error on such a transient is
    # ≈ (dt/τ)²/12 = 4e-4 at dt = 2e-4 s, and the closure inside a step adds O(dt²) too:
    # impact peaks (force, indentation, wall displacement, impulse) within 2e-3 (measured
    # ≤ 4e-4); the base displacement follows the slow isolation mode (ω ≈ 5 rad/s): 1e-4.
    model = paper_model("steel", "J")
    gm = _first_seconds(paper_motion(), 4.0)
    os_run = opensees_run(model, gm, 2e-4, duration=5.0)
    fm = run(model, gm, Integrator(rtol=1e-8), duration=5.0)
    p, q = os_run["peaks"], fm.peaks
    assert (p["impacts_pos"], p["impacts_neg"]) == (q["impacts_pos"], q["impacts_neg"]) == (1, 2)
    for key in ("peak_impact_force", "peak_impact_force_pos", "peak_impact_force_neg",
                "peak_indentation", "peak_wall_displacement", "peak_impulse"):
        assert p[key] == pytest.approx(q[key], rel=2e-3), key
    assert p["peak_base_displacement"] == pytest.approx(q["peak_base_displacement"], rel=1e-4)
    # each impact starts at the same time: OpenSees' closure, interpolated linearly inside its
    # step, is off by ≈ (a/v)·dt²/8 ≈ 5e-8 s (a ≈ 1 g, v ≈ 40 in/s at closure): within 1 % of dt
    for a, b in zip(os_run["impacts"], fm.impacts):
        assert a["side"] == b["side"]
        assert a["start"] == pytest.approx(b["start"], abs=0.01 * 2e-4)


@pytest.mark.opensees
@needs_opensees
def test_p_delta_run_matches_femoat():
    from femoat.opensees import opensees_run

    # The run above with P-Delta: femoat adds the linear geometric stiffness −P_k/h_k to each
    # story (P_k the weight of floor k and above: 23, 15, 7 kip; h = 39 in), the twin an
    # Elastic(−P_k/h_k) beside each story's material. The same step and contact arguments as
    # above: impact peaks within 2e-3, the base displacement within 1e-4; the drifts and floor
    # accelerations follow the stories' modes, resolved at 2e-4 s (measured ≤ 1.6e-5): 1e-4.
    # Without P-Delta the twin's drifts are 3-13 % off femoat's P-Delta run, so the
    # comparison sees the geometric stiffness.
    model = paper_model("steel", "J", building=Building(p_delta=True))
    gm = _first_seconds(paper_motion(), 4.0)
    p = opensees_run(model, gm, 2e-4, duration=5.0)["peaks"]
    q = run(model, gm, Integrator(rtol=1e-8), duration=5.0).peaks
    assert (p["impacts_pos"], p["impacts_neg"]) == (q["impacts_pos"], q["impacts_neg"]) == (1, 2)
    assert p["peak_impact_force"] == pytest.approx(q["peak_impact_force"], rel=2e-3)
    assert p["peak_base_displacement"] == pytest.approx(q["peak_base_displacement"], rel=1e-4)
    for key in ("peak_drift", "peak_floor_acceleration"):
        np.testing.assert_allclose(p[key], q[key], rtol=1e-4, err_msg=key)
    plain = opensees_run(paper_model("steel", "J"), gm, 2e-4, duration=5.0)["peaks"]
    off = np.abs(np.asarray(plain["peak_drift"]) / np.asarray(q["peak_drift"]) - 1.0)
    assert off.min() > 0.02, off


@pytest.mark.opensees
@needs_opensees
def test_p_delta_on_one_axis_is_a_negative_story_spring():
    from femoat.opensees import opensees_run

    # OpenSees alone, exact: the 1D twin of an elastic building with P-Delta is the twin of the
    # same building without it whose stories are softened to k − P_k/h_k (P_k = 23, 15, 7 kip,
    # h = 39 in), undamped on both sides; equal to round-off. Stories of 2 kip/in make the
    # geometric terms O(1) (up to 0.59 kip/in), so a wrong sign shows.
    gm = _first_seconds(paper_motion(), 3.0)

    def floors(stories, p_delta):
        b = Building(stories=stories, p_delta=p_delta, isolator=Elastic(2.0),
                     story_damping_ratio=0.0)
        return opensees_run(PoundingModel(b), gm, 1e-3, duration=3.0)["floor_displacement"]

    theirs = floors(tuple(Elastic(2.0 - p / 39.0) for p in (23.0, 15.0, 7.0)), False)
    ours = floors((Elastic(2.0),) * 3, True)
    scale = np.abs(theirs).max()
    assert np.abs(ours - theirs).max() <= 1e-9 * scale
    assert np.abs(floors((Elastic(2.0),) * 3, False) - theirs).max() > 0.05 * scale


@pytest.mark.opensees
@needs_opensees
def test_cli_prints_both_summaries(tmp_path, capsys):
    from femoat.commands import opensees as cmd

    # A 0.6 s, 0.8 g sine pulse pushes the default building 0.5 in into the concrete walls.
    t = np.arange(0, 0.61, 0.01)
    (tmp_path / "pulse.txt").write_text("\n".join(f"{0.8 * math.sin(math.pi * x / 0.3):.6f}"
                                                  for x in t))
    (tmp_path / "s.toml").write_text(
        '[walls]\nlaw = "E"\ngap = 0.5\n[motion]\nsource = "text"\npath = "pulse.txt"\n'
        'dt = 0.01\nextra_time = 0.4\n[solver]\nrtol = 1e-6\n')
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers()
    cmd.add_parser(sub)
    args = parser.parse_args(["opensees", str(tmp_path / "s.toml"), "--dt", "1e-4", "--json",
                              "--script", str(tmp_path / "twin.py")])
    assert cmd.run(args) == 0
    out = json.loads(capsys.readouterr().out)
    fm, os_peaks = out["femoat"], out["opensees"]
    assert fm["impacts_pos"] + fm["impacts_neg"] >= 1
    # linear contact law, same model: the peaks agree to Newmark's O((dt/τ)²) (see above)
    assert os_peaks["peak_impact_force"] == pytest.approx(fm["peak_impact_force"], rel=5e-3)
    assert "ops.analyze(" in (tmp_path / "twin.py").read_text()


@pytest.mark.opensees
@needs_opensees
def test_cli_refuses_a_plan_scenario_naming_the_3d_twin(tmp_path, capsys):
    # `femoat opensees` compares 1D scenarios; a plan file gets exit 2 and the way to its 3D
    # twin, not a bare type error.
    from femoat.commands import opensees as cmd

    (tmp_path / "s.toml").write_text(
        '[building]\nplan = true\n[moat]\nlaw = "E"\n[motion]\nsource = "fema"\n'
        'record_set = "farfield"\nrecord_id = 1\n')
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers()
    cmd.add_parser(sub)
    assert cmd.run(parser.parse_args(["opensees", str(tmp_path / "s.toml")])) == 2
    err = capsys.readouterr().err
    assert "plan scenario" in err and "opensees_plan_run" in err


def test_export_refuses_what_has_no_opensees_twin():
    rate = Building(isolator=FrictionPendulum(mu=0.05, mu_fast=0.1, a=1.0))
    with pytest.raises(ValueError, match="mu_fast"):
        opensees_commands(PoundingModel(rate), paper_motion(quick=True))


def test_export_maps_materials_and_dashpots():
    # IMK stories become Bilin with femoat's own argument list; each story dashpot is
    # Elastic(0, c = β·k0) in Parallel with the spring, as PoundingModel.pack() assembles C.
    imk = IMKBilinear(theta_p=1.0, theta_pc=3.0)
    b = Building(stories=(imk,) * 3)
    model = PoundingModel(b, paper_model("steel", "M").walls)
    cmds = opensees_commands(model, paper_motion(quick=True))
    mats = [c for c in cmds if c[0] == "uniaxialMaterial"]
    assert [m[3:] for m in mats if m[1] == "Bilin"] == [tuple(imk.opensees_bilin_args())] * 3
    c = b.story_damping_beta * imk.K0
    assert sum(1 for m in mats if m[1] == "Elastic" and m[3:] == (0.0, c)) == 3
    contacts = [c for c in cmds if c[0] == "element" and c[2] >= 200]
    # side +1: base (2) → wall; side −1: wall → base, so closing is compression on both
    assert [(e[3], e[4]) for e in contacts] == [(2, 100), (101, 2)]
    assert [m[1] for m in mats].count("ImpactMaterial") == 2
