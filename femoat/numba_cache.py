"""Keep numba's on-disk cache honest across modules.

numba keys a cached function on the modification time of *its own* source file only. The
time-stepping loop inlines the contact-law and material kernels from other files, so editing a
kernel would leave a stale compiled loop in the cache. :func:`drop_stale_cache` hashes the files
a compiled module depends on and deletes that module's cache entries when the hash changes.
"""

import hashlib
import os
from pathlib import Path


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


def drop_stale_cache(module_file, dependencies, tag="deps"):
    """Delete ``module_file``'s numba cache files if any file in ``dependencies`` changed.

    ``tag`` names the stamp file, so that independent checks of one module (its inlined
    dependencies; femoat.jit's compile options) do not overwrite each other's stamps.
    """
    module_file = Path(module_file)
    h = hashlib.sha256()
    for dep in sorted(str(d) for d in dependencies):
        try:
            h.update(Path(dep).read_bytes())
        except OSError:
            return
    digest = h.hexdigest()
    for cache_dir in cache_dirs(module_file):
        _drop_if_stale(cache_dir, module_file.stem, tag, digest)


def _drop_if_stale(cache_dir, stem, tag, digest):
    stamp = cache_dir / f"{stem}.{tag}-sha256"
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
