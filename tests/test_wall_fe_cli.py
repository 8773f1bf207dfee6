"""``femoat wall`` subcommand, called through argparse and run()."""

import argparse
import json

import meshio
import numpy as np
import pytest

from femoat.commands import wall as wall_command
from femoat.walls.fe import WallGeometry, concrete


def _run(argv, capsys):
    parser = argparse.ArgumentParser()
    wall_command.add_parser(parser.add_subparsers())
    code = wall_command.run(parser.parse_args(["wall", *argv]))
    return code, capsys.readouterr().out


@pytest.fixture
def geometry_file(tmp_path):
    g = WallGeometry(height=100.0, length=10.0, thickness=5.0, material=concrete(),
                     impact_height=100.0, impact_patch=2.0)
    g.save(tmp_path / "wall.toml")
    return tmp_path / "wall.toml"


@pytest.mark.parametrize("model", ["beam", "plane", "solid"])
def test_json_output_and_mode_mesh(tmp_path, geometry_file, capsys, model):
    code, out = _run([str(geometry_file), "--model", model, "--modes", "3", "--json",
                      "--out", str(tmp_path / "out")], capsys)
    assert code == 0
    data = json.loads(out)
    for key in ("K1", "M1", "frequencies", "static_stiffness"):
        assert key in data
    assert len(data["frequencies"]) == 3
    # Uniform cantilever hit at the top: K1 ≈ 3.09·EI/H³, within a few % for every model.
    EI = 3605.0 * 10.0 * 5.0**3 / 12
    assert data["K1"] == pytest.approx(3.0906 * EI / 100.0**3, rel=0.03)
    m = meshio.read(data["mesh_file"])
    assert {"mode_1", "mode_2", "mode_3"} <= set(m.point_data)
    assert np.abs(m.point_data["mode_1"]).max() == pytest.approx(1.0)


def test_mesh_source_uses_the_toml_beside_it(tmp_path, geometry_file, capsys):
    from femoat.walls.fe import solid_model
    from femoat.walls.fe.geometry import load_geometry
    from femoat.walls.fe.mesh_io import write_mesh

    mesh = solid_model(load_geometry(geometry_file), 8, 2, 1).mesh
    write_mesh(tmp_path / "wall.vtu", mesh)
    code, out = _run([str(tmp_path / "wall.vtu"), "--out", str(tmp_path / "o")], capsys)
    assert code == 0 and "solid model" in out and "K1 =" in out
    with pytest.raises(ValueError, match="plane"):
        _run([str(tmp_path / "wall.vtu"), "--model", "plane"], capsys)
    (tmp_path / "lonely.vtu").write_bytes((tmp_path / "wall.vtu").read_bytes())
    with pytest.raises(ValueError, match="geometry TOML"):
        _run([str(tmp_path / "lonely.vtu")], capsys)
