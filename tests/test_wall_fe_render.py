"""Off-screen renders of wall meshes and modes, each in a subprocess (a missing OpenGL backend
can crash VTK outright)."""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "VTK_DEFAULT_OPENGL_WINDOW": "vtkEGLRenderWindow",
       "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}

PROBE = ("import pyvista as pv; p = pv.Plotter(off_screen=True, window_size=(64, 64)); "
         "p.add_mesh(pv.Sphere()); p.screenshot({path!r}); p.close()")


def _python(code, cwd):
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, env=ENV, capture_output=True,
                          text=True, timeout=240)


@pytest.fixture(scope="module")
def render_backend(tmp_path_factory):
    """Skip when, and only when, plain pyvista cannot render a sphere off-screen in a fresh
    process: that is the definition of "no render backend" here. Anything else fails."""
    tmp = tmp_path_factory.mktemp("probe")
    probe = _python(PROBE.format(path=str(tmp / "probe.png")), tmp)
    if probe.returncode != 0 or not (tmp / "probe.png").is_file():
        pytest.skip(f"no off-screen render backend (pyvista probe exited {probe.returncode}: "
                    f"{probe.stderr.strip()[-300:]})")


def _image(path):
    import matplotlib.image

    return matplotlib.image.imread(path)[..., :3]


def _share(img, rgb, tol=0.12):
    return np.mean(np.all(np.abs(img - np.array(rgb)) < tol, axis=-1))


def test_regions_and_modes_render(tmp_path, render_backend):
    script = textwrap.dedent("""
        from femoat.walls.fe import WallGeometry, concrete, modal_analysis, plane_model, solid_model
        from femoat.walls.fe.render import render_modes, render_regions
        g = WallGeometry(height=60.0, length=30.0, thickness=4.0, material=concrete(),
                         impact_height=50.0, impact_patch=8.0)
        solid = solid_model(g, 6, 4, 1)
        render_regions(solid.mesh, "regions_solid.png")
        render_modes(solid, modal_analysis(solid, 3), "modes_solid.png", n_modes=3)
        plane = plane_model(g, 8, 1)
        render_regions(plane.mesh, "regions_plane.png")
        render_modes(plane, modal_analysis(plane, 2), "modes_plane.png", n_modes=2)
    """)
    run = _python(script, tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    for name in ("regions_solid", "modes_solid", "regions_plane", "modes_plane"):
        img = _image(tmp_path / f"{name}.png")
        assert img.std() > 0.05, f"{name}.png is blank"
    # The impact patch is drawn red (REGION_COLORS) and is visible from the moat side.
    assert _share(_image(tmp_path / "regions_solid.png"), (0.8, 0.0, 0.0), tol=0.25) > 1e-4
    # Three mode panels side by side.
    assert _image(tmp_path / "modes_solid.png").shape[1] == 3 * _image(
        tmp_path / "modes_solid.png").shape[0] * 400 // 700
