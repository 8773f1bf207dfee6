"""Keep numba's on-disk cache honest across modules.

numba keys a cached function on the modification time of *its own* source file only. The
time-stepping loop inlines the contact-law and material kernels from other files, so editing a
kernel would leave a stale compiled loop in the cache. :func:`drop_stale_cache` deletes a
module's cache entries when the fingerprint of every kernel source
(:func:`femoat.compilation.sources.fingerprint`) differs from the one they were compiled with;
:mod:`femoat.compilation.jit` calls it before numba first compiles or loads a module's kernels.
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
