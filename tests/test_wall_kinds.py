"""The wall-kind registry (femoat.walls.kinds): a kind added from this file alone builds, runs in a
scenario, answers on the command line, is written to a mesh file and is drawn; and no module but
the registry names a kind."""

import ast
import json
from pathlib import Path

import numpy as np
import pytest

from femoat.walls import kinds
from femoat.walls.kinds import WallKind

ROOT = Path(__file__).resolve().parents[1]
GEOMETRY = ROOT / "meshes" / "concrete_wall.toml"


def plane_strain_model(geometry, mesh=None, n_height=20, n_thickness=2):
    """The wall section in plane strain (a long wall in cylindrical bending): the plane-stress
    section with the 3D Lamé parameters."""
    from skfem.models.elasticity import lame_parameters

    from femoat.walls.fe._continuum import assemble_continuum
    from femoat.walls.fe.plane_stress import plane_mesh

    if mesh is None:
        mesh = plane_mesh(geometry, n_height, n_thickness)
    mat = geometry.material
    return assemble_continuum("plane_strain", geometry, mesh,
                              lame_parameters(mat.youngs_modulus, mat.poisson_ratio),
                              width=geometry.length)


def plane_strain_mesh(geometry, n_height=20, n_thickness=2):
    from femoat.walls.fe.plane_stress import plane_mesh

    return plane_mesh(geometry, n_height, n_thickness)


PLANE_STRAIN = WallKind("plane_strain", axes=(0, 2), builder=plane_strain_model,
                        mesher=plane_strain_mesh, line_width=2.0)


@pytest.fixture
def plane_strain(monkeypatch):
    """The registry with the plane-strain kind added (one row, as a new module would add it)."""
    monkeypatch.setattr(kinds, "KINDS", (*kinds.KINDS, PLANE_STRAIN))
    return PLANE_STRAIN


def test_a_kind_added_here_is_a_continuum_wall_with_the_plane_strain_modulus(plane_strain):
    from femoat.walls.fe import load_geometry, modal_analysis

    g = load_geometry(GEOMETRY)
    strain = modal_analysis(kinds.build_model("plane_strain", g), 3)
    stress = modal_analysis(kinds.build_model("plane", g), 3)
    # A slender cantilever (H/t = 27) bends with E/(1 - nu^2) in plane strain and E in plane
    # stress; the shear modulus is the same in both and shear holds < 0.1 % of the flexibility:
    # K_strain/K_stress = 1/(1 - 0.2^2) = 1.0417, the masses equal (same mesh and density).
    nu = g.material.poisson_ratio
    assert strain.static_stiffness / stress.static_stiffness == pytest.approx(1 / (1 - nu**2),
                                                                              rel=2e-3)
    assert strain.M1 == pytest.approx(stress.M1, rel=1e-3)
    # The continuum assembly put its displacement components on the kind's axes (x, z): the
    # first mode moves the wall top in x, never in y.
    model = kinds.build_model("plane_strain", g)
    u = model.vertex_vectors(strain.shapes[:, 0])
    assert np.all(u[:, 1] == 0.0) and np.abs(u[:, 0]).max() > 10 * np.abs(u[:, 2]).max()


def test_a_kind_added_here_is_read_by_the_scenario_the_mesh_writer_and_the_cli(
        plane_strain, tmp_path, capsys):
    from femoat.cli import main
    from femoat.scenario import scenario_from_dict
    from femoat.walls.fe import load_geometry
    from femoat.walls.fe.calibrate import write_wall
    from femoat.walls.modal import ModalWall

    fe = {"geometry": str(GEOMETRY), "modes": 3, "residual": False}
    walls = {"sides": "pos", "fe": {**fe, "model": "plane_strain"}}
    wall = scenario_from_dict({"walls": walls}).model.walls[0].wall
    # the scenario's modal wall is the kind's model reduced to 3 modes
    same = ModalWall.from_fe(plane_strain_model(load_geometry(GEOMETRY)), n_modes=3,
                             residual=False, damping_ratio=wall.damping_ratios[0])
    np.testing.assert_allclose(wall.modal_stiffnesses, same.modal_stiffnesses, rtol=1e-6)

    # its mesher writes a 2D mesh; read back, that mesh makes a plane wall (the first kind of
    # its dimension) unless the scenario names the plane-strain kind
    mesh, _ = write_wall(load_geometry(GEOMETRY), tmp_path / "strain", model="plane_strain")
    by_mesh = {"sides": "pos", "fe": {**fe, "mesh": str(mesh)}}
    plane = scenario_from_dict({"walls": by_mesh}).model.walls[0].wall
    strain = scenario_from_dict({"walls": {**by_mesh, "fe": {**by_mesh["fe"],
                                                             "model": "plane_strain"}}})
    ratio = strain.model.walls[0].wall.modal_stiffnesses[0] / plane.modal_stiffnesses[0]
    assert ratio == pytest.approx(1 / (1 - 0.2**2), rel=2e-3)  # as in the test above
    with pytest.raises(ValueError, match=r"\[walls.fe\] mesh is 2D, which makes a plane or "
                                         r"plane_strain model, not model = 'beam'"):
        scenario_from_dict({"walls": {**by_mesh, "fe": {**by_mesh["fe"], "model": "beam"}}})

    # the command line offers it (K1 stiffer than the plane-stress wall's by 1/(1 - nu^2)) and
    # refuses the beam's option for it, naming the beam
    k1 = {}
    for model in ("plane", "plane_strain"):
        assert main(["wall", str(GEOMETRY), "--model", model, "--modes", "2", "--json",
                     "--out", str(tmp_path)]) == 0
        out = json.loads(capsys.readouterr().out)
        assert out["model"] == model
        k1[model] = out["K1"]
    assert k1["plane_strain"] / k1["plane"] == pytest.approx(1 / (1 - 0.2**2), rel=2e-3)
    assert main(["wall", str(GEOMETRY), "--model", "plane_strain", "--timoshenko"]) == 2
    assert "--timoshenko applies to the beam model only" in capsys.readouterr().err


def test_the_renders_read_the_kind(plane_strain):
    from femoat.render.fe_wall import impact_point, line_style
    from femoat.walls.fe import load_geometry

    g = load_geometry(GEOMETRY)
    # a section in the x-z plane is hit at (0, 0, impact height); the 3D wall at mid-length
    np.testing.assert_array_equal(impact_point(kinds.build_model("plane_strain", g)),
                                  [0.0, 0.0, g.impact_height])
    solid = kinds.build_model("solid", g, n_height=4, n_length=2, n_thickness=1)
    np.testing.assert_array_equal(impact_point(solid), [0.0, g.length / 2, g.impact_height])
    assert line_style("plane_strain") == dict(show_edges=True, line_width=2.0)
    assert line_style("beam") == dict(show_edges=False, line_width=6.0)  # a line: no faces


def test_a_kind_added_in_a_fresh_process_is_drawn(tmp_path, render_backend):
    # (VTK may crash without a render backend: draw in a subprocess, which adds the kind itself)
    import inspect
    import textwrap

    import matplotlib.image
    from conftest import run_python

    script = "\n".join([
        "from femoat.walls import kinds",
        "from femoat.walls.kinds import WallKind",
        "from femoat.walls.fe import load_geometry, modal_analysis",
        "from femoat.render.fe_wall import render_modes, render_regions",
        textwrap.dedent(inspect.getsource(plane_strain_model)),
        "kinds.KINDS = (*kinds.KINDS, WallKind('plane_strain', axes=(0, 2), "
        "builder=plane_strain_model, line_width=2.0))",
        f"model = kinds.build_model('plane_strain', load_geometry({str(GEOMETRY)!r}))",
        "render_regions(model.mesh, 'regions.png', kind='plane_strain')",
        "render_modes(model, modal_analysis(model, 2), 'modes.png', n_modes=2)",
    ])
    run = run_python(script, tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    for name in ("regions", "modes"):
        img = matplotlib.image.imread(tmp_path / f"{name}.png")[..., :3]
        assert img.std() > 0.05, f"{name}.png is blank"
    # one elevation panel for the regions, two mode panels of 400 x 700 px side by side
    assert matplotlib.image.imread(tmp_path / "modes.png").shape[:2] == (700, 800)


def test_no_module_names_a_wall_kind_but_the_registry():
    # A kind's name compared, used as a dict key or as a subscript anywhere in femoat but
    # kinds.py is a second list of kinds, which a new kind would have to be added to.
    names = set(kinds.names())
    found = []
    for path in sorted((ROOT / "femoat").rglob("*.py")):
        if path == ROOT / "femoat" / "walls" / "kinds.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Compare):
                sides = [node.left, *node.comparators]
                constants = [e for s in sides for e in [s, *getattr(s, "elts", [])]]
            elif isinstance(node, ast.Dict):
                constants = [k for k in node.keys if k is not None]
            elif isinstance(node, ast.Subscript):
                constants = [node.slice]
            else:
                continue
            found += [f"{path.relative_to(ROOT)}:{node.lineno} {c.value!r}" for c in constants
                      if isinstance(c, ast.Constant) and c.value in names]
    assert not found, "wall kinds named outside femoat/walls/kinds.py: " + ", ".join(found)


def test_a_bad_row_or_registry_is_refused_by_name(monkeypatch):
    with pytest.raises(ValueError, match=r"axes = \(2, 0\)"):
        WallKind("upside", axes=(2, 0), builder=plane_strain_model)
    with pytest.raises(ValueError, match="views"):
        WallKind("odd", axes=(0, 2), builder=plane_strain_model, views=("top",))
    with pytest.raises(ValueError, match=r"model = 'shell': use 'beam', 'plane' or 'solid'"):
        kinds.wall_kind("shell")
    from femoat.walls.fe import load_geometry

    # a builder must make its own kind: the renders and the mesh files look the model's kind up
    borrowed = WallKind("beam2", axes=(2,),
                        builder=lambda g, mesh=None: kinds.build_model("beam", g))
    with pytest.raises(ValueError, match="made a 'beam' model"):
        borrowed.build(load_geometry(GEOMETRY))
    monkeypatch.setattr(kinds, "KINDS", (*kinds.KINDS, kinds.KINDS[0]))
    with pytest.raises(ValueError, match="distinct names"):
        kinds.names()
