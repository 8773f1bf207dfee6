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
    """Make ``dispatcher`` (a femoat kernel's numba dispatcher) write its on-disk cache entries
    under an exclusive lock beside the cache files (POSIX), the data file before the index.
    Without an on-disk cache a no-op; where the lock cannot be taken (not POSIX, a file system
    without ``flock``), the entry is still written data first.

    numba writes an entry (``IndexDataCacheFile.save``) by reading the kernel's index, taking
    the first data-file number the index does not list, writing the index, then the data
    file. Two processes writing two entries of one kernel at once (the compile helper of
    :mod:`femoat.compilation.compile_plan` beside the first run; a test session's workers)
    could each read the index before the other wrote it and give both entries the same data
    file: one key would then load the other's code. And a data file left from an index numba
    discarded (another numba version's) still holds old code: a process reading the new index
    before the new data file is written, or after the writer was stopped between the two,
    would load that old code under the new key. Under the lock, reading the index, choosing
    the number and both writes are one step; written data first, an index never names a data
    file that is not yet its entry's."""
    from numba.core import caching

    cache = getattr(dispatcher, "_cache", None)
    if not isinstance(cache, caching.Cache):
        return dispatcher
    files = cache._cache_file

    def save(key, data):
        handle = None
        if fcntl is not None:
            try:
                os.makedirs(files._cache_path, exist_ok=True)
                handle = open(os.path.join(files._cache_path, "femoat-save.lock"), "a")
                fcntl.flock(handle, fcntl.LOCK_EX)
            except OSError:  # no lock here (e.g. a mount without flock): write unlocked
                if handle is not None:
                    handle.close()
                handle = None
        try:
            _save_data_first(files, key, data)
        finally:
            if handle is not None:
                fcntl.flock(handle, fcntl.LOCK_UN)
                handle.close()

    save.__wrapped__ = files.save
    files.save = save
    return dispatcher


def _save_data_first(files, key, data):
    """numba's ``IndexDataCacheFile.save`` (``files``), the data file written before the
    index: the same data file name for ``key`` (its own if listed, else the first number the
    index does not list), the same two files."""
    import itertools

    overloads = files._load_index()
    name = overloads.get(key)
    if name is None:
        existing = set(overloads.values())
        name = next(n for n in (files._data_name(i) for i in itertools.count(1))
                    if n not in existing)
    files._save_data(name, data)
    if overloads.get(key) != name:
        overloads[key] = name
        files._save_index(overloads)
