"""Kernels loaded from numba's cache without numba's context refresh (femoat.compilation.cache_load).

What must hold: a new process loads a kernel from the cache and runs it without numba's
refresh (so without the modules it imports, scipy.linalg among them), also a kernel calling
numba's reference-counted runtime (NRT) and one hashing a string (CPython's hash secret, read
through symbols numba registers): the runtime symbols are there and the results are right.
The first compile of that process still refreshes (numba's compiler does, before typing).
``FEMOAT_CACHE_LOAD_WITHOUT_REFRESH=0`` gives numba's load, refresh included. Each case runs in
a fresh process on a private numba cache. The solver's own warm start is checked in
tests/test_startup.py.
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
import numpy as np

from femoat.compilation.jit import njit


@njit(cache=True)
def spring(k, u):
    """A hardening spring's force [kip]: k u + 0.1 k u^3 (k [kip/in], u [in])."""
    return k * u + 0.1 * k * u ** 3


@njit(cache=True, _nrt=True)
def salted(n):
    """hash("femoat") + n: numba hashes a string with CPython's secret, which it reads through
    the symbols numba.cpython.hashing registers."""
    return hash("femoat") + n


@njit(cache=True, _nrt=True)
def triangle(n):
    """0 + 1 + ... + (n - 1), summed from an array that numba's runtime (NRT) allocates."""
    a = np.empty(n)
    for i in range(n):
        a[i] = i
    s = 0.0
    for i in range(n):
        s += a[i]
    return s
'''

BODY = '''
import json, sys
from numba.core import base
refreshes = []
_refresh = base.BaseContext.refresh
def counting(self):
    refreshes.append(1)
    return _refresh(self)
base.BaseContext.refresh = counting
import loaded
out = {"spring": loaded.spring(2.0, 1.5)}
out["after_spring"] = [len(refreshes), "scipy.linalg" in sys.modules]
out["salted"] = loaded.salted(7) - hash("femoat")
out["triangle"] = loaded.triangle(100)
out["loaded"] = [len(refreshes)] + [
    [sum(k.dispatcher.stats.cache_hits.values()), sum(k.dispatcher.stats.cache_misses.values())]
    for k in (loaded.spring, loaded.salted, loaded.triangle)]
if sys.argv[1] == "warm":
    out["spring_int"] = loaded.spring(2, 3)  # integer arguments: a signature not in the cache
    out["after_compile"] = [len(refreshes), "scipy.linalg" in sys.modules]
print(json.dumps(out))
'''


def _run(tmp_path, cache, stage, **env):
    folder = tmp_path / "src"
    folder.mkdir(exist_ok=True)
    (folder / "loaded.py").write_text(KERNELS)
    environ = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / cache), **env,
               "PYTHONPATH": os.pathsep.join([str(folder), str(ROOT),
                                              os.environ.get("PYTHONPATH", "")])}
    r = subprocess.run([sys.executable, "-c", textwrap.dedent(BODY), stage], env=environ,
                       capture_output=True, text=True, timeout=300, check=False)
    assert r.returncode == 0, r.stderr[-3000:]
    return json.loads(r.stdout.strip().splitlines()[-1])


def test_a_cached_kernel_loads_and_runs_without_numbas_refresh(tmp_path):
    from femoat.compilation.cache_load import NUMBA_VERSIONS
    from femoat.compilation.numba_version import supported

    if not supported(NUMBA_VERSIONS):
        pytest.skip("femoat.compilation.cache_load is not installed on this numba")
    # the spring's force at u = 1.5 in, k = 2 kip/in, the operations in Python's order:
    # 2*1.5 + (0.1*2)*1.5**3 = 3.675 kip; the triangle number 99*100/2 = 4950 (exact in
    # floating point: every partial sum is an integer below 2^53)
    spring = 2.0 * 1.5 + 0.1 * 2.0 * 1.5 ** 3
    cold = _run(tmp_path, "cache", "cold")
    assert cold["spring"] == spring and cold["salted"] == 7 and cold["triangle"] == 4950.0
    assert cold["after_spring"][0] >= 1  # compiled: numba's compiler refreshed
    shutil.copytree(tmp_path / "cache", tmp_path / "cache-numba")

    warm = _run(tmp_path, "cache", "warm")
    # each kernel loaded from the cache (one hit, no miss), none refreshing numba's context,
    # and scipy.linalg (imported by the refresh, for numba's BLAS check) never imported
    assert warm["after_spring"] == [0, False]
    assert warm["loaded"] == [0, [1, 0], [1, 0], [1, 0]]
    # the runtime's symbols are there: the right hash (this process's secret) and the sum
    assert warm["spring"] == spring and warm["salted"] == 7 and warm["triangle"] == 4950.0
    # the first compile refreshes as numba always did: 2*3 + (0.1*2)*3**3 = 11.4 kip
    assert warm["spring_int"] == 2 * 3 + 0.1 * 2 * 3 ** 3
    assert warm["after_compile"][0] >= 1 and warm["after_compile"][1]

    # the switch off: numba's load, which refreshes before the first entry it loads
    numba = _run(tmp_path, "cache-numba", "warm", FEMOAT_CACHE_LOAD_WITHOUT_REFRESH="0")
    assert numba["after_spring"][0] >= 1 and numba["after_spring"][1]
    assert numba["loaded"][1:] == warm["loaded"][1:]
    assert (numba["spring"], numba["salted"], numba["triangle"], numba["spring_int"]) == (
        warm["spring"], warm["salted"], warm["triangle"], warm["spring_int"])
