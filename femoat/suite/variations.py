"""``[variations]``: scenario keys in dotted form, each with a list, run as a cartesian product.

``"walls.law" = ["E", "V"]`` and ``"walls.gap" = [3, 4]`` make four variations. A key is
``table.key`` or ``table.subtable.key`` of the model tables of a scenario file (``building``,
``building.story``, ``building.isolator``, ``walls``, ``walls.fe``, ``solver``, ``collapse``; a plan suite's
``moat``, ``moat.+x`` (one wall: ``"moat.+x.gap"``), ``moat.fe``, ``building.story_y``);
anything else is rejected by name before any run starts.
"""

import copy
import dataclasses
import itertools

MODEL_TABLES = ("building", "walls", "moat", "solver", "collapse")


def allowed_keys():
    """{table path: allowed keys} of the model tables (from femoat.scenario and the materials)."""
    from femoat import scenario
    from femoat.scenario.building import STORY_MODELS
    from femoat.bearings import registry

    known = {}
    for keys in (scenario.KEYS, scenario.PLAN_KEYS):
        for table, names in keys.items():
            if table.split(".")[0] in MODEL_TABLES:
                known.setdefault(table.replace('"', ""), set()).update(names)
    known["building.story"] = {f.name for m in STORY_MODELS.values()
                               for f in dataclasses.fields(m)} | {"k0"}
    known["building.story_y"] = known["building.story"]
    known["building.isolator"] = {"type"} | {  # every bearing kind's parameters
        f.name for cls in registry.axis_classes() for f in dataclasses.fields(cls)} | {
        key for i in range(len(registry.kinds()))  # and the geometry a kind may take instead
        for key in getattr(registry.module(i), "GEOMETRY_KEYS", ())}
    return known


def variations_from_dict(d, plan=False):
    """``(keys, combos)``: the varied dotted keys in file order and one dict per combination;
    ``plan`` a plan suite (its walls are ``moat``, a 1D suite's ``walls``)."""
    known = allowed_keys()
    keys = list(d)
    for key in keys:
        table, _, leaf = key.rpartition(".")
        top, _, rest = key.partition(".")
        if plan and top == "walls":
            raise ValueError(f"[variations] {key!r}: a plan suite's walls are [moat]; vary "
                             f"'moat.{rest}' (every wall) or 'moat.+x.{rest}' (one wall).")
        if not plan and top == "moat":
            raise ValueError(f"[variations] {key!r}: [moat] is a plan suite's; vary "
                             f"'walls.{rest}', or add plan = true to [building].")
        if table not in known or leaf not in known[table]:
            raise ValueError(
                f"[variations] {key!r} is not a scenario key; use 'table.key' with table in "
                f"{sorted(known)} (e.g. 'walls.law', 'walls.gap', 'building.story.Fy').")
        values = d[key]
        if not isinstance(values, list) or not values:
            raise ValueError(f"[variations] {key!r} = {values!r}: give a non-empty list of values.")
        if len({repr(v) for v in values}) != len(values):
            raise ValueError(f"[variations] {key!r} lists a value twice: {values!r}.")
    combos = [dict(zip(keys, vals)) for vals in itertools.product(*(d[k] for k in keys))]
    return keys, combos


def apply(tables, combo):
    """A deep copy of the model ``tables`` ({'building': {...}, ...}) with ``combo`` set in."""
    out = copy.deepcopy(tables)
    for key, value in combo.items():
        *path, leaf = key.split(".")
        node = out
        for part in path:
            node = node.setdefault(part, {})
        node[leaf] = value
    return out


def label(combo):
    """A short text label, e.g. ``walls.law=E, walls.preset=steel`` (``base`` when empty)."""
    return ", ".join(f"{k}={v}" for k, v in combo.items()) or "base"
