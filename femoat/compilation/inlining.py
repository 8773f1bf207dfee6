"""Make numba's ``inline="always"`` cost what the inlined code costs, not what it costs again.

femoat's loop is one compiled function into which numba inlines, at the IR level, about a
hundred helpers (``njit(inline="always")``), many of them inside others: the methods' steps,
the force routine, the recorder, the bearings' kernels. numba's inliner
(``numba.core.untyped_passes.InlineInlinables``, through
``numba.core.inline_closurecall.InlineWorker``) spent most of femoat's compile on three things
that grow with the number of call sites rather than with the code:

1. **the callee's untyped pipeline at every call site**: ``InlineWorker.inline_function``
   translates the callee's bytecode and runs its whole untyped pipeline (its own inlines
   included) each time it inlines it, so a helper inlined at ten sites, each of which is
   itself inlined at five, is rebuilt fifty times. :func:`_memo_untyped_passes` keeps the
   canonical IR of each femoat function (per SSA flag) and hands the same IR to every call site;
   ``inline_ir`` copies what it receives before it changes anything, so the kept IR is never
   touched.
2. **the copy of the callee's IR**: ``inline_ir`` deep-copies the callee block by block, each
   block with a memo of its own, so the callee's scope (every variable of the function) is
   copied once per block, and compared once per block when the scopes are gathered:
   quadratic in the function's size. :func:`_one_scope_copy` copies a whole IR with one memo
   while ``inline_ir`` runs (the blocks share one scope, as in the original), which is what
   each per-block copy would give less the duplicates; the copy keeps the callee's source
   locations (:func:`_loc_deepcopy`).
3. **the inlined calls' argument copies**: inlining makes each parameter of the callee a copy
   of the caller's argument (``param = arg``); femoat's helpers take the loop's bundles
   (tuples of ~30 arrays each), so every inlined call copied hundreds of values into new
   locals, which LLVM's scalar replacement then took apart again (its largest pass on the
   loop). :func:`_drop_aliases` replaces, after the inlining pass, each variable that is only
   ever a copy of another variable assigned once by that variable.

None of them changes what the compiled code computes, only how often the IR is built, how it
is copied and how many names hold one value: the compiled kernels do the same arithmetic
(``tests/test_inlining.py``: a nested inline tree's results, bit for bit against numba's own
inliner; the solver's stored fingerprints). They are installed by
:func:`install` when femoat first imports numba (:mod:`femoat.compilation.jit`), only on the
numba versions whose inliner was read and tested (:data:`NUMBA_VERSIONS`); on any other
version numba runs unchanged (slower to compile, the same results), and
``FEMOAT_FAST_INLINE=0`` turns them off.
"""

import collections
import threading

from femoat.compilation import numba_version

NUMBA_VERSIONS = ((0, 68), (0, 68))
"""The first and last numba minor versions whose ``InlineWorker`` this module was read and
tested against (both ends included); on others numba's own inliner runs."""

_installed = []
_session = threading.local()


def supported():
    """Whether this numba's inliner is one :func:`install` knows."""
    return numba_version.supported(NUMBA_VERSIONS)


def enabled():
    """Whether the faster inliner is installed in this process."""
    return bool(_installed)


def install():
    """Install the three into numba (once a process): the memo and the one-memo copy into
    ``InlineWorker``, the copies dropped after ``InlineInlinables``. Returns whether they are
    installed (False on an unknown numba, or when ``FEMOAT_FAST_INLINE=0``)."""
    if _installed:
        return True
    if not numba_version.wanted("FEMOAT_FAST_INLINE", NUMBA_VERSIONS):
        return False
    import numba.core.inline_closurecall as icc
    from numba.core import ir

    worker = icc.InlineWorker
    if not (hasattr(worker, "run_untyped_passes") and hasattr(worker, "inline_ir")
            and "__deepcopy__" not in vars(ir.Block)):
        return False
    worker.run_untyped_passes = _memo_untyped_passes(worker.run_untyped_passes)
    worker.inline_ir = _one_scope_copy(worker.inline_ir)
    ir.Block.__deepcopy__ = _block_deepcopy
    if "__deepcopy__" not in vars(ir.Loc):
        ir.Loc.__deepcopy__ = _loc_deepcopy
    from numba.core.untyped_passes import InlineInlinables

    InlineInlinables.run_pass = _then_drop_aliases(InlineInlinables.run_pass)
    _installed.append(True)
    return True


# ---- 1. the callee's canonical IR, built once per function ---------------------------------------

_kept = {}
"""{(function, enable_ssa): its IR after the untyped pipeline}: femoat's functions only."""

BUILDS = collections.Counter()
"""{function: how many times its untyped pipeline ran for the inliner} (femoat's functions)."""


def _ours(func):
    # numba compiles functions of its own made with exec, whose __module__ is None
    return (getattr(func, "__module__", None) or "").split(".")[0] == "femoat"


def _memo_untyped_passes(original):
    def run_untyped_passes(self, func, enable_ssa=False):
        if not _ours(func) or self.locals:
            return original(self, func, enable_ssa)
        key = (func, enable_ssa)
        kept = _kept.get(key)
        if kept is None:
            kept = _kept[key] = original(self, func, enable_ssa)
            BUILDS[func] += 1
        else:
            self.flags.enable_ssa = enable_ssa  # the one side effect of a run, kept
        return kept

    run_untyped_passes.__wrapped__ = original
    return run_untyped_passes


def forget():
    """Drop the kept IRs (they are only needed while a process compiles)."""
    _kept.clear()


# ---- 2. one copy of the callee's scope, not one per block ---------------------------------------

def _one_scope_copy(original):
    def inline_ir(self, *args, **kwargs):
        outer = getattr(_session, "memo", None)
        _session.memo = {}
        try:
            return original(self, *args, **kwargs)
        finally:
            _session.memo = outer

    inline_ir.__wrapped__ = original
    return inline_ir


def _block_deepcopy(self, memo):
    """``copy.deepcopy`` of a block, as Python's default does it, with the memo of the
    :func:`_one_scope_copy` call in progress when there is one: the blocks of one IR copied
    one by one then share their copies (one scope, one copy of each variable)."""
    shared = getattr(_session, "memo", None)
    if shared is not None:
        memo = shared
    done = memo.get(id(self))
    if done is not None:
        return done
    return _default_deepcopy(self, memo)


def _default_deepcopy(self, memo):
    """``copy.deepcopy`` of an object with a ``__dict__``, as Python's default makes it."""
    import copy

    out = type(self).__new__(type(self))
    memo[id(self)] = out
    copy._keep_alive(self, memo)
    out.__dict__.update(copy.deepcopy(self.__dict__, memo))
    return out


def _loc_deepcopy(self, memo):
    """``copy.deepcopy`` of a source location: the location itself while ``inline_ir`` copies a
    callee (as numba's own copies of a variable, a constant or a free variable keep theirs: a
    location is never changed, and its copy would carry the source file's lines once they
    have been read for a message), else a copy as Python's default makes it."""
    if getattr(_session, "memo", None) is not None:
        return self
    return _default_deepcopy(self, memo)


# ---- 3. the inlined calls' argument copies --------------------------------------------------

def _then_drop_aliases(original):
    def run_pass(self, state):
        changed = original(self, state)
        if _ours(state.func_id.func) and not state.locals:
            changed = _drop_aliases(state.func_ir) or changed
        return changed

    run_pass.__wrapped__ = original
    return run_pass


def _drop_aliases(func_ir):
    """Replace every variable that is only ever a copy of another variable (``a = b``, each the
    only assignment of its name in the function) by that variable. Returns whether any was.

    Inlining a call turns each argument into such a copy (the callee's parameter assigned the
    caller's variable); femoat's helpers take the loop's bundles, tuples of ~30 arrays, so each
    inlined call copied hundreds of values into a new local that LLVM then had to take apart
    again. With one assignment each, ``b`` is assigned before ``a = b`` runs and never again,
    so ``a`` and ``b`` hold the same value wherever ``a`` is read."""
    from numba.core import ir
    from numba.core.ir_utils import build_definitions, replace_vars

    defs = collections.Counter()
    for block in func_ir.blocks.values():
        for stmt in block.body:
            if isinstance(stmt, ir.Del):
                return False
            if isinstance(stmt, ir.Assign):
                defs[stmt.target.name] += 1
    alias = {}
    for block in func_ir.blocks.values():
        for stmt in block.body:
            if (isinstance(stmt, ir.Assign) and isinstance(stmt.value, ir.Var)
                    and defs[stmt.target.name] == 1 and defs[stmt.value.name] == 1
                    and stmt.target.name != stmt.value.name):
                alias[stmt.target.name] = stmt.value
    if not alias:
        return False
    for name in list(alias):
        source = alias[name]
        while source.name in alias:
            source = alias[source.name]
        alias[name] = source
    replace_vars(func_ir.blocks, alias)
    for block in func_ir.blocks.values():
        block.body = [stmt for stmt in block.body
                      if not (isinstance(stmt, ir.Assign) and isinstance(stmt.value, ir.Var)
                              and stmt.target.name == stmt.value.name)]
    func_ir._definitions = build_definitions(func_ir.blocks)
    return True
