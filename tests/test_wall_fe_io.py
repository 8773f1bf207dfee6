"""Wall meshes and geometries on disk: .vtu round trip, gmsh physical groups, TOML, guards."""

import numpy as np
import pytest

from femoat.walls.fe import (WallGeometry, beam_model, concrete, load_geometry, modal_analysis,
                             plane_model, solid_model, steel)
from femoat.walls.fe.mesh_io import read_mesh, write_mesh


def _wall(**changes):
    base = dict(height=100.0, length=10.0, thickness=5.0, material=concrete(),
                impact_height=60.0, impact_patch=4.0)
    return WallGeometry(**{**base, **changes})


@pytest.mark.parametrize("build", [lambda g: beam_model(g, 10), lambda g: plane_model(g, 10, 2),
                                   lambda g: solid_model(g, 6, 2, 1)])
def test_vtu_round_trip_keeps_nodes_cells_and_boundaries(tmp_path, build):
    mesh = build(_wall()).mesh
    path = write_mesh(tmp_path / "wall.vtu", mesh, point_data={"u": np.ones((mesh.nvertices, 3))})
    back = read_mesh(path)
    assert type(back) is type(mesh)
    assert np.allclose(back.p, mesh.p, rtol=0, atol=1e-12)
    assert np.array_equal(back.t, mesh.t)
    assert set(back.boundaries) == set(mesh.boundaries)
    for name, facets in mesh.boundaries.items():
        assert np.array_equal(np.sort(back.boundaries[name]), np.sort(facets))


def test_model_from_a_read_mesh_equals_the_generated_one(tmp_path):
    g = _wall()
    generated = plane_model(g, 10, 2)
    read = plane_model(g, mesh=read_mesh(write_mesh(tmp_path / "w.vtu", generated.mesh)))
    assert abs(read.stiffness - generated.stiffness).max() == 0
    assert np.array_equal(read.impact, generated.impact)


def _gmsh_section(path):
    """A 2 x 10 quad section (5 x 100 in) in the x-y plane, as gmsh draws it, MSH 2.2."""
    import meshio

    x, y = np.linspace(0, 5, 3), np.linspace(0, 100, 11)
    X, Y = np.meshgrid(x, y, indexing="ij")
    points = np.column_stack([X.ravel(), Y.ravel(), np.zeros(X.size)])

    def node(i, j):
        return i * len(y) + j

    quads = [[node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)]
             for i in range(2) for j in range(10)]
    base = [[node(i, 0), node(i + 1, 0)] for i in range(2)]
    back = [[node(2, j), node(2, j + 1)] for j in range(10)]
    impact = [[node(0, 5), node(0, 6)]]
    tags = np.array([1] * 2 + [2] * 10 + [3])
    mesh = meshio.Mesh(
        points, [("line", np.array(base + back + impact)), ("quad", np.array(quads))],
        cell_data={"gmsh:physical": [tags, np.full(20, 4)],
                   "gmsh:geometrical": [tags, np.full(20, 1)]},
        field_data={"base": np.array([1, 1]), "back": np.array([2, 1]),
                    "impact": np.array([3, 1]), "wall": np.array([4, 2])})
    meshio.write(path, mesh, file_format="gmsh22", binary=False)
    return path


def test_gmsh_physical_groups_become_boundaries(tmp_path):
    mesh = read_mesh(_gmsh_section(tmp_path / "section.msh"))
    assert {k: len(v) for k, v in mesh.boundaries.items()} == {"base": 2, "back": 10, "impact": 1}
    # The x-y drawing plane is read as (x, z): 100 in tall.
    assert mesh.p[1].max() == pytest.approx(100.0)
    g = _wall(impact_height=55.0, impact_patch=10.0)
    from_gmsh = modal_analysis(plane_model(g, mesh=mesh), 2)
    generated = modal_analysis(plane_model(g, n_height=10, n_thickness=2), 2)
    # Same cells, same patch (z in [50, 60]): same model up to node numbering, which changes
    # only the round-off of the Lanczos iteration.
    assert from_gmsh.K1 == pytest.approx(generated.K1, rel=1e-8)


@pytest.mark.parametrize("content, suffix", [(b"not a mesh at all", ".vtu"),
                                             (b"$MeshFormat\ngarbage", ".msh")])
def test_unreadable_mesh_raises_value_error_not_system_exit(tmp_path, content, suffix):
    path = tmp_path / f"broken{suffix}"
    path.write_bytes(content)
    with pytest.raises(ValueError, match="could not read"):
        read_mesh(path)


def test_missing_or_foreign_mesh_file_is_refused(tmp_path):
    with pytest.raises(ValueError, match="does not exist"):
        read_mesh(tmp_path / "none.vtu")
    (tmp_path / "wall.stl").write_text("solid x")
    with pytest.raises(ValueError, match="suffix"):
        read_mesh(tmp_path / "wall.stl")


def test_geometry_toml_round_trip(tmp_path):
    g = _wall(material=steel(), base="pinned", subgrade_modulus=0.1)
    g.save(tmp_path / "wall.toml")
    assert load_geometry(tmp_path / "wall.toml") == g


def test_geometry_toml_preset_and_errors(tmp_path):
    path = tmp_path / "wall.toml"
    path.write_text('[wall]\nheight = 80.0\nlength = 48.0\nthickness = 3.0\n'
                    'impact_height = 78.0\nimpact_patch = 4.0\n[material]\npreset = "concrete"\n')
    g = load_geometry(path)
    # ACI 318: E = 57·√(1000·f'c) ksi = 3605 ksi for f'c = 4 ksi; ρ = 0.150 kcf / 1728 / g.
    assert g.material.youngs_modulus == pytest.approx(3605.0, abs=0.5)
    assert g.material.density == pytest.approx(0.150 / 1728 / 386.09, rel=1e-12)
    path.write_text(path.read_text().replace("thickness", "thickness_in"))
    with pytest.raises(ValueError, match="thickness_in"):
        load_geometry(path)
    path.write_text("[wall\nheight = ")
    with pytest.raises(ValueError, match="not valid TOML"):
        load_geometry(path)
