"""A second process compiles the loop's callees while the first compiles the loop.

numba compiles on one core. A cold start compiles the solver's loop (``run_chunk``) and,
while numba types it, about 170 kernels that the loop calls without inlining them: about two
fifths of the compile. On a machine with a second core, the process that compiles first (the
holder of :func:`femoat.compilation.numba_cache.first_compile_lock`, when the loop is not in
numba's cache) starts a helper process (:func:`helper_while_compiling`) and compiles the loop
first. The helper compiles the kernels of the plan in the reverse of the order a cold start
finishes them, each into numba's on-disk cache; the first process, reaching a callee, finds it
there when the helper has finished it (a cache load instead of a compile) and compiles it
itself otherwise. The two meet in the middle. The helper stops when the first run ends, or when
it is done.

The plan (:data:`PLAN_FILE`): per choice of bearing kinds (:mod:`femoat.bearings.registry`),
the femoat kernels a cold warm-up compiles, each with its argument types (numba's types,
pickled), in the order they finish; and the fingerprint of the kernel sources it was recorded
from. A plan recorded from other sources or another numba minor version is not used (and
tests/test_compile_plan.py fails until it is recorded again:
``python -m femoat.compilation.compile_plan --record``, a cold compile per choice).

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

CHOICES = ("fp", "all")
"""The choices of bearing kinds the plan is recorded for: the paper's pendulum alone, every
kind (:mod:`femoat.startup.bearing_kinds`)."""

_helped = []


def choice_key(kinds=None):
    """The plan's key for the bearing kinds ``kinds`` (indices; default: this process's
    loop): their scenario keys, comma-separated."""
    from femoat.bearings import registry

    kinds = registry.compiled_kinds() if kinds is None else kinds
    return ",".join(registry.keys()[k] for k in kinds)


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
    """The plan's kernels for the choice ``key`` (:func:`choice_key`), in the order a cold
    warm-up finished them: (module, name, python, argument types)."""
    signatures = pickle.loads(zlib.decompress(base64.b64decode(plan["signatures"])))
    return [(e["module"], e["name"], e["python"], signatures[e["signature"]])
            for e in plan["choices"].get(key, ())]


@contextlib.contextmanager
def helper_while_compiling():
    """Around this process's first run: start the helper if the loop must be compiled (not in
    numba's cache) and a plan, a second core and POSIX locks are there; stop it at the end.
    Later runs of the process pass straight through."""
    if _helped:
        yield
        return
    _helped.append(True)
    helper, loop = _start_helper()
    try:
        if helper is not None:  # the loop first: the helper meets it in the middle sooner
            loop()
        yield
    finally:
        if helper is not None:
            helper.terminate()  # numba writes a cache file whole (a rename) or not at all
            helper.wait()


def _start_helper():
    """(the helper process, a function compiling the loop) when a helper is wanted, else
    (None, None)."""
    if os.environ.get(SWITCH, "1") == "0" or _cores() < 2:
        return None, None
    from femoat.compilation import numba_cache

    if numba_cache.fcntl is None:
        return None, None
    plan = load_plan()
    key = choice_key()
    if plan is None or key not in plan["choices"]:
        return None, None
    loop = [(python, sig) for module, name, python, sig in entries(plan, key)
            if (module, name) == LOOP]
    if not loop or not _missing(loop[0][1]):
        return None, None
    try:
        helper = subprocess.Popen([sys.executable, "-m", "femoat.compilation.compile_plan",
                                   "--help-compile", key, str(os.getpid())],
                                  stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.DEVNULL, start_new_session=True)
    except OSError:  # no Python to start (an embedded interpreter): compile alone
        return None, None
    python, sig = loop[0]

    def compile_loop():
        from femoat.integration.driver import run_chunk

        (run_chunk.python_dispatcher if python else run_chunk.dispatcher).compile(sig)

    return helper, compile_loop


def _cores():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def _missing(sig):
    """Whether numba's cache holds no entry of the loop for the argument types ``sig``."""
    from femoat.compilation import machine_code
    from femoat.integration.driver import run_chunk

    dispatcher = run_chunk.python_dispatcher
    cache = getattr(dispatcher, "_cache", None)
    index_key = getattr(cache, "_index_key", None)
    if index_key is None:
        return False  # no on-disk cache: nothing the helper could hand over
    codegen = dispatcher.targetctx.codegen()
    index = cache._cache_file._load_index()
    return not any(index_key(s, codegen) in index
                   for s in (sig, machine_code._deferred_key(sig)))


def help_compile(key, parent):
    """The helper: compile the plan's kernels for the choice ``key`` in reverse order (the
    loop left out), each into numba's cache, until done or until ``parent`` (a process id)
    is gone. A kernel that fails to compile is skipped: the first process compiles it."""
    from importlib import import_module

    from femoat.bearings import registry

    plan = load_plan()
    if plan is None:
        return
    if key != choice_key():
        registry.select(tuple(key.split(",")))
    for module, name, python, sig in reversed(entries(plan, key)):
        if os.getppid() != parent:
            return
        if (module, name) == LOOP:
            continue
        try:
            kernel = getattr(import_module(module), name)
            dispatcher = kernel.python_dispatcher if python else kernel.dispatcher
            dispatcher.compile(sig)
        except Exception:  # noqa: BLE001 (a plan out of step with the code: skip it)
            continue


def record(path=PLAN_FILE):
    """Record the plan: for each of :data:`CHOICES`, a cold warm-up in a fresh process on an
    empty numba cache, listing the femoat kernels compiled in the order they finish. Minutes."""
    import tempfile

    from femoat.atomic import write_text
    from femoat.compilation import numba_version
    from femoat.compilation.sources import fingerprint

    choices = {}
    with contextlib.ExitStack() as stack:
        running = []
        for choice in CHOICES:  # side by side, a core each
            folder = stack.enter_context(tempfile.TemporaryDirectory(prefix="femoat-plan-"))
            env = {**os.environ, "NUMBA_CACHE_DIR": folder, SWITCH: "0"}
            env.pop("FEMOAT_BEARINGS", None)
            running.append((choice, subprocess.Popen(
                [sys.executable, "-m", "femoat.compilation.compile_plan", "--record-one",
                 choice], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)))
        for choice, process in running:
            out, err = process.communicate()
            if process.returncode != 0:
                raise RuntimeError(f"recording the compile plan for {choice}: {err[-3000:]}")
            listed = json.loads(out.strip().splitlines()[-1])
            choices[listed["key"]] = listed["kernels"]
    signatures = []  # each distinct signature once, the entries naming it by its index
    for kernels in choices.values():
        for e in kernels:
            sig = pickle.loads(base64.b64decode(e["signature"]))
            if sig not in signatures:
                signatures.append(sig)
            e["signature"] = signatures.index(sig)
    packed = base64.b64encode(zlib.compress(pickle.dumps(signatures), 9)).decode()
    plan = {"numba": list(numba_version.minor()), "kernels_fingerprint": fingerprint("kernels"),
            "choices": choices, "signatures": packed}
    write_text(path, json.dumps(plan, indent=1) + "\n")
    return plan


def _record_one(choice):
    """In a fresh process on an empty cache: select ``choice``, warm up, print what compiled."""
    from numba.core import event

    from femoat.bearings import registry
    from femoat.compilation import jit

    registry.select(choice)
    finished = []

    class Listener(event.Listener):
        def on_start(self, ev):
            pass

        def on_end(self, ev):
            finished.append((ev.data["dispatcher"], tuple(ev.data["args"])))

    event.register("numba:compile", Listener())
    from femoat.startup.warmup import warm_up

    warm_up()
    owners = {}
    for kernel in jit._started:
        for python, d in ((False, kernel._dispatcher), (True, kernel._python_dispatcher)):
            if d is not None:
                owners[id(d)] = (kernel, python and d is not kernel._dispatcher)
    kernels = []
    for d, sig in finished:
        if id(d) not in owners:
            continue  # numba's own (an @overload's implementation): not cached on disk
        kernel, python = owners[id(d)]
        module, name = kernel.py_func.__module__, kernel.py_func.__name__
        if name.endswith("__python"):
            name = name[:-len("__python")]
        if module.startswith("femoat_bearings_dispatch_"):
            module = "femoat.bearings.dispatch"  # the chosen kinds' copy of the dispatcher
        kernels.append({"module": module, "name": name, "python": python,
                        "signature": base64.b64encode(pickle.dumps(sig)).decode()})
    print(json.dumps({"key": choice_key(), "kernels": kernels}))


if __name__ == "__main__":
    if sys.argv[1:2] == ["--help-compile"]:
        help_compile(sys.argv[2], int(sys.argv[3]))
    elif sys.argv[1:2] == ["--record-one"]:
        _record_one(sys.argv[2])
    elif sys.argv[1:2] == ["--record"]:
        print(f"recorded {len(record()['choices'])} choices in {PLAN_FILE}")
    else:
        raise SystemExit("usage: python -m femoat.compilation.compile_plan --record")
