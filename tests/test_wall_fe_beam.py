"""Beam wall model against closed forms for a uniform cantilever (impact at the tip)."""

import numpy as np
import pytest

from femoat.walls.fe import (WallGeometry, beam_model, concrete, flexibility_fraction,
                             impact_modes, modal_analysis, modes_for_flexibility, static_stiffness)

BETA1 = 1.8751040687  # first root of 1 + cos(b)cosh(b) = 0 (Blevins, Formulas for Natural
# Frequency and Mode Shape, table 8-1, clamped-free beam)


def _wall(**changes):
    base = dict(height=100.0, length=10.0, thickness=5.0, material=concrete(),
                impact_height=100.0, impact_patch=2.0)
    return WallGeometry(**{**base, **changes})


def _section(g):
    E = g.material.youngs_modulus
    EI = E * g.length * g.thickness**3 / 12
    m = g.material.density * g.length * g.thickness  # mass per unit height [kip·s²/in²]
    return EI, m


def test_f1_converges_at_fourth_order():
    g = _wall()
    EI, m = _section(g)
    # Euler-Bernoulli cantilever: f1 = β1²/(2π)·√(EI/(m·L⁴)) (Blevins table 8-1).
    exact = BETA1**2 / (2 * np.pi) * np.sqrt(EI / (m * g.height**4))
    ns = np.array([2, 4, 8])
    errors = [modal_analysis(beam_model(g, n_height=n), 1).frequencies[0] / exact - 1 for n in ns]
    slope = -np.polyfit(np.log(ns), np.log(errors), 1)[0]
    # Hermite cubics with consistent mass: eigenvalue error O(h^(2(p+1-m))) = O(h^4) for p = 3,
    # m = 2 (Strang & Fix, An Analysis of the FEM, ch. 6); the error is positive (Rayleigh-Ritz).
    assert min(errors) > 0
    assert slope == pytest.approx(4.0, abs=0.3)


def test_tip_sdof_matches_closed_forms():
    g = _wall()
    EI, m = _section(g)
    L = g.height
    r = modal_analysis(beam_model(g, n_height=80), 3)
    # Mode 1 of a uniform cantilever normalised to unit tip displacement has ∫φ² dz = L/4 (every
    # clamped-free mode does: Blevins table 8-1 shape with φ(L) = 2 and ∫φ² = L), so
    # M1 = 0.25·(total mass) and K1 = ω1²·M1 = β1⁴/4·EI/L³ = 3.0906·EI/L³.
    assert r.M1 == pytest.approx(0.25 * m * L, rel=1e-4)
    assert r.K1 == pytest.approx(BETA1**4 / 4 * EI / L**3, rel=1e-4)
    assert BETA1**4 / 4 == pytest.approx(3.0906, abs=1e-4)
    # rᵀMr of the consistent mass is the beam's mass m·L; mode 1 of a cantilever carries
    # 61.3 % of it as effective mass (Chopra, Dynamics of Structures, uniform cantilever).
    assert r.total_mass == pytest.approx(m * L, rel=1e-12)
    assert r.effective_masses[0] / r.total_mass == pytest.approx(0.613, abs=1e-3)
    # Higher modes: β2 = 4.694091, β3 = 7.854757 (Blevins table 8-1).
    f = BETA1**2 / (2 * np.pi) * np.sqrt(EI / (m * L**4))
    assert r.frequencies[1] / f == pytest.approx((4.694091 / BETA1) ** 2, rel=1e-5)
    assert r.frequencies[2] / f == pytest.approx((7.854757 / BETA1) ** 2, rel=1e-5)


def test_static_tip_stiffness_is_3EI_over_L3():
    g = _wall()
    EI, _ = _section(g)
    # Cantilever tip load: δ = P·L³/(3EI) (any beam text); cubic elements are nodally exact.
    assert static_stiffness(beam_model(g, n_height=3)) == pytest.approx(3 * EI / g.height**3,
                                                                        rel=1e-12)


def test_timoshenko_static_adds_shear_flexibility():
    g = _wall(thickness=20.0)
    EI, _ = _section(g)
    kGA = 5 / 6 * g.material.shear_modulus * g.length * g.thickness
    # Timoshenko cantilever tip load: δ = P·L³/(3EI) + P·L/(κGA); the Friedman-Kosmatka element
    # is exact for static end loads.
    expected = 1 / (g.height**3 / (3 * EI) + g.height / kGA)
    assert static_stiffness(beam_model(g, n_height=2, timoshenko=True)) == pytest.approx(
        expected, rel=1e-10)
    # Shear deformation and rotary inertia can only lower f1.
    f_eb = modal_analysis(beam_model(g), 1).frequencies[0]
    f_t = modal_analysis(beam_model(g, timoshenko=True), 1).frequencies[0]
    assert f_t < f_eb


def test_winkler_backfill_shifts_omega_squared_by_k_over_m():
    ks = 0.05  # [kip/in³]
    g = _wall(subgrade_modulus=ks)
    _, m = _section(g)
    free = modal_analysis(beam_model(_wall(), n_height=40), 2).angular_frequencies
    backed = modal_analysis(beam_model(g, n_height=40), 2).angular_frequencies
    # EI·w'''' + k·w = m·ω²·w with uniform k = ks·L and m: same modes, ω² = ω0² + k/m.
    assert backed**2 == pytest.approx(free**2 + ks * g.length / m, rel=1e-9)


def test_pinned_base_with_backfill_is_stable_and_softer():
    fixed = modal_analysis(beam_model(_wall(subgrade_modulus=0.05)), 1)
    pinned = modal_analysis(beam_model(_wall(subgrade_modulus=0.05, base="pinned")), 1)
    assert 0 < pinned.frequencies[0] < fixed.frequencies[0]
    with pytest.raises(ValueError, match="mechanism"):
        _wall(base="pinned")


def test_flexibility_fraction_tends_to_one_and_picks_n():
    g = _wall(impact_height=60.0)
    model = beam_model(g, n_height=10)
    r = modal_analysis(model, model.free.size)  # every mode (dense path)
    # Spectral expansion K⁻¹ = Σ φφᵀ/ω² (mass-normalised): all modes give the static flexibility.
    assert flexibility_fraction(r, len(r.frequencies)) == pytest.approx(1.0, rel=1e-10)
    n = modes_for_flexibility(r, 0.99)
    assert flexibility_fraction(r, n) >= 0.99 > flexibility_fraction(r, n - 1)
    modes = impact_modes(r, n)
    # Unit impact displacement: c·ψ = 1, and k_i = ω_i²·m_i.
    assert model.impact @ modes.shapes == pytest.approx(np.ones(len(modes.mode_numbers)))
    assert modes.modal_stiffnesses == pytest.approx(
        (2 * np.pi * modes.frequencies) ** 2 * modes.modal_masses)
    # Ground coupling of the impact-normalised modes: L_i = ψ_iᵀ·M·r.
    assert modes.ground_factors == pytest.approx(modes.shapes.T @ (model.mass @ model.ground))
    # SDOF of mode 1 normalised at the impact point: M1 = ψᵀMψ.
    psi = modes.shapes[:, 0]
    assert r.M1 == pytest.approx(psi @ (model.mass @ psi), rel=1e-12)
    with pytest.raises(ValueError, match="n_modes"):
        modes_for_flexibility(modal_analysis(model, 1), 0.999999)


@pytest.mark.parametrize("changes, word", [
    (dict(height=-1.0), "height"), (dict(thickness=0.0), "thickness"),
    (dict(impact_height=150.0), "impact_height"), (dict(impact_patch=20.0), "impact_patch"),
    (dict(base="rolled"), "base"), (dict(subgrade_modulus=-1.0), "subgrade_modulus"),
])
def test_bad_geometry_names_the_parameter(changes, word):
    with pytest.raises(ValueError, match=word):
        _wall(**changes)
