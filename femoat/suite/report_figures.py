"""Which figures a suite report draws, from the per-variation data :mod:`femoat.suite.report`
gathers (the drawing itself is in :mod:`femoat.plotting.suite_figures`)."""

import numpy as np

SIDE_BY_SIDE = {"peak_impact_force": "peak impact force [kip]",
                "peak_wall_displacement": "peak wall displacement [in]",
                "peak_drift_ratio": "peak drift ratio [-]",
                "peak_floor_acceleration": "peak floor acceleration [g]"}
UNITS = {"peak_impact_force": "kip", "peak_wall_displacement": "in", "peak_drift_ratio": "-",
         "peak_floor_acceleration": "g"}


def im_label(meta):
    if meta.get("im_kind") == "pga":
        return "PGA [g]"
    return f"Sa(T = {float(meta['period']):.2f} s) [g]"


def write_figures(figs, meta, out, ida):
    """``figs`` = [(label, key, fragility curve, response table, {metric: IDA panel})];
    returns the PNG paths written into ``out``."""
    from femoat.plotting import suite_figures as sf

    smt, label_im = float(meta["smt"]), im_label(meta)
    labels = [f[0] for f in figs]
    styles = sf.variation_styles([f[1] for f in figs])
    paths = [out / "fragility.png", out / "pounding_probability.png"]
    sf.plot_fragilities([(lb, s, f[2]) for lb, s, f in zip(labels, styles, figs)], paths[0],
                        label_im, smt)
    sf.plot_pounding_probability(
        [(lb, s, f[3]["im [g]"].to_numpy(), f[3]["pounding probability [-]"].to_numpy())
         for lb, s, f in zip(labels, styles, figs) if len(f[3])], paths[1], label_im, smt)
    if ida:
        for metric, xlabel in (("peak_drift_ratio", "peak drift ratio [-]"),
                               ("peak_base_displacement", "peak isolator displacement [in]")):
            paths.append(out / f"ida_{metric}.png")
            sf.plot_ida_curves([(lb, f[4][metric]) for lb, f in zip(labels, figs)], paths[-1],
                               xlabel, label_im, smt)
    near = [_nearest(f[3], smt) for f in figs]
    if any(r is not None for r in near):
        metrics = {title: ([_get(r, f"{m} median [{UNITS[m]}]") for r in near],
                           [_get(r, f"{m} dispersion [-]") for r in near])
                   for m, title in SIDE_BY_SIDE.items()}
        paths.append(out / "responses_near_mce.png")
        sf.plot_responses_side_by_side(labels, styles, metrics, paths[-1],
                                       "median across records (bars: median·exp(±β)) at the "
                                       "intensity nearest S_MT; runs that collapsed left out")
    return paths


def _nearest(resp, smt):
    if not len(resp):
        return None
    return resp.iloc[int(np.argmin(np.abs(np.log(resp["im [g]"].to_numpy(float) / smt))))]


def _get(row, column):
    return np.nan if row is None else float(row[column])
