"""Lognormal collapse fragilities: IDA (with right-censoring) and multiple-stripe MLE."""

import numpy as np
import pytest
from scipy import optimize, stats

from femoat.suite.fragility import (FragilityError, fit_ida, fit_stripes, ida_negloglik,
                                    stripes_negloglik)

THETA, BETA = 1.2, 0.4  # [g], [-]


def _nelder_mead(nll, start, args):
    """An independent minimiser of the same negative log-likelihood, to tight tolerances."""
    res = optimize.minimize(nll, start, args=args, method="Nelder-Mead",
                            options=dict(xatol=1e-11, fatol=1e-13, maxiter=20000))
    return np.exp(res.x[0]), np.exp(res.x[1])


def test_ida_recovers_a_known_lognormal_within_its_sampling_error():
    n = 2000
    x = THETA * np.exp(BETA * np.random.default_rng(1).standard_normal(n))
    f = fit_ida(x)
    # MLE standard errors of a normal sample in ln x (Fisher information):
    # se(ln θ) = β/√n = 0.4/√2000 = 0.0089, se(β) = β/√(2n) = 0.0063; allow 4 se.
    assert abs(np.log(f.theta / THETA)) < 4 * BETA / np.sqrt(n)
    assert abs(f.beta - BETA) < 4 * BETA / np.sqrt(2 * n)
    # the empirical median of a lognormal sample has se ≈ 1.2533 β/√n in ln x
    assert abs(np.log(f.empirical_median / THETA)) < 4 * 1.2533 * BETA / np.sqrt(n)
    assert (f.n_records, f.n_collapsed, f.n_censored, f.method) == (n, n, 0, "ida")


def test_ida_closed_form_equals_a_numerical_maximum_of_the_likelihood():
    x = THETA * np.exp(BETA * np.random.default_rng(2).standard_normal(30))
    f = fit_ida(x)
    ln_x = np.log(x)
    theta, beta = _nelder_mead(ida_negloglik, [0.0, np.log(0.8)], (ln_x, np.array([])))
    assert abs(f.theta / theta - 1) < 1e-6 and abs(f.beta - beta) < 1e-6


def test_ida_right_censoring_uses_the_survival_term():
    n, cap = 2000, THETA * np.exp(0.5 * BETA)  # cap: Φ(0.5) = 69 % collapse below it
    x = THETA * np.exp(BETA * np.random.default_rng(3).standard_normal(n))
    collapsed, censored = x[x <= cap], np.full(np.sum(x > cap), cap)
    f = fit_ida(collapsed, censored)
    nc = collapsed.size
    # censored records still carry information, so β/√n_collapsed bounds se(ln θ) and
    # √2 times se(β) of an uncensored sample of n_collapsed; allow 4 of it for both
    assert abs(np.log(f.theta / THETA)) < 4 * BETA / np.sqrt(nc)
    assert abs(f.beta - BETA) < 4 * BETA / np.sqrt(nc)
    assert (f.n_records, f.n_collapsed, f.n_censored) == (n, nc, n - nc)
    assert "censored" in f.note
    # the same optimum as an independent minimiser of the same likelihood
    theta, beta = _nelder_mead(ida_negloglik, [0.5, np.log(0.3)],
                               (np.log(collapsed), np.log(censored)))
    assert abs(f.theta / theta - 1) < 1e-6 and abs(f.beta - beta) < 1e-6
    # dropping the censored records instead would bias θ low by far more than its error
    assert np.log(THETA / fit_ida(collapsed).theta) > 10 * BETA / np.sqrt(nc)
    # the empirical median counts censored records above every collapse: still the sample median
    assert f.empirical_median == pytest.approx(np.median(x))


def test_ida_median_undefined_when_most_records_never_collapse():
    f = fit_ida([1.0, 1.5], [2.0, 2.0, 2.0])
    assert np.isnan(f.empirical_median) and "undefined" in f.note
    assert np.isfinite(f.theta) and np.isfinite(f.beta)


def test_ida_degenerate_inputs_raise_with_a_sentence():
    with pytest.raises(FragilityError, match="non-empty"):
        fit_ida([], [2.0, 2.0])  # no record collapsed
    with pytest.raises(FragilityError, match="β = 0"):
        fit_ida([0.8, 0.8, 0.8])
    with pytest.raises(FragilityError, match="positive"):
        fit_ida([0.8, -1.0])


def test_stripes_with_expected_counts_return_the_generating_fragility():
    # With z_j = n_j Φ(ln(x_j/θ)/β) exactly, the binomial score vanishes at (θ, β): the MLE is
    # the generating fragility itself.
    im = np.array([0.4, 0.6, 0.8, 1.0, 1.2, 1.6, 2.0, 2.5])
    n = np.full(im.size, 44.0)
    z = n * stats.norm.cdf(np.log(im / THETA) / BETA)
    f = fit_stripes(im, n, z)
    assert abs(f.theta / THETA - 1) < 1e-6 and abs(f.beta - BETA) < 1e-6
    assert (f.n_records, f.method) == (int(n.sum()), "stripes")


def test_stripes_agree_with_scipy_minimize_on_the_same_likelihood():
    im = np.array([0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 1.8, 2.0])
    n = np.full(im.size, 40)
    z = np.random.default_rng(4).binomial(n, stats.norm.cdf(np.log(im / THETA) / BETA))
    f = fit_stripes(im, n, z)
    theta, beta = _nelder_mead(stripes_negloglik, [np.log(2.0), np.log(0.8)], (np.log(im), n, z))
    assert abs(f.theta / theta - 1) < 1e-6 and abs(f.beta - beta) < 1e-6
    assert f.n_collapsed == z.sum() and f.n_records == n.sum()


def test_stripes_empirical_median_interpolates_the_fraction_in_ln_im():
    # fractions 0.25 at 1 g and 0.75 at 4 g: 0.5 is halfway in ln IM, at √(1·4) = 2 g
    f = fit_stripes([1.0, 4.0], [4, 4], [1, 3])
    assert f.empirical_median == pytest.approx(2.0)
    # symmetric data about 2 g in ln IM: the fitted median is also 2 g
    assert f.theta == pytest.approx(2.0, rel=1e-6)


@pytest.mark.parametrize("z, match", [([10, 10, 10], "every run collapsed"),
                                      ([0, 0, 0], "no collapse"),
                                      ([0, 10, 10], "do not overlap"),
                                      ([0, 3, 10], "do not overlap")])
def test_stripes_degenerate_inputs_raise_with_a_sentence(z, match):
    # [0, 3, 10]: one partial stripe between all-survive and all-collapse ones. Along
    # ln θ = −β Φ⁻¹(0.3) the 1 g stripe keeps p = 0.3 while, as β → 0, p → 0 at 0.5 g and p → 1
    # at 1.5 g: the likelihood rises towards its supremum without reaching it (quasi-separation)
    with pytest.raises(FragilityError, match=match):
        fit_stripes([0.5, 1.0, 1.5], [10, 10, 10], z)


def test_a_single_stripe_does_not_fix_two_parameters():
    # Φ(ln(x/θ)/β) = 3/10 holds along a whole line of (θ, β)
    with pytest.raises(FragilityError, match="do not overlap"):
        fit_stripes([1.0], [10], [3])


def test_probability_is_the_lognormal_cdf():
    f = fit_ida([0.5, 1.0, 2.0])
    # θ = (0.5·1·2)^(1/3) = 1 g, so P(1 g) = Φ(0) = 0.5
    assert f.theta == pytest.approx(1.0) and f.probability(1.0) == pytest.approx(0.5)
