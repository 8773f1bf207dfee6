"""ASCE 7-16 Chapter 17's MCE displacement from a bearing's own hysteresis
(femoat.structure.isolation_design), against the single friction pendulum's closed forms."""

import math

import pytest
from scipy.optimize import brentq

from femoat.bearings.friction_pendulum import FrictionPendulum
from femoat.bearings.lead_rubber import LeadRubberBearing
from femoat.structure.isolation_design import (
    damping_coefficient,
    effective_properties,
    match_displacement,
    mce_displacement,
)
from femoat.units import G

FP = FrictionPendulum(W=33.0, R=30.0, u_y=0.01, mu=0.06)


def _fp_closed_form(d):
    # elastic-perfectly-plastic friction beside W/R: the tip force W/R·D + μW, the loop a
    # parallelogram of height 2μW and width 2(D − u_y): E = 4μW(D − u_y)
    w, r, mu, uy = FP.W, FP.R, FP.mu, FP.u_y
    k = w / r + mu * w / d
    return k, 4 * mu * w * (d - uy) / (2 * math.pi * k * d * d)


@pytest.mark.parametrize("beta, expected", [(0.0, 0.8), (0.02, 0.8), (0.05, 1.0), (0.15, 1.35),
                                            (0.35, 1.8), (0.5, 2.0), (0.9, 2.0)])
def test_the_damping_coefficient_is_asce_table_17_5_1(beta, expected):
    # Table 17.5-1's rows, linear between them (15 %: halfway 1.2-1.5; 35 %: halfway 1.7-1.9)
    assert damping_coefficient(beta) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("d", [0.5, 2.0, 4.7])
def test_effective_properties_of_the_friction_pendulum_are_its_closed_forms(d):
    k, beta = effective_properties(FP, d)
    k_ref, beta_ref = _fp_closed_form(d)
    assert k == pytest.approx(k_ref, rel=1e-12)  # the tip of the loop is exact
    # the trapezoidal loop cuts each reversal's corner within one increment 4D/2000: 1e-4
    assert beta == pytest.approx(beta_ref, rel=1e-4)


def test_the_mce_displacement_is_the_fixed_point_of_eq_17_5_1():
    # with the closed forms: D = g·S_M1·T(D)/(4π²·B(β(D))), T = 2π·sqrt(W/(k(D)·g)); S_M1 =
    # 0.45 g·s (SDC Dmax's 0.9 at time scale 0.5)
    def excess(d):
        k, beta = _fp_closed_form(d)
        t = 2 * math.pi * math.sqrt(FP.W / (k * G))
        return G * 0.45 * t / (4 * math.pi ** 2 * damping_coefficient(beta)) - d

    d_ref = brentq(excess, 0.1, 50.0, xtol=1e-12)
    # (β within 1.2e-4 of its 0.181, B_M = 1.2 + 3·(β − 0.1) there: B_M within 5e-5, and
    # D ∝ 1/B_M: D within 1e-4)
    d, t, beta = mce_displacement(FP, 33.0, 0.45)
    assert d == pytest.approx(d_ref, rel=1e-4)
    k_ref, beta_ref = _fp_closed_form(d_ref)
    assert t == pytest.approx(2 * math.pi * math.sqrt(33.0 / (k_ref * G)), rel=1e-4)
    assert beta == pytest.approx(beta_ref, rel=2e-4)


def test_a_bearing_is_tuned_to_a_target_displacement():
    target = mce_displacement(FP, 33.0, 0.45)[0]
    lrb, kd = match_displacement(lambda x: LeadRubberBearing(Q_d=1.98, K_d=x, K_u=10 * x),
                                 target, 33.0, 0.45, (0.2, 2.0))
    assert lrb.K_d == kd and mce_displacement(lrb, 33.0, 0.45)[0] == pytest.approx(target,
                                                                                  rel=1e-8)


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="amplitude"):
        effective_properties(FP, -1.0)
    with pytest.raises(ValueError, match="not a registered bearing"):
        effective_properties(object(), 1.0)
    with pytest.raises(ValueError, match="no MCE displacement"):
        mce_displacement(FP, 33.0, 0.45, bracket=(0.1, 0.2))
