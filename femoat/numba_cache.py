"""Keep numba's on-disk cache honest across modules.

numba keys a cached function on the modification time of *its own* source file only. The
time-stepping loop inlines the contact-law and material kernels from other files, so editing a
kernel would leave a stale compiled loop in the cache. :func:`drop_stale_cache` hashes the files
a compiled module depends on and deletes that module's cache entries when the hash changes.
"""

import hashlib
from pathlib import Path


def drop_stale_cache(module_file, dependencies, tag="deps"):
    """Delete ``module_file``'s numba cache files if any file in ``dependencies`` changed.

    ``tag`` names the stamp file, so that independent checks of one module (its inlined
    dependencies; femoat.jit's compile options) do not overwrite each other's stamps.
    """
    module_file = Path(module_file)
    cache_dir = module_file.parent / "__pycache__"
    h = hashlib.sha256()
    for dep in sorted(str(d) for d in dependencies):
        try:
            h.update(Path(dep).read_bytes())
        except OSError:
            return
    digest = h.hexdigest()
    stamp = cache_dir / f"{module_file.stem}.{tag}-sha256"
    try:
        if stamp.read_text() == digest:
            return
    except OSError:
        pass
    try:
        for f in cache_dir.glob(f"{module_file.stem}.*.nb[ic]"):
            f.unlink()
        cache_dir.mkdir(exist_ok=True)
        stamp.write_text(digest)
    except OSError:
        pass  # read-only install: numba falls back to compiling in memory
