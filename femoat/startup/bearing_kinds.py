"""Which bearing kinds a command compiles the solver loop for: the paper's bearing alone, or all.

Every bearing kind's kernels sit in the one compiled loop, so a process whose models all stand
on the paper's single friction pendulum would pay the compile of the others' too
(``docs/startup.md`` measures it). A command that knows its models before its first run (the
paper study, a scenario, a suite, a study) asks :func:`select_for`, which compiles the loop for
the pendulum alone when that is all the models need, else for every kind. Two loops at most, so
that a user who runs the paper study, then a plan run of the pendulum, then a triple pendulum
compiles twice, never once per combination of kinds.

``FEMOAT_BEARINGS`` (``all``, or kinds' scenario keys such as ``fp,tfp``) overrides the choice;
the test session sets ``all``, so that the commands it runs share its one loop. A Python user
gets every kind unless they call :func:`femoat.bearings.registry.select` first.
"""

import os

from femoat.bearings import registry

PAPER_KIND = 0
"""The paper's bearing (the single friction pendulum): the registry's first kind."""


def isolator_of(model):
    """The isolator of ``model`` (a 1D or plan model or building, or a bearing itself)."""
    building = getattr(model, "building", model)
    return getattr(building, "isolator", building)


def kinds_for(models, env=None):
    """The bearing kinds (indices) a process running ``models`` compiles: ``FEMOAT_BEARINGS``
    if set, else the paper's bearing alone when no model needs another kind, else every kind."""
    env = os.environ if env is None else env
    given = env.get(registry.ENV, "").strip()
    if given:
        return registry.indices(given)
    needed = {registry.kind_of(isolator_of(m)) for m in models} - {None}
    if needed <= {PAPER_KIND}:
        return (PAPER_KIND,)
    return tuple(range(len(registry.kinds())))


def select_for(models):
    """Compile this process's loop for :func:`kinds_for` ``(models)`` (a no-op once the loop is
    compiled for every kind); returns the kinds' scenario keys."""
    chosen = registry.select(tuple(registry.keys()[k] for k in kinds_for(models)))
    return tuple(registry.keys()[k] for k in chosen)
