"""A kernel loaded from numba's on-disk cache without refreshing numba's whole target context.

Before numba loads a cache entry (``Cache.load_overload``) it refreshes its CPU target context:
it imports every module of implementations (numpy's functions, the typed containers, the
random generators; ``numba.np.arraymath`` imports scipy.linalg on the way, to check for BLAS),
installs their registries, refreshes the typing context and loads third-party extensions'
entry points. An entry loaded from the cache is compiled code: linking it into numba's JIT
engine needs only the run-time symbols that the refresh registers (those of numba's
reference-counted runtime, NRT, and the hash secrets of ``numba.cpython.hashing``), and a call
from Python needs the dispatcher's argument types, which numba's ``typeof`` gives without the
registries. In a process that only loads the solver from the cache, the refresh is about a
third of its start-up.

A femoat kernel's cache entry is loaded here after :func:`prepare` (those symbols, once a
process). The refresh itself waits for the first compile: numba's compiler refreshes the
contexts before it types anything, and femoat's late build of a kernel's machine code
(:func:`femoat.compilation.machine_code.materialize`) refreshes them before it builds the
Python wrapper. Installed with femoat's other numba replacements (:mod:`femoat.compilation.jit`),
on the numba versions whose ``caching``, ``base``, ``cpu`` and ``compiler`` modules were read
and tested (:data:`NUMBA_VERSIONS`); ``FEMOAT_CACHE_LOAD_WITHOUT_REFRESH=0`` leaves numba's
load.
"""

from femoat.compilation import numba_version

NUMBA_VERSIONS = ((0, 68), (0, 68))
"""The first and last numba minor versions whose cache loading and context refresh this module
was read and tested against (both ends included)."""

_installed = []
_prepared = []


def install():
    """Let :func:`without_refresh` act (once a process). Returns whether it is installed (False
    on an unknown numba or with ``FEMOAT_CACHE_LOAD_WITHOUT_REFRESH=0``)."""
    if _installed:
        return True
    if not numba_version.wanted("FEMOAT_CACHE_LOAD_WITHOUT_REFRESH", NUMBA_VERSIONS):
        return False
    _installed.append(True)
    return True


def without_refresh(dispatcher):
    """Make ``dispatcher`` (a femoat kernel's numba dispatcher) load its on-disk cache entries
    after :func:`prepare` instead of numba's context refresh. No-op unless :func:`install` ran,
    or when the dispatcher has no on-disk cache (numba's ``NullCache`` loads nothing)."""
    if not _installed:
        return dispatcher
    from numba.core import caching

    cache = dispatcher._cache
    if not isinstance(cache, caching.Cache):
        return dispatcher

    def load_overload(sig, target_context):
        prepare(target_context)
        with cache._guard_against_spurious_io_errors():
            return cache._load_overload(sig, target_context)

    load_overload.__wrapped__ = cache.load_overload
    cache.load_overload = load_overload
    return dispatcher


def prepare(target_context):
    """Register the run-time symbols that compiled code loaded into ``target_context``'s JIT
    engine may call, as numba's refresh would (numba's NRT: its C helpers and its atomic
    operations, compiled once; the hash secrets, registered when ``numba.cpython.hashing`` is
    imported). Once a process; numba's own refresh, when it comes, finds both done."""
    if _prepared:
        return
    import numba.cpython.hashing  # noqa: F401  (registers the _numba_hashsecret_* symbols)
    from numba.core.runtime import rtsys

    rtsys.initialize(target_context)
    _prepared.append(True)
