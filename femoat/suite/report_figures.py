"""Which figures a suite report draws, from the per-variation data :mod:`femoat.suite.report`
gathers (the drawing itself is in :mod:`femoat.plotting.suite_figures`)."""

from typing import NamedTuple

import numpy as np

SIDE_BY_SIDE = {"peak_impact_force": "peak impact force [kip]",
                "peak_wall_displacement": "peak wall displacement [in]",
                "peak_drift_ratio": "peak drift ratio [-]",
                "peak_floor_acceleration": "peak floor acceleration [g]"}
UNITS = {"peak_impact_force": "kip", "peak_wall_displacement": "in", "peak_drift_ratio": "-",
         "peak_floor_acceleration": "g"}


class VariationFigures(NamedTuple):
    """What the figures draw of one variation."""

    label: str  # e.g. "E / concrete"
    key: dict  # {varied key: value}
    curve: dict  # fragility: empirical points and the fitted lognormal (margin.collapse_row)
    responses: object  # its response_by_variation.csv rows (a DataFrame)
    ida_panels: dict  # {metric: [(im [g], value, collapsed) per record]}
    near_mce: list  # responses near S_MT, split by pounding (report.near_mce_by_pounding)
    pounding: object  # its pounding_probability.csv rows (femoat.suite.pounding)
    onset: object  # its pounding_fragility.csv rows (θ [g], β [-] per wall)


def im_label(meta):
    if meta.get("im_kind") == "pga":
        return "PGA [g]"
    return f"Sa(T = {float(meta['period']):.2f} s) [g]"


def panel_of(key):
    """The fragility panel of a variation ({varied key: value}): every key but the law."""
    return " / ".join(str(v) for k, v in key.items() if k != "walls.law") or "all"


def curve_label(label, key):
    """A variation's label inside its panel: the law when the law varies."""
    return str(key["walls.law"]) if "walls.law" in key and len(key) > 1 else label


def distinct_curves(curves):
    """[(labels, im, p, *fit)]: the pounding curves (label, im [g], p [-], *fit: the fitted
    θ [g], β [-] or nothing) that coincide to 1e-9, merged, in first-seen order."""
    out = []
    for label, im, p, *fit in curves:
        for labels, im0, p0, *fit0 in out:
            if im.shape == im0.shape and np.allclose(im, im0, rtol=1e-9, atol=0) \
                    and np.allclose(p, p0, rtol=0, atol=1e-9) \
                    and np.allclose(fit, fit0, rtol=1e-9, atol=0, equal_nan=True):
                labels.append(label)
                break
        else:
            out.append(([label], im, p, *fit))
    return out


def pounding_panels(figs):
    """[(wall, distinct curves)]: a panel per wall ("any" first), in each the variations'
    fractions pounding and fitted onset (θ [g], β [-])."""
    walls = list(dict.fromkeys(w for f in figs for w in f.pounding["wall"]))
    out = []
    for w in walls:
        curves = []
        for f in figs:
            p = f.pounding[f.pounding["wall"] == w]
            o = f.onset[f.onset["wall"] == w].iloc[0]
            curves.append((f.label, p["im [g]"].to_numpy(float),
                           p["P(pounding) [-]"].to_numpy(float),
                           float(o["theta fitted [g]"]), float(o["beta fitted [-]"])))
        out.append((w, distinct_curves(curves)))
    return out


def write_figures(figs, meta, out, ida, smt):
    """``figs`` a :class:`VariationFigures` per variation; ``smt`` [g] or None. Returns the PNG
    paths written."""
    from femoat.plotting import suite_figures as sf

    label_im = im_label(meta)
    labels = [f.label for f in figs]
    styles = sf.variation_styles([f.key for f in figs])
    paths = [out / "fragility.png", out / "pounding_probability.png"]
    panels = {}
    for f, s in zip(figs, styles):
        panels.setdefault(panel_of(f.key), []).append((curve_label(f.label, f.key), s, f.curve))
    sf.plot_fragilities(list(panels.items()), paths[0], label_im, smt)
    sf.plot_pounding_probability(pounding_panels(figs), paths[1], label_im, smt)
    if ida:
        for metric, xlabel in (("peak_drift_ratio", "peak drift ratio [-]"),
                               ("peak_base_displacement", "peak isolator displacement [in]")):
            paths.append(out / f"ida_{metric}.png")
            sf.plot_ida_curves([(f.label, f.ida_panels[metric]) for f in figs], paths[-1],
                               xlabel, label_im, smt)
    if any(f.near_mce for f in figs):
        groups = {}
        for name, title in (("yes", "runs that pounded"), ("no", "runs without pounding")):
            rows = [next((r for r in f.near_mce if r["pounding"] == name), None) for f in figs]
            groups[title] = ([_get(r, "n_not_collapsed") for r in rows],
                             {t: ([_get(r, f"{m} median [{UNITS[m]}]") for r in rows],
                                  [_get(r, f"{m} dispersion [-]") for r in rows])
                              for m, t in SIDE_BY_SIDE.items()})
        at = next(r["im [g]"] for f in figs for r in f.near_mce)
        paths.append(out / "responses_near_mce.png")
        sf.plot_responses_side_by_side(
            labels, styles, groups, paths[-1],
            f"median across records at {at:.3g} g ({'nearest S_MT' if smt else 'median IM'}); "
            "bars median·exp(±β); runs that collapsed left out; n runs per bar")
    return paths


def _get(row, column):
    return np.nan if row is None else float(row[column])
