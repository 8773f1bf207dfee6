"""Off-screen renders of wall meshes and modes, each in a subprocess (a missing OpenGL backend
can crash VTK outright)."""

import textwrap

import numpy as np
from conftest import run_python






def _image(path):
    import matplotlib.image

    return matplotlib.image.imread(path)[..., :3]


def _share(img, rgb, tol=0.12):
    return np.mean(np.all(np.abs(img - np.array(rgb)) < tol, axis=-1))


def test_regions_and_modes_render(tmp_path, render_backend):
    script = textwrap.dedent("""
        from femoat.walls.fe import WallGeometry, concrete, modal_analysis, plane_model, solid_model
        from femoat.render.fe_wall import render_modes, render_regions
        g = WallGeometry(height=60.0, length=30.0, thickness=4.0, material=concrete(),
                         impact_height=50.0, impact_patch=8.0)
        solid = solid_model(g, 6, 4, 1)
        render_regions(solid.mesh, "regions_solid.png")
        render_modes(solid, modal_analysis(solid, 3), "modes_solid.png", n_modes=3)
        plane = plane_model(g, 8, 1)
        render_regions(plane.mesh, "regions_plane.png")
        render_modes(plane, modal_analysis(plane, 2), "modes_plane.png", n_modes=2)
    """)
    run = run_python(script, tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    for name in ("regions_solid", "modes_solid", "regions_plane", "modes_plane"):
        img = _image(tmp_path / f"{name}.png")
        assert img.std() > 0.05, f"{name}.png is blank"
    # The impact patch is drawn red (REGION_COLORS) and is visible from the moat side.
    assert _share(_image(tmp_path / "regions_solid.png"), (0.8, 0.0, 0.0), tol=0.25) > 1e-4
    # Three mode panels side by side.
    assert _image(tmp_path / "modes_solid.png").shape[1] == 3 * _image(
        tmp_path / "modes_solid.png").shape[0] * 400 // 700
