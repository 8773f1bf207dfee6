"""One variation's model from the scenario tables, and one run of it with collapse detection.

The model tables are parsed by :mod:`femoat.scenario` (``building_from_dict``,
``walls_from_dict``, ``Integrator``, ``collapse_from_dict``): a suite accepts exactly what a
scenario file accepts. Collapse criteria (:mod:`femoat.collapse`) are checked by the solver after
every step; ``[run] stop_on_collapse`` is the default of ``[collapse] stop``.
"""

from dataclasses import dataclass
from pathlib import Path

from femoat.collapse import CRITERIA  # noqa: F401  (re-exported: the table's column order)


@dataclass(frozen=True)
class Model:
    """A parsed variation: everything one run needs besides the motion."""

    pounding: object  # PoundingModel
    integrator: object  # Integrator
    criteria: object  # CollapseCriteria

    @property
    def story_heights(self):
        """Story heights [in], bottom to top."""
        return self.pounding.building.heights


def build_model(tables, stop_on_collapse=True, base_dir=Path(".")):
    """A :class:`Model` from the model tables {'building', 'walls', 'solver', 'collapse'}."""
    from femoat import scenario
    from femoat.structure.pounding import PoundingModel
    from femoat.units import G

    building = scenario.building_from_dict(tables.get("building", {}))
    walls = scenario.walls_from_dict(tables.get("walls", {}), base_dir, building.base_weight / G)
    collapse = dict(tables.get("collapse", {}))
    collapse.setdefault("stop", bool(stop_on_collapse))
    integrator = scenario.solver_from_dict(tables.get("solver", {}))
    return Model(PoundingModel(building, walls), integrator,
                 scenario.collapse_from_dict(collapse))


PEAK_CHANNELS = ("displacement", "velocity", "acceleration", "contacts")
"""The histories a row's peaks need (the element forces and deformations are not recorded
unless the run's history is saved: the step sequence, and so every peak, is the same)."""


def run_model(model, motion, extra_time, history=False):
    """Run ``model`` under ``motion``; return ``(RunResult, collapse)`` where collapse is
    dict(collapsed, stopped, drift, isolator, wall_displacement, wall_force) with the time [s]
    each criterion was first reached (None if not). ``history``: record every channel."""
    from femoat.run import run

    result = run(model.pounding, motion, model.integrator, extra_time=extra_time,
                 collapse=model.criteria, channels=None if history else PEAK_CHANNELS)
    return result, dict(result.collapse)
