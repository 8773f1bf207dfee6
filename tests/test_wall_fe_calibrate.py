"""Calibrating wall dimensions to the paper's SDOF walls (Table 3: K1, M1·g)."""

import pytest

from femoat.units import G
from femoat.walls.fe import WallGeometry, beam_model, concrete, modal_analysis, solid_model, steel
from femoat.walls.fe.calibrate import PAPER_CONCRETE, PAPER_STEEL, SdofTarget, calibrate

COARSE_SOLID = dict(n_height=8, n_length=4, n_thickness=1)


def _template(material, height, thickness):
    return WallGeometry(height=height, length=48.0, thickness=thickness, material=material,
                        impact_height=height - 2.0, impact_patch=4.0)


@pytest.mark.parametrize("target, material, guess", [
    (PAPER_CONCRETE, concrete(), (80.0, 3.0)), (PAPER_STEEL, steel(), (40.0, 2.5))])
def test_beam_calibration_reproduces_table_3(target, material, guess):
    wall = calibrate(_template(material, *guess), target)
    r = modal_analysis(beam_model(wall), 2)
    # Paper Table 3: concrete K1 = 2.4 kip/in, M1·g = 0.29 kip; steel 100 kip/in, 0.41 kip.
    assert r.K1 == pytest.approx(target.K1, rel=0.01)
    assert r.M1 == pytest.approx(target.M1, rel=0.01)
    assert r.M1 * G == pytest.approx({"concrete": 0.29, "steel": 0.41}[target.name], rel=0.01)
    # The base mat keeps its depth below the top: 2 in.
    assert wall.height - wall.impact_height == pytest.approx(2.0)


def test_solid_refined_calibration_hits_the_target_in_3d():
    wall = calibrate(_template(steel(), 40.0, 2.5), PAPER_STEEL, refine_with="solid",
                     model_options=COARSE_SOLID)
    r = modal_analysis(solid_model(wall, **COARSE_SOLID), 3)
    assert r.K1 == pytest.approx(PAPER_STEEL.K1, rel=0.01)
    assert r.M1 == pytest.approx(PAPER_STEEL.M1, rel=0.01)


def test_calibrating_other_dimensions():
    # Thickness and length at a given height.
    wall = calibrate(_template(concrete(), 84.0, 3.0), PAPER_CONCRETE, free=("thickness", "length"))
    assert wall.height == 84.0
    r = modal_analysis(beam_model(wall), 1)
    assert (r.K1, r.M1) == pytest.approx((PAPER_CONCRETE.K1, PAPER_CONCRETE.M1), rel=0.01)


def test_calibration_input_errors():
    with pytest.raises(ValueError, match="free"):
        calibrate(_template(concrete(), 80.0, 3.0), PAPER_CONCRETE, free=("height",))
    with pytest.raises(ValueError, match="K1"):
        SdofTarget(K1=-1.0, M1=1e-3)
    with pytest.raises(ValueError, match="refine_with"):
        calibrate(_template(concrete(), 80.0, 3.0), PAPER_CONCRETE, refine_with="shell")


def test_shipped_paper_meshes_reproduce_table_3():
    from pathlib import Path

    from femoat.walls.fe import load_geometry
    from femoat.walls.fe.mesh_io import read_mesh

    meshes = Path(__file__).resolve().parents[1] / "meshes"
    for target in (PAPER_CONCRETE, PAPER_STEEL):
        geometry = load_geometry(meshes / f"{target.name}_wall.toml")
        mesh = read_mesh(meshes / f"{target.name}_wall.vtu")
        r = modal_analysis(solid_model(geometry, mesh=mesh), 3)
        # meshes/*_wall.* were calibrated on this very 3D mesh (python -m femoat.walls.fe.calibrate).
        assert r.K1 == pytest.approx(target.K1, rel=0.01)
        assert r.M1 == pytest.approx(target.M1, rel=0.01)
