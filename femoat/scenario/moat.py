"""``[moat]`` and ``[moat."+x"]`` ... ``[moat."-y"]``: the walls of a plan scenario's
rectangular moat (:class:`~femoat.plan.PlanWall`, one per side).

``[moat]`` is the default wall of every side, with the keys of ``[walls]`` (preset, damping,
law, gap, calibrate, calibrate_v0 and an optional ``[moat.fe]`` wall, read by
:func:`~femoat.scenario.walls.contact_from_dict`) plus ``friction``, the Coulomb coefficient
μ_w [-] of the base mat sliding along a wall in contact; ``sides`` lists the walls the moat has.
A side's own table (``[moat."+x"]``, the TOML key quoted; a typographic minus "−x" reads as
"-x") overrides the default key by key; its ``fe`` table replaces the default's.

Defaults are :func:`~femoat.plan.rectangular_moat`'s (so an empty ``[moat]`` is
:class:`~femoat.plan.PlanModel`'s moat: the paper's concrete wall, Hertzdamp law, 4 in gap on all
four sides, frictionless), and ``[walls]``'s own for calibrate and calibrate_v0. An error names
the table the wrong value came from: ``[moat."+x"]`` when the side sets it, ``[moat]`` otherwise.
"""

import dataclasses
from pathlib import Path

from femoat.plan.moat import SIDES, PlanWall, rectangular_moat, wall_side
from femoat.scenario import walls
from femoat.scenario.reading import check_keys, naming, number, parameter_default, subtable

SIDE_KEYS = ("preset", "damping", "law", "gap", "friction", "calibrate", "calibrate_v0", "fe")
"""The keys of a side's table, and of ``[moat]`` as the default of every side."""
KEYS = SIDE_KEYS + ("sides",)
"""The keys of ``[moat]`` besides the side tables ``"+x"``, ``"-x"``, ``"+y"``, ``"-y"``."""
_CONTACT_KEYS = ("preset", "damping", "law", "calibrate", "calibrate_v0", "fe")
"""The keys that make a side's contact law and wall (the rest: its gap and friction)."""


def defaults():
    """The ``[moat]`` table of a plan scenario without one (TOML-shaped)."""
    out = {key: parameter_default(rectangular_moat, key)
           for key in ("preset", "damping", "law", "gap", "friction")}
    own = walls.defaults()
    out.update(calibrate=own["calibrate"], calibrate_v0=own["calibrate_v0"],
               sides=list(parameter_default(rectangular_moat, "sides")))
    return out


def moat_from_dict(d, base_dir=Path("."), base_mass=None):
    """The walls (tuple of :class:`~femoat.plan.PlanWall`, in SIDES order) of a ``[moat]``
    table.

    base_mass : float or None  the base mat's mass [kip·s²/in], for a ``fe`` wall's automatic
        number of modes (as :func:`~femoat.scenario.walls.walls_from_dict`)
    """
    d = dict(d)
    where = "[moat]"
    overrides = _side_tables(d)
    check_keys(d, KEYS, where)
    default = defaults()
    sides = _sides(d, default)
    for side in overrides:
        if side not in sides:
            raise ValueError(f'[moat."{side}"]: the moat has no {side} wall (sides = '
                             f'{list(sides)}): add "{side}" to [moat] sides or remove the table.')
    base = {**default, **{k: v for k, v in d.items() if k != "sides"}}  # every side's wall
    shared = walls.contact_from_dict(d, default, where, base_dir, base_mass)
    out = []
    for side in sides:
        own = overrides.get(side, {})
        table = f'[moat."{side}"]'
        check_keys(own, SIDE_KEYS, table)
        contact = shared  # one law and wall for the sides that keep the default's
        if any(k in own for k in _CONTACT_KEYS):
            contact = walls.contact_from_dict({**base, **own}, base, table, base_dir, base_mass)
        out.append(_wall(side, contact, own, base, table))
    return tuple(out)


def _wall(side, contact, own, base, table):
    """One side's PlanWall; a range error names the table its gap or friction came from."""
    law, wall = contact
    origin = {key: table if key in own else "[moat]" for key in ("gap", "friction")}
    value, example = {**base, **own}, defaults()
    gap = number(value, "gap", example["gap"], origin["gap"], "in")
    friction = number(value, "friction", example["friction"], origin["friction"])
    with naming(origin["gap"]):
        built = PlanWall(law, wall, gap, side)
    with naming(origin["friction"]):
        return dataclasses.replace(built, friction=friction)


def _side_tables(d):
    """Pop the side tables (``"+x"``, ... and their typographic spellings) out of ``d``:
    {canonical side: table}. A table under another name is not a wall side: the error says so."""
    out = {}
    for key in [k for k, v in d.items() if isinstance(v, dict) and k != "fe"]:
        with naming(f'[moat."{key}"]:'):
            side = wall_side(key)
        if side in out:
            raise ValueError(f'[moat."{key}"]: a second table for the {side} wall; give one.')
        out[side] = subtable(d, key, "[moat]")
        del d[key]
    return out


def _sides(d, default):
    """``sides`` of ``[moat]``: the canonical sides, in SIDES order."""
    value = d.get("sides", default["sides"])
    if not (isinstance(value, list) and all(isinstance(s, str) for s in value)):
        raise ValueError(f"[moat] sides = {value!r}: expected a list of wall sides, e.g. "
                         f"sides = {list(SIDES)!r} (or [] for no moat).")
    with naming("[moat] sides:"):
        sides = [wall_side(s) for s in value]
    doubled = sorted({s for s in sides if sides.count(s) > 1})
    if doubled:
        raise ValueError(f"[moat] sides = {value!r}: {', '.join(doubled)} given twice; name each "
                         "wall once.")
    return tuple(s for s in SIDES if s in sides)


def wall_label(d):
    """The walls' name in reports: the presets of the sides (with "FE" for a finite-element
    wall), joined by " / " when they differ; "none" without walls."""
    d = dict(d)
    overrides = _side_tables(d)
    default = defaults()

    def label(t):
        return str(t.get("preset", d.get("preset", default["preset"]))) + \
            (" FE" if "fe" in t or "fe" in d else "")

    names = [label(overrides.get(side, {})) for side in _sides(d, default)]
    return " / ".join(dict.fromkeys(names)) or "none"
