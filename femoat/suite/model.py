"""One variation of a suite: its model from the scenario tables, and one run of it with
collapse detection.

The model tables are parsed by :mod:`femoat.scenario` (``model_from_dict``,
``integrator_for``, ``collapse_from_dict``): a suite accepts exactly what a scenario file
accepts, a building in plan (``[building] plan = true`` with ``[moat]``) included. Collapse
criteria (:mod:`femoat.collapse`) are checked by the solver after every step; ``[run]
stop_on_collapse`` is the default of ``[collapse] stop``.
"""

from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Variation:
    """A parsed variation: everything one run needs besides the motion."""

    pounding: object  # PoundingModel, or PlanModel (a plan suite)
    integrator: object  # Integrator
    criteria: object  # CollapseCriteria

    @property
    def story_heights(self):
        """Story heights [in], bottom to top."""
        return self.pounding.building.heights


def build_variation(tables, stop_on_collapse=True, base_dir=Path(".")):
    """A :class:`Variation` from the model tables {'building', 'walls' or 'moat', 'solver',
    'collapse'}."""
    from femoat import scenario

    model = scenario.model_from_dict(tables, base_dir)
    collapse = dict(tables.get("collapse", {}))
    collapse.setdefault("stop", bool(stop_on_collapse))
    return Variation(model, scenario.integrator_for(model, tables.get("solver", {})),
                     scenario.collapse_from_dict(collapse))


def run_variation(variation, motion, extra_time, history=False):
    """Run ``variation`` under ``motion``; return its RunResult, whose ``collapse`` holds the
    time [s] each criterion was first reached (None if not). ``history``: record every
    channel; without it the run keeps no history (its peaks and impact table are kept inside
    the solver's loop, the same values: the step sequence does not depend on what is
    recorded)."""
    from femoat.run import run

    return run(variation.pounding, motion, variation.integrator, extra_time=extra_time,
               collapse=variation.criteria, history=history)
