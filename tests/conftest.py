import os

# Many tiny matrix operations thrash a threaded BLAS: pin it to one thread (as pycba does).
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

# One compiled loop for the whole session: the commands the tests run (in this process or in a
# subprocess) would otherwise compile a second one for the paper's bearing alone
# (femoat.startup.bearing_kinds); tests/test_kind_selection.py checks that choice itself.
os.environ["FEMOAT_BEARINGS"] = "all"

from pathlib import Path  # noqa: E402

# Test records shipped with the repository (provenance, licence and sha256 in data/README.md).
DATA = Path(__file__).resolve().parent / "data"
SUITE_RECORDS = ("Rinaldi228.AT2", "RSN77_SFERN_PUL164.AT2", "RSN181_IMPVALL.H_H-E06230.AT2")


def write_at2(path, accel, dt):
    """A PEER AT2 file of ``accel`` [g] at ``dt`` [s] (the header read_at2 parses)."""
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", "test record, 1/1/2000, station, 0",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS= {len(accel):6d}, DT= {dt:.4f} SEC"]
    lines += ["".join(f"{a:15.7E}" for a in accel[i:i + 5]) for i in range(0, len(accel), 5)]
    path.write_text("\n".join(lines) + "\n")
    return path


def three_records(folder):
    """A folder holding three of the shipped PEER records (the suites' tests use these)."""
    import shutil

    folder.mkdir(parents=True, exist_ok=True)
    for name in SUITE_RECORDS:
        shutil.copyfile(DATA / "peer" / name, folder / name)
    return folder


# ---- the optional OpenSees cross-checks: one probe, one skip reason ----------------------------
from functools import lru_cache  # noqa: E402


@lru_cache(maxsize=1)
def opensees_missing():
    """None when openseespy imports; otherwise the skip reason, which names what to install
    (pip extra, the system packages libblas3/liblapack3 and the apt-get command), whatever the
    import raised (openseespy raises RuntimeError, not ImportError, without libblas3)."""
    from femoat.opensees.available import import_opensees

    try:
        import_opensees()
    except ImportError as exc:
        return str(exc)
    return None


def opensees_or_skip():
    """``openseespy.opensees``, or skip the calling test module (or test) with that reason."""
    import pytest

    reason = opensees_missing()
    if reason is not None:
        pytest.skip(reason, allow_module_level=True)
    from femoat.opensees.available import import_opensees

    return import_opensees()


# ---- off-screen rendering in a subprocess (a missing OpenGL backend can crash VTK outright) --
import subprocess  # noqa: E402
import sys  # noqa: E402

import pytest  # noqa: E402


@pytest.fixture
def no_figures(monkeypatch):
    """A suite report without its figures, for the tests reading its tables and README only: a
    report's figures take two thirds of its time; they are drawn and checked by
    tests/test_suite_report.py (the synthetic IDA, stripes, a messy suite, four variations),
    test_suite_methods.py (every scaling method through the command line) and
    test_suite_pounding.py."""
    from femoat.suite import report_figures

    monkeypatch.setattr(report_figures, "write_figures", lambda *args, **kwargs: [])


_ROOT = Path(__file__).resolve().parents[1]
RENDER_ENV = {**os.environ, "VTK_DEFAULT_OPENGL_WINDOW": "vtkEGLRenderWindow",
              "PYTHONPATH": os.pathsep.join([str(_ROOT), os.environ.get("PYTHONPATH", "")])}
_PROBE = ("import pyvista as pv; p = pv.Plotter(off_screen=True, window_size=(64, 64)); "
          "p.add_mesh(pv.Sphere()); p.screenshot({path!r}); p.close()")


def run_python(code, cwd):
    """Run ``code`` in a fresh Python with the off-screen render environment."""
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, env=RENDER_ENV,
                          capture_output=True, text=True, timeout=300, check=False)


@pytest.fixture(scope="session")
def render_backend(tmp_path_factory):
    """Skip when, and only when, plain pyvista cannot render a sphere off-screen in a fresh
    process: that is the definition of "no render backend" here. Anything else fails."""
    tmp = tmp_path_factory.mktemp("probe")
    probe = run_python(_PROBE.format(path=str(tmp / "probe.png")), tmp)
    if probe.returncode != 0 or not (tmp / "probe.png").is_file():
        pytest.skip(f"no off-screen render backend: VTK needs EGL or OSMesa (Debian/Ubuntu: "
                    f"apt-get install libegl1 libgl1) or an X display (xvfb-run); the pyvista "
                    f"probe exited {probe.returncode}: {probe.stderr.strip()[-300:]}")


# ---- a fresh Python, as a user starts one -----------------------------------------------------


def _python_env(cache):
    """The environment of a fresh Python using femoat's cache folder ``cache`` (numba's cache
    is the session's: a fresh Python loads the kernels the tests compiled)."""
    return {**os.environ, "FEMOAT_CACHE": str(cache),
            "PYTHONPATH": os.pathsep.join([str(_ROOT), os.environ.get("PYTHONPATH", "")])}


def run_in(code, env):
    """Run ``code`` in a fresh Python in the repository's root with environment ``env``."""
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                          timeout=900, check=False, cwd=_ROOT)


def shear_chain(weights, ks):
    """Mass [kip·s²/in] and stiffness [kip/in] matrices of a linear shear chain on a spring to
    the ground (weights [kip] bottom up, ks[0] the ground spring, ks[k] the story below DOF k):
    the closed-form references of the linear solver tests, independent of femoat's packing."""
    import numpy as np

    from femoat.units import G

    m = np.diag(weights) / G
    n = len(ks)
    K = np.zeros((n, n))
    for i, k in enumerate(ks):
        K[i, i] += k
        if i > 0:
            K[i - 1, i - 1] += k
            K[i, i - 1] -= k
            K[i - 1, i] -= k
    return m, K


# ---- a parallel session (pytest-xdist, -n N): the solver compiled while the tests run ---------
# The first use of the solver in a process holds a lock beside numba's cache (compile once,
# load everywhere else: femoat.compilation.numba_cache.first_compile_lock). On a fresh clone
# the compile takes about two minutes of one core, most of the default tier's time, so the
# session is built around it (tests/README.md, "Where the time goes"):
# - the controller starts the compile at once in a background process, then lowers its own
#   priority (nice 5), which the workers and the process below inherit: the compile keeps a
#   core to itself; a worker takes its priority back once the compile is done;
# - the tests are ordered: first those that never use the building solver (SOLVER_FREE,
#   each checked by running it while another process held the lock; not the tests that call
#   the loop's own kernels from Python, the bearings', materials' and contact laws' files, the
#   isolators' design, the single-impact and wall-coupling tests through the contact laws: run
#   before the compile has cached those kernels they compiled them a second time beside it, 40 s
#   of a fresh clone's session at stop 44, more found at stop 45 by running each solver-free
#   test alone on an empty cache; after it they load them), then the solver files
#   that take seconds, longest first (HEAVY_FIRST), then the rest; a worker's first solver
#   test waits for the lock and loads the kernels;
# - they are handed out by work stealing: neither worker idles while the other has a queue;
# - beside the workers a process started by the controller computes the OpenSees twins that
#   solver tests compare against (AHEAD), so that these too run while the solver compiles.
# Warm (the kernels in numba's cache) all of this still holds, the compile a second's load.
SOLVER_FREE = ("test_atomic.py", "test_ground_motions_fema.py", "test_ground_motions_peer.py",
               "test_ground_motions_record.py", "test_ground_motions_spectrum.py",
               "test_imports.py", "test_numba_cache.py", "test_opensees_plan.py",
               "test_optional_dependencies.py", "test_plan_figures.py", "test_plan_model.py",
               "test_plan_results.py", "test_plotting_drift.py", "test_readers_fuzz.py",
               "test_record_pair.py", "test_repository.py", "test_scenario_defaults.py",
               "test_scenario_strict.py", "test_suite_definition.py", "test_suite_fragility.py",
               "test_suite_huntfill.py", "test_suite_pounding.py", "test_suite_progress.py",
               "test_suite_record_rule.py", "test_suite_report.py", "test_wall_fe_beam.py",
               "test_wall_fe_calibrate.py", "test_wall_fe_cli.py", "test_wall_fe_io.py",
               "test_wall_fe_models.py", "test_wall_fe_render.py", "test_wall_kinds.py",
               # and the solver-free tests of the other files that take a second or more
               "test_opensees_plan_walls.py::test_plan_twin_with_modal_walls_along_x_is_the_1d_twin",
               "test_opensees_plan_walls.py::test_rescaled_modes_are_the_same_wall",
               "test_plan_render.py::test_a_frame_draws_the_wall_labels_and_the_axes",
               "test_plan_render.py::test_plan_animation_flashes_the_wall_in_contact",
               "test_plan_suite.py::test_each_kind_of_suite_gets_its_own_columns_and_every_shared_one",
               "test_scenario_plan.py::test_the_example_plan_file_is_the_paper_building_at_the_mce",
               "test_study_bidirectional.py::test_quick_scales_its_pairs_as_the_full_study_does")
HEAVY_FIRST = ("test_study_bidirectional.py", "test_study_isolators.py", "test_suite_run.py",
               "test_render_runs.py", "test_suite_methods.py", "test_suite_cluster.py",
               "test_plan_ark5.py", "test_peak_accuracy.py", "test_examples.py",
               "test_render_backend.py", "test_timings.py", "test_startup.py",
               "test_plan_render.py", "test_bearing_twins_farfield.py", "test_paper_study.py",
               "test_fingerprints.py")
"""The solver files taking seconds (2-18 s of CPU each, measured), first among the solver tests,
longest first: the session ends on short tests, the two workers finishing together."""


def _solver_free(item):
    """In SOLVER_FREE: the item's file, or the item (its parameters aside)."""
    name = item.nodeid.split("/")[-1]
    return name.split("::")[0] in SOLVER_FREE or name.split("[")[0] in SOLVER_FREE


def _order(item):
    if _solver_free(item):
        return (0, 0)
    name = item.nodeid.split("/")[-1].split("::")[0]
    return (1, HEAVY_FIRST.index(name)) if name in HEAVY_FIRST else (2, 0)


def pytest_collection_modifyitems(config, items):
    # a stable sort (the same in every worker, as pytest-xdist requires)
    items.sort(key=_order)


@pytest.hookimpl(tryfirst=True, optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """``-n N`` hands the tests out by work stealing (pytest-xdist's ``--dist worksteal``) rather
    than in fixed runs (``load``): each worker starts on its half of the ordered tests, and one
    that runs out takes half of what the other has queued (with ``load``, a run of long tests
    handed out late kept one worker busy 27 s after the other had finished)."""
    if config.getvalue("dist") != "load":
        return None
    from xdist.scheduler import WorkStealingScheduling

    return WorkStealingScheduling(config, log)


WORKER_NICENESS = 5
"""The workers' priority below the compile's while it runs: with nice 5 on two cores the
compile keeps one alone (and a process of another user is not starved)."""

_COMPILE_ENV = "FEMOAT_TESTS_COMPILE"
_AHEAD_ENV = "FEMOAT_TESTS_AHEAD"
_POSIX = os.name == "posix"


def _parallel_controller(config):
    workers = config.getoption("numprocesses", None)
    return (workers not in (None, 0, "0") and os.environ.get("PYTEST_XDIST_WORKER") is None
            and not config.getoption("collectonly", False))


def _python_path():
    return os.pathsep.join([str(_ROOT), os.environ.get("PYTHONPATH", "")])


def _background(code):
    """A Python running ``code``, reaped as soon as it ends (so that its pid dies with it)."""
    import threading

    proc = subprocess.Popen([sys.executable, "-c", code],
                            env={**os.environ, "PYTHONPATH": _python_path()},
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    threading.Thread(target=proc.wait, daemon=True).start()
    return proc


def pytest_configure(config):
    if not _parallel_controller(config):
        return
    # without the compile helper (femoat.compilation.compile_plan): the session keeps both
    # cores busy, so a helper would only add the work the two processes do twice
    config._femoat_compile = proc = _background(
        "import os; os.environ['FEMOAT_COMPILE_HELPER'] = '0'\n"
        "from femoat.startup.warmup import warm_up; warm_up()")
    if _POSIX:
        import tempfile

        os.environ[_COMPILE_ENV] = f"{proc.pid} {os.nice(0)}"  # the workers inherit these
        os.nice(WORKER_NICENESS)
        config._femoat_ahead = tempfile.TemporaryDirectory(prefix="femoat-tests-ahead-")
        os.environ[_AHEAD_ENV] = config._femoat_ahead.name


def pytest_runtest_setup(item):
    """A worker takes its priority back once the compile is done (where allowed: lowering
    one's niceness needs the privilege; without it the worker stays at nice 5)."""
    if not os.environ.get("PYTEST_XDIST_WORKER") or _COMPILE_ENV not in os.environ:
        return
    pid, nice = map(int, os.environ[_COMPILE_ENV].split())
    if _alive(pid):
        return  # still compiling: ask again at the next test
    del os.environ[_COMPILE_ENV]
    try:
        os.nice(nice - os.nice(0))
    except OSError:
        pass


def pytest_unconfigure(config):
    proc = _AHEAD_PROC[0] if _AHEAD_PROC else None
    if proc is not None and proc.poll() is None:
        proc.kill()  # twins no test needs any more
        proc.wait()
    proc = getattr(config, "_femoat_compile", None)
    if proc is not None and proc.poll() is None:
        proc.wait()
    folder = getattr(config, "_femoat_ahead", None)
    if folder is not None:
        folder.cleanup()


def _alive(pid):
    try:
        os.kill(pid, 0)
    except OSError:
        return False
    return True


# ---- the OpenSees twins computed ahead ----------------------------------------------------------
AHEAD = (
    # (the test needing it, the test module and its function computing it, the arguments):
    # OpenSees twins only (never the building solver: the process would wait for the compile),
    # computed in the reverse of the order the workers reach them (those they reach first they
    # may well compute themselves, warm)
    ("test_plan_solver.py::test_against_the_opensees_twin_in_3d[ff6]",
     "test_plan_solver", "opensees_3d_twin", ("ff6",)),
    ("test_plan_solver.py::test_against_the_opensees_twin_in_3d[ff1]",
     "test_plan_solver", "opensees_3d_twin", ("ff1",)),
    ("test_plan_solver.py::test_against_the_opensees_twin_in_3d[ff1-5.3s]",
     "test_plan_solver", "opensees_3d_twin", ("ff1-5.3s",)),
    ("test_opensees_plan_walls.py::test_1d_twin_of_a_modal_wall_matches_femoat",
     "test_opensees_plan_walls", "opensees_modal_1d_twin", ()),
    ("test_bearing_runs.py::test_a_plan_run_matches_its_opensees_twin[tfp]",
     "test_bearing_runs", "opensees_plan_twin", ("tfp",)),
    ("test_bearing_runs.py::test_a_plan_run_matches_its_opensees_twin[lrb]",
     "test_bearing_runs", "opensees_plan_twin", ("lrb",)),
    ("test_bearing_runs.py::test_a_1d_run_matches_its_opensees_twin[tfp]",
     "test_bearing_runs", "opensees_1d_twin", ("tfp",)),
    ("test_bearing_runs.py::test_a_1d_run_matches_its_opensees_twin[lrb]",
     "test_bearing_runs", "opensees_1d_twin", ("lrb",)),
)
_AHEAD_PROC = []


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_node_collection_finished(node, ids):
    """The controller, once the first worker has collected: a process computing ahead the twins
    of the tests selected."""
    if _AHEAD_PROC or not os.environ.get(_AHEAD_ENV):
        return
    names = {i.split("/")[-1] for i in ids}
    entries = [(m, f, list(a)) for test, m, f, a in AHEAD if test in names]
    _AHEAD_PROC.append(None)
    if entries:
        import json

        _AHEAD_PROC[0] = _background(
            f"import sys; sys.path.insert(0, {str(_ROOT / 'tests')!r}); import json, conftest; "
            f"conftest.compute_ahead(json.loads({json.dumps(entries)!r}))")


def compute_ahead(entries):
    """The controller's process computing ahead: each (module, function, args) in turn that no
    worker has claimed yet."""
    import importlib

    for module, function, args in entries:
        f = getattr(importlib.import_module(module), function)
        base = Path(os.environ[_AHEAD_ENV]) / _ahead_key(module, function, tuple(args))
        if _claim(base):
            try:
                _compute(base, f, tuple(args))
            except BaseException:
                pass  # the test computes it again and says why


def ahead(function, *args):
    """``function(*args)``: a module-level function of a test module (a pure function of its
    plain arguments, an AHEAD entry). In a parallel session the result of whichever process
    claimed it first (the controller's process computing ahead, or this one); else computed
    here. One claim per twin: never computed twice; a failure is raised by the test's own
    computation."""
    folder = os.environ.get(_AHEAD_ENV)
    if not folder:
        return function(*args)
    base = Path(folder) / _ahead_key(function.__module__, function.__name__, args)
    if _claim(base):
        return _compute(base, function, args)
    import pickle
    import time

    while True:  # claimed by another process: wait for its result
        if base.with_suffix(".pkl").exists():
            return pickle.loads(base.with_suffix(".pkl").read_bytes())
        if base.with_suffix(".failed").exists() or not _claimer_alive(base):
            return function(*args)  # its own error (or skip) in this test
        time.sleep(0.05)


def _ahead_key(module, function, args):
    import hashlib

    return hashlib.sha1(f"{module}.{function}{args!r}".encode()).hexdigest()


def _claim(base):
    try:
        fd = os.open(base.with_suffix(".claim"), os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except FileExistsError:
        return False
    with os.fdopen(fd, "w") as f:
        f.write(str(os.getpid()))
    return True


def _claimer_alive(base):
    pid = base.with_suffix(".claim").read_text()
    return not pid or _alive(int(pid))  # no pid yet: claimed this instant


def _compute(base, function, args):
    import pickle

    try:
        result = function(*args)
    except BaseException:
        base.with_suffix(".failed").touch()
        raise
    tmp = base.with_suffix(".tmp")
    tmp.write_bytes(pickle.dumps(result))
    os.replace(tmp, base.with_suffix(".pkl"))
    return result
