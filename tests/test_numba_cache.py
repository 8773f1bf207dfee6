"""femoat.numba_cache: stale compiled loops are dropped wherever numba keeps them."""

from pathlib import Path

from femoat.numba_cache import cache_dirs, drop_stale_cache


def test_cache_dirs_follow_numba_cache_dir(tmp_path, monkeypatch):
    # numba's own locator for a user cache folder (numba.core.caching) names the subfolder
    from numba.core.caching import UserProvidedCacheLocator

    src = tmp_path / "pkg" / "kernel.py"
    src.parent.mkdir()
    src.write_text("x = 1\n")
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    sub = UserProvidedCacheLocator.get_suitable_cache_subpath(str(src))
    assert cache_dirs(src) == [src.parent / "__pycache__", tmp_path / "cache" / sub]


def test_a_changed_dependency_drops_the_cached_module_in_both_folders(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    src = tmp_path / "pkg" / "kernel.py"
    dep = tmp_path / "pkg" / "law.py"
    src.parent.mkdir()
    src.write_text("x = 1\n")
    dep.write_text("k = 1\n")
    drop_stale_cache(src, [dep])  # first stamp
    planted = [Path(d) / "kernel.run-1.py311.nbi" for d in cache_dirs(src)]
    for p in planted:
        p.write_bytes(b"stale")
    drop_stale_cache(src, [dep])  # nothing changed: kept
    assert all(p.exists() for p in planted)
    dep.write_text("k = 2\n")     # an inlined kernel changed: dropped everywhere
    drop_stale_cache(src, [dep])
    assert not any(p.exists() for p in planted)
