"""The whole scenario file: its tables, the :class:`Scenario` they make and the defaults of an
empty file."""

from dataclasses import dataclass
from pathlib import Path

from femoat.integration.settings import Integrator
from femoat.scenario import building, motion, solver, walls
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
"""Every table (dotted for a sub-table with its own reader) and its keys."""


@dataclass(frozen=True)
class Scenario:
    """A parsed scenario: the model, the motion, the integrator and output options.

    model : PoundingModel  the building and its walls
    motion : GroundMotion  scaled and time-scaled
    integrator : Integrator
    extra_time : float  [s] free vibration after the record
    collapse : CollapseCriteria or None  (None: no ``[collapse]`` table)
    output_folder : Path  where ``femoat run`` writes
    figures : bool  whether it draws the figures
    source : dict  the parsed TOML document
    wall_label : str  the walls' name in reports: the preset, with "FE" for a finite-element wall
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


def defaults():
    """The scenario of an empty file, table by table (TOML-shaped: ``scenario_from_dict`` of it
    gives the same scenario). No ``[collapse]``: without the table no criterion is checked (with
    it, the keys left out take :class:`~femoat.collapse.CollapseCriteria`'s defaults)."""
    return {"building": building.defaults(), "walls": walls.defaults(),
            "motion": motion.defaults(), "solver": solver.defaults(),
            "output": dict(OUTPUT_DEFAULTS)}


def scenario_from_dict(d, base_dir=Path(".")):
    """Build a :class:`Scenario` from a parsed TOML document."""
    check_keys(d, set(KEYS) - {"walls.fe"}, "scenario")
    from femoat.units import G

    built = building.building_from_dict(subtable(d, "building", "scenario"))
    walls_d = subtable(d, "walls", "scenario")
    model = PoundingModel(built, walls.walls_from_dict(walls_d, base_dir,
                                                       built.base_weight / G))
    motion_d = subtable(d, "motion", "scenario")
    ground = motion.motion_from_dict(motion_d, base_dir)
    extra_time = motion.extra_time_from_dict(motion_d)
    integ = solver.solver_from_dict(subtable(d, "solver", "scenario"))
    out = subtable(d, "output", "scenario")
    check_keys(out, OUTPUT_KEYS, "[output]")
    collapse = solver.collapse_from_dict(subtable(d, "collapse", "scenario")) \
        if "collapse" in d else None
    label = str(walls_d.get("preset", walls.defaults()["preset"])) + \
        (" FE" if "fe" in walls_d else "")
    return Scenario(model=model, motion=ground, integrator=integ, extra_time=extra_time,
                    collapse=collapse, wall_label=label,
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
