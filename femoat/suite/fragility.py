"""Lognormal collapse fragility P(collapse | IM = x) = Φ(ln(x/θ)/β), fitted by maximum likelihood.

Two kinds of data (intensities IM in [g], the suite's intensity measure):

- **IDA** (:func:`fit_ida`): one collapse intensity per record (per record-variation). A record's
  collapse intensity is the *lowest* IM at which it collapsed. With hunt-and-fill tracing this is
  the upper bound of the final bracket (the lower bound is the highest IM below it that did not
  collapse); we take the upper bound, as FEMA P695 does (the collapse intensity is the intensity at
  which collapse is first observed), so Ŝ_CT is never unconservative by more than the bracket.
  Records that never collapse up to their largest IM are right-censored at that IM: they enter the
  likelihood through the survival term ln(1 − Φ(ln(c/θ)/β)), not as collapses and not dropped.
- **Multiple stripes** (:func:`fit_stripes`, Baker 2015, Earthquake Spectra 31(1) 579-599): at each
  IM level x_j, z_j of n_j runs collapse; the likelihood is binomial,
  Π_j C(n_j, z_j) p_j^z_j (1 − p_j)^(n_j − z_j), p_j = Φ(ln(x_j/θ)/β).

FEMA P695 feeds the collapse margin ratio with the *empirical* median collapse intensity Ŝ_CT of
the records (Section 6.4); the fitted θ is reported beside it. Inputs that define no fragility
(no collapse, every run collapsing, stripes that do not overlap, zero spread) raise
:class:`FragilityError` with a sentence; nothing returns NaN silently.
"""

from dataclasses import dataclass

import numpy as np
from scipy import optimize, stats


class FragilityError(ValueError):
    """The data define no lognormal fragility (the message says why)."""


@dataclass(frozen=True)
class Fragility:
    """A fitted lognormal collapse fragility with the counts behind it."""

    theta: float  # [g] fitted median collapse intensity
    beta: float  # [-] fitted lognormal dispersion
    empirical_median: float  # [g] Ŝ_CT: median of the data (NaN only with a note)
    n_records: int  # IDA: records; stripes: runs
    n_collapsed: int  # IDA: records with a collapse; stripes: collapsed runs
    n_censored: int  # IDA: records never collapsing (right-censored); stripes: 0
    method: str  # "ida" | "stripes"
    note: str = ""

    def probability(self, im):
        """P(collapse | IM = im) [-] for im [g]."""
        return stats.norm.cdf(np.log(np.asarray(im, float) / self.theta) / self.beta)


def _positive(name, x):
    x = np.asarray(x, float)
    if x.ndim != 1 or x.size == 0 or not np.all(np.isfinite(x)) or np.any(x <= 0):
        raise FragilityError(f"{name} must be a non-empty 1-D array of positive finite IM [g]")
    return x


def ida_negloglik(params, ln_x, ln_c):
    """Negative log-likelihood of (ln θ, ln β): collapses at ln_x, right-censored at ln_c."""
    mu, beta = params[0], np.exp(params[1])
    ll = stats.norm.logpdf((ln_x - mu) / beta).sum() - ln_x.size * np.log(beta)
    return -(ll + stats.norm.logsf((ln_c - mu) / beta).sum())


def fit_ida(collapse_im, censored_im=()):
    """Fit θ, β to IDA collapse intensities ``collapse_im`` [g] and censoring IMs [g].

    Without censoring the MLE is closed form: ln θ = mean(ln x), β = sqrt(mean((ln x − ln θ)²))
    (the 1/n MLE, not the 1/(n−1) sample deviation). With censoring it is found numerically.
    """
    x = _positive("collapse_im", collapse_im)
    c = np.asarray(censored_im, float)
    if c.size:
        c = _positive("censored_im", c)
    ln_x, ln_c = np.log(x), np.log(c)
    if np.ptp(ln_x) == 0.0:
        raise FragilityError(f"all {x.size} collapse intensities equal {x[0]:.4g} g: β = 0")
    mu, beta = ln_x.mean(), ln_x.std()
    notes = []
    if c.size:
        res = optimize.minimize(ida_negloglik, [mu, np.log(beta)], args=(ln_x, ln_c),
                                method="BFGS", options=dict(gtol=1e-10))
        if not np.all(np.isfinite(res.x)) or res.x[1] > np.log(50.0):
            raise FragilityError("the censored IDA likelihood has no finite maximum")
        mu, beta = res.x[0], float(np.exp(res.x[1]))
        notes.append(f"{c.size} record(s) never collapsed: right-censored at their largest IM")
    med = ida_empirical_median(x, c)
    if not np.isfinite(med):
        notes.append("empirical median undefined: half or more of the records never collapsed")
    return Fragility(float(np.exp(mu)), float(beta), med, x.size + c.size, x.size, c.size, "ida",
                     "; ".join(notes))


def ida_empirical_median(x, c):
    """Median [g] of collapse intensities ``x`` with the censored records ``c`` counted above
    every collapse; NaN when it falls on a censored record (half or more never collapsed)."""
    x, c = np.asarray(x, float), np.asarray(c, float)
    if x.size + c.size == 0:
        return float("nan")
    v = np.sort(np.concatenate([x, np.full(c.size, np.inf)]))
    med = float(np.median(v))
    return med if np.isfinite(med) else float("nan")


def stripes_negloglik(params, ln_im, n, z):
    """Negative binomial log-likelihood of (ln θ, ln β) over stripes (constant term dropped)."""
    u = (ln_im - params[0]) / np.exp(params[1])
    return -(z * stats.norm.logcdf(u) + (n - z) * stats.norm.logsf(u)).sum()


def fit_stripes(im, n_runs, n_collapsed):
    """Fit θ, β to multiple-stripe counts: ``n_collapsed[j]`` of ``n_runs[j]`` at ``im[j]`` [g]."""
    x = _positive("im", im)
    n = np.asarray(n_runs, float)
    z = np.asarray(n_collapsed, float)
    if n.shape != x.shape or z.shape != x.shape or np.any(n < 1) or np.any((z < 0) | (z > n)):
        raise FragilityError("need 1 <= n_runs and 0 <= n_collapsed <= n_runs at every stripe")
    if z.sum() == 0:
        raise FragilityError(f"no collapse in {int(n.sum())} runs up to {x.max():.4g} g")
    if z.sum() == n.sum():
        raise FragilityError(f"every run collapsed, down to the lowest stripe {x.min():.4g} g")
    # (quasi-)separation: no stripe with a survivor lies above a stripe with a collapse (a single
    # stripe, or one partial stripe between all-survive and all-collapse ones): the likelihood
    # grows as β → 0 and no finite MLE exists
    top_alive, low_dead = x[z < n].max(), x[z > 0].min()
    if top_alive <= low_dead:
        raise FragilityError(f"the stripes do not overlap (no run survives above {low_dead:.4g} g "
                             f"and none collapses below {top_alive:.4g} g): β → 0 and θ is not "
                             "identified; add stripes where some but not all runs collapse")
    ln_x = np.log(x)
    frac = np.clip(z / n, 0.05, 0.95)  # start: least-squares probit line through the fractions
    slope, icpt = np.polyfit(ln_x, stats.norm.ppf(frac), 1, w=np.sqrt(n))
    start = [-icpt / slope, -np.log(slope)] if slope > 0 else [np.median(ln_x), np.log(0.5)]
    res = optimize.minimize(stripes_negloglik, start, args=(ln_x, n, z), method="BFGS",
                            options=dict(gtol=1e-10))
    if not np.all(np.isfinite(res.x)) or res.x[1] > np.log(50.0):
        raise FragilityError("the stripe likelihood has no finite maximum")
    theta, beta = float(np.exp(res.x[0])), float(np.exp(res.x[1]))
    med = stripe_empirical_median(x, n, z)
    note = "" if np.isfinite(med) else "empirical median undefined: no stripe reaches 50 %"
    return Fragility(theta, beta, med, int(n.sum()), int(z.sum()), 0, "stripes", note)


def stripe_empirical_median(x, n, z):
    """IM [g] where the empirical collapse fraction first reaches 0.5 (linear in ln IM between
    stripes); NaN when it never does."""
    x, n, z = (np.asarray(a, float) for a in (x, n, z))
    order = np.argsort(x)
    x, f = x[order], (z / n)[order]
    k = np.flatnonzero(f >= 0.5)
    if k.size == 0:
        return float("nan")
    k = k[0]
    if k == 0 or f[k] == f[k - 1]:
        return float(x[k])
    w = (0.5 - f[k - 1]) / (f[k] - f[k - 1])
    return float(np.exp(np.log(x[k - 1]) + w * (np.log(x[k]) - np.log(x[k - 1]))))
