"""femoat's replacements of numba internals: installed on the numba they were read against, each
off with its switch (femoat.compilation.numba_version)."""

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MODULES = {"inlining": "FEMOAT_FAST_INLINE", "ssa": "FEMOAT_FAST_SSA",
           "liveness": "FEMOAT_FAST_LIVENESS", "flags": "FEMOAT_FAST_FLAGS",
           "call_types": "FEMOAT_CALL_TYPES_MEMO", "error_markup": "FEMOAT_FAST_ERROR_MARKUP",
           "cache_load": "FEMOAT_CACHE_LOAD_WITHOUT_REFRESH"}


def test_supported_is_a_closed_range_of_minor_versions(monkeypatch):
    from femoat.compilation import numba_version

    monkeypatch.setattr(numba_version, "minor", lambda: (0, 68))
    assert numba_version.supported(((0, 68), (0, 68)))
    assert numba_version.supported(((0, 60), (0, 68)))
    assert numba_version.supported(((0, 68), (1, 0)))
    assert not numba_version.supported(((0, 69), (0, 70)))
    monkeypatch.setenv("FEMOAT_SOMETHING", "0")
    assert not numba_version.wanted("FEMOAT_SOMETHING", ((0, 68), (0, 68)))
    monkeypatch.setenv("FEMOAT_SOMETHING", "1")
    assert numba_version.wanted("FEMOAT_SOMETHING", ((0, 68), (0, 68)))


def test_each_is_installed_with_femoats_kernels_and_off_with_its_switch():
    # a fresh process each way (installation happens once, when femoat first imports numba)
    names = ", ".join(MODULES)
    code = (f"from femoat.compilation import jit, {names}; jit._register(); "
            f"print(*(bool(m._installed) for m in ({names},)))")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get(
        "PYTHONPATH", "")])}
    on = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                        check=True)
    off = subprocess.run([sys.executable, "-c", code],
                         env={**env, **dict.fromkeys(MODULES.values(), "0")},
                         capture_output=True, text=True, check=True)
    from femoat.compilation import numba_version
    from femoat.compilation.ssa import NUMBA_VERSIONS

    assert on.stdout.split() == [str(numba_version.supported(NUMBA_VERSIONS))] * len(MODULES)
    assert off.stdout.split() == ["False"] * len(MODULES)
