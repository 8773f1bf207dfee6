"""``[building]``, ``[building.story]`` and ``[building.isolator]``: a
:class:`~femoat.structure.building.Building`.

A key left out takes the default of what it sets: :class:`Building`'s fields, the story
material's (every story gets the same material), :class:`FrictionPendulum`'s. Two defaults are
the scenario's own: the isolator carries the building's total weight W [kip], and a
deteriorating ("imk") story, which has no default capping deformations, gets
:data:`IMK_CAPPING`.
"""

import dataclasses

from femoat.scenario.reading import (check_keys, field_default, field_defaults, flag, naming,
                                     number, numbers, numeric_table, one_of, subtable, text)
from femoat.structure.building import DEFAULT_STORY_HEIGHT, Building
from femoat.structure.materials import Bilinear, Elastic, FrictionPendulum, IMKBilinear

KEYS = ("base_weight", "floor_weights", "story_model", "story_damping_ratio",
        "story_damping_period", "story", "isolator", "story_heights", "p_delta",
        "isolator_capacity")

STORY_MODELS = {"elastic": Elastic, "bilinear": Bilinear, "imk": IMKBilinear}
"""``story_model`` → the material of every story."""

IMK_CAPPING = {"theta_p": 1.0, "theta_pc": 3.0}
"""Plastic deformation before capping θp and post-capping deformation θpc [in] of an "imk"
story whose ``[building.story]`` leaves them out."""


def _model_name(material):
    return next(name for name, cls in STORY_MODELS.items() if isinstance(material, cls))


def defaults():
    """The ``[building]`` table of an empty scenario (TOML-shaped): Building's defaults, its
    default story material's and the friction pendulum's (W: the building's weight)."""
    out = field_defaults(Building, leave_out=("isolator", "stories"))
    out["floor_weights"] = list(out["floor_weights"])
    story = field_default(Building, "stories")[0]
    out["story_model"] = _model_name(story)
    out["story"] = {k: v for k, v in dataclasses.asdict(story).items() if v is not None}
    out["isolator"] = field_defaults(FrictionPendulum, leave_out=("W",))
    return out


def _story(model, story):
    """The material of every story from ``[building.story]``."""
    where = "[building.story]"
    if model == "elastic":  # k (or k0, as for the other models); default: the bilinear k0
        check_keys(story, {"k", "k0"}, where)
        key = "k" if "k" in story or "k0" not in story else "k0"
        k = number(story, key, field_default(Bilinear, "k0"), where, "kip/in")
        with naming(where):
            return Elastic(k=k)
    if model == "imk":
        story = {**IMK_CAPPING, **story}
    return numeric_table(story, STORY_MODELS[model], where)


def building_from_dict(d):
    """A :class:`Building` from the ``[building]`` table."""
    d = dict(d)
    where = "[building]"
    check_keys(d, KEYS, where)
    default = defaults()
    floors = numbers(d, "floor_weights", default["floor_weights"], where, "kip")
    base = number(d, "base_weight", default["base_weight"], where, "kip")
    model = text(d, "story_model", default["story_model"], where)
    story = subtable(d, "story", where)
    if model not in STORY_MODELS:
        raise ValueError(f"{where} story_model = {model!r}: use {one_of(STORY_MODELS)}.")
    material = _story(model, story)
    iso = subtable(d, "isolator", where)
    iso.setdefault("W", base + sum(floors))
    isolator = numeric_table(iso, FrictionPendulum, "[building.isolator]")
    ratio = number(d, "story_damping_ratio", default["story_damping_ratio"], where)
    period = number(d, "story_damping_period", default["story_damping_period"], where, "s")
    heights = d.get("story_heights")
    if heights is not None:
        heights = numbers(d, "story_heights", [DEFAULT_STORY_HEIGHT] * len(floors), where, "in")
    capacity = d.get("isolator_capacity", default["isolator_capacity"])
    if not (isinstance(capacity, (int, float)) and not isinstance(capacity, bool)):
        raise ValueError(f"{where} isolator_capacity = {capacity!r}: expected a number [in].")
    with naming(where):
        return Building(base_weight=base, floor_weights=floors, isolator=isolator,
                        stories=tuple(material for _ in floors), story_damping_ratio=ratio,
                        story_damping_period=period, story_heights=heights,
                        p_delta=flag(d, "p_delta", default["p_delta"], where),
                        isolator_capacity=float(capacity))
