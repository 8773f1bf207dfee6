"""The building solver's kernels compiled ahead of time, so a new process starts without numba.

numba's on-disk cache saves compiling, but not numba itself: importing it and initialising its
CPU target costs each process more than many paper runs (``benchmarks/README.md``). After
the first run, :func:`build` compiles the solver's entry points with ``numba.pycc`` into a
plain CPython extension module kept in femoat's cache folder; later processes load it
(:func:`load`, a few milliseconds) and never import numba. Results are bit-identical to the
JIT kernels (the same LLVM code).

* The module is keyed by a hash of every kernel source file, the Python and numba versions and
  the platform, so an edit or an upgrade makes femoat use the JIT again until it is rebuilt.
* ``femoat paper`` and ``femoat run`` build it once at the end of a run when it is missing (tens
  of seconds; ``femoat compile`` does it on its own). It needs setuptools and a C compiler; without
  them femoat keeps using the JIT.
* ``FEMOAT_AOT=0`` switches it off (load nothing, build nothing); the cache folder is
  ``$FEMOAT_CACHE`` or ``~/.cache/femoat`` (``FEMOAT_CACHE=off`` also switches it off).
* Generic x86-64 (or the platform's generic) code: the cache may be shared between machines; it
  is within a few per cent of host-tuned code on this solver.
"""

import os
import shutil
import tempfile
from pathlib import Path

from femoat import compiled
from femoat.compiled import (  # noqa: F401  (the module's public face, kept here)
    _SOURCES,
    EXPORTS,
    MODULE,
    _key,
    enabled,
    load,
    module_path,
)
from femoat.jit import OPTIONS

_NEEDS = ("this needs a C compiler (cc/gcc; Debian/Ubuntu: apt-get install gcc) and setuptools "
          "(pip install setuptools). femoat keeps using numba's JIT.")


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
    compiled._loaded.pop(path, None)
    return path


def ensure(report=print):
    """Build the module if it is missing and allowed; report what happens. Never raises."""
    if not enabled() or module_path().is_file():
        return None
    report("femoat: compiling the solver ahead of time so that later runs start fast (once; "
           "about 45 s; FEMOAT_AOT=0 skips this)")
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
    from femoat.integration.probe import run_probe
    from femoat.structure import materials

    entry = {"run_chunk": kn.run_chunk, "ground_accel": kn.ground_accel,
             "internal_force": kn.internal_force, "start_peaks": kn.start_peaks,
             "finish_peaks": kn.finish_peaks, "material_commit": materials.material_commit,
             "material_recoverable_energy": materials.material_recoverable_energy,
             "contact_stored_energy": contact.contact_stored_energy}
    if not kn.run_chunk.dispatcher.signatures:
        run_probe(backend="jit")
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
