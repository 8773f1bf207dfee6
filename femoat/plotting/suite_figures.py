"""Figures of a record-suite report: IDA curves, collapse fragilities, pounding probability and
the responses side by side per variation (contact law × wall, or whatever the suite varied).

Plain data in (arrays and dicts from :mod:`femoat.suite.report`), one PNG out, written atomically.
"""

import math

import numpy as np
from scipy.special import ndtr

from femoat.plotting.paper_figures import _save
from femoat.plotting.style import LAW_STYLE, pyplot

_LINESTYLES = ("-", "--", ":", "-.")


def variation_styles(keys):
    """A colour and line style per variation ({varied key: value}): the law's colour when
    "walls.law" varies, a line style per value of the other keys."""
    others = [tuple(v for k, v in key.items() if k != "walls.law") for key in keys]
    order = list(dict.fromkeys(others))
    out = []
    for i, (key, other) in enumerate(zip(keys, others)):
        law = key.get("walls.law")
        color = LAW_STYLE[law]["color"] if law in LAW_STYLE else f"C{i % 10}"
        out.append(dict(color=color, linestyle=_LINESTYLES[order.index(other) % 4]))
    return out


def _grid(plt, n, width=3.2, height=2.8):
    ncols = min(n, 5)
    nrows = math.ceil(n / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(width * ncols, height * nrows),
                             constrained_layout=True, squeeze=False, sharey=True)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    return fig, axes.flat


def plot_ida_curves(panels, path, xlabel, im_label, s_mt=None):
    """IDA curves, a panel per variation: ``panels`` = [(label, [(im, edp, collapse), ...])]
    with one (im [g], edp, collapse bool) triple of arrays per record. A collapsed run is an
    'x' in a strip right of the axis, labelled "collapsed" (its EDP is meaningless and must not
    read as a value of the axis), joined to the curve by a flat line."""
    plt = pyplot()
    fig, axes = _grid(plt, len(panels))
    for ax, (label, records) in zip(axes, panels):
        alive = [e[~c] for _, e, c in records if np.any(~c)]
        top = max([np.nanmax(a) for a in alive if a.size] or [1.0])
        edge = 1.25 * top  # the "collapsed" strip
        for im, edp, collapse in records:
            order = np.argsort(im)
            im, edp, collapse = im[order], np.where(collapse[order], edge, edp[order]), \
                collapse[order]
            stop = np.argmax(collapse) + 1 if collapse.any() else im.size
            ax.plot(edp[:stop], im[:stop], color="0.4", lw=0.8, marker=".", ms=3)
            if collapse.any():  # the lowest collapse intensity (IDA: collapsed from there on)
                ax.plot(edp[stop - 1], im[stop - 1], "x", color="C3", ms=6)
        if s_mt:
            ax.axhline(s_mt, color="k", lw=0.8, ls="--")
        ax.axvline(1.12 * top, color="0.5", lw=0.8, ls=":")
        ticks = [t for t in ax.get_xticks() if 0 <= t <= 1.05 * top]
        ax.set_xticks(ticks + [edge], [f"{t:g}" for t in ticks] + ["collapsed"])
        ax.set_title(label, fontsize=9)
        ax.set_xlabel(xlabel)
        ax.set_xlim(left=0, right=1.33 * top)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel(im_label)
    _save(fig, path, plt)


def plot_fragilities(panels, path, im_label, s_mt=None):
    """Collapse fragilities, a panel per group (e.g. per wall) and a curve per variation in it:
    ``panels`` = [(title, [(label, style, d)])] with d holding ``x``, ``fraction`` (empirical
    points), ``theta`` [g], ``beta`` [-] (NaN: no fit), ``n_collapsed`` and ``n`` (counts in
    the legend) and ``ida`` (points joined as an empirical CDF; stripes: points only)."""
    plt = pyplot()
    fig, axes = _grid(plt, len(panels), width=4.6, height=3.8)
    xs = [np.max(d["x"]) for _, curves in panels for _, _, d in curves if len(d["x"])]
    top = max(xs or [1.0]) * 1.3
    grid = np.linspace(top / 400, top, 400)
    for ax, (title, curves) in zip(axes, panels):
        for label, style, d in curves:
            text = f"{label} ({d['n_collapsed']}/{d['n']})"
            if d.get("ida", True):  # the empirical CDF of the records' collapse intensities
                ax.step(d["x"], d["fraction"], where="post", color=style["color"], lw=0.6,
                        alpha=0.5)
            ax.plot(d["x"], d["fraction"], "o", color=style["color"], ms=2.5)
            if np.isfinite(d["theta"]) and np.isfinite(d["beta"]):
                p = ndtr(np.log(grid / d["theta"]) / d["beta"])
                text += f" θ = {d['theta']:.2f} g, β = {d['beta']:.2f}"
                ax.plot(grid, p, lw=1.4, label=text, color=style["color"])
            else:
                ax.plot([], [], label=text + ": no fit", color=style["color"])
        if s_mt:
            ax.axvline(s_mt, color="k", lw=0.8, ls="--", label=f"S_MT = {s_mt:.2f} g")
        ax.set_title(title, fontsize=9)
        ax.set_xlabel(im_label)
        ax.set_xlim(0, top)
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6.5, title="collapsed / records", title_fontsize=6.5)
    axes[0].set_ylabel("P(collapse)")
    _save(fig, path, plt)


WALL_TITLES = {"any": "any wall", "pos": "wall pos (+)", "neg": "wall neg (-)",
               "px": "wall +x", "mx": "wall -x", "py": "wall +y", "my": "wall -y"}


def plot_pounding_probability(panels, path, im_label, s_mt=None):
    """P(pounding) against intensity, a panel per wall: ``panels`` = [(wall key, [(labels,
    im [g], fraction pounding [-], θ [g], β [-])])], one line per distinct curve (the labels of
    the variations sharing it): the fractions as markers, the fitted lognormal onset as a line
    (none where θ is NaN)."""
    plt = pyplot()
    fig, axes = _grid(plt, len(panels), width=3.4, height=3.0)
    for ax, (wall, curves) in zip(axes, panels):
        top = max((im.max() for _, im, *_ in curves if im.size), default=1.0) * 1.1
        x = np.linspace(top / 200, top, 200)
        for i, (labels, im, p, theta, beta) in enumerate(curves):
            text = ", ".join(labels) if len(labels) <= 3 else \
                f"{len(labels)} variations: {labels[0]}, ..., {labels[-1]}"
            style = dict(color=f"C{i % 10}", linestyle=_LINESTYLES[(i // 10) % 4])
            if np.isfinite(theta) and np.isfinite(beta) and beta > 0:
                text += f" (theta {theta:.2f} g, beta {beta:.2f})"
                ax.plot(x, ndtr(np.log(x / theta) / beta), lw=1.2, **style)
            ax.plot(im, p, marker="o", ms=3, lw=0, label=text, color=style["color"])
        if s_mt:
            ax.axvline(s_mt, color="k", lw=0.8, ls="--", label=f"S_MT = {s_mt:.2f} g")
        ax.set_title(WALL_TITLES.get(wall, wall), fontsize=9)
        ax.set_xlabel(im_label)
        ax.set_xlim(0, top)
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6)
    axes[0].set_ylabel("fraction of records that pound [-]")
    _save(fig, path, plt)


def plot_responses_side_by_side(labels, styles, groups, path, title):
    """Bars of the median response per variation with the lognormal band median·exp(±β), a
    row per group of runs (e.g. with and without pounding): ``groups`` = {row title: (counts,
    {panel title: (medians, dispersions)})}, arrays over ``labels``."""
    plt = pyplot()
    n_panels = len(next(iter(groups.values()))[1])
    fig, axes = plt.subplots(len(groups), n_panels,
                             figsize=(3.4 * n_panels, 3.3 * len(groups) + 0.6),
                             constrained_layout=True, squeeze=False)
    x = np.arange(len(labels))
    for row, (group, (counts, metrics)) in zip(axes, groups.items()):
        for ax, (name, (med, beta)) in zip(row, metrics.items()):
            med, beta = np.asarray(med, float), np.nan_to_num(np.asarray(beta, float))
            err = np.vstack([med - med * np.exp(-beta), med * np.exp(beta) - med])
            ax.bar(x, np.nan_to_num(med), yerr=np.nan_to_num(err), capsize=2,
                   color=[s["color"] for s in styles], alpha=0.8)
            ticks = [f"{lb} (n={int(n) if np.isfinite(n) else 0})"
                     for lb, n in zip(labels, counts)]
            ax.set_xticks(x, ticks, rotation=60, ha="right", fontsize=7)
            ax.set_title(f"{name}\n{group}", fontsize=8)
            ax.grid(alpha=0.3, axis="y")
    fig.suptitle(title, fontsize=9)
    _save(fig, path, plt)
