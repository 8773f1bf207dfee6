"""Process start-up: numba is imported only when the solver runs, and a second process loads
the solver's kernels from numba's on-disk cache instead of compiling them.

Derived from the design, not timed: numba's dispatchers count, per process, the signatures they
compiled (``stats.cache_misses``) and those they loaded from the cache (``stats.cache_hits``).
"""

import json

from conftest import _python_env, run_in

from femoat.startup.warmup import warm_up


def test_importing_the_solver_does_not_import_numba(tmp_path):
    code = ("import sys, femoat.paper, femoat.run, femoat.scenario, femoat.cli; "
            "print('numba' in sys.modules)")
    done = run_in(code, _python_env(tmp_path))
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "False"


_COUNTS = (
    "import json, sys\n"
    "from numba.core import base\n"
    "refreshes = []\n"
    "_refresh = base.BaseContext.refresh\n"
    "base.BaseContext.refresh = lambda self: refreshes.append(1) or _refresh(self)\n"
    "from femoat.startup.warmup import warm_up\n"
    "from femoat.compilation.exports import EXPORTS\n"
    "from femoat.integration.solve import kernels\n"
    "warm_up()\n"
    "k = kernels()\n"
    "out = {}\n"
    "for name in EXPORTS:\n"
    "    d = getattr(k, name).dispatcher\n"
    "    out[name] = [sum(d.stats.cache_hits.values()), sum(d.stats.cache_misses.values())]\n"
    "refreshed = [len(refreshes), 'scipy.linalg' in sys.modules]\n"
    "print(json.dumps({'counts': out, 'refreshed': refreshed}))\n"
)


def test_a_second_process_loads_every_entry_point_from_numbas_cache(tmp_path):
    # This process compiled (or loaded) the kernels and numba wrote them to its cache; a new
    # process running the same probe must find every entry point there: a hit, no miss, and
    # load them without refreshing numba's target context.
    warm_up()
    done = run_in(_COUNTS, _python_env(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    found = json.loads(done.stdout.strip().splitlines()[-1])
    for name, (hits, misses) in found["counts"].items():
        assert hits >= 1 and misses == 0, (name, hits, misses)
    # loaded without numba's context refresh (femoat.compilation.cache_load), so without the
    # modules it imports: scipy.linalg among them (numba's BLAS check), a third of a warm start
    from femoat.compilation import cache_load, jit

    jit._register()
    if cache_load._installed:
        assert found["refreshed"] == [0, False]


def test_femoat_compile_warms_the_cache_and_says_so(tmp_path):
    done = run_in("from femoat.cli import main; raise SystemExit(main(['compile']))",
                  _python_env(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    assert "numba's cache" in done.stdout
