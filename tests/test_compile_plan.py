"""A helper process compiles the loop's callees beside the first compile
(femoat.compilation.compile_plan, femoat.startup.compile_helper), and saves to numba's cache are serialized between processes
(femoat.compilation.numba_cache.locked_saves).

What must hold: the recorded plan is the one of today's kernel sources and names femoat
kernels; what the helper compiles from a plan, the first process loads from numba's cache
instead of compiling it, with the same result to the bit as a compile of its own; no helper
starts when the loop is cached or the switch is off, and the helper stops with the first run;
a save holds the lock. The slow tier records the pendulum's plan again on an empty cache and
finds the stored one.
"""

import base64
import json
import os
import pickle
import subprocess
import sys
import textwrap
import zlib
from pathlib import Path

import pytest

from femoat.compilation import compile_plan, numba_cache
from femoat.startup import compile_helper

ROOT = Path(__file__).resolve().parents[1]


def test_the_recorded_plan_is_todays_and_names_femoat_kernels():
    from femoat.compilation import jit, numba_version

    stored = json.loads(compile_plan.PLAN_FILE.read_text())
    if tuple(stored["numba"]) != numba_version.minor():
        pytest.skip(f"the plan was recorded on numba {stored['numba']}: not used on this one")
    assert compile_plan.load_plan() is not None, (
        "femoat/compilation/compile_plan.json was recorded from other kernel sources: record "
        "it again (python -m femoat.startup.compile_helper --record)")
    plan = compile_plan.load_plan()
    from femoat.bearings import registry

    every = ",".join(registry.keys())
    assert set(plan["choices"]) == {"fp", every}
    for key in plan["choices"]:
        listed = compile_plan.entries(plan, key)
        assert sum((m, n) == compile_plan.LOOP for m, n, *_ in listed) == 1
        for module, name, python, sig in listed:
            kernel = getattr(__import__(module, fromlist=[name]), name)
            assert isinstance(kernel, jit.Kernel), (module, name)
            assert isinstance(sig, tuple) and not (python and kernel.python)
    # the pendulum's loop calls a subset of the kernels of every kind's loop
    fp = {(m, n) for m, n, *_ in compile_plan.entries(plan, "fp")}
    assert fp < {(m, n) for m, n, *_ in compile_plan.entries(plan, every)}


KERNELS = '''
from femoat.compilation.jit import njit


@njit(cache=True)
def spring(k, u):
    """A hardening spring's force [kip]: k u + 0.1 k u^3 (k [kip/in], u [in])."""
    return k * u + 0.1 * k * u ** 3


@njit(cache=True)
def stiffness(k, u):
    """The spring's tangent [kip/in]: k + 0.3 k u^2."""
    return k + 0.3 * k * u ** 2


@njit(cache=True)
def work(k, u_max, n):
    """The spring's work from 0 to u_max [kip in], trapezoid rule on n intervals, and its
    tangent at u_max [kip/in]."""
    h = u_max / n
    s = 0.5 * (spring(k, 0.0) + spring(k, u_max))
    for i in range(1, n):
        s += spring(k, i * h)
    return s * h, stiffness(k, u_max)
'''

HELPER = '''
import json, os, sys
from femoat.startup import compile_helper
plan = json.loads(open(sys.argv[1]).read())
compile_helper.load_plan = lambda path=None: plan
compile_helper.LOOP = ("springs", "work")
compile_helper.help_compile(compile_helper.choice_key(), os.getppid())
'''

MAIN = '''
import json
import springs
out = {"result": list(springs.work(2.0, 1.5, 2000))}
for name in ("spring", "stiffness", "work"):
    d = getattr(springs, name).dispatcher
    out[name] = [sum(d.stats.cache_hits.values()), sum(d.stats.cache_misses.values())]
print(json.dumps(out))
'''


def _python(tmp_path, code, cache, *args):
    folder = tmp_path / "src"
    folder.mkdir(exist_ok=True)
    (folder / "springs.py").write_text(KERNELS)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / cache),
           "PYTHONPATH": os.pathsep.join([str(folder), str(ROOT),
                                          os.environ.get("PYTHONPATH", "")])}
    r = subprocess.run([sys.executable, "-c", textwrap.dedent(code), *args], env=env,
                       capture_output=True, text=True, timeout=300, check=False)
    assert r.returncode == 0, r.stderr[-3000:]
    return r.stdout


def test_what_the_helper_compiled_the_first_process_loads_with_the_same_bits(tmp_path):
    from numba import float64, int64

    from femoat.compilation import machine_code
    from femoat.compilation.numba_version import supported

    if not supported(machine_code.NUMBA_VERSIONS):
        pytest.skip("femoat.compilation.machine_code is not installed on this numba")
    # the plan a cold compile of work(2.0, 1.5, 2000) records: its callees, then itself
    signatures = [(float64, float64), (float64, float64, int64)]
    entries = [{"module": "springs", "name": name, "python": False, "signature": i}
               for name, i in (("spring", 0), ("stiffness", 0), ("work", 1))]
    from femoat.bearings import registry

    plan = {"choices": {",".join(registry.keys()): entries},
            "signatures": base64.b64encode(zlib.compress(pickle.dumps(signatures))).decode()}
    (tmp_path / "plan.json").write_text(json.dumps(plan))
    _python(tmp_path, HELPER, "cache", str(tmp_path / "plan.json"))  # the helper, run through
    helped = json.loads(_python(tmp_path, MAIN, "cache").strip().splitlines()[-1])
    alone = json.loads(_python(tmp_path, MAIN, "cache-alone").strip().splitlines()[-1])
    # the callees found in the cache (a hit each, no compile), the loop compiled
    assert helped["spring"] == [1, 0] and helped["stiffness"] == [1, 0]
    assert helped["work"] == [0, 1]
    assert alone["spring"] == [0, 1] and alone["stiffness"] == [0, 1] and alone["work"] == [0, 1]
    # the same bits as a process compiling everything itself; the work k U^2/2 + 0.1 k U^4/4
    # = 2.503125 kip in (U = 1.5 in, k = 2 kip/in) within the trapezoid rule's error
    # (U^3/12) max f''/n^2 <= 1.3e-7; the tangent 2 + 0.3*2*1.5^2 = 3.35 kip/in
    assert helped == {**alone, "spring": [1, 0], "stiffness": [1, 0]}
    assert abs(alone["result"][0] - 2.503125) < 2e-7
    assert alone["result"][1] == 2.0 + 0.3 * 2.0 * 1.5 ** 2


def test_no_helper_for_a_cached_loop_or_with_the_switch_off(monkeypatch):
    from femoat.startup.warmup import warm_up

    warm_up()  # the session's loop: compiled or loaded, so in numba's cache
    plan = compile_plan.load_plan()
    if plan is None:
        pytest.skip("no plan for these kernel sources and this numba")
    from femoat.integration.solve import kernels

    key = compile_helper.choice_key()
    (loop,) = [s for m, n, _, s in compile_plan.entries(plan, key) if (m, n) == compile_plan.LOOP]
    assert not compile_plan._missing(kernels().run_chunk.python_dispatcher, loop)
    assert compile_plan._start_helper(key, lambda: kernels().run_chunk) == (None, None)
    monkeypatch.setenv(compile_plan.SWITCH, "0")
    monkeypatch.setattr(compile_plan, "_missing", lambda d, sig: True)  # even when cold
    assert compile_plan._start_helper(key, lambda: kernels().run_chunk) == (None, None)


def test_the_helper_stops_with_the_first_run(monkeypatch):
    started, loops = [], []

    def sleeper(key, loop):
        started.append(subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"]))
        return started[-1], lambda: loops.append(started[-1].poll())

    monkeypatch.setattr(compile_plan, "_helped", [])
    monkeypatch.setattr(compile_plan, "_start_helper", sleeper)
    with compile_plan.helper_while_compiling("fp", None):
        assert started[0].poll() is None  # running beside the first run
        assert loops == [None]  # the loop compiled first, the helper running
    assert started[0].poll() is not None  # stopped (terminated, not waited 60 s for)
    with compile_plan.helper_while_compiling("fp", None):  # a later run: no helper
        pass
    assert len(started) == 1


def _saved_module(tmp_path, monkeypatch):
    # a module of its own in tmp_path: numba caches it beside it (or under the session's
    # NUMBA_CACHE_DIR, in a folder named after its path)
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "saved.py").write_text("def f(x):\n    return x * x + 1\n")
    monkeypatch.syspath_prepend(str(tmp_path / "src"))
    monkeypatch.delitem(sys.modules, "saved", raising=False)  # another test's file
    import saved

    return saved


@pytest.mark.skipif(numba_cache.fcntl is None, reason="no fcntl: the lock is POSIX only")
def test_an_entry_is_written_data_first_under_the_lock(tmp_path, monkeypatch):
    import fcntl

    import numba

    saved = _saved_module(tmp_path, monkeypatch)

    def probed(dispatcher):
        files = dispatcher._cache._cache_file
        lock = Path(files._cache_path) / "femoat-save.lock"
        events = []

        def held():
            # another open file description of the lock file cannot take it while it is held
            lock.parent.mkdir(parents=True, exist_ok=True)
            with open(lock, "a") as other:
                try:
                    fcntl.flock(other, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    fcntl.flock(other, fcntl.LOCK_UN)
                    return False
                except BlockingIOError:
                    return True

        save_data, save_index = files._save_data, files._save_index
        files._save_data = lambda *a: (events.append(("data", held())), save_data(*a))[1]
        files._save_index = lambda *a: (events.append(("index", held())), save_index(*a))[1]
        return events

    locked = numba.njit(cache=True)(saved.f)
    events = probed(locked)
    numba_cache.locked_saves(locked)
    assert locked(1.5) == 3.25 and events == [("data", True), ("index", True)]
    # numba's own save (another signature, a dispatcher of its own): the index first, unlocked
    plain = numba.njit(cache=True)(saved.f)
    events_plain = probed(plain)
    assert plain(2) == 5 and events_plain == [("index", False), ("data", False)]


def test_a_write_stopped_halfway_never_lists_old_code(tmp_path, monkeypatch):
    # A data file left from an index numba discarded holds old code (here: f for an integer,
    # its index deleted as numba drops another version's). A new entry (f for a float) takes
    # that file's number; the writer stops between its two writes. Written data first, the
    # index never names the file, so a new process compiles; numba's order (index first)
    # would list the old code under the new key: f(1.5) = 1*1 + 1 = 2, not 1.5^2 + 1 = 3.25.
    import numba

    saved = _saved_module(tmp_path, monkeypatch)

    class Stopped(Exception):
        pass

    def entry_from(dispatcher):
        return dispatcher._cache._cache_file

    def stale():
        first = numba.njit(cache=True)(saved.f)
        assert first(3) == 10  # written: the index lists f.1 for an integer
        files = first._cache._cache_file
        Path(files._index_path).unlink()  # the index discarded, its data file left behind
        return files

    def stop(*args):
        raise Stopped

    for order in ("numba", "femoat"):
        files = stale()
        second = numba.njit(cache=True)(saved.f)
        if order == "femoat":
            numba_cache.locked_saves(second)
            second._cache._cache_file._save_index = stop  # stopped after the data file
        else:
            second._cache._cache_file._save_data = stop  # after the index (numba's first)
        with pytest.raises(Stopped):
            second.compile((numba.float64,))
        assert Path(files._index_path).exists() == (order == "numba")
        third = numba.njit(cache=True)(saved.f)
        loaded = third._cache.load_overload((numba.float64,), third.targetctx)
        if order == "femoat":
            assert loaded is None  # not listed: the next process compiles f for a float
        else:
            assert loaded is not None and loaded.entry_point(1.5) == 2  # the old code
        Path(files._index_path).unlink(missing_ok=True)


@pytest.mark.slow
def test_recording_the_pendulums_plan_again_gives_the_stored_one(tmp_path):
    # A cold warm-up of the pendulum's loop on an empty cache, as --record runs it: the same
    # kernels, finished in the same order, with the same argument types (about a minute).
    plan = compile_plan.load_plan()
    if plan is None:
        pytest.skip("no plan for these kernel sources and this numba")
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba"), compile_plan.SWITCH: "0",
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    env.pop("FEMOAT_BEARINGS", None)
    done = subprocess.run([sys.executable, "-m", "femoat.startup.compile_helper",
                           "--record-one", "fp"], env=env, capture_output=True, text=True,
                          timeout=900, check=False)
    assert done.returncode == 0, done.stderr[-3000:]
    listed = json.loads(done.stdout.strip().splitlines()[-1])
    assert listed["key"] == "fp"
    again = [(e["module"], e["name"], e["python"], pickle.loads(base64.b64decode(e["signature"])))
             for e in listed["kernels"]]
    assert again == compile_plan.entries(plan, "fp")


COLD_PAPER_RUN = '''
import json, os
from femoat.bearings import registry
registry.select("fp")
from femoat.compilation import jit
from femoat.paper import paper_model, paper_motion
from femoat.run import run
result = run(paper_model("steel", "J"), paper_motion())
hits = sum(sum(d.stats.cache_hits.values()) for k in jit._started
           for d in (k._dispatcher, k._python_dispatcher) if d is not None)
helper_cpu = os.times().children_user
print(json.dumps({"peaks": {k: v for k, v in result.peaks.items() if "second" not in k},
                  "hits": hits, "helper_cpu": helper_cpu}))
'''


@pytest.mark.slow
def test_a_cold_paper_run_with_the_helper_loads_its_callees_and_gives_the_same_peaks(tmp_path):
    # The pendulum's loop compiled on an empty cache with the helper beside it (about a
    # minute): the first process loads callees the helper compiled (numba's cache hits: with
    # no helper a cold process has none) and the run's peaks are this session's to the bit.
    from femoat.paper import paper_model, paper_motion
    from femoat.run import run

    if compile_plan.load_plan() is None:
        pytest.skip("no plan for these kernel sources and this numba")
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba"), compile_plan.SWITCH: "1",
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    env.pop("FEMOAT_BEARINGS", None)
    done = subprocess.run([sys.executable, "-c", COLD_PAPER_RUN], env=env, capture_output=True,
                          text=True, timeout=900, check=False)
    assert done.returncode == 0, done.stderr[-3000:]
    cold = json.loads(done.stdout.strip().splitlines()[-1])
    assert cold["hits"] > 0 and cold["helper_cpu"] > 0
    here = run(paper_model("steel", "J"), paper_motion()).peaks
    assert cold["peaks"] == {k: v for k, v in here.items() if "second" not in k}
