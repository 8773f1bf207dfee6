"""``[building]``, ``[building.story]`` and ``[building.isolator]``: a
:class:`~femoat.structure.building.Building`, or with ``plan = true`` a
:class:`~femoat.plan.PlanBuilding`.

A key left out takes the default of what it sets: :class:`Building`'s fields, the story
material's (every story gets the same material), the isolator's (``[building.isolator] type``
names its bearing kind, a key of :mod:`femoat.bearings.registry`: "fp" by default, the single
:class:`FrictionPendulum`). Two defaults are
the scenario's own: the isolator carries the building's total weight W [kip], and a
deteriorating ("imk") story, which has no default capping deformations, gets
:data:`IMK_CAPPING`.

In plan (``plan = true``) the building is this 1D building in both directions
(:meth:`PlanBuilding.from_building`): the same stories in x and y, the friction pendulum made
bidirectional (friction coupled in plan), ``isolator_capacity`` measured in plan (|u| of the
base mat). The y stories may differ: ``story_model_y`` and ``[building.story_y]``
(:data:`PLAN_KEYS`).
"""

import dataclasses
import math

from femoat.bearings import registry as bearing_registry
from femoat.scenario.reading import (check_keys, field_default, field_defaults, flag, naming,
                                     number, numbers, numeric_table, one_of, subtable, text)
from femoat.structure.building import DEFAULT_STORY_HEIGHT, Building
from femoat.structure.materials import Bilinear, Elastic, FrictionPendulum, IMKBilinear

KEYS = ("base_weight", "floor_weights", "story_model", "story_damping_ratio",
        "story_damping_period", "story", "isolator", "story_heights", "p_delta",
        "isolator_capacity", "plan")
PLAN_KEYS = ("story_model_y", "story_y")
"""Keys only a plan building reads: the y stories' material and its parameters. Left out, the y
stories are the x ones; ``[building.story_y]`` overrides ``[building.story]`` key by key when
``story_model_y`` is ``story_model`` (the default), and stands alone for another model."""

STORY_MODELS = {"elastic": Elastic, "bilinear": Bilinear, "imk": IMKBilinear}
"""``story_model`` → the material of every story."""

ISOLATOR_TYPE = "fp"
"""``[building.isolator] type`` left out: the single friction pendulum (the paper's)."""

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
    out["isolator"] = {"type": ISOLATOR_TYPE,
                       **field_defaults(FrictionPendulum, leave_out=("W",))}
    out["plan"] = False  # the scenario's own: a 1D building unless the file says plan = true
    return out


def is_plan(d):
    """``plan`` of a ``[building]`` table: whether the scenario is a plan scenario."""
    return flag(d, "plan", defaults()["plan"], "[building]")


def _story(model, story, where="[building.story]"):
    """The material of every story from ``[building.story]`` (or the table ``where``)."""
    if model == "elastic":  # k (or k0, as for the other models); default: the bilinear k0
        check_keys(story, {"k", "k0"}, where)
        key = "k" if "k" in story or "k0" not in story else "k0"
        k = number(story, key, field_default(Bilinear, "k0"), where, "kip/in")
        with naming(where):
            return Elastic(k=k)
    if model == "imk":
        story = {**IMK_CAPPING, **story}
    return numeric_table(story, STORY_MODELS[model], where)


def _isolator(iso, weight):
    """The isolator of ``[building.isolator]``: the bearing kind its ``type`` names (a key of
    :mod:`femoat.bearings.registry`, default "fp"), on one axis, its parameters from the other
    keys (or, for a kind with ``GEOMETRY_KEYS``, from its geometry: :func:`_geometry_isolator`);
    a bearing with a weight W [kip] carries ``weight`` unless the table gives W."""
    where = "[building.isolator]"
    iso = dict(iso)
    key = text(iso, "type", ISOLATOR_TYPE, where)
    iso.pop("type", None)
    kind = bearing_registry.by_key(key)
    if kind is None:
        raise ValueError(f"{where} type = {key!r}: use {one_of(bearing_registry.keys())}.")
    cls = kind.AXIS_CLASS
    if "W" in {f.name for f in dataclasses.fields(cls)}:
        iso.setdefault("W", weight)
    if set(iso) & set(getattr(kind, "GEOMETRY_KEYS", ())):
        return _geometry_isolator(iso, kind, where)
    return numeric_table(iso, cls, where)


def _geometry_isolator(iso, kind, where):
    """The bearing of an isolator table that gives its kind's geometry, ``kind.GEOMETRY_KEYS``
    (the triple friction pendulum's radii R1..R3, pivot heights h1..h3 and nominal capacities
    d1_nominal..d3_nominal [in]), in place of the fields it determines,
    ``kind.GEOMETRY_REPLACES`` (L1..L3, d1..d3): ``AXIS_CLASS.from_geometry`` of all the
    geometry keys (they have no defaults) and the class's other fields."""
    cls, geometry, replaced = kind.AXIS_CLASS, kind.GEOMETRY_KEYS, kind.GEOMETRY_REPLACES
    given = [k for k in geometry if k in iso]
    mixed = [k for k in replaced if k in iso]
    if mixed:
        raise ValueError(
            f"{where} {', '.join(mixed)} with {', '.join(given)}: give the bearing either by "
            f"{', '.join(replaced)} or by its geometry, which determines them, not both: remove "
            f"{', '.join(mixed)} (or the geometry keys).")
    missing = [k for k in geometry if k not in iso]
    if missing:
        raise ValueError(
            f"{where} {', '.join(missing)}: missing; a bearing given by its geometry needs all of "
            f"{', '.join(geometry)} (they have no defaults), or give {', '.join(replaced)} "
            "instead.")
    check_keys(iso, set(geometry) | ({f.name for f in dataclasses.fields(cls)} - set(replaced)),
               where)
    for k, value in iso.items():  # ranges (and whether inf is allowed) are the class's to check
        if not isinstance(value, (int, float)) or isinstance(value, bool) or math.isnan(value):
            raise ValueError(f"{where} {k} = {value!r}: expected a number.")
    with naming(where):
        return cls.from_geometry(**iso)


def building_from_dict(d):
    """A :class:`Building` from the ``[building]`` table (``plan = true``: use
    :func:`plan_building_from_dict`)."""
    d = dict(d)
    where = "[building]"
    given = sorted(set(d) & set(PLAN_KEYS))
    if given:
        raise ValueError(f"{where} {', '.join(given)}: the y stories of a plan building; add "
                         "plan = true to [building] (or remove the key).")
    check_keys(d, KEYS, where)
    if is_plan(d):
        raise ValueError(f"{where} plan = true: a building in plan, which the 1D building reader "
                         "cannot build: read the tables with femoat.scenario.model_from_dict "
                         "(or plan_building_from_dict), as scenario files are.")
    default = defaults()
    floors = numbers(d, "floor_weights", default["floor_weights"], where, "kip")
    base = number(d, "base_weight", default["base_weight"], where, "kip")
    model = text(d, "story_model", default["story_model"], where)
    story = subtable(d, "story", where)
    if model not in STORY_MODELS:
        raise ValueError(f"{where} story_model = {model!r}: use {one_of(STORY_MODELS)}.")
    material = _story(model, story)
    isolator = _isolator(subtable(d, "isolator", where), base + sum(floors))
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


def plan_building_from_dict(d):
    """A :class:`~femoat.plan.PlanBuilding` from a ``[building]`` table: the 1D building of its
    keys in both directions, with the y stories of ``story_model_y`` and ``[building.story_y]``
    when given (module docstring)."""
    from femoat.plan import PlanBuilding

    d = dict(d)
    where = "[building]"
    check_keys(d, KEYS + PLAN_KEYS, where)
    if not is_plan(d):
        raise ValueError(f"{where} plan = false: plan_building_from_dict reads a plan building "
                         "(plan = true).")
    plan = {key: d.pop(key) for key in PLAN_KEYS if key in d}
    d.pop("plan")
    one_d = building_from_dict(d)
    stories_y = None
    if plan:
        model = text(d, "story_model", defaults()["story_model"], where)
        model_y = text(plan, "story_model_y", model, where)
        if model_y not in STORY_MODELS:
            raise ValueError(f"{where} story_model_y = {model_y!r}: use {one_of(STORY_MODELS)}.")
        story_y = subtable(plan, "story_y", where)
        if model_y == model:  # overrides of the x stories' parameters
            story_y = {**subtable(d, "story", where), **story_y}
        material = _story(model_y, story_y, "[building.story_y]")
        stories_y = tuple(material for _ in one_d.floor_weights)
    with naming(where):
        return PlanBuilding.from_building(one_d, stories_y=stories_y)
