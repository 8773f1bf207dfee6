"""numba's typing of calls resolved once per argument types and flags
(femoat.compilation.call_types).

What must hold: a repeat gets numba's answer and leaves numba's state as resolving the call
again would have (the implementation key of the signature, the compiled overload and the
inlining information of a template that compiles one), also when the flags in force changed
in between; a call that fails fails each time. The solver's stored fingerprints
(tests/test_fingerprints.py) are computed with it installed.
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]


def _context():
    from numba.core.registry import cpu_target

    from femoat.compilation import jit

    jit._register()
    context = cpu_target.typing_context
    context.refresh()
    return context


def _overloaded(inline="never"):
    """A new function with a numba ``@overload`` (each its own template and tables)."""
    from numba.extending import overload

    def twice(x):
        return 2 * x

    @overload(twice, inline=inline)
    def _twice(x):
        return lambda x: 2 * x

    return twice


def _flags(**set_):
    from numba.core.compiler import Flags

    flags = Flags()
    for name, value in set_.items():
        setattr(flags, name, value)
    return flags


def _resolve(context, fnty, args, flags):
    from numba.core.targetconfig import ConfigStack

    with ConfigStack().enter(flags):
        return fnty.get_call_type(context, args, {})


def _same(ours, theirs):
    """The same object; or what numba makes anew on every resolution, equal: the inlining
    information of an always-inlined overload, and its placeholder for a compiled one."""
    if isinstance(ours, dict):
        assert ours["folded_args"] == theirs["folded_args"]
    elif type(ours).__name__ == "_EmptyImplementationEntry":
        assert type(theirs) is type(ours) and str(theirs) == str(ours)
    else:
        assert ours is theirs


def _state(fnty, args):
    from femoat.compilation.call_types import _tables

    return fnty._impl_keys.get(args), [t.get(args) for t in _tables(fnty)]


@pytest.mark.parametrize("inline", ["never", "always"])
def test_a_repeat_under_other_flags_in_between_leaves_numbas_state(inline):
    import operator

    from numba.core import types

    from femoat.compilation import call_types

    context = _context()
    assert call_types._installed
    numbas = call_types.get_call_type.__wrapped__
    twice = _overloaded(inline)
    context.refresh()  # (numba's registries: the new @overload)
    fnty = context.resolve_value_type(twice)
    args = (types.float64,)
    a, b = _flags(), _flags(fastmath=True, error_model="numpy")
    first = _resolve(context, fnty, args, a)
    state_a = _state(fnty, args)
    _resolve(context, fnty, args, b)  # another compiled overload for b (not inlined)
    state_b = _state(fnty, args)
    if inline == "never":
        assert state_b[0] is not state_a[0]  # the flags make another implementation
    again = _resolve(context, fnty, args, a)  # from the memo
    assert again == first and again.return_type == types.float64
    ours = _state(fnty, args)
    assert ours[0] is state_a[0] and all(x is y for x, y in zip(ours[1], state_a[1]))
    # numba resolving it again under a: the same signature and the same implementation
    # (its caches give the same objects), inlining information equal
    from numba.core.targetconfig import ConfigStack

    with ConfigStack().enter(a):
        theirs_sig = numbas(fnty, context, args, {})
    theirs = _state(fnty, args)
    assert theirs_sig == again
    for x, y in zip([ours[0], *ours[1]], [theirs[0], *theirs[1]]):
        _same(x, y)
    # a builtin operator: the memo's answer is numba's
    add = context.resolve_value_type(operator.add)
    for pair in ((types.float64, types.float64), (types.int64, types.float64),
                 (types.Array(types.float64, 1, "C"), types.float64)):
        assert _resolve(context, add, pair, a) == numbas(add, context, pair, {})
        assert _resolve(context, add, pair, a) == numbas(add, context, pair, {})


def test_a_failing_call_fails_each_time_and_is_not_kept():
    from numba.core import errors, types

    from femoat.compilation import call_types

    context = _context()
    fnty = context.resolve_value_type(np.sqrt)
    args = (types.unicode_type,)
    for _ in range(2):
        with pytest.raises(errors.TypingError):
            _resolve(context, fnty, args, _flags())
    assert not any(k[0] is fnty and k[3] == args for k in call_types._memo)


def test_the_compiled_code_is_numbas():
    # a kernel with operators, a ufunc and an @overload typed many times in one function,
    # compiled with the memo and without (FEMOAT_CALL_TYPES_MEMO=0, the switch) in two fresh
    # processes: the same results to the bit and the same LLVM IR of the kernel
    code = """
import json, sys, numpy as np
from femoat.compilation import call_types
from femoat.compilation.jit import njit
@njit(cache=False)
def k(x, y):
    s = 0.0
    for i in range(x.size):
        s += np.sqrt(abs(x[i])) * y[i] + np.hypot(x[i], 1.5) - min(x[i], y[i]) ** 2
        if x[i] > y[i]:
            s -= np.exp(-abs(x[i] - y[i]))
    return s
x = np.linspace(-2.0, 3.0, 101); y = np.cos(x)
v = k(x, y)
d = k.dispatcher
ir = next(iter(d.inspect_llvm().values()))
body = ir[ir.index("define"):]
print(bool(call_types._installed))
print(json.dumps([v.hex(), len(body), hash(body)]))
"""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get(
        "PYTHONPATH", "")]), "PYTHONHASHSEED": "0"}
    runs = [subprocess.run([sys.executable, "-c", code], env={**env, **extra},
                           capture_output=True, text=True, timeout=300, check=False)
            for extra in ({}, {"FEMOAT_CALL_TYPES_MEMO": "0"})]
    for r in runs:
        assert r.returncode == 0, r.stderr[-2000:]
    from femoat.compilation.call_types import NUMBA_VERSIONS
    from femoat.compilation.numba_version import supported

    (installed, ours), (off, theirs) = (r.stdout.strip().splitlines()[-2:] for r in runs)
    assert (installed, off) == (str(supported(NUMBA_VERSIONS)), "False")
    assert ours == theirs
