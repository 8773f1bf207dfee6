"""The plain arrays a plan-view figure or render needs: :class:`PlanHistory`.

The figures (:mod:`femoat.plotting.plan_figures`) and the top-view animation
(:mod:`femoat.render.plan`) read only this object, so that any plan run can feed them: the
OpenSees twin in 3D (:meth:`PlanHistory.from_opensees`) and any
:class:`~femoat.results.plan.PlanRunResult` (:meth:`PlanHistory.from_result`).

Conventions (docs/plan.md §2): plan axes x, y are the building's; ``base`` is the base mat's
displacement relative to the ground; walls are named by their outward normal ("+x", "-x", "+y",
"-y") and every per-wall array is in :data:`femoat.plan.moat.SIDES` order; a wall's force is the
contact force, compression positive, so a wall is in contact exactly where its force is > 0.
"""

from dataclasses import dataclass

import numpy as np

from femoat.plan.moat import SIDES, wall_side

WALL_COLORS = {"+x": "tab:red", "-x": "tab:blue", "+y": "tab:green", "-y": "tab:orange"}
"""One colour per wall, shared by the figures' markers and panels."""


def _array(name, value, shape):
    """``value`` as a read-only float array of ``shape`` (None: any length) with finite values."""
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"PlanHistory.{name} must be an array of numbers, shape "
                         f"{_shape_text(shape)}.") from None
    if a.ndim != len(shape) or any(s is not None and s != d for s, d in zip(shape, a.shape)):
        raise ValueError(f"PlanHistory.{name} has shape {a.shape}; it must be "
                         f"{_shape_text(shape)}.")
    bad = ~np.isfinite(a)
    if bad.any():
        where = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ValueError(f"PlanHistory.{name}{list(where)} = {float(a[where])!r} is not finite: "
                         "give a finished run's samples (no NaN or inf).")
    a.flags.writeable = False
    return a


def _shape_text(shape):
    return "(" + ", ".join("n" if s is None else str(s) for s in shape) + \
        ("," if len(shape) == 1 else "") + ")"


@dataclass(frozen=True, eq=False)
class PlanHistory:
    """The base mat's plan orbit and the moat walls' contact forces over a run.

    Parameters
    ----------
    time : array (n,)
        Sample times [s], increasing, n >= 2.
    base : array (n, 2)
        The base mat's displacement relative to the ground, (x, y) [in].
    wall_force : array (n, walls)
        Contact force of each wall, compression positive [kip]; > 0 while in contact.
    gaps : array (walls,)
        Each wall's clearance at rest [in], >= 0.
    sides : tuple of str
        The walls, by outward normal, in the columns' order: a subset of ("+x", "-x", "+y",
        "-y") in that order (default all four).
    title : str
        A caption for the figures (the record pair, the model).
    """

    time: np.ndarray
    base: np.ndarray
    wall_force: np.ndarray
    gaps: np.ndarray
    sides: tuple = SIDES
    title: str = ""

    def __post_init__(self):
        if isinstance(self.sides, str) or not hasattr(self.sides, "__iter__"):
            raise ValueError(f"PlanHistory.sides = {self.sides!r} must be a tuple of wall sides, "
                             "e.g. ('+x', '-x', '+y', '-y').")
        sides = tuple(wall_side(s) for s in self.sides)
        if sorted(sides, key=SIDES.index) != list(sides) or len(set(sides)) != len(sides):
            raise ValueError(f"PlanHistory.sides = {self.sides!r}: each wall at most once, in the "
                             "order '+x', '-x', '+y', '-y' (the order of every per-wall array).")
        time = _array("time", self.time, (None,))
        if time.size < 2 or np.any(np.diff(time) <= 0):
            raise ValueError("PlanHistory.time must hold at least two increasing times [s].")
        n, w = time.size, len(sides)
        base = _array("base", self.base, (n, 2))
        force = _array("wall_force", self.wall_force, (n, w))
        gaps = _array("gaps", self.gaps, (w,))
        if np.any(gaps < 0):
            k = int(np.argmax(gaps < 0))
            raise ValueError(f"PlanHistory.gaps: wall {sides[k]} has gap = {float(gaps[k])!r}; a "
                             "gap is a clearance >= 0 [in].")
        if not isinstance(self.title, str):
            raise ValueError(f"PlanHistory.title = {self.title!r} must be a string.")
        for name, value in (("sides", sides), ("time", time), ("base", base),
                            ("wall_force", force), ("gaps", gaps)):
            object.__setattr__(self, name, value)

    @classmethod
    def from_opensees(cls, result, model, title=""):
        """The history of an OpenSees twin run: ``result`` from
        :func:`femoat.opensees.plan.opensees_plan_run` on ``model`` (the PlanModel it ran, for
        the gaps)."""
        sides = tuple(w.side for w in model.walls)
        if tuple(result["walls"]) != sides:
            raise ValueError(f"the run's walls {tuple(result['walls'])} are not the model's "
                             f"{sides}: give the PlanModel the run was made with.")
        return cls(time=result["time"], base=result["base_displacement"],
                   wall_force=result["contact_force"], gaps=[w.gap for w in model.walls],
                   sides=sides, title=title)

    @classmethod
    def from_result(cls, result, title=""):
        """The history of a plan run's :class:`~femoat.results.plan.PlanRunResult` (femoat's plan
        solver or :meth:`~femoat.results.plan.PlanRunResult.from_opensees`). Of two samples at
        one instant (an event, the record's end: the left and the right limit) the later is
        kept."""
        t = np.asarray(result.time, dtype=float)
        keep = np.ones(t.size, dtype=bool)
        keep[:-1] = t[1:] != t[:-1]
        return cls(time=t[keep], base=np.asarray(result.base_displacement)[keep],
                   wall_force=np.asarray(result.contact_force)[keep], gaps=result.meta["gaps"],
                   sides=tuple(result.sides), title=title)

    @property
    def contact(self):
        """(n, walls) bool: the wall is in contact (its force > 0)."""
        return self.wall_force > 0.0

    def gap(self, side):
        """The gap [in] of wall ``side``, or None when the moat has no wall there."""
        side = wall_side(side)
        return float(self.gaps[self.sides.index(side)]) if side in self.sides else None

    def reach(self):
        """The moat's half-extents [in] as {side: distance}: a wall's gap, or where it has no
        wall, the orbit's farthest excursion that way (at least the opposite wall's gap, or
        1 in), so that the outline closes around the orbit."""
        out = {}
        for side in SIDES:
            gap = self.gap(side)
            if gap is None:
                axis, sign = (0 if side[1] == "x" else 1), (1.0 if side[0] == "+" else -1.0)
                opposite = self.gap(("-" if sign > 0 else "+") + side[1])
                gap = max(float(np.max(sign * self.base[:, axis])), opposite or 0.0, 1.0)
            out[side] = gap
        return out

    def impacts(self):
        """(walls,) int: the closures of each wall (a sample in contact after one that was not,
        the first sample counting when in contact)."""
        c = self.contact
        before = np.vstack([np.zeros((1, c.shape[1]), bool), c[:-1]])
        return np.sum(c & ~before, axis=0)

    def peak_plan_displacement(self):
        """The base mat's largest plan displacement |u| [in] (the vector norm)."""
        return float(np.max(np.hypot(self.base[:, 0], self.base[:, 1])))


def check_history(history):
    """``history`` if it is a :class:`PlanHistory`, else a ValueError saying how to make one."""
    if not isinstance(history, PlanHistory):
        raise ValueError(f"history must be a PlanHistory (femoat.plotting.plan_history), not "
                         f"{type(history).__name__}; from the OpenSees twin: "
                         "PlanHistory.from_opensees(result, model).")
    return history

