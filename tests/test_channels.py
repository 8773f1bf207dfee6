"""One home per concept in the solver: the output channels' registry and the methods' registry.

A channel is one line in ``recording/channels.py`` and its line in ``recorder.record``; a method
is its module in ``methods/``, its line in ``methods.MODULES`` and its branch in the three
dispatchers. These tests fail when a registered channel is not written, when a result or a file
does not follow the registry, or when a registered method is not dispatched.
"""

import ast
import inspect
import textwrap

import numba
import numpy as np
import pytest

from femoat.integration import Integrator, methods, solve
from femoat.integration.recording import channels, recorder
from femoat.integration.settings import DEFAULT_RTOL, METHODS
from femoat.paper import paper_model, paper_motion
from femoat.results import ARRAY_UNITS, RunResult
from femoat.run import run


def _written_buffers(func):
    """The recorder buffers ``func`` assigns into (``rec.<buffer>[...] = ...``)."""
    tree = ast.parse(textwrap.dedent(inspect.getsource(func.py_func)))
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign):
            for target in node.targets:
                if (isinstance(target, ast.Subscript) and isinstance(target.value, ast.Attribute)
                        and isinstance(target.value.value, ast.Name)
                        and target.value.value.id == "rec"):
                    out.add(target.value.attr)
    return out


def test_every_registered_channel_is_written_by_the_recorder():
    # the registry lists the buffers; record() must write each (and nothing else)
    assert _written_buffers(recorder.record) == set(channels.BUFFERS)


@pytest.fixture(scope="module")
def short_run():
    motion = paper_motion(quick=True)
    return run(paper_model("concrete", "H"), motion, duration=3.0)


def test_a_result_has_every_channel_with_its_width_and_unit(short_run, tmp_path):
    r = short_run
    n, nel, nc = len(r.meta["dof_names"]), len(r.meta["element_names"]), 2
    width = dict(dofs=n, elements=nel, contacts=nc)
    rows = r.time.size
    for c in channels.CHANNELS:
        arr = getattr(r, c.name)
        # one row per sample, a column per DOF / element / contact (none for a scalar channel)
        # (the one ground component of a 1D model: one value per sample)
        flat = c.width is None or c.width == "ground"
        assert arr.shape == ((rows,) if flat else (rows, width[c.width])), c.name
        assert arr.dtype == c.dtype, c.name
        assert r.meta["units"][c.name] == c.unit == ARRAY_UNITS[c.name]
    # the file holds every channel under its name, bit for bit
    r.save(tmp_path / "run.npz")
    back = RunResult.load(tmp_path / "run.npz")
    with np.load(tmp_path / "run.npz") as z:
        assert set(z.files) == {c.name for c in channels.CHANNELS} | {"meta"}
    for c in channels.CHANNELS:
        assert np.array_equal(getattr(back, c.name), getattr(r, c.name)), c.name


def test_a_sample_costs_the_bytes_the_registry_says(short_run):
    # the record budget is counted from the registry: it must equal what a sample really takes
    r = short_run
    cols = {c.buffer: (None if getattr(r, c.name).ndim == 1 else getattr(r, c.name).shape[1])
            for c in channels.CHANNELS}
    recorded = sum(a.nbytes for a in r.arrays.values()) / r.time.size
    assert channels.row_bytes(cols) == recorded


def test_channel_groups_turn_channels_off_and_unknown_ones_are_named():
    motion = paper_motion(quick=True)
    packed = paper_model("concrete", "H").pack()
    hist = solve(packed, motion.accel, motion.dt, 1.0, channels=("displacement",))
    a = hist.arrays
    # velocity, acceleration and elements not asked: written nowhere (no columns)
    for name in ("velocity", "acceleration", "element_force", "element_deformation"):
        assert a[name].shape == (a["time"].size, 0), name
    assert a["displacement"].shape[1] == packed.n and a["contact_force"].shape[1] == 2
    with pytest.raises(ValueError, match="'speed'"):
        solve(packed, motion.accel, motion.dt, 1.0, channels=("speed",))


# ---- methods -----------------------------------------------------------------------------------


def test_the_methods_registry_is_the_integrators():
    assert METHODS == methods.NAMES == tuple(m.NAME for m in methods.MODULES)
    assert set(DEFAULT_RTOL) == set(METHODS)
    for name in METHODS:
        assert Integrator(method=name).rtol == methods.module(name).DEFAULT_RTOL
    assert methods.MODULES[methods.CONTACT].NAME == "newmark"


@pytest.mark.parametrize("module", methods.MODULES, ids=lambda m: m.NAME)
def test_every_method_has_the_interface_and_is_dispatched(module):
    for attr in ("NAME", "DEFAULT_RTOL", "EXPLICIT", "QUINTIC_DENSE", "SAFETY", "SHRINK_MIN",
                 "GROW_MAX", "ERROR_EXPONENT"):
        assert hasattr(module, attr), f"{module.NAME} lacks {attr}"
    alias = module.__name__.rsplit(".", 1)[1]
    for kernel in ("step", "retry", "next_step"):
        # the same arguments in every method
        assert (list(inspect.signature(getattr(module, kernel).py_func).parameters)
                == list(inspect.signature(getattr(methods.newmark, kernel).py_func).parameters))
        # the dispatcher calls this method's kernel under this method's code
        code = methods.CODES[module.NAME]
        src = inspect.getsource(getattr(methods, kernel).py_func)
        if hasattr(module, "PAIR"):
            # an explicit pair runs on dp5's one step with its own tableau, and takes dp5's
            # retry and next step (the same controller constants)
            if kernel == "step":
                assert "dp5.pair_step(pair," in src, alias
                if alias == "dp5":  # the pair every other explicit code (1, ark5's line) takes
                    assert "else dp5.PAIR" in src
                    continue
                assert f"{alias}.PAIR if code == {code}" in src, alias
            else:
                assert getattr(module, kernel) is getattr(methods.dp5, kernel), (alias, kernel)
                assert f"dp5.{kernel}(" in src
        else:
            assert f"{alias}.{kernel}(" in src, f"methods.{kernel} never calls {alias}.{kernel}"
        if code != 0:  # (code 0 is the fall-through)
            assert f"code == {code}" in src, f"methods.{kernel} has no branch for code {code}"


def test_settings_are_named_and_typed_alike_for_every_run():
    # one compiled signature per kernel, loaded from numba's cache by every process: every
    # run's Settings must have the same numba type, whatever the Integrator and the duration's
    # Python type
    from femoat.integration.solve import _settings

    packed = paper_model("concrete", "H").pack()
    ag = np.zeros(10)
    a = _settings(packed, Integrator(), ag, 0.01, 10, None, True, False, True)
    b = _settings(packed, Integrator(method="newmark", max_step=0.002, alpha=-0.1), ag, 0.005,
                  2.5, None, False, True, False)
    assert numba.typeof(a) == numba.typeof(b)
    assert "fopt" not in a._fields and "iopt" not in a._fields
    assert a.t_end == 10.0 and b.h_max == 0.002 and b.stop_at_limit and b.ring
