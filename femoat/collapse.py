"""Collapse criteria (limit states) of a building run, each recorded with the time it is first
reached, an early stop once one is reached, and the runaway bounds that end every run.

A criterion is a bound the compiled loop checks after every accepted step (at step ends; the
time reported is that of the first step end beyond the bound):

* ``drift``: a story drift ratio |u_k − u_{k−1}| / h_k above ``drift_ratio``;
* ``isolator``: the isolator displacement above the building's ``isolator_capacity`` [in];
* ``wall_displacement``: a moat wall's displacement at the impact point above a bound [in];
* ``wall_force``: a contact force on a moat wall above a bound [kip].

Each criterion is a small object with a ``name`` and ``limits(model, packed)``, the rows
(:class:`~femoat.integration.limits.Limit`) the solver checks for it: a new criterion on a
quantity the solver knows (:data:`femoat.integration.limits.QUANTITIES`, e.g. a floor's absolute
acceleration or the base velocity) is such an object, given in ``CollapseCriteria(extra=...)``.

Whether or not a run has criteria, it always ends once a story drifts by more than its height
or the isolator by more than ten times its capacity (runaway: a collapsed structure whose
displacements grow without bound would otherwise cost ever smaller steps, without end);
:func:`runaway_summary` then names the bound and the time (``RunResult.runaway``).

A solver failure is not a criterion: it is reported as an error (``SolverError``), never counted
as collapse here; a suite decides how to treat it.
"""

import math
from dataclasses import dataclass

import numpy as np

from femoat.integration.limits import Limit
from femoat.structure.roles import ISOLATOR, STORY

RUNAWAY_DRIFT = 1.0
"""Drift ratio [-] beyond which a run always ends (a story displaced by its own height)."""
RUNAWAY_ISOLATOR = 10.0
"""Isolator displacement / capacity [-] beyond which a run always ends."""


def _positive(name, x, unit):
    if not (isinstance(x, (int, float)) and not isinstance(x, bool) and x > 0
            and not math.isnan(x)):
        raise ValueError(f"collapse {name} = {x!r} must be a positive bound {unit} "
                         "or omitted (no criterion).")


def _bounded(x):
    """A bound that is on: given and finite (``inf``, as in a scenario file, means none)."""
    return x is not None and math.isfinite(x)


@dataclass(frozen=True)
class DriftRatio:
    """Every story: |drift| / story height above ``ratio`` [-]."""

    ratio: float
    name = "drift"

    def limits(self, model, packed):
        heights = model.building.heights
        return [Limit("element_deformation", e, self.ratio * heights[role.story - 1],
                      criterion=self.name)
                for e, role in enumerate(packed.el_roles) if role.kind == STORY]


def isolator_capacity(building):
    """The isolator's displacement capacity [in]: the building's ``isolator_capacity``, or the
    bearing's own ``capacity`` where smaller (a triple friction pendulum's ultimate displacement,
    a lead-rubber bearing's given limit; a single friction pendulum has none of its own)."""
    own = getattr(building.isolator, "capacity", math.inf)
    return min(building.isolator_capacity, own)


@dataclass(frozen=True)
class IsolatorCapacity:
    """The isolator: |displacement| above the building's ``isolator_capacity`` [in] (none when
    that is infinite); a plan friction pendulum's displacement in plan √(u_x² + u_y²)."""

    name = "isolator"

    def limits(self, model, packed):
        capacity = isolator_capacity(model.building)
        if not math.isfinite(capacity):
            return []
        rows = [Limit("element_deformation", e, capacity, criterion=self.name)
                for e, role in enumerate(packed.el_roles) if role.kind == ISOLATOR]
        if packed.bearing_dofs.size:  # in plan: its plan displacement
            rows.append(Limit("plan_displacement", 0, capacity, criterion=self.name))
        return rows


@dataclass(frozen=True)
class WallDisplacement:
    """Every moat wall: |displacement| at the impact point above ``bound`` [in]."""

    bound: float
    name = "wall_displacement"

    def limits(self, model, packed):
        return [Limit("wall_displacement", c, self.bound, criterion=self.name)
                for c in range(packed.c_code.size)]


@dataclass(frozen=True)
class WallForce:
    """Every contact: the force on the moat wall above ``bound`` [kip]."""

    bound: float
    name = "wall_force"

    def limits(self, model, packed):
        return [Limit("contact_force", c, self.bound, criterion=self.name)
                for c in range(packed.c_code.size)]


BUILT_IN = (DriftRatio, IsolatorCapacity, WallDisplacement, WallForce)
CRITERIA = tuple(c.name for c in BUILT_IN)
"""The built-in criteria's names, in the order of the summary (and of a suite table's
columns): drift, isolator, wall_displacement, wall_force."""


@dataclass(frozen=True)
class CollapseCriteria:
    """Which limit states count as collapse, and whether a run stops at the first.

    Parameters
    ----------
    drift_ratio : float or None
        Story drift ratio limit [-] (0.10 by default, a common sidesway-collapse proxy); None
        (or ``inf``) switches the criterion off.
    isolator : bool
        Whether the isolator displacement capacity (``Building.isolator_capacity`` [in]) is a
        criterion.
    wall_displacement : float or None
        Moat-wall displacement capacity at the impact point [in]; None (or ``inf``): no
        criterion.
    wall_force : float or None
        Moat-wall contact-force capacity [kip]; None (or ``inf``): no criterion.
    stop : bool
        End the run at the first step beyond any criterion (nothing is computed that the answer
        does not need); False runs to the end and records the first time of each.
    extra : tuple
        More criteria: objects with a ``name`` (a key of the summary, not one of
        :data:`CRITERIA`) and ``limits(model, packed)`` returning their
        :class:`~femoat.integration.limits.Limit` rows (see the built-in ones above).
    """

    drift_ratio: float | None = 0.10
    isolator: bool = True
    wall_displacement: float | None = None
    wall_force: float | None = None
    stop: bool = True
    extra: tuple = ()

    def __post_init__(self):
        units = {"drift_ratio": "[-]", "wall_displacement": "[in]", "wall_force": "[kip]"}
        for name, unit in units.items():
            if getattr(self, name) is not None:
                _positive(name, getattr(self, name), unit)
        for name in ("isolator", "stop"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"collapse {name} = {getattr(self, name)!r} must be true or "
                                 "false.")
        if not isinstance(self.extra, tuple):
            raise ValueError(f"collapse extra = {self.extra!r} must be a tuple of criteria.")
        names = list(CRITERIA)
        for c in self.extra:
            name = getattr(c, "name", None)
            if not isinstance(name, str) or not callable(getattr(c, "limits", None)):
                raise ValueError(f"collapse extra: {c!r} is not a criterion (it needs a name and "
                                 "limits(model, packed), see femoat.collapse).")
            if name in names or name in ("collapsed", "stopped"):
                raise ValueError(f"collapse extra: a criterion named {name!r} is already there "
                                 "(or is a key of the summary); give it another name.")
            names.append(name)

    def criteria(self):
        """The criteria that are on, built-in ones first."""
        out = []
        if _bounded(self.drift_ratio):
            out.append(DriftRatio(self.drift_ratio))
        if self.isolator:
            out.append(IsolatorCapacity())
        if _bounded(self.wall_displacement):
            out.append(WallDisplacement(self.wall_displacement))
        if _bounded(self.wall_force):
            out.append(WallForce(self.wall_force))
        return (*out, *self.extra)

    @property
    def names(self):
        """Every key of the summary's criteria: :data:`CRITERIA`, then the extra ones."""
        return (*CRITERIA, *(c.name for c in self.extra))

    def limits(self, model, packed):
        """The criteria's rows for the solver (:func:`femoat.integration.solve.solve`)."""
        rows = []
        for c in self.criteria():
            for row in c.limits(model, packed):
                if not isinstance(row, Limit) or row.runaway or row.criterion != c.name:
                    raise ValueError(f"collapse criterion {c.name!r}: limits() must return "
                                     f"Limit rows with criterion={c.name!r} and runaway=False; "
                                     f"got {row!r}.")
                rows.append(row)
        return rows


def runaway_limits(model, packed):
    """The rows that end every run: a story drift of RUNAWAY_DRIFT × its height, an isolator
    displacement of RUNAWAY_ISOLATOR × its capacity (none when the capacity is infinite)."""
    b = model.building
    capacity = isolator_capacity(b)
    rows = []
    for e, role in enumerate(packed.el_roles):
        if role.kind == STORY:
            rows.append(Limit("element_deformation", e, RUNAWAY_DRIFT * b.heights[role.story - 1],
                              runaway=True, criterion=DriftRatio.name))
        elif role.kind == ISOLATOR and math.isfinite(capacity):
            rows.append(Limit("element_deformation", e, RUNAWAY_ISOLATOR * capacity,
                              runaway=True, criterion=IsolatorCapacity.name))
    if packed.bearing_dofs.size and math.isfinite(capacity):
        # a plan bearing: its displacement in plan (femoat.plan)
        rows.append(Limit("plan_displacement", 0, RUNAWAY_ISOLATOR * capacity,
                          runaway=True, criterion=IsolatorCapacity.name))
    return rows


def collapse_summary(limits, limit_times, stopped, names=CRITERIA):
    """{criterion: first time [s] or None, "collapsed": bool, "stopped": bool} for every name
    of ``names``, from the solver's first-exceedance time of each row of ``limits`` (NaN where
    never reached; runaway rows are not criteria)."""
    out = {}
    for name in names:
        times = [t for lim, t in zip(limits, limit_times)
                 if lim.criterion == name and not lim.runaway and np.isfinite(t)]
        out[name] = float(min(times)) if times else None
    out["collapsed"] = any(out[name] is not None for name in names)
    out["stopped"] = bool(stopped)
    return out


_RUNAWAY_REASON = {DriftRatio.name: f"a drift of {RUNAWAY_DRIFT:g} x the story height",
                   IsolatorCapacity.name: f"{RUNAWAY_ISOLATOR:g} x the isolator capacity"}


def runaway_summary(limits, limit_times, packed):
    """None, or {time [s], element, bound [in], reason} of the runaway bound that ended the
    run (the first one exceeded)."""
    hits = [(t, lim) for lim, t in zip(limits, limit_times) if lim.runaway and np.isfinite(t)]
    if not hits:
        return None
    t, lim = min(hits, key=lambda h: h[0])
    element = ("isolator (in plan)" if lim.quantity == "plan_displacement"
               else packed.el_names[lim.index])
    return dict(time=float(t), element=element, bound=float(lim.bound),
                reason=_RUNAWAY_REASON[lim.criterion])


def describe_runaway(runaway):
    """One sentence for a :func:`runaway_summary`."""
    return (f"ended at t = {runaway['time']:.6g} s: {runaway['element']} deformed beyond "
            f"{runaway['bound']:.4g} in ({runaway['reason']})")
