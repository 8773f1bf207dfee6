"""The ahead-of-time compiled solver module: where it lives, what it is keyed on, loading it.

numba's on-disk cache saves compiling, but not numba itself: importing it and initialising its
CPU target costs each process more than many paper runs (``benchmarks/README.md``). So the
solver's entry points (:data:`~femoat.compilation.exports.EXPORTS`) are also compiled with
``numba.pycc`` into a plain CPython extension module in femoat's cache folder
(:mod:`~femoat.compilation.aot_build`); later processes load it (:func:`load`, milliseconds)
and never import numba. Results are bit-identical to the JIT kernels (the same LLVM code).

* The module is keyed by the fingerprint of the kernel sources
  (:func:`~femoat.compilation.sources.fingerprint`), the Python, numba and numpy versions and the
  platform, so an edit or an upgrade makes femoat use the JIT again until it is rebuilt. The
  fingerprint is remembered in the cache folder: loading reads no source file while the sources'
  sizes and modification times are unchanged.
* ``FEMOAT_AOT=0`` switches it off (load nothing, build nothing); the cache folder is
  ``$FEMOAT_CACHE`` or ``~/.cache/femoat`` (``FEMOAT_CACHE=off`` also switches it off).

This is the part the solver needs at run time; building sits above the solver, since it runs it
to learn the kernels' signatures. Nothing here imports numba.
"""

import functools
import hashlib
import importlib.machinery
import importlib.util
import os
import platform
import sys
from importlib import metadata
from pathlib import Path

from femoat.compilation.exports import EXPORTS
from femoat.compilation.jit import OPTIONS
from femoat.compilation.sources import PACKAGE, fingerprint

MODULE = "femoat_aot_kernels"
_loaded = {}


def enabled():
    """False when ``FEMOAT_AOT=0`` or ``FEMOAT_CACHE=off``."""
    return os.environ.get("FEMOAT_AOT", "1") != "0" and os.environ.get("FEMOAT_CACHE") != "off"


def folder():
    """The folder of the compiled modules (and of the remembered source fingerprints)."""
    root = os.environ.get("FEMOAT_CACHE")
    base = Path(root) if root else (Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache"))
                                    / "femoat")
    return base / "aot"


def module_path():
    """Where the compiled module for these sources, this Python and this numba lives."""
    suffix = importlib.machinery.EXTENSION_SUFFIXES[0]
    return folder() / f"{MODULE}-{key(PACKAGE, folder())}{suffix}"


@functools.lru_cache(maxsize=4)
def key(root, memo=None):
    """Hash of the kernel sources under ``root``, Python, numba, numpy and the platform (once
    per process; ``memo``: the folder remembering the sources' fingerprint)."""
    versions = []
    for package in ("numba", "numpy"):  # the module links numba's runtime and numpy's C API
        try:
            versions.append(f"{package} {metadata.version(package)}")
        except metadata.PackageNotFoundError:
            versions.append(f"{package} none")
    h = hashlib.sha256(fingerprint("kernels", root, memo).encode())
    h.update(f"{sys.implementation.cache_tag} {versions} {sys.platform} "
             f"{platform.machine()} {sorted(OPTIONS.items())} {sorted(EXPORTS)}".encode())
    return h.hexdigest()[:16]


def load():
    """The compiled module, or None (not built for these sources, switched off, or unloadable)."""
    if not enabled():
        return None
    try:
        path = module_path()
    except Exception:  # e.g. an install without the kernel sources: nothing to key on
        return None
    if path in _loaded:
        return _loaded[path]
    module = None
    if path.is_file():
        try:
            loader = importlib.machinery.ExtensionFileLoader(MODULE, str(path))
            spec = importlib.util.spec_from_file_location(MODULE, path, loader=loader)
            module = importlib.util.module_from_spec(spec)
            loader.exec_module(module)
            if not all(hasattr(module, name) for name in EXPORTS):
                module = None
        except Exception:
            module = None  # built for another interpreter or damaged: the JIT is used
    _loaded[path] = module
    return module
