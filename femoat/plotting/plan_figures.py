"""Figures of a plan run (issue 18): the base mat's orbit inside the moat, impact force per wall.

Plain data in (a :class:`~femoat.plotting.plan_history.PlanHistory`), one PNG out, written
atomically; each function returns its (closed) matplotlib Figure, whose artists can be read.

The orbit is drawn in displacement space: the base mat is the point u = (x, y) [in] (its
displacement relative to the ground, at rest at the origin), and the moat outline is where that
point meets a wall: the +x wall is the line x = gap(+x), the −x wall x = −gap(−x), and so on, so
the outline's corners are (±gap, ±gap). A point beyond a wall's line is an indentation into it.
Drawing the mat as a point keeps the picture true to scale whatever the mat's size (the mat's
footprint moves with the same u; the top-view render, :mod:`femoat.render.plan`, draws it).
"""

import numpy as np

from femoat.plotting.paper_figures import _save
from femoat.plotting.plan_history import WALL_COLORS, check_history
from femoat.plotting.style import pyplot


def _peak(force):
    """The largest force [kip], 0 without contact (never -0.0, which a twin's negated zero
    would print)."""
    return float(np.max(force, initial=0.0)) + 0.0


def _count(n):
    return f"{n} impact" if n == 1 else f"{n} impacts"


def wall_segment(history, side):
    """The two ends [in] of wall ``side``'s line in the orbit plot: ((x0, y0), (x1, y1))."""
    r = history.reach()
    if side in ("+x", "-x"):
        x = r["+x"] if side == "+x" else -r["-x"]
        return (x, -r["-y"]), (x, r["+y"])
    y = r["+y"] if side == "+y" else -r["-y"]
    return (-r["-x"], y), (r["+x"], y)


def plot_plan_orbit(history, path):
    """The base mat's plan orbit inside the moat outline, impacts marked.

    One line per wall at its gap (the wall's colour, ``gid`` "wall +x", ...); the orbit as a grey
    line (``gid`` "orbit"); at every sample where a wall's force is > 0 a marker at the base
    mat's position, in that wall's colour (``gid`` "impacts +x", ...; a corner sample touching two
    walls has a marker for each); the largest plan displacement as a black dot. Equal axes, [in].
    """
    h = check_history(history)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.2, 6.0), constrained_layout=True)
    x, y = h.base[:, 0], h.base[:, 1]
    ax.plot(x, y, color="0.55", lw=0.8, gid="orbit", label="base mat orbit")
    contact = h.contact
    impacts = h.impacts()
    for c, side in enumerate(h.sides):
        (x0, y0), (x1, y1) = wall_segment(h, side)
        color = WALL_COLORS[side]
        ax.plot([x0, x1], [y0, y1], color=color, lw=2.5, solid_capstyle="butt",
                gid=f"wall {side}")
        hit = contact[:, c]
        ax.plot(x[hit], y[hit], linestyle="none", marker="o", ms=3.5, color=color,
                gid=f"impacts {side}",
                label=f"{side} wall: gap {h.gaps[c]:g} in, {_count(impacts[c])}, "
                      f"peak {_peak(h.wall_force[:, c]):.0f} kip")
    k = int(np.argmax(np.hypot(x, y)))
    ax.plot(x[k], y[k], "ko", ms=5, gid="peak",
            label=f"largest |u| = {h.peak_plan_displacement():.2f} in")
    ax.plot(0.0, 0.0, "k+", ms=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("base mat displacement x [in]")
    ax.set_ylabel("base mat displacement y [in]")
    ax.set_title(h.title or "base mat orbit in the moat")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=1, frameon=False)
    _save(fig, path, plt)
    return fig


def plot_plan_impact_forces(history, path):
    """Impact force [kip] against time [s], one panel per wall (its colour), sharing the time
    axis; each panel's title gives the wall's impact count and peak force."""
    h = check_history(history)
    plt = pyplot()
    n = max(len(h.sides), 1)
    fig, axes = plt.subplots(n, 1, figsize=(7.5, 1.9 * n + 0.6), sharex=True,
                             constrained_layout=True, squeeze=False)
    impacts = h.impacts()
    for c, side in enumerate(h.sides):
        ax = axes[c, 0]
        f = h.wall_force[:, c]
        ax.plot(h.time, f, color=WALL_COLORS[side], lw=0.9, gid=f"force {side}")
        ax.set_title(f"{side} wall (gap {h.gaps[c]:g} in): {_count(impacts[c])}, peak "
                     f"{_peak(f):.1f} kip", fontsize=9)
        ax.set_ylabel("impact force [kip]")
        ax.set_ylim(bottom=0.0, top=max(1.1 * _peak(f), 1.0))
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    axes[-1, 0].set_xlim(h.time[0], h.time[-1])
    if h.title:
        fig.suptitle(h.title, fontsize=10)
    _save(fig, path, plt)
    return fig
