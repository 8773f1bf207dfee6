"""femoat.compilation: one list of the sources that matter, hashed lazily, and numba's cache
kept honest with it (stale compiled loops dropped wherever numba keeps them)."""

import ast
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from femoat.compilation import sources as src
from femoat.compilation.exports import EXPORTS
from femoat.compilation.numba_cache import cache_dirs, drop_stale_cache

PACKAGE = src.PACKAGE


def test_cache_dirs_follow_numba_cache_dir(tmp_path, monkeypatch):
    # numba's own locator for a user cache folder (numba.core.caching) names the subfolder
    from numba.core.caching import UserProvidedCacheLocator

    f = tmp_path / "pkg" / "kernel.py"
    f.parent.mkdir()
    f.write_text("x = 1\n")
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    sub = UserProvidedCacheLocator.get_suitable_cache_subpath(str(f))
    assert cache_dirs(f) == [f.parent / "__pycache__", tmp_path / "cache" / sub]


def test_a_changed_fingerprint_drops_the_cached_module_in_both_folders(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    f = tmp_path / "pkg" / "kernel.py"
    f.parent.mkdir()
    f.write_text("x = 1\n")
    drop_stale_cache(f, "a" * 64)  # first stamp
    planted = [Path(d) / "kernel.run-1.py311.nbi" for d in cache_dirs(f)]
    other = [Path(d) / "law.force-1.py311.nbi" for d in cache_dirs(f)]  # another module's
    for p in planted + other:
        p.write_bytes(b"stale")
    drop_stale_cache(f, "a" * 64)  # compiled from these sources: kept
    assert all(p.exists() for p in planted)
    drop_stale_cache(f, "b" * 64)  # a kernel source changed: dropped everywhere
    assert not any(p.exists() for p in planted)
    assert all(p.exists() for p in other)  # only this module's entries


def test_first_compile_of_a_module_drops_its_kernels_compiled_from_other_sources(tmp_path):
    # A module of femoat kernels whose numba cache was stamped by other sources (as after an
    # edit of an inlined kernel): its first compile in a process must drop the planted entry
    # and stamp the cache with the current kernel fingerprint, before numba loads anything.
    (tmp_path / "mykernels.py").write_text(
        "from femoat.compilation.jit import njit\n\n\n"
        "@njit(cache=True)\ndef twice(x):\n    return 2.0 * x\n")
    cache = tmp_path / "__pycache__"
    cache.mkdir()
    (cache / "mykernels.sources-sha256").write_text("0" * 64)
    planted = cache / "mykernels.twice-4.py311.nbi"
    planted.write_bytes(b"stale")
    code = ("import mykernels; from femoat.compilation.sources import fingerprint; "
            "print(mykernels.twice(1.5), fingerprint('kernels'))")
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["PYTHONPATH"] = os.pathsep.join([str(tmp_path), str(PACKAGE.parent)])
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr[-2000:]
    value, digest = done.stdout.split()
    assert float(value) == 3.0
    assert not planted.exists() or planted.read_bytes() != b"stale"
    assert (cache / "mykernels.sources-sha256").read_text() == digest


# ---- the one list of sources ----------------------------------------------------------------

def _module_name(path):
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _defines_kernels(tree):
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef):
            for d in node.decorator_list:
                f = d.func if isinstance(d, ast.Call) else d
                if getattr(f, "id", getattr(f, "attr", None)) == "njit":
                    return True
    return False


def _module_imports(tree, modules):
    """femoat modules imported at module level (what a kernel may read as a global)."""
    out = set()
    for node in tree.body:
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("femoat"):
            out |= {f"{node.module}.{a.name}" if f"{node.module}.{a.name}" in modules
                    else node.module for a in node.names}
        elif isinstance(node, ast.Import):
            out |= {a.name for a in node.names if a.name.startswith("femoat")}
    return out


def _unlisted(listed):
    """Modules defining njit kernels, or imported (transitively) by one, missing from
    ``listed`` (a set of files)."""
    modules = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    trees = {m: ast.parse(p.read_text()) for m, p in modules.items()}
    stack = [m for m, t in trees.items() if _defines_kernels(t)]
    assert len(stack) >= 10, stack  # the contact laws, materials and solver at least
    seen = set()
    while stack:
        m = stack.pop()
        if m not in seen:
            seen.add(m)
            stack += _module_imports(trees[m], modules)
    return sorted(m for m in seen if modules[m] not in listed)


def test_every_kernel_module_and_what_it_imports_is_a_kernel_source(monkeypatch):
    assert _unlisted(set(src.sources("kernels"))) == []
    # the check can fail: with the contact folder left out of the list, its laws are missing
    monkeypatch.setattr(src, "KERNELS", tuple(e for e in src.KERNELS if e != "contact"))
    missing = _unlisted(set(src.sources("kernels")))
    assert "femoat.contact.kernels" in missing and "femoat.contact.hertzdamp" in missing


def test_the_suite_fingerprint_covers_the_kernels_and_every_listed_file_exists():
    kernels, results = src.sources("kernels"), src.sources("results")
    assert all(f.is_file() for f in kernels + results)
    assert set(kernels) <= set(results)  # an edited kernel changes the suite's code version
    assert PACKAGE / "suite" / "runs.py" in results  # the suite's run path counts ...
    assert not any(f.relative_to(PACKAGE).parts[0] == "plotting" for f in results)  # ... figures not
    with pytest.raises(ValueError, match="scope = 'everything'"):
        src.sources("everything")


def test_every_export_is_a_femoat_kernel_of_its_module_and_the_solver_calls_only_those():
    from femoat.compilation.jit import Kernel
    from femoat.integration.solve import kernels

    jit = kernels()
    assert sorted(vars(jit)) == sorted(EXPORTS)
    for name, module in EXPORTS.items():
        kernel = getattr(jit, name)
        assert isinstance(kernel, Kernel) and kernel.py_func.__module__ == module, name
    # every entry point the solver calls from Python is exported (else the warm-up misses it)
    import re

    called = set(re.findall(r"\bkern\.(\w+)", (PACKAGE / "integration" / "solve.py").read_text()))
    assert called and called <= set(EXPORTS)


# ---- hashed lazily: once per process, and not at all while nothing changed -------------------

def _copy_kernels(dst):
    for f in src.sources("kernels"):
        target = dst / f.relative_to(PACKAGE)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(f, target)
    return dst


def test_the_fingerprint_is_remembered_until_a_source_changes(tmp_path, monkeypatch):
    root, memo = _copy_kernels(tmp_path / "femoat"), tmp_path / "memo"
    reads = []
    real = Path.read_bytes
    monkeypatch.setattr(Path, "read_bytes", lambda p: reads.append(p) or real(p))

    def fresh_process():  # what a new process knows: only the memo on disk
        monkeypatch.setattr(src, "_digests", {})
        reads.clear()
        return src.fingerprint("kernels", root, memo)

    first = fresh_process()
    assert len(reads) == len(src.sources("kernels", root))  # each source read once
    assert first == src.fingerprint("kernels", root)  # the same as hashing without a memo
    assert fresh_process() == first and reads == []  # remembered: nothing read
    f = root / "structure" / "materials" / "imk.py"
    st = f.stat()  # a new modification time (a git checkout): read again, same fingerprint
    os.utime(f, ns=(st.st_atime_ns, st.st_mtime_ns + 1_000_000))
    assert fresh_process() == first and len(reads) > 0
    with open(f, "a") as fh:  # an edit: a new fingerprint
        fh.write("\n# edited\n")
    edited = fresh_process()
    assert edited != first and len(reads) > 0
    assert fresh_process() == edited and reads == []
