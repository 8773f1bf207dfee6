"""The building solver's kernels compiled ahead of time, so a new process starts without numba.

numba's on-disk cache saves compiling, but not numba itself: importing it and initialising its
CPU target takes about 1.2 s per process on a 2-core machine, thirty paper runs' worth. After
the first run, :func:`build` compiles the solver's entry points with ``numba.pycc`` into a
plain CPython extension module kept in femoat's cache folder; later processes load it
(:func:`load`, a few milliseconds) and never import numba. Results are bit-identical to the
JIT kernels (the same LLVM code).

* The module is keyed by a hash of every kernel source file, the Python and numba versions and
  the platform, so an edit or an upgrade makes femoat use the JIT again until it is rebuilt.
* ``femoat paper`` and ``femoat run`` build it once at the end of a run when it is missing (about
  25 s; ``femoat compile`` does it on its own). It needs setuptools and a C compiler; without
  them femoat keeps using the JIT.
* ``FEMOAT_AOT=0`` switches it off (load nothing, build nothing); the cache folder is
  ``$FEMOAT_CACHE`` or ``~/.cache/femoat`` (``FEMOAT_CACHE=off`` also switches it off).
* Generic x86-64 (or the platform's generic) code: the cache may be shared between machines; it
  is within a few per cent of host-tuned code on this solver.
"""

import functools
import hashlib
import importlib.machinery
import importlib.util
import os
import platform
import shutil
import sys
import tempfile
from importlib import metadata
from pathlib import Path

from femoat.jit import OPTIONS

MODULE = "femoat_aot_kernels"
EXPORTS = ("run_chunk", "ground_accel", "internal_force", "material_commit",
           "material_recoverable_energy", "contact_stored_energy")
"""The functions the building solver calls from Python (:mod:`femoat.integration.solve`)."""

_ROOT = Path(__file__).resolve().parent
_SOURCES = ("jit.py", "contact/kernels.py", "integration/kernel.py", "structure/materials")
_loaded = {}
_NEEDS = ("this needs a C compiler (cc/gcc; Debian/Ubuntu: apt-get install gcc) and setuptools "
          "(pip install setuptools). femoat keeps using numba's JIT.")


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


def build(force=False):
    """Compile the kernels ahead of time into :func:`module_path`; return that path.

    Runs the JIT solver once on a tiny model (instant when numba's cache is warm) to learn the
    exact argument types, then compiles with ``numba.pycc``. Raises RuntimeError naming what is
    missing (setuptools, a C compiler) when it cannot build.
    """
    path = module_path()
    if path.is_file() and not force:
        return path
    signatures = _signatures()
    try:
        from numba.pycc import CC
    except ImportError as err:
        raise RuntimeError(f"cannot compile ahead of time: {err}; {_NEEDS}") from None
    import warnings

    path.parent.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=".build-", dir=path.parent))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # numba.pycc's pending-deprecation notice
            try:  # CC() itself raises when it finds no compiler (with conda-only advice)
                cc = CC(MODULE)
                cc.output_dir = str(work)
                cc.output_file = path.name
                cc.use_nrt = OPTIONS.get("_nrt", True)  # the kernels' own compile options
                for name, (kernel, sig) in signatures.items():
                    cc.export(name, sig)(kernel.py_func)
                cc.compile()
            except Exception as err:
                raise RuntimeError(f"cannot compile ahead of time ({type(err).__name__}: "
                                   f"{str(err).strip()}); {_NEEDS}") from None
        os.replace(work / path.name, path)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    _loaded.pop(path, None)
    return path


def ensure(report=print):
    """Build the module if it is missing and allowed; report what happens. Never raises."""
    if not enabled() or module_path().is_file():
        return None
    report("femoat: compiling the solver ahead of time so that later runs start fast (once; "
           "about 25 s; FEMOAT_AOT=0 skips this)")
    try:
        path = build()
    except Exception as err:  # a missing compiler must not fail the user's run
        report(f"femoat: ahead-of-time compilation skipped: {err}")
        return None
    report(f"femoat: wrote {path}")
    return path


def _signatures():
    """{exported name: (Kernel, numba signature)} from a JIT run of a tiny model."""
    import numpy as np
    from numba.core.types import Literal

    from femoat.contact import kernels as contact
    from femoat.integration import kernel as kn
    from femoat.run import run
    from femoat.structure import materials

    entry = {"run_chunk": kn.run_chunk, "ground_accel": kn.ground_accel,
             "internal_force": kn._internal_force, "material_commit": materials.material_commit,
             "material_recoverable_energy": materials.material_recoverable_energy,
             "contact_stored_energy": contact.contact_stored_energy}
    if not kn.run_chunk.dispatcher.signatures:
        from femoat.ground_motions import GroundMotion
        from femoat.paper import paper_model

        t = np.arange(0.0, 0.2, 0.01)
        quake = GroundMotion(np.sin(2 * np.pi * t), 0.01, name="aot signature probe")
        run(paper_model("concrete", "H"), quake, extra_time=0.0, backend="jit")
    out = {}
    for name, kernel in entry.items():
        d = kernel.dispatcher
        if not d.signatures:  # only called when a run ends in contact: compile it here
            args = {"contact_stored_energy": (0, np.zeros(contact.N_PARAMS),
                                              np.zeros(contact.N_HISTORY), 0.0)}[name]
            d(*args)
        # the Python-facing signature: kernels compiled as callees inside other kernels may
        # add variants specialised on literal arguments (want_tangent=True, ...)
        plain = [s for s in d.signatures if not any(isinstance(t, Literal) for t in s)]
        if len(plain) != 1:
            raise RuntimeError(f"{name} has {len(plain)} compiled signatures without literal "
                               f"arguments ({d.signatures}); expected 1")
        out[name] = (kernel, d.overloads[plain[0]].signature)
    return out
