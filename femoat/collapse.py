"""Collapse criteria (limit states) of a building run, each recorded with the time it is first
reached, and an early stop once one is reached.

A criterion is a bound the compiled loop checks after every accepted step (at step ends; the
time reported is that of the first step end beyond the bound):

* ``drift``: a story drift ratio |u_k − u_{k−1}| / h_k above ``drift_ratio``;
* ``isolator``: the isolator displacement above the building's ``isolator_capacity`` [in];
* ``wall_displacement``: a moat wall's displacement at the impact point above a bound [in];
* ``wall_force``: a contact force on a moat wall above a bound [kip].

Whether or not a run stops at its first criterion, it always ends once a story drifts by more
than its height or the isolator by more than ten times its capacity (runaway: a collapsed
structure whose displacements grow without bound would otherwise cost ever smaller steps);
``stopped`` then says so.

A solver failure is not a criterion: it is reported as an error (``SolverError``), never counted
as collapse here; a suite decides how to treat it.
"""

import math
from dataclasses import dataclass

import numpy as np

CRITERIA = ("drift", "isolator", "wall_displacement", "wall_force")
RUNAWAY_DRIFT = 1.0
"""Drift ratio [-] beyond which a run always ends (a story displaced by its own height)."""
RUNAWAY_ISOLATOR = 10.0
"""Isolator displacement / capacity [-] beyond which a run always ends."""


@dataclass(frozen=True)
class CollapseCriteria:
    """Which limit states count as collapse, and whether a run stops at the first.

    Parameters
    ----------
    drift_ratio : float or None
        Story drift ratio limit [-] (0.10 by default, a common sidesway-collapse proxy); None
        switches the criterion off.
    isolator : bool
        Whether the isolator displacement capacity (``Building.isolator_capacity`` [in]) is a
        criterion.
    wall_displacement : float or None
        Moat-wall displacement capacity at the impact point [in]; None: no criterion.
    wall_force : float or None
        Moat-wall contact-force capacity [kip]; None: no criterion.
    stop : bool
        End the run at the first step beyond any criterion (nothing is computed that the answer
        does not need); False runs to the end and records the first time of each.
    """

    drift_ratio: float | None = 0.10
    isolator: bool = True
    wall_displacement: float | None = None
    wall_force: float | None = None
    stop: bool = True

    def __post_init__(self):
        for name in ("drift_ratio", "wall_displacement", "wall_force"):
            x = getattr(self, name)
            if x is not None and not (isinstance(x, (int, float)) and not isinstance(x, bool)
                                      and x > 0 and not math.isnan(x)):
                unit = {"drift_ratio": "[-]", "wall_displacement": "[in]",
                        "wall_force": "[kip]"}[name]
                raise ValueError(f"collapse {name} = {x!r} must be a positive bound {unit} "
                                 "or omitted (no criterion).")
        for name in ("isolator", "stop"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"collapse {name} = {getattr(self, name)!r} must be true or "
                                 "false.")

    def limits(self, model, packed):
        """Bounds for the solver (see :func:`femoat.integration.solve.solve`): per element of
        ``packed`` (isolator, stories), then per contact the wall displacement and the force;
        row 0 the criteria, row 1 the runaway bounds."""
        b = model.building
        heights = dict(zip((f"story{k + 1}" for k in range(len(b.heights))), b.heights))
        out = []
        for name in packed.el_names:
            if name == "isolator":
                out.append(b.isolator_capacity if self.isolator else math.inf)
            elif name in heights and self.drift_ratio is not None:
                out.append(self.drift_ratio * heights[name])
            else:
                out.append(math.inf)
        ncon = packed.c_code.size
        out += [self.wall_displacement or math.inf] * ncon
        out += [self.wall_force or math.inf] * ncon
        runaway = [RUNAWAY_ISOLATOR * b.isolator_capacity if name == "isolator"
                   else RUNAWAY_DRIFT * heights.get(name, math.inf) for name in packed.el_names]
        runaway += [math.inf] * (2 * ncon)
        return np.array([out, runaway], dtype=float)


def collapse_summary(limit_times, packed, stopped):
    """{criterion: first time [s] or None, "collapsed": bool, "stopped": bool} from the solver's
    first-exceedance times (NaN where never reached)."""
    nel, ncon = packed.el_code.size, packed.c_code.size
    groups = dict(
        drift=[e for e, nm in enumerate(packed.el_names) if nm.startswith("story")],
        isolator=[e for e, nm in enumerate(packed.el_names) if nm == "isolator"],
        wall_displacement=list(range(nel, nel + ncon)),
        wall_force=list(range(nel + ncon, nel + 2 * ncon)),
    )
    out = {}
    for name in CRITERIA:
        times = [limit_times[i] for i in groups[name] if np.isfinite(limit_times[i])]
        out[name] = float(min(times)) if times else None
    out["collapsed"] = any(out[name] is not None for name in CRITERIA)
    out["stopped"] = bool(stopped)
    return out
