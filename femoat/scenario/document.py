"""The whole scenario file: its tables, the :class:`Scenario` they make and the defaults of an
empty file. ``[building] plan = true`` makes it a plan scenario (:data:`PLAN_KEYS`): a
:class:`~femoat.plan.PlanModel` in a ``[moat]`` under a record pair."""

from dataclasses import dataclass
from pathlib import Path

from femoat.integration.methods import EXPLICIT_PAIRS
from femoat.integration.settings import Integrator
from femoat.plan.model import PlanModel
from femoat.plan.moat import SIDES
from femoat.run import PLAN_METHOD, axis_method, plan_method
from femoat.scenario import building, moat, motion, pair, solver, walls
from femoat.scenario.reading import check_keys, flag, read_toml, subtable, text
from femoat.structure.pounding import PoundingModel

OUTPUT_KEYS = ("folder", "figures")
OUTPUT_DEFAULTS = dict(folder="femoat_output", figures=True)
"""Where ``femoat run`` writes (relative to the working folder), and whether it draws figures."""

KEYS = {
    "building": building.KEYS,
    "collapse": solver.COLLAPSE_KEYS,
    "walls": walls.KEYS,
    "walls.fe": walls.FE_KEYS,
    "motion": motion.KEYS,
    "solver": solver.KEYS,
    "output": OUTPUT_KEYS,
}
"""Every table of a 1D scenario (dotted for a sub-table with its own reader) and its keys."""

PLAN_KEYS = {
    "building": building.KEYS + building.PLAN_KEYS,
    "collapse": solver.COLLAPSE_KEYS,
    "moat": moat.KEYS,
    **{f'moat."{side}"': moat.SIDE_KEYS for side in SIDES},
    "moat.fe": walls.FE_KEYS,
    "motion": pair.KEYS,
    "solver": solver.KEYS,
    "output": OUTPUT_KEYS,
}
"""Every table of a plan scenario (``[building] plan = true``) and its keys."""

TABLES = tuple(sorted({table.split(".")[0] for table in (*KEYS, *PLAN_KEYS)}))
"""The top-level tables a scenario file may have (1D or plan)."""


@dataclass(frozen=True)
class Scenario:
    """A parsed scenario: the model, the motion, the integrator and output options.

    model : PoundingModel or PlanModel  the building and its walls (a plan scenario: the
        building in plan and its moat)
    motion : GroundMotion or RecordPair  scaled and time-scaled (a plan scenario: a pair,
        turned by its angle)
    integrator : Integrator
    extra_time : float  [s] free vibration after the record
    collapse : CollapseCriteria or None  (None: no ``[collapse]`` table)
    output_folder : Path  where ``femoat run`` writes
    figures : bool  whether it draws the figures
    source : dict  the parsed TOML document
    wall_label : str  the walls' name in reports: the preset, with "FE" for a finite-element wall
    intensity : SaScaling or None  how ``[motion] sa`` scaled the record to Sa(T) (the factor,
        echoed by ``femoat run``); None without ``sa``
    """

    model: PoundingModel
    motion: object
    integrator: Integrator
    extra_time: float
    collapse: object
    output_folder: Path
    figures: bool
    source: dict
    wall_label: str
    intensity: object = None

    @property
    def plan(self):
        """Whether this is a plan scenario (a PlanModel under a RecordPair)."""
        return not isinstance(self.model, PoundingModel)


def defaults(plan=False):
    """The scenario of an empty file, table by table (TOML-shaped: ``scenario_from_dict`` of it
    gives the same scenario). No ``[collapse]``: without the table no criterion is checked (with
    it, the keys left out take :class:`~femoat.collapse.CollapseCriteria`'s defaults).

    plan : bool  the tables of a plan scenario (``[building] plan = true``): ``[moat]`` instead
        of ``[walls]``, a record pair's ``[motion]``
    """
    out = {"building": building.defaults()}
    if plan:
        out["building"]["plan"] = True
        out.update(moat=moat.defaults(), motion=pair.defaults())
    else:
        out.update(walls=walls.defaults(), motion=motion.defaults())
    solver_table = solver.defaults()
    if plan:  # a plan run's own method (the default isolator's: the friction pendulum's)
        solver_table["method"] = PLAN_METHOD
    return {**out, "solver": solver_table, "output": dict(OUTPUT_DEFAULTS)}


def model_from_dict(d, base_dir=Path(".")):
    """The model of a scenario's (or a suite's) tables: a
    :class:`~femoat.structure.pounding.PoundingModel` from ``[building]`` and ``[walls]``, or
    with ``[building] plan = true`` a :class:`~femoat.plan.PlanModel` from ``[building]`` and
    ``[moat]``."""
    from femoat.units import G

    table = subtable(d, "building", "scenario")
    if not building.is_plan(table):
        if "moat" in d:
            raise ValueError("[moat]: the walls of a building in plan; add plan = true to "
                             "[building] (a 1D scenario's walls are [walls]).")
        built = building.building_from_dict(table)
        return PoundingModel(built, walls.walls_from_dict(subtable(d, "walls", "scenario"),
                                                          base_dir, built.base_weight / G))
    if "walls" in d:
        raise ValueError("[walls]: a plan scenario's walls are [moat] (a default wall and "
                         "[moat.\"+x\"] ... per side); rename the table.")
    built = building.plan_building_from_dict(table)
    return PlanModel(built, moat.moat_from_dict(subtable(d, "moat", "scenario"), base_dir,
                                                built.base_weight / G))



def integrator_for(model, table):
    """The Integrator of a ``[solver]`` table for ``model``: a plan model's method defaults to
    a plan run's own (:func:`femoat.run.plan_method`), a 1D model's to a 1D run's
    (:func:`femoat.run.axis_method`: the Integrator's, Newmark on velocity-dependent friction)."""
    table = dict(table)
    if not isinstance(model, PlanModel) and axis_method(model) != Integrator().method:
        table.setdefault("method", axis_method(model))
        if table["method"] != "newmark":
            raise ValueError(
                f"[solver] method = {table['method']!r}: this isolator's velocity-dependent "
                "friction is a return over each step, which only Newmark's step gives the "
                "step's duration; write method = \"newmark\" in [solver] or leave method out "
                "(this file's default).")
    if isinstance(model, PlanModel):
        default = plan_method(model)
        table.setdefault("method", default)
        if table["method"] in EXPLICIT_PAIRS or (table["method"] == "ark5" and default != "ark5"):
            raise ValueError(
                f"[solver] method = {table['method']!r}: on this plan isolator its "
                "stages would read the friction from a path between stage values (or, for "
                "velocity-dependent friction, a return over each stage's offset), only first "
                f"order in the step (docs/coupled_friction.md); write method = \"{default}\" "
                "in [solver] or leave method out (this plan file's default).")
    return solver.solver_from_dict(table)

def scenario_from_dict(d, base_dir=Path(".")):
    """Build a :class:`Scenario` from a parsed TOML document."""
    check_keys(d, TABLES, "scenario")
    model = model_from_dict(d, base_dir)
    motion_d = subtable(d, "motion", "scenario")
    plan = not isinstance(model, PoundingModel)
    if plan:
        ground, scaled = pair.pair_and_scaling_from_dict(motion_d, base_dir)
        label = moat.wall_label(subtable(d, "moat", "scenario"))
    else:
        stray = sorted(set(motion_d) & set(pair.KEYS) - set(motion.KEYS))
        if stray:
            raise ValueError(f"[motion] {', '.join(stray)}: a record pair's key; add plan = true "
                             "to [building] for a plan scenario (or remove the key).")
        ground, scaled = motion.motion_and_scaling_from_dict(motion_d, base_dir)
        walls_d = subtable(d, "walls", "scenario")
        label = str(walls_d.get("preset", walls.defaults()["preset"])) + \
            (" FE" if "fe" in walls_d else "")
    extra_time = motion.extra_time_from_dict(motion_d)
    integ = integrator_for(model, subtable(d, "solver", "scenario"))
    out = subtable(d, "output", "scenario")
    check_keys(out, OUTPUT_KEYS, "[output]")
    collapse = solver.collapse_from_dict(subtable(d, "collapse", "scenario")) \
        if "collapse" in d else None
    return Scenario(model=model, motion=ground, integrator=integ, extra_time=extra_time,
                    collapse=collapse, wall_label=label, intensity=scaled,
                    output_folder=Path(text(out, "folder", OUTPUT_DEFAULTS["folder"], "[output]")),
                    figures=flag(out, "figures", OUTPUT_DEFAULTS["figures"], "[output]"),
                    source=d)


def load_scenario(path):
    """Parse a scenario TOML file.

    Raises
    ------
    FileNotFoundError
        The file (or a file it names) does not exist.
    ValueError
        The file is not UTF-8 TOML (the message names the file and TOML's line and column), or
        a table or key is unknown, of the wrong type or out of range (the message names the
        table and the key).
    """
    path = Path(path)
    return scenario_from_dict(read_toml(path, "scenario"), path.parent)
