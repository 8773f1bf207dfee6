"""A kernel's machine code built only when Python calls it (femoat.compilation.machine_code).

What must hold: a kernel compiled for a caller gets no machine code and no Python wrapper; its
caller computes what it computed before, with the same LLVM IR as when every kernel is built
at once (``FEMOAT_LAZY_MACHINE_CODE=0``); a call from Python builds the kernel then, also from
an on-disk cache entry written without machine code, and replaces that entry by an ordinary
one; a kernel declared ``python=False`` says how to call it. Each case runs in a fresh process
on a private numba cache. The solver's stored fingerprints (tests/test_fingerprints.py) are
computed with it installed.
"""

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

KERNELS = '''
from numba import objmode

from femoat.compilation.jit import njit


@njit(cache=True)
def spring(k, u):
    """A hardening spring's force [kip]: k u + 0.1 k u^3 (k [kip/in], u [in])."""
    return k * u + 0.1 * k * u ** 3


@njit(cache=True)
def work(k, u_max, n):
    """The spring's work from 0 to u_max [kip in], trapezoid rule on n intervals."""
    h = u_max / n
    s = 0.5 * (spring(k, 0.0) + spring(k, u_max))
    for i in range(1, n):
        s += spring(k, i * h)
    return s * h


@njit(cache=True, python=False)
def internal(k, u):
    return 2.0 * spring(k, u)


@njit(cache=True)
def uses_internal(k, u):
    return internal(k, u)


@njit(cache=True)
def uses_internal_too(k, u):
    return 0.5 * internal(k, u)


@njit(cache=True)
def is_even(n):
    return True if n == 0 else is_odd(n - 1)


@njit(cache=True)
def is_odd(n):
    return False if n == 0 else is_even(n - 1)


@njit(cache=True)
def parity(n):
    return is_odd(n)


@njit(cache=True)
def halved_in_python(x):
    with objmode(y="float64"):
        y = x / 2.0
    return y


@njit(cache=True)
def calls_python(x):
    return halved_in_python(x) + 1.0
'''

PRELUDE = '''
import json, re, sys
from femoat.compilation import machine_code
import springs
built = []
_materialize = machine_code.materialize
def counting(dispatcher, entry):
    built.append(dispatcher.py_func.__name__)
    return _materialize(dispatcher, entry)
machine_code.materialize = counting
def lazy(kernel):
    (cres,) = kernel.dispatcher.overloads.values()
    return isinstance(cres.entry_point, machine_code.LazyEntry)
out = {}
'''

FIRST = r'''
out["work"] = springs.work(2.0, 1.5, 2000)
out["spring_lazy"] = lazy(springs.spring)
out["uses_internal"] = springs.uses_internal(2.0, 1.5)
out["parity"] = [springs.parity(n) for n in (0, 1, 6, 7)]  # mutual recursion below a caller
out["calls_python"] = springs.calls_python(3.0)  # an object-mode block in a callee
out["internal_lazy"] = lazy(springs.internal)
out["built_before"] = list(built)
out["internal_error"] = ""
if machine_code.enabled():  # (numba's own: a function without a wrapper, not to be called)
    try:
        springs.internal.dispatcher(2.0, 1.5)
    except TypeError as e:
        out["internal_error"] = str(e)
ir = next(iter(springs.work.dispatcher.inspect_llvm().values()))
out["work_ir"] = re.sub(r"%[\w.$\-]+", "%v", ir[ir.index("define"):])  # values unnamed
'''

SECOND = '''
from numba import float64
lazy_entry = springs.spring.dispatcher.compile((float64, float64))  # typed as a caller would
out["typed_lazy"] = isinstance(lazy_entry, machine_code.LazyEntry)
out["spring"] = springs.spring(2.0, 1.5)
(cres,) = springs.spring.dispatcher.overloads.values()
out["built_once"] = out["typed_lazy"] and (
    _materialize(springs.spring.dispatcher, lazy_entry) is cres.entry_point)
out["spring_lazy"] = lazy(springs.spring)
out["spring_hits"] = sum(springs.spring.dispatcher.stats.cache_hits.values())
out["uses_internal_too"] = springs.uses_internal_too(2.0, 1.5)  # new caller, cached callee
out["work"] = springs.work(2.0, 1.5, 2000)
out["work_misses"] = sum(springs.work.dispatcher.stats.cache_misses.values())
(args,) = springs.spring.dispatcher.overloads
again = springs.spring.dispatcher._cache.load_overload(args, springs.spring.dispatcher.targetctx)
out["cache_entry_lazy"] = isinstance(again.entry_point, machine_code.LazyEntry)
'''

PLAIN = '''
import numba
plain = numba.njit(cache=True)(springs.spring.py_func)
out["plain"] = plain(2.0, 1.5)
out["plain_misses"] = sum(plain.stats.cache_misses.values())
'''

DONE = '''
out["built"] = built
out["enabled"] = machine_code.enabled()
print(json.dumps(out))
'''


def _run(tmp_path, body, cache, **env):
    folder = tmp_path / "src"
    folder.mkdir(exist_ok=True)
    (folder / "springs.py").write_text(KERNELS)
    code = textwrap.dedent(PRELUDE) + textwrap.dedent(body) + textwrap.dedent(DONE)
    environ = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / cache), **env,
               "PYTHONPATH": os.pathsep.join([str(folder), str(ROOT),
                                              os.environ.get("PYTHONPATH", "")])}
    r = subprocess.run([sys.executable, "-c", code], env=environ, capture_output=True,
                       text=True, timeout=300, check=False)
    assert r.returncode == 0, r.stderr[-3000:]
    return json.loads(r.stdout.strip().splitlines()[-1])


def test_a_callee_gets_machine_code_when_python_calls_it_and_from_the_cache(tmp_path):
    from femoat.compilation.machine_code import NUMBA_VERSIONS
    from femoat.compilation.numba_version import supported

    if not supported(NUMBA_VERSIONS):
        pytest.skip("femoat.compilation.machine_code is not installed on this numba")
    # The spring's work from 0 to U = 1.5 in with k = 2 kip/in: k U^2/2 + 0.1 k U^4/4
    # = 2.25 + 0.253125 = 2.503125 kip in; the trapezoid rule's error is -(U^3/12) f''/n^2
    # with f'' = 0.6 k u <= 1.8 kip/in^3: below 1.3e-7 kip in at n = 2000.
    exact = 2.0 * 1.5 ** 2 / 2 + 0.1 * 2.0 * 1.5 ** 4 / 4
    first = _run(tmp_path, FIRST, "cache")
    assert first["enabled"]
    assert abs(first["work"] - exact) < 2e-7
    # compiled for work and for internal only: no machine code, nothing built
    assert first["spring_lazy"] and first["internal_lazy"]
    assert first["built_before"] == []
    assert first["uses_internal"] == 2.0 * (2.0 * 1.5 + 0.1 * 2.0 * 1.5 ** 3)
    assert "python_dispatcher" in first["internal_error"]
    # 7 is odd, 6, 0 are even (is_odd(n) = not is_even(n - 1), down to 0); 3.0/2 + 1 = 2.5
    assert first["parity"] == [False, True, False, True] and first["calls_python"] == 2.5

    # a new process on that cache: work loads (no compile); the spring, called from Python,
    # is built from its cache entry (an optimized module, no object code), then its entry is
    # numba's ordinary one
    shutil.copytree(tmp_path / "cache", tmp_path / "cache-first")
    second = _run(tmp_path, SECOND, "cache")
    assert second["work"] == first["work"] and second["work_misses"] == 0
    # the same operations in the same order as Python's: 2*1.5 + (0.1*2)*1.5**3, 1.5**3 exact
    assert second["spring"] == 2.0 * 1.5 + 0.1 * 2.0 * 1.5 ** 3
    assert second["spring_hits"] == 1 and second["built"] == ["spring"]
    # typed first (as for a caller: no machine code), then built by the call; building the
    # same entry again (another thread that saw it unbuilt) returns the built code
    assert second["typed_lazy"] and second["built_once"]
    assert not second["spring_lazy"] and not second["cache_entry_lazy"]

    # every kernel built at once (the switch), on a cache of its own: the caller's LLVM IR
    # (its instructions, values unnamed) and its result are the same as with its callee
    # linked before LLVM's module passes and left without machine code
    off = _run(tmp_path, FIRST, "cache-off", FEMOAT_LAZY_MACHINE_CODE="0")
    assert not off["enabled"] and not off["spring_lazy"] and not off["internal_lazy"]
    assert off["work"] == first["work"] and off["work_ir"] == first["work_ir"]
    # ... and on the first process's cache, whose spring entry has no object code, a Python
    # call builds it as well
    shutil.copytree(tmp_path / "cache-first", tmp_path / "cache-plain")
    off_warm = _run(tmp_path, SECOND, "cache-first", FEMOAT_LAZY_MACHINE_CODE="0")
    assert off_warm["spring"] == second["spring"] and off_warm["work"] == first["work"]
    assert off_warm["built"] == ["spring"] and not off_warm["cache_entry_lazy"]
    # a new caller of the python=False kernel, whose cache entry has no machine code and no
    # wrapper to build: it links it as it is, with the switch off too (0.5 * 2 * 3.675)
    assert off_warm["uses_internal_too"] == second["uses_internal_too"] == 0.5 * 2.0 * (
        2.0 * 1.5 + 0.1 * 2.0 * 1.5 ** 3)
    assert not off_warm["typed_lazy"]  # built at once, on loading

    # numba's own dispatcher over the same function, on the same cache file, never reads an
    # entry without machine code (its index key is femoat's): it compiles the spring itself
    plain = _run(tmp_path, PLAIN, "cache-plain")
    assert plain["plain"] == second["spring"] and plain["plain_misses"] == 1
