"""Process start-up: lazy numba, no source read, and the ahead-of-time compiled solver kernels
(femoat.compilation.aot).

A new process must not pay for numba (≈1.2 s here) when the compiled kernels exist; the AOT
kernels must give exactly the JIT's results. The build runs in a temporary cache folder
(FEMOAT_CACHE) in a subprocess, so the user's cache is never touched.
"""

import json
import shutil


import numpy as np
import pytest
from conftest import _python_env, run_in

from femoat.compilation import aot, sources
from femoat.paper import paper_model, paper_motion
from femoat.run import run


def _python(code, env):
    return run_in(code, env)


def _env(cache, aot_on=True):
    return _python_env(cache, aot_on)


def test_importing_the_solver_does_not_import_numba(tmp_path):
    code = ("import sys, femoat.paper, femoat.run, femoat.scenario, femoat.cli; "
            "print('numba' in sys.modules)")
    done = _python(code, _env(tmp_path))
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "False"


@pytest.fixture(scope="module")
def built(aot_cache):
    return aot_cache


def test_aot_kernels_match_the_jit_and_skip_numba(built, tmp_path):
    out = tmp_path / "aot.npz"
    code = (
        "import sys, json\n"
        "from femoat.paper import paper_model, paper_motion\n"
        "from femoat.run import run\n"
        "r = run(paper_model('steel', 'J'), paper_motion(quick=True))\n"
        f"r.save({str(out)!r})\n"
        "print(json.dumps([r.meta['stats']['kernels'], 'numba' in sys.modules]))\n"
    )
    done = _python(code, _env(built))
    assert done.returncode == 0, done.stderr[-3000:]
    kernels, numba_imported = json.loads(done.stdout.strip().splitlines()[-1])
    assert kernels == "aot" and not numba_imported
    # Same LLVM code for the same inputs: bit-identical histories, not merely close.
    from femoat.results import RunResult

    a = RunResult.load(out)
    j = run(paper_model("steel", "J"), paper_motion(quick=True), backend="jit")
    assert j.meta["stats"]["kernels"] == "jit"
    np.testing.assert_array_equal(a.time, j.time)
    np.testing.assert_array_equal(a.displacement, j.displacement)
    np.testing.assert_array_equal(a.contact_force, j.contact_force)
    assert a.meta["stats"]["steps"] == j.meta["stats"]["steps"]
    assert a.energy == j.energy


def test_aot_kernels_take_any_array_layout(built, tmp_path):
    # The compiled module checks only the item size of its arguments: solve() hands it
    # C-contiguous float64/int64 copies of whatever the PackedModel holds.
    code = (
        "import json, numpy as np\n"
        "from femoat.integration.solve import solve\n"
        "from femoat.paper import paper_model, paper_motion\n"
        "m, gm = paper_model('concrete', 'H'), paper_motion(quick=True)\n"
        "out = []\n"
        "for odd in (False, True):\n"
        "    p = m.pack()\n"
        "    if odd:\n"
        "        p.M, p.K = np.asfortranarray(p.M), np.asfortranarray(p.K)\n"
        "        p.el_code = p.el_code.astype(np.int32)\n"
        "        p.c_gap = np.repeat(p.c_gap, 2)[::2]\n"
        "    h = solve(p, gm.accel, gm.dt, 5.0, backend='aot')\n"
        "    out.append([float(np.abs(h.arrays['contact_force']).max()), int(h.stats['steps'])])\n"
        "print(json.dumps(out))\n"
    )
    done = _python(code, _env(built))
    assert done.returncode == 0, done.stderr[-3000:]
    canonical, odd = json.loads(done.stdout.strip().splitlines()[-1])
    assert odd == canonical


def test_compile_check_and_switch(built, tmp_path):
    check = "from femoat.cli import main; raise SystemExit(main(['compile', '--check']))"
    assert _python(check, _env(built)).returncode == 0
    assert _python(check, _env(tmp_path)).returncode == 1  # an empty cache: not built
    # FEMOAT_AOT=0: the built module is ignored, the JIT runs.
    code = ("from femoat.integration.solve import kernels; print(kernels()[1])")
    assert _python(code, _env(built, aot_on=False)).stdout.strip() == "jit"
    assert _python(code, _env(built)).stdout.strip() == "aot"


def test_asking_for_missing_aot_kernels_is_explained():
    # The test session runs with FEMOAT_AOT=0 (conftest), so nothing is loaded.
    with pytest.raises(ValueError, match="femoat compile"):
        run(paper_model("concrete", "H"), paper_motion(quick=True), duration=0.1, backend="aot")
    with pytest.raises(ValueError, match="backend = 'gpu'"):
        run(paper_model("concrete", "H"), paper_motion(quick=True), duration=0.1, backend="gpu")


def test_module_key_follows_the_kernel_sources(tmp_path, monkeypatch):
    # A copy of the package's kernel sources: the key must change when any of them changes,
    # so an edited kernel is never served by a stale compiled module.
    for f in sources.sources("kernels"):
        dst = tmp_path / f.relative_to(sources.PACKAGE)
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(f, dst)
    first = aot.key(tmp_path)
    assert first == aot.key(sources.PACKAGE)  # same sources, same key
    with open(tmp_path / "structure" / "materials" / "imk.py", "a") as f:
        f.write("\n# edited\n")
    # (computed once per process: sources do not change under a run)
    aot.key.cache_clear()
    monkeypatch.setattr(sources, "_digests", {})
    assert aot.key(tmp_path) != first


_READS = (
    "import sys\n"
    "root = {root!r}\n"
    "reads = []\n"
    "def hook(event, args):\n"
    "    if event == 'open' and isinstance(args[0], str) and args[0].startswith(root) \\\n"
    "            and args[0].endswith('.py'):\n"
    "        f = sys._getframe(1)\n"
    "        while f and not f.f_code.co_filename.startswith('<frozen importlib'):\n"
    "            f = f.f_back\n"
    "        if f is None:  # not the import system reading a module to compile it\n"
    "            reads.append(args[0])\n"
    "sys.addaudithook(hook)\n"
    "import femoat.cli, femoat.paper, femoat.run, femoat.scenario, femoat.suite\n"
    "from femoat.integration.solve import kernels\n"
    "print(kernels()[1], reads)\n"
)


def test_importing_femoat_and_loading_the_aot_module_reads_no_source_file(built, tmp_path):
    # Python's audit hook sees every file opened; the import system's own reads (compiling a
    # module whose bytecode is stale) do not count. The first process after a change of the
    # sources hashes them once (here: the build); later ones read none.
    code = _READS.format(root=str(sources.PACKAGE))
    for _ in range(2):
        done = _python(code, _env(built))
        assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.strip() == "aot []"
    # the check can fail: the process that first keys the module on a fresh cache reads them
    done = _python(code, _env(tmp_path))
    used, reads = done.stdout.strip().split(" ", 1)
    assert used == "jit" and str(sources.PACKAGE / "integration" / "driver.py") in reads
