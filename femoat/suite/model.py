"""One variation's model from the scenario tables, and one run of it with collapse detection.

The model tables are parsed by :mod:`femoat.scenario` (``building_from_dict``,
``walls_from_dict``, ``Integrator``, ``collapse_from_dict``): a suite accepts exactly what a
scenario file accepts.

TODO(model API, suite-run branch only): until ``femoat.collapse.CollapseCriteria``,
``scenario.collapse_from_dict`` and the ``[building] story_heights / p_delta /
isolator_capacity`` keys land on main, :class:`_Criteria` stands in for CollapseCriteria and the
criteria are checked on the finished history (the run is not stopped at collapse, and
``p_delta`` is accepted but has no effect). Delete the fallback after merging main.
"""

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

CRITERIA = ("drift", "isolator", "wall_displacement", "wall_force")
"""Collapse criteria, in the order of the table's columns."""

STORY_HEIGHT = 39.0  # [in] default story height (quarter-scale paper building)
ISOLATOR_CAPACITY = 7.0  # [in] default isolator displacement capacity


def has_model_api():
    """True once main's collapse API (femoat.collapse, scenario.collapse_from_dict) is here."""
    from femoat import scenario

    return hasattr(scenario, "collapse_from_dict")


@dataclass(frozen=True)
class _Criteria:
    """Stand-in for femoat.collapse.CollapseCriteria (same fields); see the module TODO.

    drift_ratio : float  story drift / story height [-] that means collapse
    isolator : bool  collapse when the isolator displacement reaches its capacity
    wall_displacement : float or None  wall displacement [in] that means collapse
    wall_force : float or None  wall spring + dashpot force [kip] that means collapse
    stop : bool  stop the run at collapse (ignored by the stand-in)
    """

    drift_ratio: float = 0.10
    isolator: bool = True
    wall_displacement: float | None = None
    wall_force: float | None = None
    stop: bool = True


def collapse_keys():
    """The keys of the ``[collapse]`` table."""
    if has_model_api():
        from femoat.collapse import CollapseCriteria

        return {f.name for f in dataclasses.fields(CollapseCriteria)}
    return {f.name for f in dataclasses.fields(_Criteria)}


def building_keys():
    """The keys of the ``[building]`` table (main's, plus the model API's while it is missing)."""
    from femoat import scenario

    return set(scenario._KNOWN["building"]) | {"story_heights", "p_delta", "isolator_capacity"}


@dataclass(frozen=True)
class Model:
    """A parsed variation: everything one run needs besides the motion."""

    pounding: object  # PoundingModel
    integrator: object  # Integrator
    criteria: object  # CollapseCriteria (or the stand-in)
    story_heights: tuple  # [in]
    isolator_capacity: float  # [in]


def build_model(tables, stop_on_collapse=True, base_dir=Path(".")):
    """A :class:`Model` from the model tables {'building', 'walls', 'solver', 'collapse'}."""
    from femoat import scenario
    from femoat.integration.settings import Integrator
    from femoat.scenario import _check_keys
    from femoat.structure.pounding import PoundingModel
    from femoat.units import G

    bd = dict(tables.get("building", {}))
    nfloors = len(bd.get("floor_weights", (8.0, 8.0, 7.0)))
    heights = tuple(float(h) for h in bd.get("story_heights", (STORY_HEIGHT,) * nfloors))
    capacity = float(bd.get("isolator_capacity", ISOLATOR_CAPACITY))
    if len(heights) != nfloors or not all(math.isfinite(h) and h > 0 for h in heights):
        raise ValueError(f"[building] story_heights = {list(heights)}: give {nfloors} positive "
                         "heights [in], one per story.")
    if not has_model_api():  # TODO(model API): main's building_from_dict takes these keys
        for key in ("story_heights", "p_delta", "isolator_capacity"):
            bd.pop(key, None)
    building = scenario.building_from_dict(bd)
    walls = scenario.walls_from_dict(tables.get("walls", {}), base_dir, building.base_weight / G)
    solver = dict(tables.get("solver", {}))
    _check_keys(solver, scenario._KNOWN["solver"], "[solver]")
    cd = dict(tables.get("collapse", {}))
    cd.setdefault("stop", bool(stop_on_collapse))
    if has_model_api():
        criteria = scenario.collapse_from_dict(cd)
    else:
        _check_keys(cd, collapse_keys(), "[collapse]")
        criteria = _Criteria(**cd)
    return Model(PoundingModel(building, walls), Integrator(**solver), criteria, heights, capacity)


def run_model(model, motion, extra_time):
    """Run ``model`` under ``motion``; return ``(RunResult, collapse)`` where collapse is
    dict(collapsed, stopped, drift, isolator, wall_displacement, wall_force) with the time [s]
    each criterion was first reached (None if not)."""
    from femoat.run import run

    if has_model_api():
        result = run(model.pounding, motion, model.integrator, extra_time=extra_time,
                     collapse=model.criteria)
        return result, dict(result.collapse)
    result = run(model.pounding, motion, model.integrator, extra_time=extra_time)
    return result, _collapse_after(result, model)


def _collapse_after(result, model):
    """The criteria checked on a finished history (stand-in; see the module TODO)."""
    c, t = model.criteria, result.time
    out = dict(collapsed=False, stopped=False, drift=None, isolator=None,
               wall_displacement=None, wall_force=None)
    ratio = np.abs(result.story_drifts()) / np.asarray(model.story_heights)[None, :]
    out["drift"] = _first(t, ratio.max(axis=1, initial=0.0) >= c.drift_ratio)
    if c.isolator:
        out["isolator"] = _first(t, np.abs(result.base_displacement) >= model.isolator_capacity)
    if c.wall_displacement is not None and result.meta["walls"]:
        wall = np.abs(result.wall_displacement()).max(axis=1)
        out["wall_displacement"] = _first(t, wall >= c.wall_displacement)
    if c.wall_force is not None and result.meta["walls"]:
        force = np.abs(result.wall_force()).max(axis=1)
        out["wall_force"] = _first(t, force >= c.wall_force)
    out["collapsed"] = any(out[k] is not None for k in CRITERIA)
    return out


def _first(t, hit):
    idx = np.flatnonzero(hit)
    return float(t[idx[0]]) if idx.size else None
