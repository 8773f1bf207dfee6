"""numba's inliner made to build each inlined function once (femoat.compilation.inlining).

What must hold: the compiled code does the same arithmetic as with numba's own inliner. The
solver's stored fingerprints (tests/test_fingerprints.py: the paper runs of both methods, plan
runs, a 72-run suite) are computed with it installed; here a tree of nested inline helpers is
compiled both ways and compared to the bit, and the memo is checked to build each helper's IR
once however many times it is inlined.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]

# A tree of inline="always" helpers, four levels, each calling the next one at two sites (so
# the leaf is inlined 2**4 times into the kernel), with branches, loops and arrays: the shapes
# femoat's loop is made of (no allocation: femoat compiles without numba's runtime). Its module
# is named under femoat (the memo keeps femoat's functions only); its values are checked
# against the same recursion in plain Python.
TREE = '''
import numpy as np
from femoat.compilation.jit import njit

@njit(inline="always")
def level0(x, a):
    s = 0.0
    for k in range(a.size):
        s += a[k] * x
    if s > 1.0:
        return np.sqrt(s) - 0.25 * x
    return s * s + 0.5

@njit(inline="always")
def level1(x, a):
    return level0(x, a) * 0.75 + level0(0.5 * x, a)

@njit(inline="always")
def level2(x, a):
    y = level1(x, a)
    return y - 0.125 * level1(y, a)

@njit(inline="always")
def level3(x, a):
    y = level2(x, a)
    z = level2(1.0 / (1.0 + y * y), a)
    a[0] = a[0] * 0.5 + 0.01 * z
    return z

@njit
def tree(xs, a, out):
    for i in range(xs.size):
        out[i] = level3(xs[i], a) + level3(-xs[i], a)
'''

LOAD_TREE = '''
import json, sys, types, numpy as np
mod = types.ModuleType(TREE_MODULE)
sys.modules[mod.__name__] = mod
exec(compile(TREE, "<" + TREE_MODULE + ">", "exec"), mod.__dict__)
for f in (mod.level0, mod.level1, mod.level2, mod.level3, mod.tree):
    f.py_func.__module__ = mod.__name__
'''
"""Code that makes ``TREE`` the module ``TREE_MODULE`` (a name under femoat: the memo keeps
femoat's functions only), ``mod``, in a fresh process."""

DRIVER = LOAD_TREE + '''
xs = np.linspace(-3.0, 3.0, 41)
a = np.array([0.3, -0.2, 0.7, 0.1])
out = np.zeros_like(xs)
mod.tree(xs, a, out)
from femoat.compilation import inlining
print(json.dumps({"out": out.tobytes().hex(), "a": a.tobytes().hex(),
                  "fast": inlining.enabled(),
                  "builds": {f.__name__: n for f, n in inlining.BUILDS.items()
                             if f.__module__ == mod.__name__}}))
'''


def _compile_tree(fast):
    env = {**os.environ, "FEMOAT_FAST_INLINE": "1" if fast else "0",
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    code = f"TREE = {TREE!r}\nTREE_MODULE = 'femoat._inline_tree'\n" + DRIVER
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                          text=True, timeout=600, check=False, cwd=ROOT)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="module")
def both():
    from femoat.compilation.inlining import supported

    if not supported():
        pytest.skip("this numba's inliner is not one femoat.compilation.inlining knows: "
                    "numba's own runs (the same results, a slower compile)")
    return _compile_tree(True), _compile_tree(False)


def _python_tree(xs, a):
    # The same recursion as TREE, evaluated by Python and numpy (the reference of both
    # compiles; the round-off may differ from the compiled code's, hence allclose).
    def level0(x):
        s = sum(float(v) * x for v in a)
        return np.sqrt(s) - 0.25 * x if s > 1.0 else s * s + 0.5

    def level1(x):
        return level0(x) * 0.75 + level0(0.5 * x)

    def level2(x):
        y = level1(x)
        return y - 0.125 * level1(y)

    def level3(x):
        y = level2(x)
        z = level2(1.0 / (1.0 + y * y))
        a[0] = a[0] * 0.5 + 0.01 * z
        return z

    return np.array([level3(x) + level3(-x) for x in xs])


def test_the_tree_compiles_to_the_same_bits_with_and_without_the_memo(both):
    fast, plain = both
    assert fast["fast"] and not plain["fast"]
    assert fast["out"] == plain["out"]
    assert fast["a"] == plain["a"]  # the side effect on the array, in the same order
    out = np.frombuffer(bytes.fromhex(fast["out"]))
    expected = _python_tree(np.linspace(-3.0, 3.0, 41), np.array([0.3, -0.2, 0.7, 0.1]))
    np.testing.assert_allclose(out, expected, rtol=1e-13)


def test_each_inlined_helper_is_built_once(both):
    # tree inlines level3 at 2 sites, level3 inlines level2 at 2, level2 level1 at 2, level1
    # level0 at 2: numba's own inliner runs a helper's untyped pipeline at every site of every
    # copy of its callers (each build of level3 builds level2 twice, ...): level3 2 times,
    # level2 4, level1 8, level0 16 for the tree's one compile. The memo builds each once.
    fast, _ = both
    assert fast["builds"] == {"level0": 1, "level1": 1, "level2": 1, "level3": 1}


def test_a_copy_is_dropped_only_where_both_names_are_assigned_once():
    # Inlining turns each argument into a copy `param = caller_var`; femoat's helpers take the
    # loop's bundles, so the copies are dropped (femoat.compilation.inlining._drop_aliases):
    # `a = t` goes (t and a each assigned once: the same value wherever a is read) while the
    # copies of b stay (b is assigned again in the loop: `c = b` must keep the value b had
    # then, and `b = x` is one of b's two assignments).
    import numpy as np
    from numba.core import ir
    from numba.core.compiler import run_frontend

    from femoat.compilation.inlining import _drop_aliases

    def f(x, t, n):
        a = t
        b = x
        c = x
        for _ in range(n):
            c = b
            b = b + 1.0
        return a[0] + c + b

    func_ir = run_frontend(f)

    def copies():
        return {(s.target.name, s.value.name) for blk in func_ir.blocks.values()
                for s in blk.body if isinstance(s, ir.Assign) and isinstance(s.value, ir.Var)}

    assert {("a", "t"), ("b", "x"), ("c", "b")} <= copies()
    assert _drop_aliases(func_ir)
    left = copies()
    assert ("a", "t") not in left and ("b", "x") in left and ("c", "b") in left
    reads = {v.name for blk in func_ir.blocks.values() for s in blk.body for v in s.list_vars()}
    assert "a" not in reads and "t" in reads

    # and compiled (a femoat kernel, so the copies are dropped in its pipeline): t[0] + the
    # last c (x + n - 1) + the last b (x + n) = 5 + 2.5 + 3.5 for x = 0.5, n = 3
    from femoat.compilation.jit import njit

    f.__module__ = "femoat._copy_check"
    assert njit(f)(0.5, np.array([5.0]), 3) == 11.0


def test_a_callee_copy_keeps_its_source_locations_and_other_copies_do_not():
    # While inline_ir copies a callee (one memo for the whole IR), a location is kept as it is
    # (numba keeps a variable's, a constant's and a free variable's); any other deep copy
    # makes an equal new one, with its own fields.
    import copy

    from numba.core import ir

    from femoat.compilation import inlining, jit

    jit._register()
    if not inlining.enabled():
        pytest.skip("femoat's inliner is not installed on this numba")
    loc = ir.Loc("kernel.py", 12, col=4)
    loc.lines = ["a = 1\n"] * 3
    inlining._session.memo = {}
    try:
        assert copy.deepcopy(loc) is loc
    finally:
        inlining._session.memo = None
    other = copy.deepcopy(loc)
    assert other is not loc and other == loc and other.lines == loc.lines
    assert other.lines is not loc.lines
