"""The compile helper's process, and the recording of its plan.

:mod:`femoat.compilation.compile_plan` starts this module as a process beside a cold first
run (``--help-compile KEY PID``): it compiles the plan's kernels for the loop of the bearing
kinds ``KEY`` into numba's cache, in reverse order, the loop left out. ``--record`` records
the plan: for each of :data:`CHOICES`, a cold warm-up in a fresh process on an empty numba
cache (``--record-one``), listing the femoat kernels it compiled in the order they finished.
"""

import base64
import contextlib
import json
import os
import pickle
import subprocess
import sys
import zlib

from femoat.compilation.compile_plan import LOOP, PLAN_FILE, SWITCH, entries, load_plan

CHOICES = ("fp", "all")
"""The choices of bearing kinds the plan is recorded for: the paper's pendulum alone, every
kind (:mod:`femoat.startup.bearing_kinds`)."""


def choice_key(kinds=None):
    """The plan's key for the bearing kinds ``kinds`` (indices; default: this process's
    loop): their scenario keys, comma-separated."""
    from femoat.bearings import registry

    kinds = registry.compiled_kinds() if kinds is None else kinds
    return ",".join(registry.keys()[k] for k in kinds)


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
                [sys.executable, "-m", "femoat.startup.compile_helper", "--record-one",
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
        raise SystemExit("usage: python -m femoat.startup.compile_helper --record")
