"""P-Delta, story heights and collapse criteria: closed forms and the early stop."""

import math

import numpy as np
import pytest
import scipy.linalg

from femoat.collapse import CollapseCriteria
from femoat.ground_motions import GroundMotion
from femoat.integration.settings import Integrator
from femoat.paper import paper_model, paper_motion
from femoat.run import run
from femoat.scenario import collapse_from_dict, scenario_from_dict
from femoat.structure.building import Building
from femoat.structure.materials import Elastic, IMKBilinear
from femoat.structure.pounding import PoundingModel
from femoat.units import G

K_STORY, W_FLOOR, H_STORY, K_ISO = 10.0, 100.0, 20.0, 1e5   # [kip/in], [kip], [in], [kip/in]


def _one_story(p_delta, k=K_STORY):
    b = Building(base_weight=1.0, floor_weights=(W_FLOOR,), isolator=Elastic(k=K_ISO),
                 stories=(Elastic(k=k),), story_damping_ratio=0.0, story_heights=(H_STORY,),
                 p_delta=p_delta)
    return PoundingModel(b, ())


def _free(model, u0, duration):
    quiet = GroundMotion(np.zeros(int(duration / 0.01) + 1), 0.01, name="quiet")
    return run(model, quiet, Integrator(rtol=1e-7, max_step=1e-3), duration=duration,
               u0=u0)


def test_story_loses_exactly_p_over_h():
    # the packed stiffness of the story block differs by exactly −P/h = −100/20 = −5 kip/in
    k0 = _one_story(False).pack().K
    k1 = _one_story(True).pack().K
    dk = -W_FLOOR / H_STORY
    assert np.allclose(k1 - k0, dk * np.array([[1.0, -1.0], [-1.0, 1.0]]), rtol=0, atol=1e-14)


@pytest.mark.parametrize("p_delta", [False, True])
def test_free_vibration_period_with_p_delta(p_delta):
    # 2-DOF eigenproblem: base m_b on K_ISO, floor m on k' = k − P/h (P-Delta) or k.
    # ω² from scipy.linalg.eigh(K, M); the free vibration from the mode shape repeats at 2π/ω.
    model = _one_story(p_delta)
    packed = model.pack()
    # tangent stiffness: the packed linear part (P-Delta) plus the isolator and story springs
    kt = packed.K + K_ISO * np.diag([1.0, 0.0]) + K_STORY * np.array([[1.0, -1.0], [-1.0, 1.0]])
    w2, phi = scipy.linalg.eigh(kt, packed.M)
    period = 2 * math.pi / math.sqrt(w2[0])
    # the story stiffness with P-Delta is 10 − 5 = 5 kip/in: period ≈ 2π√(m/5) = 1.43 s
    k_eff = K_STORY - (W_FLOOR / H_STORY if p_delta else 0.0)
    assert period == pytest.approx(2 * math.pi * math.sqrt(W_FLOOR / G / k_eff), rel=1e-4)
    u0 = phi[:, 0] / phi[1, 0]
    r = _free(model, u0, 2.2 * period)
    x = r.displacement[:, 1]
    # upward zero crossings of the floor displacement, linearly interpolated
    idx = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    tz = r.time[idx] - x[idx] * (r.time[idx + 1] - r.time[idx]) / (x[idx + 1] - x[idx])
    assert len(tz) >= 2
    assert tz[1] - tz[0] == pytest.approx(period, rel=1e-5)


def test_story_beyond_its_buckling_load_diverges_at_the_closed_form_rate():
    # P/h = 5 kip/in against k = 2.5 kip/in: the story's stiffness is −2.5 kip/in, so the floor
    # (base held by K_ISO) moves as x ∝ cosh(λt), λ = √(2.5/m), m = 100/386.09 kip·s²/in.
    model = _one_story(True, k=2.5)
    lam = math.sqrt((W_FLOOR / H_STORY - 2.5) / (W_FLOOR / G))
    r = _free(model, np.array([0.0, 1e-3]), 3.0)
    t, x = r.time, r.displacement[:, 1]
    late = t > 1.5  # cosh(λt) ≈ e^{λt}/2 there (e^{−2λt} < 1e-3)
    slope = np.polyfit(t[late], np.log(x[late]), 1)[0]
    assert slope == pytest.approx(lam, rel=1e-3)


def _imk_building(p_delta=True):
    return Building(stories=tuple(IMKBilinear(theta_p=1.0, theta_pc=3.0) for _ in range(3)),
                    p_delta=p_delta)


def test_imk_building_with_p_delta_collapses_and_the_time_is_recorded():
    model = paper_model("concrete", "H", building=_imk_building())
    motion = paper_motion().scaled_to_pga(2.5)
    r = run(model, motion, collapse=CollapseCriteria(drift_ratio=0.10))
    c = r.collapse
    assert c["collapsed"] and c["stopped"] and c["drift"] is not None
    assert c["isolator"] is None and c["wall_force"] is None
    # the run ended at the first step end beyond 10 % drift (h = 39 in: 3.9 in)
    ratio = np.abs(r.story_drifts()).max(axis=1) / 39.0
    assert r.time[-1] == pytest.approx(c["drift"], abs=0) and ratio[-1] > 0.10
    assert ratio[:-1].max() <= 0.10
    assert r.meta["stats"]["t_reached"] == c["drift"] < motion.duration
    # without the stop the drift keeps growing past the limit (the story has capped and P-Delta
    # pulls it over) until the runaway bound, a drift of one story height, ends the run
    r2 = run(model, motion, collapse=CollapseCriteria(drift_ratio=0.10, stop=False))
    assert r2.collapse["drift"] == c["drift"] and r2.collapse["stopped"]
    assert max(r2.peaks["peak_drift_ratio"]) > 1.0 > np.abs(r2.story_drifts()[:-1]).max() / 39.0


def test_collapse_criteria_do_not_change_a_run_that_reaches_none():
    model, motion = paper_model("steel", "J"), paper_motion(quick=True)
    plain = run(model, motion)
    checked = run(model, motion, collapse=CollapseCriteria(stop=False))
    assert plain.collapse is None and checked.collapse["collapsed"] is False
    for name in ("time", "displacement", "contact_force"):
        assert np.array_equal(getattr(plain, name), getattr(checked, name))
    # and the paper's model has no P-Delta: its stiffness is that of the stories alone
    assert not Building().p_delta
    assert all(k == 0.0 for k in Building().geometric_stiffnesses())


def test_wall_limits_and_drift_ratio_peaks():
    model, motion = paper_model("concrete", "E"), paper_motion(quick=True)
    r = run(model, motion, collapse=CollapseCriteria(drift_ratio=None, isolator=False,
                                                     wall_force=10.0, wall_displacement=0.1,
                                                     stop=False))
    # the first impact (≈ 90 kip, ≈ 0.5 in of wall) exceeds both bounds during its first contact
    first = r.impacts[0]["start"]
    assert first <= r.collapse["wall_force"] < first + r.impacts[0]["duration"]
    assert r.collapse["wall_displacement"] > r.collapse["wall_force"]
    assert r.peaks["peak_drift_ratio"] == pytest.approx(
        [d / 39.0 for d in r.peaks["peak_drift"]], rel=1e-15)


def test_scenario_keys_and_bad_values():
    sc = scenario_from_dict({"building": {"story_model": "imk", "p_delta": True,
                                          "story_heights": [40.0, 38.0, 36.0],
                                          "isolator_capacity": 6.5},
                             "collapse": {"drift_ratio": 0.08, "stop": False}})
    b = sc.model.building
    assert b.p_delta and b.heights == (40.0, 38.0, 36.0) and b.isolator_capacity == 6.5
    # gravity on each story: floors above it, 8 + 8 + 7 = 23, 15, 7 kip
    assert b.gravity_loads() == (23.0, 15.0, 7.0)
    assert sc.collapse == CollapseCriteria(drift_ratio=0.08, stop=False)
    with pytest.raises(ValueError, match="drift_limit"):
        collapse_from_dict({"drift_limit": 0.1})
    with pytest.raises(ValueError, match="drift_ratio"):
        collapse_from_dict({"drift_ratio": -0.1})
    with pytest.raises(ValueError, match="story_heights"):
        Building(story_heights=(39.0, 39.0))
    with pytest.raises(ValueError, match=r"story_heights\[1\]"):
        Building(story_heights=(39.0, 0.0, 39.0))
    with pytest.raises(ValueError, match="isolator_capacity"):
        Building(isolator_capacity=-1.0)


# (The OpenSees twins carry P-Delta on one axis and in plan: tests/test_opensees_building.py,
# tests/test_opensees_plan.py.)
