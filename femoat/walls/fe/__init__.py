"""The moat wall as a finite-element model, reduced to the paper's SDOF wall (K1, M1).

Units kip, in, s. Frame: x normal to the wall (impact face x = 0, backfill at x = t), y along
the moat, z up from the wall base (see :mod:`femoat.walls.fe.geometry`).

    geometry = WallGeometry(height=86.0, length=48.0, thickness=3.25, material=concrete(),
                            impact_height=84.0, impact_patch=4.0)
    model = beam_model(geometry)            # or plane_model, solid_model
    result = modal_analysis(model, n_modes=6)
    result.K1, result.M1, result.frequencies, result.static_stiffness

Modules: materials, geometry (the wall), beam / plane_stress / solid (the models of the wall
kinds in :mod:`femoat.walls.kinds`, each returning a :class:`~femoat.walls.fe.model.WallModel`),
modal (modes, SDOF, modal reduction at the impact point), mesh_io (.vtu/.msh), calibrate
(dimensions for a target K1, M1). Pictures of the models: :mod:`femoat.render.fe_wall`.
"""

from femoat.walls.fe.beam import beam_model
from femoat.walls.fe.geometry import WallGeometry, load_geometry
from femoat.walls.fe.materials import Material, concrete, steel
from femoat.walls.fe.modal import (ImpactModes, ModalResult, ResidualMode, flexibility_fraction,
                                   impact_modes, modal_analysis, modes_for_flexibility,
                                   residual_mode, static_stiffness)
from femoat.walls.fe.model import WallModel
from femoat.walls.fe.plane_stress import plane_model
from femoat.walls.fe.solid import solid_model

__all__ = [
    "ImpactModes", "Material", "ModalResult", "WallGeometry", "WallModel", "beam_model",
    "concrete", "flexibility_fraction", "impact_modes", "load_geometry", "modal_analysis",
    "modes_for_flexibility", "plane_model", "ResidualMode", "residual_mode", "solid_model",
    "static_stiffness", "steel",
]
