"""A second process compiles the loop's callees while the first compiles the loop.

numba compiles on one core. A cold start compiles the solver's loop (``run_chunk``) and,
while numba types it, about 110-170 kernels that the loop calls without inlining them: about
two fifths of the compile. On a machine with a second core, the process that compiles first
(the holder of :func:`femoat.compilation.numba_cache.first_compile_lock`, when the loop is not
in numba's cache) starts a helper process (:func:`helper_while_compiling`; the helper is
:mod:`femoat.startup.compile_helper`) and compiles the loop first. The helper compiles the
kernels of the plan in the reverse of the order a cold start finishes them, each into numba's
on-disk cache; the first process, reaching a callee, finds it there when the helper has
finished it (a cache load instead of a compile) and compiles it itself otherwise. The two meet
in the middle. The helper stops when the first run ends, or when it is done.

The plan (:data:`PLAN_FILE`): per choice of bearing kinds (:mod:`femoat.bearings.registry`),
the femoat kernels a cold warm-up compiles, each with its argument types (numba's types,
pickled), in the order they finish; and the fingerprint of the kernel sources it was recorded
from. A plan recorded from other sources or another numba minor version is not used (and
tests/test_compile_plan.py fails until it is recorded again:
``python -m femoat.startup.compile_helper --record``, a cold compile per choice).

What is compiled is unchanged: a kernel the helper compiled is the kernel's own cache entry, as
a later process would load it (:mod:`femoat.compilation.machine_code` keeps a callee's module
there); only its symbol names differ. The two processes' saves to numba's cache are serialized
(:func:`femoat.compilation.numba_cache.locked_saves`). ``FEMOAT_COMPILE_HELPER=0`` starts no
helper; none is started on one core, without POSIX file locks, or for a choice of kinds
without a plan.
"""

import base64
import contextlib
import json
import os
import pickle
import subprocess
import sys
import zlib
from pathlib import Path

PLAN_FILE = Path(__file__).with_name("compile_plan.json")
"""The recorded plan (package data)."""

SWITCH = "FEMOAT_COMPILE_HELPER"
"""Environment switch: ``0`` starts no helper."""

LOOP = ("femoat.integration.driver", "run_chunk")
"""The loop itself: compiled by the first process, never by the helper."""

_helped = []


def load_plan(path=PLAN_FILE):
    """The plan (a dict: ``numba``, ``kernels_fingerprint``, ``choices``) if it was recorded
    from this numba minor version and these kernel sources; else None."""
    from femoat.compilation import numba_version
    from femoat.compilation.sources import fingerprint

    try:
        plan = json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return None
    if tuple(plan.get("numba", ())) != numba_version.minor():
        return None
    if plan.get("kernels_fingerprint") != fingerprint("kernels"):
        return None
    return plan


def entries(plan, key):
    """The plan's kernels for the choice ``key`` (the loop's bearing kinds' scenario keys,
    comma-separated), in the order a cold warm-up finished them: (module, name, python,
    argument types)."""
    signatures = pickle.loads(zlib.decompress(base64.b64decode(plan["signatures"])))
    return [(e["module"], e["name"], e["python"], signatures[e["signature"]])
            for e in plan["choices"].get(key, ())]


@contextlib.contextmanager
def helper_while_compiling(key, loop):
    """Around this process's first run: start the helper if the loop (``loop``: the loop's
    femoat kernel, a function returning it) must be compiled (not in numba's cache) and a plan
    for the choice of bearing kinds ``key``, a second core and POSIX locks are there; stop it
    at the end. Later runs of the process pass straight through."""
    if _helped:
        yield
        return
    _helped.append(True)
    helper, loop = _start_helper(key, loop)
    try:
        if helper is not None:  # the loop first: the helper meets it in the middle sooner
            loop()
        yield
    finally:
        if helper is not None:
            helper.terminate()  # numba writes a cache file whole (a rename) or not at all
            try:
                helper.wait(timeout=10)
            except subprocess.TimeoutExpired:  # SIGTERM ignored (inherited so): kill it
                helper.kill()
                helper.wait()


def _start_helper(key, kernel):
    """(the helper process, a function compiling the loop) when a helper is wanted, else
    (None, None)."""
    if os.environ.get(SWITCH, "1") == "0" or _cores() < 2:
        return None, None
    from femoat.compilation import numba_cache

    if numba_cache.fcntl is None:
        return None, None
    plan = load_plan()
    if plan is None or key not in plan["choices"]:
        return None, None
    try:
        loop = [(python, sig) for module, name, python, sig in entries(plan, key)
                if (module, name) == LOOP]
    except Exception:  # noqa: BLE001 (types that do not unpickle here: compile alone)
        return None, None
    if not loop:
        return None, None
    python, sig = loop[0]
    dispatcher = kernel().python_dispatcher if python else kernel().dispatcher
    if not _missing(dispatcher, sig):
        return None, None
    from femoat.compilation import machine_code

    package_root = str(Path(__file__).resolve().parents[2])  # the helper imports this femoat
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [package_root] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])}
    try:
        helper = subprocess.Popen([sys.executable, "-m", "femoat.startup.compile_helper",
                                   "--help-compile", key, str(os.getpid())], env=env,
                                  stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.DEVNULL, start_new_session=True)
    except OSError:  # no Python to start (an embedded interpreter): compile alone
        return None, None
    return helper, lambda: machine_code.compile_for_python(dispatcher, sig)


def _cores():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def _missing(dispatcher, sig):
    """Whether numba's cache holds no entry of ``dispatcher`` (the loop's) for the argument
    types ``sig``."""
    from femoat.compilation import machine_code

    cache = getattr(dispatcher, "_cache", None)
    index_key = getattr(cache, "_index_key", None)
    if index_key is None:
        return False  # no on-disk cache: nothing the helper could hand over
    codegen = dispatcher.targetctx.codegen()
    index = cache._cache_file._load_index()
    return not any(index_key(s, codegen) in index
                   for s in (sig, machine_code._deferred_key(sig)))
