"""Make numba's ``inline="always"`` cost what the inlined code costs, not what it costs again.

femoat's loop is one compiled function into which numba inlines, at the IR level, about a
hundred helpers (``njit(inline="always")``), many of them inside others: the methods' steps,
the force routine, the recorder, the bearings' kernels. numba's inliner
(``numba.core.untyped_passes.InlineInlinables``, through
``numba.core.inline_closurecall.InlineWorker``) spends most of femoat's compile in two pieces of
bookkeeping that grow with the number of call sites rather than with the code:

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
   quadratic in the function's size. :class:`_OneScopeCopy` copies a whole IR with one memo
   while ``inline_ir`` runs (the blocks share one scope, as in the original), which is what
   each per-block copy would give less the duplicates.

Neither changes the IR that is inlined, only how often it is built and how it is copied: the
compiled kernels do the same arithmetic (``tests/test_inlining.py``: a nested inline tree's
results and the solver's fingerprints, bit for bit). Both are installed by
:func:`install` when femoat first imports numba (:mod:`femoat.compilation.jit`), only on the
numba versions where the patched methods were read (:data:`NUMBA_VERSIONS`); on any other
version numba runs unchanged (slower to compile, the same results), and
``FEMOAT_FAST_INLINE=0`` turns them off.
"""

import collections
import os
import threading

NUMBA_VERSIONS = ((0, 68), (0, 68))
"""The first and last numba minor versions whose ``InlineWorker`` this module was read and
tested against (both ends included); on others numba's own inliner runs."""

_installed = []
_session = threading.local()


def _numba_version():
    import numba

    major, minor = numba.__version__.split(".")[:2]
    return int(major), int(minor)


def supported():
    """Whether this numba's inliner is one :func:`install` knows."""
    low, high = NUMBA_VERSIONS
    return low <= _numba_version() <= high


def enabled():
    """Whether the faster inliner is installed in this process."""
    return bool(_installed)


def install():
    """Install the memo and the one-memo copy into numba's ``InlineWorker`` (once a process).
    Returns whether they are installed (False on an unknown numba, or when
    ``FEMOAT_FAST_INLINE=0``)."""
    if _installed:
        return True
    if os.environ.get("FEMOAT_FAST_INLINE", "1") == "0" or not supported():
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
    _installed.append(True)
    return True


# ---- 1. the callee's canonical IR, built once per function ---------------------------------------

_kept = {}
"""{(function, enable_ssa): its IR after the untyped pipeline}: femoat's functions only."""

BUILDS = collections.Counter()
"""{function: how many times its untyped pipeline ran for the inliner} (femoat's functions)."""


def _ours(func):
    return getattr(func, "__module__", "").split(".")[0] == "femoat"


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
    import copy

    shared = getattr(_session, "memo", None)
    if shared is not None:
        memo = shared
    done = memo.get(id(self))
    if done is not None:
        return done
    out = type(self).__new__(type(self))
    memo[id(self)] = out
    copy._keep_alive(self, memo)
    out.__dict__.update(copy.deepcopy(self.__dict__, memo))
    return out
