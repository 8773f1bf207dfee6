"""``[walls]`` and ``[walls.fe]``: the moat walls (:class:`~femoat.structure.pounding.MoatWall`),
their contact law and, optionally, a finite-element wall reduced to modes.

Defaults: the gap is :class:`MoatWall`'s, the damping :func:`~femoat.walls.wall_preset`'s; the
finite-element wall's are its wall kind's (:mod:`femoat.walls.kinds`: the first kind, or the
first of the mesh's dimension) and :meth:`ModalWall.from_fe`'s, every mode damped at the preset
SDOF wall's ξ_imp. The rest are the scenario's own (:data:`OWN_DEFAULTS`).
"""

from pathlib import Path

from femoat.contact.laws import make_law
from femoat.scenario.reading import (check_keys, field_default, flag, integer, naming, number,
                                     one_of, parameter_default, resolve, subtable, text)
from femoat.structure.pounding import MoatWall
from femoat.walls import ModalWall, wall_preset

KEYS = ("preset", "damping", "law", "gap", "sides", "calibrate", "calibrate_v0", "fe")
FE_KEYS = ("geometry", "mesh", "model", "modes", "flexibility", "residual", "damping_ratio")

SIDES = {"both": (1, -1), "pos": (1,), "neg": (-1,), "none": ()}
"""``sides`` → the sides (+1, −1) that have a wall."""

OWN_DEFAULTS = dict(preset="concrete", law="H", sides="both", calibrate=False, calibrate_v0=10.0)
"""The paper's concrete wall and Hertzdamp law on both sides; ``calibrate_v0`` [in/s]."""


def defaults():
    """The ``[walls]`` table of an empty scenario (no finite-element wall: see
    :func:`fe_defaults`)."""
    return dict(OWN_DEFAULTS, damping=parameter_default(wall_preset, "damping"),
                gap=field_default(MoatWall, "gap"))


def fe_defaults():
    """The ``[walls.fe]`` keys that have a default (geometry is required; modes are chosen
    automatically; damping_ratio is the preset wall's ξ_imp)."""
    from femoat.walls.kinds import default_kind

    return dict(model=default_kind().name,
                flexibility=parameter_default(ModalWall.from_fe, "flexibility_target"),
                residual=parameter_default(ModalWall.from_fe, "residual"))


def walls_from_dict(d, base_dir=Path("."), base_mass=None):
    """The moat walls (tuple of :class:`MoatWall`) from the ``[walls]`` table.

    base_mass : float or None  the base mat's mass [kip·s²/in], for the contact time that sets
        the automatic number of modes of a ``[walls.fe]`` wall (default: the law's m_eff)
    """
    d = dict(d)
    where = "[walls]"
    check_keys(d, KEYS, where)
    default = defaults()
    law, wall = contact_from_dict(d, default, where, base_dir, base_mass)
    gap = number(d, "gap", default["gap"], where, "in")
    side = text(d, "sides", default["sides"], where)
    if side not in SIDES:
        raise ValueError(f"{where} sides = {side!r}: use {one_of(SIDES)}.")
    with naming(where):
        return tuple(MoatWall(law, wall, gap, s) for s in SIDES[side])


def contact_from_dict(d, default, where, base_dir=Path("."), base_mass=None):
    """The contact law and the wall behind it of a wall table (``[walls]``, or a plan
    scenario's ``[moat]`` and its sides): preset, damping, law, calibrate, calibrate_v0 and the
    optional ``fe`` sub-table (``where`` + ".fe"); a key left out takes ``default``'s.

    Returns (ContactLaw, SdofWall or ModalWall).
    """
    name, damping = text(d, "preset", default["preset"], where), \
        text(d, "damping", default["damping"], where)
    kind = text(d, "law", default["law"], where)
    with naming(f"{where} preset = {name!r}, damping = {damping!r}:"):
        preset = wall_preset(name, damping=damping)
    with naming(f"{where} law = {kind!r}:"):
        law = make_law(kind, preset.contact)
    if flag(d, "calibrate", default["calibrate"], where) and law.calibratable:
        from femoat.impact.calibration import calibrate as calibrate_law  # scipy.integrate: 1 s

        law = calibrate_law(law, number(d, "calibrate_v0", default["calibrate_v0"], where, "in/s"))
    wall = preset.wall
    if "fe" in d:
        wall = fe_wall_from_dict(subtable(d, "fe", where), law, wall.damping_ratio, base_dir,
                                 base_mass, where=f"{where[:-1]}.fe]")
    return law, wall


def fe_wall_from_dict(d, law, damping_ratio, base_dir=Path("."), base_mass=None,
                      where="[walls.fe]"):
    """A :class:`~femoat.walls.ModalWall` from the ``[walls.fe]`` table (or the ``fe`` sub-table
    named ``where``).

    law : ContactLaw  the contact law (its stiffness sets the contact time t_c)
    damping_ratio : float  ξ [-] of every mode unless the table gives ``damping_ratio``
    """
    from femoat.walls import kinds
    from femoat.walls.fe import load_geometry
    from femoat.walls.fe.mesh_io import read_mesh
    from femoat.walls.modal import contact_time

    d = dict(d)
    check_keys(d, FE_KEYS, where)
    if "geometry" not in d:
        raise ValueError(f"{where} needs geometry = 'wall.toml' (material, size, fixity, "
                         "impact height; see femoat wall --help).")
    default = fe_defaults()
    geometry = load_geometry(resolve(text(d, "geometry", "wall.toml", where), base_dir))
    name = text(d, "model", default["model"], where) if "model" in d else None
    mesh = None
    if "mesh" in d:
        mesh = read_mesh(resolve(text(d, "mesh", "wall.vtu", where), base_dir))
    with naming(where):
        kind = kinds.kind_of_mesh(mesh, name) if mesh is not None else \
            kinds.wall_kind(name or default["model"])
    modes = integer(d, "modes", 8, where) if "modes" in d else None
    flexibility = number(d, "flexibility", default["flexibility"], where)
    zeta = number(d, "damping_ratio", damping_ratio, where)
    residual = flag(d, "residual", default["residual"], where)
    model = kind.build(geometry, mesh=mesh)
    # the contact time from the wall's own M1: one modal analysis per wall
    t_c = lambda result: contact_time(law, base_mass, result.M1)  # noqa: E731
    return ModalWall.from_fe(model, n_modes=modes, contact_duration=t_c,
                             flexibility_target=flexibility, damping_ratio=zeta,
                             residual=residual)
