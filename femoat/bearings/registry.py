"""The bearing registry: which bearing kinds the compiled loop knows, and their dispatcher.

A bearing kind is one module (:mod:`femoat.bearings`' docstring lists what it provides); this
list names them. numba cannot add a branch at run time, so the loop calls the kinds through a
generated module, :mod:`femoat.bearings.dispatch`, committed beside this file: one ``if kind ==``
chain per kernel. Importing the dispatcher checks that it was generated from this list; after
adding a line here, write it anew with ``python -m femoat.bearings.registry`` (a test checks that
the committed file is what this list generates).

A kind's index in :data:`KINDS` is its code in the loop's bearing rows (plan) and, offset by
:data:`AXIS_CODE_START`, its material code on one axis (the isolator element of a 1D model), so
the list is append-only: an index, once given, is kept.

:func:`register` adds a kind for one process (a test's throwaway kind, a user's own bearing): it
writes the dispatcher with that kind to a folder of its own and points numba's cache there too
(numba keys a compiled loop on its own source file only, not on the dispatcher it inlines).
"""

import hashlib
import importlib
import importlib.util
import os
import sys
from pathlib import Path

KINDS = (
    "femoat.bearings.friction_pendulum",
    "femoat.bearings.lead_rubber",
    "femoat.bearings.triple_friction_pendulum",
)
"""The bearing kinds' modules, in code order (append only)."""

AXIS_CODE_START = 3
"""The material code of kind 0 on one axis (:mod:`femoat.structure.materials.codes`: the codes
below it are the story materials)."""

KERNELS = {
    # name in the dispatcher: (name in the kind's module, arguments after ``kind``, returns)
    "bearing_axis_trial": ("axis_trial", "p, s, u, v", "(np.nan, np.nan, np.nan)"),
    "bearing_axis_commit": ("axis_commit", "p, s, u, v", None),
    "bearing_axis_energy": ("axis_energy", "p, s", "np.nan"),
    "bearing_plan_trial": ("plan_trial", "p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau, f, k, c",
                           None),
    "bearing_plan_commit": ("plan_commit", "p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau", None),
    "bearing_plan_energy": ("plan_energy", "p, s", "np.nan"),
    "bearing_plan_branch": ("plan_branch", "p, s, ux, uy", "-1"),
    "bearing_plan_turn_direction": ("plan_turn_direction", "s", "(0.0, 0.0)"),
}
"""The kernels every kind provides, and what the dispatcher returns for an unknown kind."""

RATE_KERNELS = {
    "bearing_plan_rate_active": ("plan_rate_active", "p, s, vx, vy", "False"),
    "bearing_plan_rate_state": ("plan_rate_state", "p, s, z", "0"),
    "bearing_plan_rate": ("plan_rate", "p, s, ux, uy, vx, vy, z, g, J", None),
    "bearing_plan_rate_force": ("plan_rate_force", "p, s, ux, uy, vx, vy, z, f, k, c", None),
    "bearing_plan_rate_commit": ("plan_rate_commit", "p, s, ux, uy, vx, vy, z", None),
    "bearing_plan_rate_turn": ("plan_rate_turn", "p, s, ux, uy, vx, vy, ax, ay, z, g, J",
                               "(np.nan, np.nan)"),
    "bearing_plan_rate_branch": ("plan_rate_branch", "p, s, ux, uy, z", "-1"),
    "bearing_plan_rate_fsal": ("plan_rate_fsal", "p, s", "-1"),
}
"""The rate form a kind may declare (all five or none; :mod:`femoat.bearings`' docstring): its
friction state as an ODE for the coupled-friction step (:mod:`femoat.integration.methods.ark5`).
The state is a vector ``z`` of the kind's ``N_RATE_PLAN`` values (the arrays the loop passes are
:func:`rate_width` long: a kind uses their first ``N_RATE_PLAN``); ``plan_rate_state`` writes the
committed one and returns its width, ``plan_rate`` writes the rate ż = g(z; u, v) into ``g`` and
∂g/∂z into ``J``; ``plan_rate_turn`` returns (r, ṙ), the loading measure whose crossing of zero
downwards unloads the bearing (the pendulum's z·v) and its rate at the acceleration (ax, ay)
(``g``, ``J`` scratch); ``plan_rate_branch`` the branch at a trial point of a step that carries
z, with z given (the kink search follows z along the step); ``plan_rate_fsal`` (at a step's start,
after ``plan_rate_active``) −1, or, for a rate so stiff that its value at the committed state
is off the step's own by its transient (a state a step's stage error off the slow manifold
that the rate relaxes to), a code of the rate's regime at this step (which states are carried,
which restrainers touch): the step then takes the last accepted step's end-stage rate as its
first stage's where that step ended here in the same regime (first same as last), and the kink
search follows z on the step's own stage rates. A kind without it answers
``plan_rate_active`` False (its plan trials follow the step's path)."""

RATE_DEFAULTS = {
    "bearing_plan_rate_turn": ("_plan_rate_{k}(p, s, ux, uy, vx, vy, z, g, J)",
                               "return _turn_along(z, g, vx, vy, ax, ay)"),
    "bearing_plan_rate_branch": (None, "return _plan_branch_{k}(p, s, ux, uy)"),
    "bearing_plan_rate_fsal": (None, "return -1"),
}
"""What the dispatcher does for a kind with a rate form that leaves these out: a bearing
whose z is one sliding direction, r = z·v with ṙ = g·v + z·a (``rate_form.turn_along``), the
branch of ``plan_branch`` (z's value does not change it while z is carried), and a rate that
each step evaluates at its start (−1)."""

RATE_PYTHON_NAMES = ("N_RATE_PLAN",)
"""The names a kind with a rate form provides besides its kernels: the width of its state."""

PYTHON_NAMES = ("KEY", "N_PARAMS", "N_STATE_AXIS", "N_STATE_PLAN", "AXIS_CLASS", "PLAN_CLASS")
"""The names every kind provides on the Python side: its scenario key, its array widths and the
dataclasses of its one-axis and plan faces (they may be one class)."""

_DISPATCH = Path(__file__).with_name("dispatch.py")
_kinds = list(KINDS)


def kinds():
    """The kinds' modules in code order (the committed ones and any :func:`register` added)."""
    return tuple(_kinds)


def module(kind):
    """The module of bearing kind ``kind`` (its index)."""
    return importlib.import_module(_kinds[kind])


def kind_of(bearing):
    """The kind index of ``bearing`` (a kind's one-axis or plan dataclass), or None if it is
    not a registered bearing."""
    for kind, name in enumerate(_kinds):
        mod = importlib.import_module(name)
        if type(bearing) in (mod.AXIS_CLASS, mod.PLAN_CLASS):
            return kind
    return None


def axis_code(bearing):
    """The material code of ``bearing`` on one axis (the isolator element of a 1D model)."""
    kind = kind_of(bearing)
    if kind is None:
        raise ValueError(f"{type(bearing).__name__} is not a registered bearing kind "
                         f"({', '.join(_kinds)}).")
    return AXIS_CODE_START + kind


def axis_classes():
    """The one-axis dataclasses of every kind (what a 1D building takes as its isolator)."""
    return tuple(importlib.import_module(name).AXIS_CLASS for name in _kinds)


def plan_classes():
    """The plan dataclasses of every kind (what a plan building takes as its isolator)."""
    return tuple(importlib.import_module(name).PLAN_CLASS for name in _kinds)


def by_key(key):
    """The kind module whose scenario key is ``key`` ("fp", ...), or None."""
    for name in _kinds:
        mod = importlib.import_module(name)
        if mod.KEY == key:
            return mod
    return None


def keys():
    """Every kind's scenario key, in code order."""
    return tuple(importlib.import_module(name).KEY for name in _kinds)


def widths():
    """(params, one-axis state, plan state): the widest of every kind (the loop's arrays)."""
    mods = [importlib.import_module(name) for name in _kinds]
    return (max(m.N_PARAMS for m in mods), max(m.N_STATE_AXIS for m in mods),
            max(m.N_STATE_PLAN for m in mods))


def rate_width():
    """The widest rate-form state of every kind (the coupled-friction step's arrays), at least
    2."""
    mods = [importlib.import_module(name) for name in _kinds]
    return max([2] + [m.N_RATE_PLAN for m in mods if hasattr(m, "N_RATE_PLAN")])


def check_kind(name):
    """Import kind module ``name`` and check it provides the contract; returns the module."""
    mod = importlib.import_module(name)
    missing = [k for k in (*PYTHON_NAMES, *(v[0] for v in KERNELS.values()))
               if not hasattr(mod, k)]
    if missing:
        raise ValueError(f"bearing kind {name}: missing {', '.join(missing)}; a bearing kind "
                         "provides every name femoat.bearings' docstring lists.")
    rate = [v[0] for fn, v in RATE_KERNELS.items() if fn not in RATE_DEFAULTS]
    given = [k for k in rate if hasattr(mod, k)]
    if given and len(given) != len(rate):
        raise ValueError(f"bearing kind {name}: a rate form is all of {', '.join(rate)} "
                         f"(and optionally {', '.join(RATE_KERNELS[f][0] for f in RATE_DEFAULTS)}); "
                         f"it has only {', '.join(given)}.")
    if given and not all(hasattr(mod, k) for k in RATE_PYTHON_NAMES):
        raise ValueError(f"bearing kind {name}: a rate form also gives "
                         f"{', '.join(RATE_PYTHON_NAMES)} (the width of its state).")
    return mod


def has_rate_form(name):
    """Whether the kind module ``name`` declares the rate form (:data:`RATE_KERNELS`)."""
    return hasattr(importlib.import_module(name), RATE_KERNELS["bearing_plan_rate"][0])


def rate_form_covers(name, params):
    """Whether the kind module ``name``'s rate form covers a bearing of ``params`` (its
    optional ``rate_form_covers(params)``; a kind without one covers every bearing it declares
    the rate form for). False for a kind without a rate form."""
    mod = importlib.import_module(name)
    if not has_rate_form(name):
        return False
    covers = getattr(mod, "rate_form_covers", None)
    return True if covers is None else bool(covers(params))


def reads_duration(name, params):
    """Whether a bearing of kind module ``name`` and ``params`` reads the duration of each step
    (its friction a return over the step: the triple pendulum's velocity-dependent friction), so
    that its runs take Newmark's step, in 1D and in plan: the kind's optional
    ``reads_duration(params)``; False for a kind without one."""
    fn = getattr(importlib.import_module(name), "reads_duration", None)
    return False if fn is None else bool(fn(params))


def generate(names=None, compiled=None):
    """The dispatcher's source for the kinds ``names`` (default: the registered ones), with a
    branch for the kinds whose indices ``compiled`` lists (default: every one). A kind left
    out keeps its code and gets the dispatcher's answer for an unknown kind: numba compiles
    none of its kernels (:func:`select`)."""
    names = tuple(_kinds if names is None else names)
    branches = range(len(names)) if compiled is None else tuple(sorted(compiled))
    out = ['"""Generated by femoat.bearings.registry from its KINDS: do not edit; after changing the',
           'list run ``python -m femoat.bearings.registry``.',
           '',
           "Each function calls the kernel of the bearing kind its first argument names (the kind's",
           'index in the list), one ``if kind ==`` branch per kind (numba compiles each branch).',
           *([] if compiled is None else [
               '',
               f"Selected for this process (``registry.select``): branches for kinds {list(branches)} only."]),
           '"""',
           '',
           'import numpy as np',
           '',
           'from femoat.bearings import registry as _registry']
    rated = [has_rate_form(name) for name in names]
    for k, name in enumerate(names):
        out.append(f"from {name} import (")
        out += [f"    {v[0]} as _{v[0]}_{k}," for v in KERNELS.values()]
        if rated[k]:
            out += [f"    {v[0]} as _{v[0]}_{k}," for v in RATE_KERNELS.values()
                    if hasattr(importlib.import_module(name), v[0])]
        out.append(")")
    out.append('from femoat.bearings.rate_form import turn_along as _turn_along')
    out.append('from femoat.compilation.jit import njit')
    listed = "".join(f"\n    {name!r}," for name in names)
    out += ['', f"KINDS = ({listed}\n)", '"""The kinds this dispatcher was generated for."""', '',
            '_registry.check_dispatcher(KINDS)']
    for fn, (own, args, missing) in (*KERNELS.items(), *RATE_KERNELS.items()):
        out += ['', '', '@njit(cache=True)', f"def {fn}(kind, {args}):",
                f'    """:func:`{own}` of bearing kind ``kind``."""']
        for k in branches:
            if fn in RATE_KERNELS and not rated[k]:
                continue
            if fn in RATE_DEFAULTS and not hasattr(importlib.import_module(names[k]), own):
                first, last = RATE_DEFAULTS[fn]
                out += [f"    if kind == {k}:"] + ([f"        {first.format(k=k)}"] if first else []) \
                    + [f"        {last.format(k=k)}"]
                continue
            call = f"_{own}_{k}({args})"
            out += [f"    if kind == {k}:", f"        return {call}" if missing else
                    f"        {call}\n        return"]
        if missing:
            out.append(f"    return {missing}")
    return "\n".join(out) + "\n"


def write():
    """Write the committed dispatcher from :data:`KINDS` (``python -m femoat.bearings.registry``)."""
    for name in KINDS:
        check_kind(name)
    _atomic_write(_DISPATCH, generate(KINDS))
    return _DISPATCH


def check_dispatcher(dispatch_kinds):
    """Raise unless the dispatcher was generated for this process's kinds."""
    if tuple(dispatch_kinds) != tuple(_kinds):
        raise RuntimeError(
            f"femoat.bearings.dispatch was generated for {tuple(dispatch_kinds)} but the registry "
            f"lists {tuple(_kinds)}: run `python -m femoat.bearings.registry` to write it anew.")


def register(name, cache_dir=None):
    """Add the bearing kind of module ``name`` for this process, before the solver is imported.

    Writes a dispatcher with every registered kind and ``name`` into ``cache_dir`` (default: a
    folder keyed by the kinds under ``~/.cache/femoat``), loads it as
    :mod:`femoat.bearings.dispatch`, and points numba's on-disk cache there, so that the
    compiled loop (which inlines the dispatcher) is compiled for these kinds and cached apart
    from the loop of the committed kinds. Returns the new kind's index."""
    if name in _kinds:
        return _kinds.index(name)
    solver = [m for m in ("femoat.bearings.dispatch", "femoat.integration.forces")
              if m in sys.modules]
    if solver:
        raise RuntimeError(
            f"register({name!r}) after the solver was imported ({', '.join(solver)}): the "
            "compiled loop has already read the dispatcher. Register bearing kinds first, before "
            "running a model (in a fresh process).")
    check_kind(name)
    names = (*_kinds, name)
    source = generate(names)
    digest = hashlib.sha256(source.encode()).hexdigest()[:16]
    folder = Path(cache_dir) if cache_dir is not None else (
        Path.home() / ".cache" / "femoat" / f"bearings-{digest}")
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"femoat_bearings_dispatch_{digest}.py"
    if not path.exists() or path.read_text() != source:
        _atomic_write(path, source)
    _kinds.append(name)
    _use_numba_cache(folder / "numba")
    spec = importlib.util.spec_from_file_location("femoat.bearings.dispatch", path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules["femoat.bearings.dispatch"] = mod
    spec.loader.exec_module(mod)
    return len(_kinds) - 1


ENV = "FEMOAT_BEARINGS"
"""The environment variable that overrides which bearing kinds a command compiles (``all``, or
scenario keys such as ``fp,tfp``): :func:`femoat.startup.bearing_kinds.kinds_for` reads it."""

_ORIGINAL_CACHE = "FEMOAT_NUMBA_CACHE_DIR"
"""Where :func:`select` keeps the NUMBA_CACHE_DIR it found (empty: none), for its child
processes to find the same folders."""

_compiled = []
"""The kinds the loop of this process is compiled for (indices), once :func:`select` chose a
part of them; empty: every registered kind."""

_originals = {}
"""{dispatcher function name: its Python function} before :func:`select` retargeted it."""

_selected = []
"""Non-empty once :func:`select` chose the kinds in this process."""


def compiled_kinds():
    """The indices of the bearing kinds this process's compiled loop carries."""
    return tuple(_compiled) if _compiled else tuple(range(len(_kinds)))


def indices(chosen):
    """The kind indices of scenario keys ``chosen`` ("fp", ...; ``"all"`` for every kind)."""
    if isinstance(chosen, str):
        chosen = tuple(k.strip() for k in chosen.split(",") if k.strip())
    known = {key: kind for kind, key in enumerate(keys())}
    if tuple(chosen) == ("all",):
        return tuple(range(len(_kinds)))
    bad = [k for k in chosen if k not in known]
    if bad or not chosen:
        raise ValueError(f"bearing kinds {list(chosen)!r}: use 'all' or some of "
                         f"{', '.join(known)} (comma-separated for {ENV}).")
    return tuple(sorted({known[k] for k in chosen}))


def select(chosen, cache_dir=None):
    """Compile this process's solver loop for the bearing kinds ``chosen`` only (scenario keys,
    e.g. ``("fp",)``, or ``"all"``), before numba compiles any kernel; returns the indices of
    the kinds the loop carries.

    The loop calls the kinds through the dispatcher; numba compiles a kind's kernels only for
    its branch there. This writes a dispatcher with the branches of ``chosen`` alone into
    ``cache_dir`` (default: a folder keyed by it under $NUMBA_CACHE_DIR or ``~/.cache/femoat``),
    points the dispatcher's functions at it and numba's on-disk cache at the folder, so that the
    loop of these kinds is compiled once and cached apart from the loop of every kind. A model
    whose bearing is left out is refused by :func:`check_compiled`. Every code stays as it is:
    a run's results are the same bits in either loop.

    A later call keeps the loop when it already carries ``chosen``; before numba's first compile
    it widens the loop to both choices, after it raises RuntimeError."""
    from femoat.compilation import jit

    wanted = set(indices(chosen))
    have = compiled_kinds()
    if (_selected or jit.started()) and wanted <= set(have):
        return have
    if jit.started():
        names = ", ".join(_keys_of(have))
        raise RuntimeError(
            f"bearing kinds {', '.join(_keys_of(sorted(wanted)))}: this process already "
            f"compiled its solver for {names}; choose the kinds before the first run (in a new "
            "process).")
    if _selected:
        wanted |= set(have)
    _selected.append(True)
    dispatch = importlib.import_module("femoat.bearings.dispatch")
    functions = (*KERNELS, *RATE_KERNELS)
    for fn in functions:
        _originals.setdefault(fn, getattr(dispatch, fn).py_func)
    if wanted == set(range(len(_kinds))):
        for fn in functions:
            getattr(dispatch, fn).retarget(_originals[fn])
        _restore_numba_cache()
        _compiled.clear()
        return compiled_kinds()
    source = generate(_kinds, wanted)
    digest = hashlib.sha256(source.encode()).hexdigest()[:16]
    folder = Path(cache_dir) if cache_dir is not None else _cache_root() / f"bearings-{digest}"
    folder.mkdir(parents=True, exist_ok=True)
    name = f"femoat_bearings_dispatch_{digest}"
    path = folder / f"{name}.py"
    if not path.exists() or path.read_text() != source:
        _atomic_write(path, source)
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    for fn in functions:
        getattr(dispatch, fn).retarget(getattr(mod, fn).py_func)
    os.environ.setdefault(_ORIGINAL_CACHE, os.environ.get("NUMBA_CACHE_DIR", ""))
    _use_numba_cache(folder / "numba")
    _compiled[:] = sorted(wanted)
    return compiled_kinds()


def check_compiled(bearing):
    """Raise unless this process's loop carries the kind of ``bearing`` (an isolator: a
    bearing kind's dataclass, an Elastic spring or None pass when the loop has no kind)."""
    kind = None if bearing is None else kind_of(bearing)
    if kind is None or kind in compiled_kinds():
        return
    raise RuntimeError(
        f"isolator: a {type(bearing).__name__} (bearing kind '{keys()[kind]}') is not in "
        f"this process's compiled solver, which carries {', '.join(_keys_of(compiled_kinds()))} "
        "only (chosen by femoat.bearings.registry.select before the first run): run it in a new "
        f"process, or set {ENV}=all for the command that chose.")


def _keys_of(kinds):
    every = keys()
    return tuple(every[k] for k in kinds)


def _cache_root():
    """The folder that holds the dispatchers :func:`select` writes and their numba caches."""
    root = os.environ.get(_ORIGINAL_CACHE, os.environ.get("NUMBA_CACHE_DIR", ""))
    return Path(root) if root else Path.home() / ".cache" / "femoat"


def _restore_numba_cache():
    """Point numba's cache back where it was before :func:`select` moved it."""
    if _ORIGINAL_CACHE not in os.environ:
        return
    original = os.environ.pop(_ORIGINAL_CACHE)
    if original:
        _use_numba_cache(original)
        return
    os.environ.pop("NUMBA_CACHE_DIR", None)
    if "numba" in sys.modules:
        from numba.core import config

        config.CACHE_DIR = ""


def _use_numba_cache(folder):
    """Point numba's on-disk cache at ``folder`` for the kernels imported from now on."""
    os.environ["NUMBA_CACHE_DIR"] = str(folder)
    if "numba" in sys.modules:
        from numba.core import config

        config.CACHE_DIR = str(folder)


def _atomic_write(path, text):
    tmp = Path(f"{path}.tmp{os.getpid()}")
    tmp.write_text(text)
    os.replace(tmp, path)


if __name__ == "__main__":
    print(f"wrote {write()}")
