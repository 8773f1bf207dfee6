"""Where the ahead-of-time compiled solver module lives, what it is keyed on, and loading it.

This is the part of :mod:`femoat.aot` the solver needs at run time (:func:`load`); building the
module (:func:`femoat.aot.build`) sits above the solver, since it runs it to learn the kernels'
signatures. Loading never imports numba.
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

from femoat.jit import OPTIONS

MODULE = "femoat_aot_kernels"
EXPORTS = ("run_chunk", "ground_accel", "internal_force", "start_peaks", "finish_peaks",
           "material_commit", "material_recoverable_energy", "contact_stored_energy")
"""The functions the building solver calls from Python (:mod:`femoat.integration.solve`)."""

_ROOT = Path(__file__).resolve().parent
_SOURCES = ("jit.py", "contact", "integration", "structure/materials")
"""What the compiled module is built from: the whole integration folder (the loop, its forces,
option slots, explicit step and peaks live in separate modules since issue 15; listing only
kernel.py and bundles.py let an edited explicit step reuse a stale module)."""
_loaded = {}


def enabled():
    """False when ``FEMOAT_AOT=0`` or ``FEMOAT_CACHE=off``."""
    return os.environ.get("FEMOAT_AOT", "1") != "0" and os.environ.get("FEMOAT_CACHE") != "off"


def module_path():
    """Where the compiled module for these sources, this Python and this numba lives."""
    root = os.environ.get("FEMOAT_CACHE")
    base = Path(root) if root else (Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache"))
                                    / "femoat")
    suffix = importlib.machinery.EXTENSION_SUFFIXES[0]
    return base / "aot" / f"{MODULE}-{_key(_ROOT)}{suffix}"


@functools.lru_cache(maxsize=4)
def _key(root):
    """Hash of the kernel sources, Python, numba and platform (once per process and root)."""
    h = hashlib.sha256()
    for entry in _SOURCES:
        p = root / entry
        for f in sorted(p.glob("*.py")) if p.is_dir() else [p]:
            h.update(f.relative_to(root).as_posix().encode())
            h.update(f.read_bytes())
    versions = []
    for package in ("numba", "numpy"):  # the module links numba's runtime and numpy's C API
        try:
            versions.append(f"{package} {metadata.version(package)}")
        except metadata.PackageNotFoundError:
            versions.append(f"{package} none")
    h.update(f"{sys.implementation.cache_tag} {versions} {sys.platform} "
             f"{platform.machine()} {sorted(OPTIONS.items())}".encode())
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
