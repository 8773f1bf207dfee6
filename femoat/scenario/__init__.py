"""Scenario files: one TOML file describes the building, the walls and their contact law, the
ground motion, the solver, the collapse criteria and the output.

Every table and every key is optional. A key left out takes the default of the object it sets,
read from that object (a dataclass field, a function's parameter) by the table's module, never
copied: :func:`defaults` returns the scenario of an empty file, e.g.
``defaults()["building"]["base_weight"]``. Units: kip, in, s; accelerations and PGA in g.
Relative paths are relative to the scenario file. The tables and their keys (:data:`KEYS`):

``[building]`` a :class:`~femoat.structure.building.Building` (:mod:`.building`)
    base_weight [kip]; floor_weights [kip], a list, bottom to top; story_model, the material
    of every story: "elastic" | "bilinear" | "imk" (deteriorating); story_damping_ratio [-] at
    story_damping_period [s]; story_heights [in], a list, bottom to top; p_delta (story
    geometric stiffness −P/h, P the gravity of the floors above); isolator_capacity [in], the
    isolator's displacement capacity (a collapse criterion).
``[building.story]`` the story material's parameters: Elastic k [kip/in]; Bilinear k0
    [kip/in], Fy [kip], b [-]; IMKBilinear K0, My, alpha_s, theta_p [in], theta_pc [in], ...
``[building.isolator]`` the single friction pendulum: R [in], mu [-] (mu_slow when mu_fast is
    given), u_y [in], mu_fast [-], a [s/in], v_reg [in/s]; W [kip] is the building's weight.
    ``type`` = "tfp" or "lrb": that bearing kind's fields (femoat.bearings); a triple pendulum
    may be given by its geometry instead (R1-R3, h1-h3, d1_nominal-d3_nominal [in]).
``[walls]`` the moat walls and their contact (:mod:`.walls`)
    preset: a wall of the paper's Table 3, "concrete" | "steel"; damping: its C_imp,
    "published" | "consistent"; law: a contact law letter, E | V | J | H | M; gap [in];
    sides: "both" | "pos" | "neg" | "none"; calibrate: the law's damping calibrated to the
    exact restitution at calibrate_v0 [in/s].
``[walls.fe]`` optional: a finite-element wall, reduced to its impact modes, replaces the SDOF
    wall. geometry: the wall geometry TOML (required; see ``femoat wall --help``); mesh: your
    own mesh (.vtu/.msh), whose dimension chooses the model; model: a wall kind of
    :mod:`femoat.walls.kinds`; modes: their number (left out: automatic, from flexibility and
    the contact time); flexibility [-]: the impact flexibility the automatic modes capture;
    residual: add the residual-flexibility vector of the modes left out; damping_ratio [-] of
    every mode (default: ξ_imp of the preset's SDOF wall).
``[motion]`` the ground motion (:mod:`.motion`)
    source: "erzincan" (the paper's record) | "at2" | "text" | "fema"; path: the record file
    (at2, text); dt [s], units, column, skip_rows (text); record_set, record_id, component
    (fema); pga [g]: scale the record to this PGA (left out: the record's own, or the paper's
    for Erzincan); or sa [g] with period [s]: scale it to this 5 %-damped Sa(T), T the
    prototype's period (:mod:`.intensity`, as suites scale; the factor is echoed; not with
    pga); time_scale [-]: similitude factor on time; extra_time [s] of free vibration after
    the record.
``[solver]`` an :class:`~femoat.integration.settings.Integrator`: method ("dp5": fifth order
    while the gaps are open, Newmark in contact; "tsit5": the same with Tsitouras' pair;
    "newmark": Newmark/HHT-α throughout; "ark5": a plan run's default), rtol,
    alpha, max_step [s] (left out: the record's sample interval), min_step [s], newton_tol,
    max_newton, contact_steps, record_every, record_budget [bytes] (the recorder's memory
    ceiling: a run that would outgrow it ends with a named error).
``[collapse]`` optional, limit states checked every step: a
    :class:`~femoat.collapse.CollapseCriteria`, drift_ratio [-], isolator (the isolator beyond
    isolator_capacity), wall_displacement [in], wall_force [kip], stop (end the run at the
    first criterion reached). Without the table no criterion is checked.
``[output]`` folder (run.npz, impacts.csv, summary.csv, figures); figures.

**Plan scenarios** (issue 18, docs/plan.md §8): ``plan = true`` in ``[building]`` makes the
building a :class:`~femoat.plan.PlanBuilding` (:data:`PLAN_KEYS`), ``[moat]`` replaces
``[walls]`` and ``[motion]`` is a record pair; ``[solver]``, ``[collapse]`` and ``[output]`` are
the same.

``[building]`` plan: the building in plan, x and y (no torsion): the table's 1D building in both
    directions, its friction pendulum bidirectional (friction coupled in plan),
    isolator_capacity measured in plan; story_model_y and ``[building.story_y]``: the y
    stories (left out: the x ones; the same model's story_y overrides story key by key).
``[moat]`` the default wall of the four sides of a rectangular moat: preset, damping, law, gap
    [in], calibrate, calibrate_v0 [in/s] as in ``[walls]``, friction [-] (Coulomb coefficient of
    the base mat sliding along a wall in contact, 0: frictionless); sides, the walls the moat
    has, a list of "+x", "-x", "+y", "-y" (default all four). ``[moat.fe]``: a finite-element
    wall, keys as ``[walls.fe]``.
``[moat."+x"]``, ``[moat."-x"]``, ``[moat."+y"]``, ``[moat."-y"]`` optional: one side's wall, the
    keys of ``[moat]`` but sides, each overriding the default (``[moat."+x".fe]`` replaces
    ``[moat.fe]``). A side is named by its outward normal (docs/plan.md §2).
``[motion]`` of a plan scenario, a pair: source "fema" (record_set, record_id: component a along
    x, b along y; normalized: times FEMA P695's normalization factor NF) | "at2" (path_x,
    path_y; pad: extend the shorter with zeros); angle [deg], the pair turned in plan from +x
    toward +y; scale [-], one factor for both components; or pga [g], the target of the
    geometric mean of the two components' PGAs as recorded (FEMA P695's mean; not with scale);
    or sa [g] with period [s], the target of the geometric mean of the two components' Sa(T)
    as recorded, as suites of pairs scale (not with scale, normalized or pga); time_scale,
    extra_time [s] as for one record.

``examples/my_building.toml`` is a complete file, ``examples/plan_building.toml`` a complete plan
file.
"""

from femoat.scenario.building import building_from_dict, plan_building_from_dict
from femoat.scenario.document import (KEYS, PLAN_KEYS, Scenario, defaults, integrator_for,
                                      load_scenario,
                                      model_from_dict, scenario_from_dict)
from femoat.scenario.moat import moat_from_dict
from femoat.scenario.motion import motion_from_dict
from femoat.scenario.pair import pair_from_dict
from femoat.scenario.reading import check_keys, read_toml
from femoat.scenario.solver import collapse_from_dict, solver_from_dict
from femoat.scenario.walls import fe_wall_from_dict, walls_from_dict

__all__ = [
    "KEYS", "PLAN_KEYS", "Scenario", "building_from_dict", "check_keys", "collapse_from_dict",
    "defaults", "fe_wall_from_dict", "integrator_for", "load_scenario", "moat_from_dict",
    "model_from_dict",
    "motion_from_dict", "pair_from_dict", "plan_building_from_dict", "read_toml",
    "scenario_from_dict", "solver_from_dict", "walls_from_dict",
]
