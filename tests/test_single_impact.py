"""The precise single-impact solver against closed forms, and exact-restitution calibration."""

import math

import pytest
from scipy.special import beta

from femoat.contact import make_law
from femoat.impact import simulate_impact
from femoat.impact.calibration import achieved_restitution, calibrate
from femoat.walls import wall_preset

CONCRETE = wall_preset("concrete")
V0 = 10.0  # [in/s]


def test_linear_spring_closed_form():
    law = make_law("E", CONCRETE.contact)
    r = simulate_impact(law, V0)
    m, k = CONCRETE.contact.m_eff, CONCRETE.contact.k_eff
    # Mass on a linear spring: f_max = v0·√(k·m), contact lasts half a period π·√(m/k), e = 1.
    assert r.peak_force == pytest.approx(V0 * math.sqrt(k * m), rel=1e-4)
    assert r.contact_duration == pytest.approx(math.pi * math.sqrt(m / k), rel=1e-4)
    assert r.restitution == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize("kind", ["J", "H"])
def test_undamped_hertz_closed_form(kind):
    law = make_law(kind, CONCRETE.contact, damping=0.0)
    r = simulate_impact(law, V0)
    m, kh = CONCRETE.contact.m_eff, CONCRETE.contact.k_h
    # Energy: ½mv² = (2/5)·k_h·δ_max^2.5  →  δ_max = (5mv²/(4k_h))^(2/5), f_max = k_h·δ_max^1.5.
    d_max = (5 * m * V0**2 / (4 * kh)) ** 0.4
    assert r.max_indentation == pytest.approx(d_max, rel=1e-4)
    assert r.peak_force == pytest.approx(kh * d_max**1.5, rel=1e-4)
    # t_c = 2·(δ_max/v)·∫₀¹ dx/√(1−x^2.5) = 2·(δ_max/v)·B(2/5, 1/2)/(5/2)
    #     = 3.21806·(m²/(k_h²·v))^(1/5). (The paper prints 3.2145, docs/paper.md §5.5, from Goldsmith's
    #     rounded 2.94·δ_max/v; the exact coefficient 2·B(0.4, 0.5)/2.5 = 2.94328.)
    t_c = 2 * (d_max / V0) * beta(0.4, 0.5) / 2.5
    assert r.contact_duration == pytest.approx(t_c, rel=1e-4)
    assert t_c == pytest.approx(3.21806 * (m**2 / (kh**2 * V0)) ** 0.2, rel=1e-5)
    assert r.restitution == pytest.approx(1.0, abs=1e-6)


def test_kelvin_voigt_reaches_e_without_tension_and_not_with_it():
    law = make_law("V", CONCRETE.contact)
    # The ξ_KV relation of docs/paper.md §2 is exact for a tension-free Kelvin-Voigt contact.
    assert simulate_impact(law, V0).restitution == pytest.approx(0.700, abs=1e-3)
    # Keeping contact (and pulling) until δ = 0 lasts exactly half a damped period:
    # e = exp(−ξπ/√(1−ξ²)) = exp(−0.12221·π/0.99250) = 0.6792 (docs/paper.md §5.3).
    xi = law.damping_parameter()
    pulling = simulate_impact(make_law("V", CONCRETE.contact, allow_tension=True), V0)
    assert pulling.restitution == pytest.approx(math.exp(-xi * math.pi / math.sqrt(1 - xi**2)),
                                                rel=1e-6)


@pytest.mark.parametrize("kind", ["J", "H"])
def test_hertz_type_restitution_is_speed_independent(kind):
    # Scaling δ by Δ and t by √(m/(k_h·√Δ)) maps one impact onto another for both laws, so e is
    # independent of v0 (a check that H's δ̇₀ is taken at closure, which this scaling needs).
    law = make_law(kind, CONCRETE.contact)
    e1, e30 = achieved_restitution(law, 1.0), achieved_restitution(law, 30.0)
    assert e1 == pytest.approx(e30, abs=1e-7)


def test_published_closed_forms_miss_the_target():
    # The numbers: Hertzdamp's ξ_h = 8(1−e)/(5e) reaches ≈0.683, Jankowski's ≈0.698.
    pr = CONCRETE.contact
    assert achieved_restitution(make_law("H", pr), V0) == pytest.approx(0.683, abs=1e-3)
    assert achieved_restitution(make_law("J", pr), V0) == pytest.approx(0.698, abs=1e-3)


@pytest.mark.parametrize("kind", list("VJHM"))
@pytest.mark.parametrize("v0", [1.0, 10.0, 30.0])
def test_calibrated_laws_reach_the_target(kind, v0):
    law = calibrate(make_law(kind, CONCRETE.contact), v0)
    assert achieved_restitution(law, v0) == pytest.approx(0.70, abs=1e-3)


def test_bilinear_calibration_closed_form():
    # At δ_max = δ_me the bilinear law gives e² = (1−λ)/(1+λ): λ = (1−0.49)/(1+0.49) = 0.342282.
    law = calibrate(make_law("M", CONCRETE.contact), V0)
    assert law.damping == pytest.approx(0.51 / 1.49, rel=1e-12)
    r = simulate_impact(law, V0)
    assert r.max_indentation == pytest.approx(law.params.delta_me, rel=1e-7)


@pytest.mark.parametrize("kind", list("EVJHM"))
@pytest.mark.parametrize("wall", [None, "concrete", "steel"])
def test_energy_balance_closes(kind, wall):
    preset = wall_preset(wall or "steel")
    r = simulate_impact(make_law(kind, preset.contact), V0,
                        wall=None if wall is None else preset.wall)
    # ½mv0² = ½mv² + wall energy + contact dissipation + dashpot dissipation, integrated
    # independently; the residual measures the integration error.
    assert r.energy_residual < 1e-6
    assert r.dissipated_energy >= -1e-12
    if kind == "E" and wall is None:
        assert r.dissipated_energy == pytest.approx(0.0, abs=1e-9 * 0.5 * preset.contact.m_eff * V0**2)


def test_wall_softens_the_impact():
    # In series with a compliant wall the contact force is lower than against a rigid stop,
    # and the wall moves.
    law = make_law("H", CONCRETE.contact)
    rigid = simulate_impact(law, V0)
    soft = simulate_impact(law, V0, wall=CONCRETE.wall)
    assert soft.peak_force < rigid.peak_force
    assert soft.peak_wall_displacement > 0


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), float("inf")])
def test_bad_speed(bad):
    with pytest.raises(ValueError, match="v0 = .* must be a positive impact speed"):
        simulate_impact(make_law("E", CONCRETE.contact), bad)


def test_unreachable_calibration_target_is_explained():
    with pytest.raises(ValueError, match="reaches e between"):
        calibrate(make_law("H", CONCRETE.contact), V0, wall=CONCRETE.wall)
    with pytest.raises(ValueError, match="no damping"):
        calibrate(make_law("E", CONCRETE.contact), V0)
