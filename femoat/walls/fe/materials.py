"""Isotropic linear-elastic wall materials.

Units: E [ksi = kip/in²], ν [-], ρ [kip·s²/in⁴] (mass density: weight density [kip/in³] / g).
"""

import math
from dataclasses import dataclass

from femoat.units import G

KCF = 1.0 / 1728.0
"""One kip per cubic foot in kip/in³."""


@dataclass(frozen=True)
class Material:
    """An isotropic linear-elastic material.

    youngs_modulus : float  [ksi]
    poisson_ratio : float  [-], in (-1, 0.5)
    density : float  [kip·s²/in⁴], mass density (weight density / g)
    name : str  a label only
    """

    youngs_modulus: float
    poisson_ratio: float
    density: float
    name: str = "custom"

    def __post_init__(self):
        for field, value in (("youngs_modulus", self.youngs_modulus), ("density", self.density)):
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ValueError(f"Material.{field} must be a positive number, got {value!r}")
        nu = self.poisson_ratio
        if not (isinstance(nu, (int, float)) and -1.0 < nu < 0.5):
            raise ValueError(f"Material.poisson_ratio must lie in (-1, 0.5), got {nu!r}")

    @property
    def shear_modulus(self):
        """G = E / (2(1 + ν))  [ksi]."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def unit_weight(self):
        """Weight density ρ·g  [kip/in³]."""
        return self.density * G


def concrete(fc=4.0, unit_weight_kcf=0.150, poisson_ratio=0.2):
    """Normal-weight concrete.

    fc : float  [ksi], specified compressive strength f'c
    unit_weight_kcf : float  [kip/ft³]
    E = 57·√(1000·f'c) ksi (ACI 318-19 §19.2.2.1b, normal-weight concrete): 3605 ksi for 4 ksi.
    """
    if not fc > 0:
        raise ValueError(f"concrete fc must be positive [ksi], got {fc!r}")
    if not unit_weight_kcf > 0:
        raise ValueError(f"concrete unit_weight_kcf must be positive [kip/ft³], got {unit_weight_kcf!r}")
    return Material(
        youngs_modulus=57.0 * math.sqrt(1000.0 * fc),
        poisson_ratio=poisson_ratio,
        density=unit_weight_kcf * KCF / G,
        name=f"concrete f'c={fc:g} ksi",
    )


def steel(youngs_modulus=29000.0, unit_weight_kcf=0.490, poisson_ratio=0.3):
    """Structural steel: E 29,000 ksi, 490 lb/ft³ (AISC 360 defaults).

    youngs_modulus : float  [ksi]
    unit_weight_kcf : float  [kip/ft³]
    """
    return Material(
        youngs_modulus=youngs_modulus,
        poisson_ratio=poisson_ratio,
        density=unit_weight_kcf * KCF / G,
        name="steel",
    )


PRESETS = {"concrete": concrete, "steel": steel}
"""Material factories by name, as used by the ``preset`` key of a geometry TOML."""
