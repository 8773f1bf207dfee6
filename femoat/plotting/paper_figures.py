"""Paper Figs. 4-7 and the global response, from the runs of the paper study.

``runs`` is a dict {(wall, law): RunResult}; every figure has a panel per wall with the five
laws overlaid (docs/paper.md §1).
"""

import numpy as np

from femoat.atomic import atomic_path
from femoat.plotting.style import LAW_STYLE, pyplot


def _walls_laws(runs):
    walls = list(dict.fromkeys(w for w, _ in runs))
    laws = list(dict.fromkeys(k for _, k in runs))
    return walls, laws


def _save(fig, path, plt):
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=130)
    plt.close(fig)


def plot_ground_motion(motion, path, spectrum=None):
    """Fig. 4: the ground acceleration [g] (and its 5 % pseudo-acceleration spectrum)."""
    plt = pyplot()
    ncols = 2 if spectrum is not None else 1
    fig, axes = plt.subplots(1, ncols, figsize=(5.5 * ncols, 3.6), constrained_layout=True,
                             squeeze=False)
    ax = axes[0, 0]
    ax.plot(motion.time, motion.accel_g, lw=0.7, color="k")
    k = int(np.argmax(np.abs(motion.accel_g)))
    ax.plot(motion.time[k], motion.accel_g[k], "ro", ms=4)
    ax.annotate(f"PGA = {abs(motion.accel_g[k]):.2f} g", (motion.time[k], motion.accel_g[k]),
                xytext=(8, 0), textcoords="offset points", fontsize=8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("ground acceleration [g]")
    ax.set_title(motion.name or "ground motion")
    ax.grid(alpha=0.3)
    if spectrum is not None:
        periods, psa = spectrum
        ax2 = axes[0, 1]
        ax2.plot(periods, psa, color="k")
        ax2.set_xlabel("period [s]")
        ax2.set_ylabel("PSA [g] (5 % damping)")
        ax2.set_title("response spectrum")
        ax2.grid(alpha=0.3)
    _save(fig, path, plt)


def _largest_impact(runs, wall, laws):
    best = None
    for law in laws:
        for row in runs[(wall, law)].impacts:
            if best is None or row["peak_force"] > best["peak_force"]:
                best = row
    return best


def plot_impact_forces(runs, path):
    """Fig. 5: impact force histories, a column per wall; top full record (pos side up, neg
    side down), bottom zoomed on the largest impact."""
    plt = pyplot()
    walls, laws = _walls_laws(runs)
    fig, axes = plt.subplots(2, len(walls), figsize=(6 * len(walls), 6.5),
                             constrained_layout=True, squeeze=False)
    for col, wall in enumerate(walls):
        top, zoom = axes[0, col], axes[1, col]
        big = _largest_impact(runs, wall, laws)
        for law in laws:
            r = runs[(wall, law)]
            sign = np.array([1.0 if n == "pos" else -1.0 for n in r.meta["contact_names"]])
            f = (r.contact_force * sign[None, :]).sum(axis=1)
            top.plot(r.time, f, lw=1.0, **LAW_STYLE[law])
            zoom.plot(r.time, f, lw=1.4, **LAW_STYLE[law])
        top.set_title(f"{wall} wall: impact force (+ pos side, − neg side)")
        top.set_xlabel("time [s]")
        top.set_ylabel("impact force [kip]")
        if big is not None:
            s = 1.0 if big["side"] == "pos" else -1.0
            t0, dur = big["start"], max(big["duration"], 1e-3)
            zoom.set_xlim(t0 - 0.1 * dur, t0 + 1.3 * dur)
            zoom.set_ylim(*sorted((0.0, 1.1 * s * big["peak_force"])))
            zoom.set_title(f"zoom: largest impact ({big['side']} side, t = {t0:.3f} s)")
        zoom.set_xlabel("time [s]")
        zoom.set_ylabel("impact force [kip]")
        for ax in (top, zoom):
            ax.grid(alpha=0.3)
        top.legend(fontsize=7, loc="upper right")
    _save(fig, path, plt)


def _loops_per_wall(runs, path, curves, title, xlabel, ylabel, clip_origin):
    """A panel per wall with, for every law, the (x, y) loops ``curves(run)`` returns per side."""
    plt = pyplot()
    walls, laws = _walls_laws(runs)
    fig, axes = plt.subplots(1, len(walls), figsize=(6 * len(walls), 4.2),
                             constrained_layout=True, squeeze=False)
    for col, wall in enumerate(walls):
        ax = axes[0, col]
        for law in laws:
            for c, (x, y) in enumerate(curves(runs[(wall, law)])):
                kw = dict(LAW_STYLE[law])
                if c > 0:
                    kw.pop("label")
                ax.plot(x, y, lw=1.1, **kw)
        ax.set_title(f"{wall} wall: {title}")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        if clip_origin:
            ax.set_xlim(left=0)
            ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    _save(fig, path, plt)


def plot_contact_hysteresis(runs, path):
    """Fig. 6: contact-spring force vs indentation during the impacts, a panel per wall."""

    def curves(r):
        return [(np.where(r.indentation[:, c] > 0, r.indentation[:, c], np.nan),
                 r.contact_force[:, c]) for c in range(r.contact_force.shape[1])]

    _loops_per_wall(runs, path, curves, "contact spring", "indentation [in]",
                    "contact force [kip]", clip_origin=True)


def plot_wall_hysteresis(runs, path):
    """Fig. 7: wall (vibrational) spring-dashpot force vs wall displacement, a panel per wall."""

    def curves(r):
        wd, wf = r.wall_displacement(), r.wall_force()
        return [(wd[:, c], wf[:, c]) for c in range(wd.shape[1])]

    _loops_per_wall(runs, path, curves, "wall spring + dashpot",
                    "wall displacement at impact point, away from building [in]",
                    "wall force K1·w + C·ẇ [kip]", clip_origin=False)


def plot_global_response(runs, path):
    """Base displacement histories, peak drift and peak absolute floor acceleration profiles."""
    plt = pyplot()
    walls, laws = _walls_laws(runs)
    fig, axes = plt.subplots(len(walls), 3, figsize=(15, 3.8 * len(walls)),
                             constrained_layout=True, squeeze=False,
                             gridspec_kw=dict(width_ratios=[2.2, 1, 1]))
    for row, wall in enumerate(walls):
        a0, a1, a2 = axes[row]
        for law in laws:
            r = runs[(wall, law)]
            st = LAW_STYLE[law]
            a0.plot(r.time, r.base_displacement, lw=0.9, **st)
            acc = [r.peaks["peak_base_acceleration"]] + r.peaks["peak_floor_acceleration"]
            a2.plot(acc, np.arange(len(acc)), marker="o", **st)
        a2.set_yticks(np.arange(len(acc)))  # levels are whole numbers
        drift_panel(a1, {law: runs[(wall, law)].peaks for law in laws})
        for g in r.meta["gaps"]:
            a0.axhline(g, color="0.5", lw=0.8)
            a0.axhline(-g, color="0.5", lw=0.8)
        a0.set_title(f"{wall} wall: base displacement (gap lines grey)")
        a0.set_xlabel("time [s]")
        a0.set_ylabel("base displacement [in]")
        a2.set_title("peak absolute acceleration")
        a2.set_xlabel("acceleration [g]")
        a2.set_ylabel("level (0 = base mat)")
        a2.set_xscale("log")
        _plain_log_ticks(a2.xaxis)
        for ax in (a0, a1, a2):
            ax.grid(alpha=0.3)
        a0.legend(fontsize=7, loc="lower right")
    _save(fig, path, plt)


def _plain_log_ticks(axis):
    """One set of labels on a logarithmic axis: ticks at 1, 2, 5 x 10^k written as plain
    numbers, the minor ticks unlabelled (matplotlib otherwise labels both on a short range)."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


def drift_panel(ax, peaks_by_law):
    """Peak interstory drift per story on ``ax``: drift [in] on the x axis, stories as whole
    numbers on the y axis, and the drift ratio [%] on a second x axis (top) when the peaks carry
    ``peak_drift_ratio`` (story heights known): a scale on the same curves when every story has
    the same height, else the ratios drawn as their own dashed curves with open markers.
    Returns the ratio axis (None without ratios)."""
    n = 0
    for law, peaks in peaks_by_law.items():
        drift = peaks["peak_drift"]
        n = max(n, len(drift))
        ax.plot(drift, np.arange(1, len(drift) + 1), marker="o", **LAW_STYLE[law])
    ax.set_yticks(np.arange(1, n + 1))
    ax.set_title("peak interstory drift")
    ax.set_xlabel("drift [in]")
    ax.set_ylabel("story")
    ratios = {law: p.get("peak_drift_ratio") for law, p in peaks_by_law.items()}
    if not ratios or any(r is None for r in ratios.values()):
        return None
    heights = [d / r for law, p in peaks_by_law.items()
               for d, r in zip(p["peak_drift"], ratios[law]) if r > 0]  # story heights [in]
    if heights and np.ptp(heights) <= 1e-9 * max(heights):
        h = heights[0]  # one height: ratio = drift / h is a second scale on the same curves
        top = ax.secondary_xaxis("top", functions=(lambda d: 100.0 * d / h,
                                                   lambda pct: pct * h / 100.0))
        assumed = " (the default story height, an assumption)" if abs(h - 39.0) < 1e-9 else ""
        top.set_xlabel(f"drift ratio [%] = drift / {h:g} in{assumed}", fontsize=8)
        return top
    top = ax.twiny()  # stories of different heights: the ratios are curves of their own
    for law, ratio in ratios.items():
        top.plot(100.0 * np.asarray(ratio), np.arange(1, len(ratio) + 1), ls="--",
                 marker="o", mfc="none", **{k: v for k, v in LAW_STYLE[law].items()
                                             if k not in ("ls", "linestyle", "marker")})
    top.set_xlabel("drift ratio [%] (dashed, open markers)")
    ax.set_yticks(np.arange(1, n + 1))
    return top
