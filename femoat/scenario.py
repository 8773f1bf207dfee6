"""Scenario files: one TOML file describes model, walls, contact law, motion and solver.

Every table and key is optional; omitted values take the defaults of the paper study::

    [building]
    base_weight = 10.0            # [kip]
    floor_weights = [8.0, 8.0, 7.0]   # [kip], bottom to top
    story_model = "bilinear"      # "elastic" | "bilinear" | "imk"
    story_damping_ratio = 0.02    # [-] at story_damping_period [s]
    story_damping_period = 0.30
    story_heights = [39.0, 39.0, 39.0]   # [in], bottom to top (assumed quarter-scale default)
    p_delta = false               # story geometric stiffness −P/h (gravity of floors above)
    isolator_capacity = 7.0       # [in] isolator displacement capacity (collapse criterion)

    [building.story]              # parameters of the story material (per story_model)
    k0 = 42.799                   # [kip/in] (K0 for imk)
    Fy = 11.556                   # [kip]    (My for imk)
    b = 0.03                      # [-]      (alpha_s for imk; imk also theta_p, theta_pc, ...)

    [building.isolator]           # single friction pendulum, lumped
    R = 30.0                      # [in]
    mu = 0.06                     # [-] (mu_slow when mu_fast is given)
    u_y = 0.01                    # [in]
    # W defaults to the building's total weight [kip]; mu_fast, a [s/in] for rate dependence

    [walls]
    preset = "concrete"           # "concrete" | "steel"
    damping = "published"         # "published" | "consistent"
    law = "H"                     # E | V | J | H | M
    gap = 4.0                     # [in]
    sides = "both"                # "both" | "pos" | "neg"
    calibrate = false             # exact-restitution calibration at calibrate_v0 [in/s]
    calibrate_v0 = 10.0

    [walls.fe]                    # optional: a finite-element wall (modal) replaces the SDOF wall
    geometry = "wall.toml"        # wall geometry TOML (relative to the scenario file)
    mesh = "wall.vtu"             # optional: your own mesh (its dimension sets the model)
    model = "beam"                # "beam" | "plane" | "solid" (without a mesh)
    modes = 8                     # omit for automatic (flexibility and 4/t_c cut-off)
    flexibility = 0.99            # [-] automatic N: impact flexibility the modes must capture
    residual = true               # add the residual-flexibility vector of the modes left out
    damping_ratio = 2.0           # [-] every mode; default ξ_imp of the preset's SDOF wall

    [motion]
    source = "erzincan"           # "erzincan" | "at2" | "text" | "fema"
    path = "record.AT2"           # for at2/text (relative to the scenario file)
    dt = 0.01                     # [s], text only;  units = "g" (text only)
    record_set = "farfield"       # fema only; record_id = 1; component = "a"
    pga = 0.91                    # [g]; omit to keep the record's own amplitude
    time_scale = 0.5              # similitude factor on time
    extra_time = 2.0              # [s] of free vibration after the record

    [solver]
    rtol = 1e-4
    alpha = 0.0                   # HHT-α
    max_step = 0.0025             # [s] (default: the record's sample interval)
    record_every = 1

    [collapse]                    # optional: limit states checked every step (femoat.collapse)
    drift_ratio = 0.10            # [-] story drift ratio; omit for none
    isolator = true               # isolator displacement above isolator_capacity
    wall_displacement = 2.0       # [in] at the impact point; omit for none
    wall_force = 300.0            # [kip] contact force; omit for none
    stop = true                   # end the run at the first criterion reached

    [output]
    folder = "femoat_output"
    figures = true
"""

import tomllib
from dataclasses import dataclass
from pathlib import Path

from femoat.contact.laws import make_law
from femoat.integration.settings import Integrator
from femoat.structure.building import Building
from femoat.structure.materials import Bilinear, Elastic, FrictionPendulum, IMKBilinear
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.walls.presets import wall_preset

_KNOWN = {
    "building": {"base_weight", "floor_weights", "story_model", "story_damping_ratio",
                 "story_damping_period", "story", "isolator", "story_heights", "p_delta",
                 "isolator_capacity"},
    "collapse": {"drift_ratio", "isolator", "wall_displacement", "wall_force", "stop"},
    "walls": {"preset", "damping", "law", "gap", "sides", "calibrate", "calibrate_v0", "fe"},
    "walls.fe": {"geometry", "mesh", "model", "modes", "flexibility", "residual",
                 "damping_ratio"},
    "motion": {"source", "path", "dt", "units", "record_set", "record_id", "component", "pga",
               "time_scale", "extra_time", "column", "skip_rows"},
    "solver": {"rtol", "alpha", "max_step", "min_step", "newton_tol", "max_newton",
               "record_every", "contact_steps"},
    "output": {"folder", "figures"},
}


@dataclass(frozen=True)
class Scenario:
    """A parsed scenario: the model, the motion, the integrator and output options."""

    model: PoundingModel
    motion: object
    integrator: Integrator
    extra_time: float
    collapse: object
    output_folder: Path
    figures: bool
    source: dict


def _check_keys(table, allowed, where):
    unknown = set(table) - allowed
    if unknown:
        raise ValueError(f"{where}: unknown key(s) {sorted(unknown)}; allowed: {sorted(allowed)}.")


def building_from_dict(d):
    """A :class:`Building` from the ``[building]`` table."""
    d = dict(d)
    _check_keys(d, _KNOWN["building"], "[building]")
    floors = tuple(float(w) for w in d.get("floor_weights", (8.0, 8.0, 7.0)))
    base = float(d.get("base_weight", 10.0))
    model = d.get("story_model", "bilinear")
    story = dict(d.get("story", {}))
    if model == "elastic":
        mat = Elastic(k=float(story.pop("k", story.pop("k0", 42.799))))
    elif model == "bilinear":
        mat = Bilinear(**story)
    elif model == "imk":
        story.setdefault("theta_p", 1.0)
        story.setdefault("theta_pc", 3.0)
        mat = IMKBilinear(**story)
    else:
        raise ValueError(f"[building] story_model = {model!r}: use 'elastic', 'bilinear' or 'imk'.")
    iso = dict(d.get("isolator", {}))
    iso.setdefault("W", base + sum(floors))
    heights = d.get("story_heights")
    if heights is not None:
        if not isinstance(heights, list):
            raise ValueError(f"[building] story_heights = {heights!r} must be a list of heights "
                             "[in], one per story.")
        heights = tuple(heights)
    return Building(
        base_weight=base, floor_weights=floors, isolator=FrictionPendulum(**iso),
        stories=tuple(mat for _ in floors),
        story_damping_ratio=float(d.get("story_damping_ratio", 0.02)),
        story_damping_period=float(d.get("story_damping_period", 0.30)),
        story_heights=heights,
        p_delta=d.get("p_delta", False),
        isolator_capacity=d.get("isolator_capacity", 7.0),
    )


def collapse_from_dict(d):
    """The :class:`~femoat.collapse.CollapseCriteria` of a ``[collapse]`` table."""
    from femoat.collapse import CollapseCriteria

    d = dict(d)
    _check_keys(d, _KNOWN["collapse"], "[collapse]")
    return CollapseCriteria(**d)


def walls_from_dict(d, base_dir=Path("."), base_mass=None):
    """The moat walls (tuple of :class:`MoatWall`) from the ``[walls]`` table.

    base_mass : float or None  the base mat's mass [kip·s²/in], for the contact time that sets
        the automatic number of modes of a ``[walls.fe]`` wall (default: the law's m_eff)
    """
    d = dict(d)
    _check_keys(d, _KNOWN["walls"], "[walls]")
    preset = wall_preset(d.get("preset", "concrete"), damping=d.get("damping", "published"))
    law = make_law(d.get("law", "H"), preset.contact)
    if d.get("calibrate", False) and law.kind != "E":
        from femoat.impact.calibration import calibrate as calibrate_law  # scipy.integrate: 1 s

        law = calibrate_law(law, float(d.get("calibrate_v0", 10.0)))
    gap = float(d.get("gap", 4.0))
    sides = {"both": (1, -1), "pos": (1,), "neg": (-1,), "none": ()}.get(d.get("sides", "both"))
    if sides is None:
        raise ValueError(f"[walls] sides = {d.get('sides')!r}: use 'both', 'pos', 'neg' or 'none'.")
    wall = preset.wall
    if "fe" in d:
        wall = fe_wall_from_dict(d["fe"], law, wall.damping_ratio, base_dir, base_mass)
    return tuple(MoatWall(law, wall, gap, s) for s in sides)


def fe_wall_from_dict(d, law, damping_ratio, base_dir=Path("."), base_mass=None):
    """A :class:`~femoat.walls.ModalWall` from the ``[walls.fe]`` table.

    law : ContactLaw  the contact law (its stiffness sets the contact time t_c)
    damping_ratio : float  ξ [-] of every mode unless the table gives ``damping_ratio``
    """
    from femoat.walls.fe import beam_model, load_geometry, modal_analysis, plane_model, solid_model
    from femoat.walls.fe.mesh_io import read_mesh
    from femoat.walls.modal import ModalWall, contact_time

    d = dict(d)
    _check_keys(d, _KNOWN["walls.fe"], "[walls.fe]")
    if "geometry" not in d:
        raise ValueError("[walls.fe] needs geometry = 'wall.toml' (material, size, fixity, "
                         "impact height; see femoat wall --help).")
    geometry = load_geometry(_resolve(d["geometry"], base_dir))
    builders = {"beam": beam_model, "plane": plane_model, "solid": solid_model}
    mesh = None
    kind = d.get("model", "beam")
    if "mesh" in d:
        mesh = read_mesh(_resolve(d["mesh"], base_dir))
        dims = {1: "beam", 2: "plane", 3: "solid"}
        if "model" in d and dims[mesh.dim()] != kind:
            raise ValueError(f"[walls.fe] mesh is {mesh.dim()}D, which makes a "
                             f"{dims[mesh.dim()]} model, not model = {kind!r}.")
        kind = dims[mesh.dim()]
    if kind not in builders:
        raise ValueError(f"[walls.fe] model = {kind!r}: use 'beam', 'plane' or 'solid'.")
    model = builders[kind](geometry, mesh=mesh)
    modes = d.get("modes")
    m1 = modal_analysis(model, 1).M1
    t_c = contact_time(law, base_mass, m1)
    return ModalWall.from_fe(model, n_modes=modes, contact_duration=t_c,
                             flexibility_target=float(d.get("flexibility", 0.99)),
                             damping_ratio=float(d.get("damping_ratio", damping_ratio)),
                             residual=bool(d.get("residual", True)))


def _resolve(path, base_dir):
    p = Path(path)
    return p if p.is_absolute() else Path(base_dir) / p


def motion_from_dict(d, base_dir=Path(".")):
    """The ground motion from the ``[motion]`` table (scaled and time-scaled)."""
    from femoat import ground_motions as gmod

    d = dict(d)
    _check_keys(d, _KNOWN["motion"], "[motion]")
    source = d.get("source", "erzincan")
    if source == "erzincan":
        gm = gmod.erzincan_ns()
    elif source == "at2":
        gm = gmod.read_at2(_path(d, base_dir))
    elif source == "text":
        if "dt" not in d:
            raise ValueError("[motion] source = 'text' needs dt [s] (the sample interval).")
        gm = gmod.read_text(_path(d, base_dir), float(d["dt"]), units=d.get("units", "g"),
                            column=int(d.get("column", 0)), skip_rows=d.get("skip_rows"))
    elif source == "fema":
        gm = gmod.fema_p695_record(d.get("record_set", "farfield"), int(d.get("record_id", 1)),
                                   d.get("component", "a"))
    else:
        raise ValueError(f"[motion] source = {source!r}: use 'erzincan', 'at2', 'text' or 'fema'.")
    if source == "erzincan" and "pga" not in d:
        d["pga"] = gmod.PAPER_PGA
    if d.get("pga") is not None:
        gm = gm.scaled_to_pga(float(d["pga"]))
    ts = float(d.get("time_scale", 0.5 if source == "erzincan" else 1.0))
    if ts != 1.0:
        gm = gm.time_scaled(ts)
    return gm


def _path(d, base_dir):
    if "path" not in d:
        raise ValueError("[motion] needs path = '...' for this source.")
    return _resolve(d["path"], base_dir)


def scenario_from_dict(d, base_dir=Path(".")):
    """Build a :class:`Scenario` from a parsed TOML document."""
    _check_keys(d, set(_KNOWN), "scenario")
    from femoat.units import G

    building = building_from_dict(d.get("building", {}))
    model = PoundingModel(building, walls_from_dict(d.get("walls", {}), base_dir,
                                                    building.base_weight / G))
    motion_d = d.get("motion", {})
    motion = motion_from_dict(motion_d, base_dir)
    solver = dict(d.get("solver", {}))
    _check_keys(solver, _KNOWN["solver"], "[solver]")
    integ = Integrator(**solver)
    out = dict(d.get("output", {}))
    _check_keys(out, _KNOWN["output"], "[output]")
    collapse = collapse_from_dict(d["collapse"]) if "collapse" in d else None
    return Scenario(model=model, motion=motion, integrator=integ,
                    extra_time=float(motion_d.get("extra_time", 2.0)), collapse=collapse,
                    output_folder=Path(out.get("folder", "femoat_output")),
                    figures=bool(out.get("figures", True)), source=d)


def load_scenario(path):
    """Parse a scenario TOML file."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"scenario file {path} does not exist.")
    try:
        d = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML ({exc}).") from None
    return scenario_from_dict(d, path.parent)
