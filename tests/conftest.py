import os

# Many tiny matrix operations thrash a threaded BLAS: pin it to one thread (as pycba does).
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

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


# ---- a parallel session (pytest-xdist, -n N): the solver compiled once, while tests run -------
# The first use of the solver in a process holds a lock beside numba's cache (compile once,
# load everywhere else: femoat.compilation.numba_cache.first_compile_lock). The controller of a
# parallel session starts that compile at once in a background process, while the workers
# start, collect and run the test files that never use the building solver (run first); the
# workers' first solver test then waits for the lock and loads the kernels. tests/README.md.
SOLVER_FREE = ("test_atomic.py", "test_contact_laws.py", "test_ground_motions_fema.py",
               "test_ground_motions_peer.py", "test_ground_motions_record.py",
               "test_ground_motions_spectrum.py", "test_materials.py",
               "test_materials_opensees.py", "test_plotting_drift.py", "test_record_pair.py",
               "test_repository.py", "test_wall_fe_beam.py", "test_wall_fe_calibrate.py",
               "test_wall_fe_io.py", "test_wall_fe_models.py", "test_readers_fuzz.py",
               "test_imports.py", "test_optional_dependencies.py")


def _parallel_controller(config):
    workers = config.getoption("numprocesses", None)
    return (workers not in (None, 0, "0") and os.environ.get("PYTEST_XDIST_WORKER") is None
            and not config.getoption("collectonly", False))


def pytest_configure(config):
    if _parallel_controller(config):
        config._femoat_compile = subprocess.Popen(
            [sys.executable, "-c", "from femoat.startup.warmup import warm_up; warm_up()"],
            env={**os.environ, "PYTHONPATH": os.pathsep.join([str(_ROOT),
                                                              os.environ.get("PYTHONPATH", "")])},
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def pytest_unconfigure(config):
    proc = getattr(config, "_femoat_compile", None)
    if proc is not None and proc.poll() is None:
        proc.wait()


def pytest_collection_modifyitems(config, items):
    # a stable sort: the solver-free files first, every other order kept (the same in every
    # worker, as pytest-xdist requires)
    items.sort(key=lambda item: Path(str(item.fspath)).name not in SOLVER_FREE)
