"""``[solver]`` and ``[collapse]``: the :class:`~femoat.integration.settings.Integrator` and the
:class:`~femoat.collapse.CollapseCriteria`. Their keys are the fields of these dataclasses and
a key left out takes the field's default (the method's own rtol when none is given)."""

import dataclasses

from femoat.collapse import CollapseCriteria
from femoat.integration.settings import METHODS, Integrator
from femoat.scenario.reading import check_keys, field_defaults, naming, numeric_table

KEYS = tuple(f.name for f in dataclasses.fields(Integrator))
COLLAPSE_KEYS = tuple(f.name for f in dataclasses.fields(CollapseCriteria) if f.name != "extra")
"""The ``[collapse]`` keys: the built-in criteria and ``stop``; ``extra`` (criteria defined in
Python, :mod:`femoat.collapse`) has no form in a file."""


def defaults():
    """The ``[solver]`` table of an empty scenario (rtol and max_step, None by default, left
    out: the method's rtol and the record's sample interval)."""
    return field_defaults(Integrator)


def solver_from_dict(d):
    """The Integrator of a ``[solver]`` table (numbers, and the method's name)."""
    d = dict(d)
    method = d.pop("method", None)
    if method is not None and method not in METHODS:
        raise ValueError(f"[solver] method = {method!r}: use one of {list(METHODS)}.")
    integ = numeric_table(d, Integrator, "[solver]")  # the numbers checked here
    if method is None:
        return integ
    with naming("[solver]"):
        return Integrator(method=method, **d)  # (the method's own default rtol if none given)


def collapse_from_dict(d):
    """The CollapseCriteria of a ``[collapse]`` table."""
    d = dict(d)
    check_keys(d, COLLAPSE_KEYS, "[collapse]")
    with naming("[collapse]"):
        return CollapseCriteria(**d)
