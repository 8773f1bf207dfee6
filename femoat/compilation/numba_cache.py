"""Keep numba's on-disk cache honest across modules.

numba keys a cached function on the modification time of *its own* source file only. The
time-stepping loop inlines the contact-law and material kernels from other files, so editing a
kernel would leave a stale compiled loop in the cache. :func:`drop_stale_cache` deletes a
module's cache entries when the fingerprint of every kernel source
(:func:`femoat.compilation.sources.fingerprint`) differs from the one they were compiled with;
:mod:`femoat.compilation.jit` calls it before numba first compiles or loads a module's kernels.
"""

import contextlib
import hashlib
import os
from pathlib import Path

try:
    import fcntl
except ImportError:  # not POSIX: no lock, processes may compile side by side
    fcntl = None


def cache_dirs(module_file):
    """The folders numba may cache ``module_file``'s functions in: its ``__pycache__`` and,
    with ``NUMBA_CACHE_DIR`` set, numba's folder for it there (numba's own naming: the parent
    folder's name and the SHA-1 of its absolute path)."""
    folder = Path(module_file).resolve().parent
    out = [folder / "__pycache__"]
    user = os.environ.get("NUMBA_CACHE_DIR")
    if user:
        digest = hashlib.sha1(str(folder).encode()).hexdigest()
        out.append(Path(user) / f"{folder.name}_{digest}")
    return out


def drop_stale_cache(module_file, digest):
    """Delete ``module_file``'s numba cache files unless they were compiled from sources whose
    fingerprint is ``digest``; then stamp its cache folders with ``digest``."""
    module_file = Path(module_file)
    for cache_dir in cache_dirs(module_file):
        _drop_if_stale(cache_dir, module_file.stem, digest)


def _drop_if_stale(cache_dir, stem, digest):
    stamp = cache_dir / f"{stem}.sources-sha256"
    try:
        if stamp.read_text() == digest:
            return
    except OSError:
        pass
    try:
        for f in cache_dir.glob(f"{stem}.*.nb[ic]"):
            f.unlink()
        cache_dir.mkdir(parents=True, exist_ok=True)
        stamp.write_text(digest)
    except OSError:
        pass  # read-only install: numba falls back to compiling in memory


_locked_once = []


@contextlib.contextmanager
def first_compile_lock(module_file):
    """Hold an exclusive lock beside ``module_file``'s numba cache during this process's first
    use of the solver (reentrant calls and later uses pass straight through).

    Processes starting together on a fresh install (a suite's workers, a test session's
    workers, several commands) would otherwise each compile the same kernels at once, sharing
    the cores; with the lock one compiles and writes the cache while the others wait, then
    load the kernels from it in about a second. A folder that cannot hold the lock (read-only,
    not POSIX) gives no lock: numba's own cache writes stay safe, they only cost CPU."""
    if _locked_once or fcntl is None:
        yield
        return
    _locked_once.append(True)
    folder = cache_dirs(module_file)[-1]
    try:
        folder.mkdir(parents=True, exist_ok=True)
        handle = open(folder / "femoat-compile.lock", "a")
    except OSError:
        yield
        return
    with handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def locked_saves(dispatcher):
    """Make ``dispatcher`` (a femoat kernel's numba dispatcher) save to numba's on-disk cache
    under an exclusive lock beside the cache files (POSIX; elsewhere, or without an on-disk
    cache, a no-op).

    numba saves an entry by reading the kernel's index, adding the entry and its data file's
    number, and writing both back. Two processes saving two entries of one kernel at once (the
    compile helper of :mod:`femoat.compilation.compile_plan` beside the first run; a test
    session's workers) could each read the index before the other wrote it and give both
    entries the same data file: one key would then load the other's code. Under the lock the
    read, the choice of the number and both writes are one step."""
    from numba.core import caching

    cache = getattr(dispatcher, "_cache", None)
    if fcntl is None or not isinstance(cache, caching.Cache):
        return dispatcher
    save = cache.save_overload

    def save_overload(sig, data):
        try:
            os.makedirs(cache._cache_path, exist_ok=True)
            handle = open(os.path.join(cache._cache_path, "femoat-save.lock"), "a")
        except OSError:
            return save(sig, data)  # a folder numba cannot write either: it skips the save
        with handle:
            fcntl.flock(handle, fcntl.LOCK_EX)
            try:
                return save(sig, data)
            finally:
                fcntl.flock(handle, fcntl.LOCK_UN)

    save_overload.__wrapped__ = save
    cache.save_overload = save_overload
    return dispatcher
