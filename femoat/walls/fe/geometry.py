"""The moat wall: its dimensions, material, supports and where the building hits it.

Frame and sign convention (all wall models): x is horizontal and normal to the wall, from the
moat (impact face, x = 0) toward the backfill (back face, x = thickness); y runs along the moat
(0..length); z is up from the wall base (0..height). The building's base mat pushes the wall
in +x: a positive impact-point displacement moves the wall toward the backfill.
2D models use (x, z) and 1D models use z alone.
"""

import math
import tomllib
from dataclasses import dataclass, replace
from pathlib import Path

from femoat.atomic import write_text
from femoat.walls.fe.materials import PRESETS, Material

BASES = ("fixed", "pinned")


@dataclass(frozen=True)
class WallGeometry:
    """A prismatic moat wall.

    height : float  [in], from the wall base to its top
    length : float  [in], along the moat (the out-of-plane width of the 2D section)
    thickness : float  [in]
    material : Material  (E [ksi], ν [-], ρ [kip·s²/in⁴])
    impact_height : float  [in], level of the base mat measured from the wall base
    impact_patch : float  [in], side of the square contact patch centred at
        (y = length/2, z = impact_height) on the impact face; the part of the patch above the
        wall top or below its base is cut off (so impact_height = height puts a half patch at
        the top edge); the patch may not be longer than the wall
    base : str  "fixed" (clamped) or "pinned" (hinged about the base centre line; only stable
        with a backfill)
    subgrade_modulus : float  [kip/in³], Winkler modulus of the backfill acting on the whole back
        face (a linear, tension-carrying spring per unit area); 0 means no backfill
    """

    height: float
    length: float
    thickness: float
    material: Material
    impact_height: float
    impact_patch: float
    base: str = "fixed"
    subgrade_modulus: float = 0.0

    def __post_init__(self):
        for name in ("height", "length", "thickness", "impact_patch"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ValueError(f"WallGeometry.{name} must be a positive number [in], got {value!r}")
        if not isinstance(self.material, Material):
            raise ValueError("WallGeometry.material must be a Material; build one with "
                             "materials.concrete(), materials.steel() or Material(E, nu, rho)")
        if self.base not in BASES:
            raise ValueError(f"WallGeometry.base must be one of {BASES}, got {self.base!r}")
        k = self.subgrade_modulus
        if not (isinstance(k, (int, float)) and math.isfinite(k) and k >= 0):
            raise ValueError(f"WallGeometry.subgrade_modulus must be >= 0 [kip/in³], got {k!r}")
        if self.base == "pinned" and k == 0:
            raise ValueError("a pinned-base wall without backfill is a mechanism: set base='fixed' "
                             "or give a subgrade_modulus > 0 [kip/in³]")
        h, a = self.impact_height, self.impact_patch
        if not (isinstance(h, (int, float)) and math.isfinite(h)):
            raise ValueError(f"WallGeometry.impact_height must be a number [in], got {h!r}")
        if not (-1e-9 * self.height <= h <= self.height * (1 + 1e-9)):
            raise ValueError(f"impact_height {h:g} in must lie on the wall, in [0, {self.height:g}] in")
        if a > self.length * (1 + 1e-9):
            raise ValueError(f"impact_patch {a:g} in is wider than the wall length {self.length:g} "
                             "in: shrink impact_patch or lengthen the wall")

    @property
    def patch_z(self):
        """(bottom, top) of the impact patch [in]."""
        a = self.impact_patch / 2
        return max(self.impact_height - a, 0.0), min(self.impact_height + a, self.height)

    @property
    def patch_y(self):
        """(start, end) of the impact patch along the moat [in]."""
        a = self.impact_patch / 2
        return max(self.length / 2 - a, 0.0), min(self.length / 2 + a, self.length)

    @property
    def mass(self):
        """Total wall mass ρ·H·L·t  [kip·s²/in]."""
        return self.material.density * self.height * self.length * self.thickness

    def with_(self, **changes):
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    def to_toml(self):
        """The geometry as TOML text (the format :func:`load_geometry` reads)."""
        m = self.material
        return "\n".join([
            "# femoat wall geometry. Units: kip, in, s.",
            "[wall]",
            f"height = {float(self.height)!r}  # [in]",
            f"length = {float(self.length)!r}  # [in] along the moat",
            f"thickness = {float(self.thickness)!r}  # [in]",
            f"base = \"{self.base}\"  # \"fixed\" or \"pinned\"",
            f"impact_height = {float(self.impact_height)!r}  # [in] base-mat level above the wall base",
            f"impact_patch = {float(self.impact_patch)!r}  # [in] side of the square impact patch",
            f"subgrade_modulus = {float(self.subgrade_modulus)!r}  # [kip/in^3] Winkler backfill; 0 = none",
            "",
            "[material]",
            f"name = \"{m.name}\"",
            f"youngs_modulus = {float(m.youngs_modulus)!r}  # [ksi]",
            f"poisson_ratio = {float(m.poisson_ratio)!r}  # [-]",
            f"density = {float(m.density)!r}  # [kip*s^2/in^4]",
            "",
        ])

    def save(self, path):
        """Write :meth:`to_toml` to ``path`` atomically."""
        write_text(path, self.to_toml())


def geometry_from_dict(data):
    """Build a :class:`WallGeometry` from a dict shaped like the TOML file.

    ``data["wall"]`` holds the WallGeometry fields (except material); ``data["material"]`` either
    names a ``preset`` ("concrete" or "steel") or gives youngs_modulus, poisson_ratio and density
    (explicit values override the preset).
    """
    wall = dict(data.get("wall", {}))
    mat = dict(data.get("material", {}))
    unknown = set(data) - {"wall", "material"}
    if unknown:
        raise ValueError(f"unknown TOML table(s) {sorted(unknown)}: use [wall] and [material]")
    fields = {"height", "length", "thickness", "impact_height", "impact_patch", "base",
              "subgrade_modulus"}
    bad = set(wall) - fields
    if bad:
        raise ValueError(f"unknown [wall] key(s) {sorted(bad)}: allowed are {sorted(fields)}")
    missing = {"height", "length", "thickness", "impact_height", "impact_patch"} - set(wall)
    if missing:
        raise ValueError(f"[wall] is missing {sorted(missing)} (all lengths in inches)")
    preset = mat.pop("preset", None)
    bad = set(mat) - {"youngs_modulus", "poisson_ratio", "density", "name"}
    if bad:
        raise ValueError(f"unknown [material] key(s) {sorted(bad)}: use preset or youngs_modulus "
                         "[ksi], poisson_ratio, density [kip*s^2/in^4]")
    if preset is not None:
        if preset not in PRESETS:
            raise ValueError(f"[material] preset must be one of {sorted(PRESETS)}, got {preset!r}")
        material = replace(PRESETS[preset](), **mat)
    else:
        missing = {"youngs_modulus", "poisson_ratio", "density"} - set(mat)
        if missing:
            raise ValueError(f"[material] is missing {sorted(missing)}; or give preset = "
                             "\"concrete\" or \"steel\"")
        material = Material(**mat)
    return WallGeometry(material=material, **wall)


def load_geometry(path):
    """Read a wall geometry TOML file (see :meth:`WallGeometry.to_toml` for the format)."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"geometry file {path} does not exist")
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"geometry file {path} is not valid TOML: {err}") from None
    return geometry_from_dict(data)

