"""Building the ahead-of-time solver module (:mod:`femoat.compilation.aot`) with numba.pycc.

* ``femoat paper`` and ``femoat run`` build it once at the end of a run when it is missing (tens
  of seconds, :func:`ensure`; ``femoat compile`` does it on its own, :func:`build`). It needs
  setuptools and a C compiler; without them femoat keeps using the JIT, which stays first-class
  (numba.pycc is pending deprecation upstream).
* Generic x86-64 (or the platform's generic) code: the cache may be shared between machines; it
  is within a few per cent of host-tuned code on this solver.
"""

import os
import shutil
import tempfile
from pathlib import Path

from femoat.compilation import aot
from femoat.compilation.exports import EXPORTS
from femoat.compilation.jit import OPTIONS

_NEEDS = ("this needs a C compiler (cc/gcc; Debian/Ubuntu: apt-get install gcc) and setuptools "
          "(pip install setuptools). femoat keeps using numba's JIT.")


def build(force=False):
    """Compile the kernels ahead of time into :func:`~femoat.compilation.aot.module_path`;
    return that path.

    Runs the JIT solver once on a tiny model (instant when numba's cache is warm) to learn the
    exact argument types, then compiles with ``numba.pycc``. Raises RuntimeError naming what is
    missing (setuptools, a C compiler) when it cannot build.
    """
    path = aot.module_path()
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
                cc = CC(aot.MODULE)
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
    aot._loaded.pop(path, None)
    return path


def ensure(report=print):
    """Build the module if it is missing and allowed; report what happens. Never raises."""
    if not aot.enabled() or aot.module_path().is_file():
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
    """{exported name: (Kernel, numba signature)} from a JIT run of the probe."""
    from numba.core.types import Literal

    from femoat.compilation.probe import run_probe

    kern = run_probe(backend="jit")
    out = {}
    for name in EXPORTS:
        kernel = getattr(kern, name)
        d = kernel.dispatcher
        # the Python-facing signature: kernels compiled as callees inside other kernels may
        # add variants specialised on literal arguments (want_tangent=True, ...)
        plain = [s for s in d.signatures if not any(isinstance(t, Literal) for t in s)]
        if len(plain) != 1:
            raise RuntimeError(f"{name} has {len(plain)} compiled signatures without literal "
                               f"arguments ({d.signatures}); expected 1")
        out[name] = (kernel, d.overloads[plain[0]].signature)
    return out
