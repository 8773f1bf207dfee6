"""The paper's concrete and steel walls (Table 3, docs/paper.md §3).

C_imp is offered two ways (docs/paper.md §5.1):

* ``"published"`` (default, reproduces the paper's figures): the printed 3.3 and 5.1 kip·s/in,
  which equal 2·ξ_imp·√(K1·(M1·g)), i.e. the weight was used for the mass;
* ``"consistent"``: 2·ξ_imp·√(K1·M1) with the modal mass, 0.170 and 0.261 kip·s/in.
"""

import math
from dataclasses import dataclass

from femoat.contact.parameters import ContactParameters
from femoat.units import G
from femoat.walls.sdof import SdofWall

_TABLE3 = {
    # k_h [kip/in^1.5], m_eff·g [kip], K1 [kip/in], M1·g [kip], ξ_imp, published C_imp [kip·s/in]
    "concrete": dict(k_h=6700.0, w_eff=0.29, K1=2.4, W1=0.29, xi_imp=2.0, C_pub=3.3),
    "steel": dict(k_h=11000.0, w_eff=0.40, K1=100.0, W1=0.41, xi_imp=0.4, C_pub=5.1),
}
DAMPING_CHOICES = ("published", "consistent")


@dataclass(frozen=True)
class WallPreset:
    """A paper wall: its contact parameters and its SDOF wall."""

    name: str
    contact: ContactParameters
    wall: SdofWall
    xi_imp: float

    @property
    def damping(self):
        return self.wall.damping_source


def wall_preset(name, damping="published", e=0.70, a=0.10, delta_me=0.025):
    """The ``"concrete"`` or ``"steel"`` wall of the paper's Table 3.

    Parameters
    ----------
    name : str
        "concrete" or "steel".
    damping : str
        "published" (C_imp as printed) or "consistent" (2·ξ_imp·√(K1·M1)).
    e, a, delta_me : float
        Restitution [-], yield-indentation ratio [-] and maximum expected indentation [in].
    """
    key = str(name).lower()
    if key not in _TABLE3:
        raise ValueError(f"wall = {name!r} is unknown: choose one of {', '.join(_TABLE3)}.")
    if damping not in DAMPING_CHOICES:
        raise ValueError(
            f"damping = {damping!r} is unknown: choose 'published' (C_imp as printed in Table 3) "
            "or 'consistent' (2·xi_imp·sqrt(K1·M1))."
        )
    row = _TABLE3[key]
    m1 = row["W1"] / G
    if damping == "published":
        c = row["C_pub"]
    else:
        c = 2.0 * row["xi_imp"] * math.sqrt(row["K1"] * m1)
    contact = ContactParameters.from_weight(row["k_h"], row["w_eff"], delta_me, e, a)
    wall = SdofWall(stiffness=row["K1"], mass=m1, damping=c, damping_source=damping)
    return WallPreset(name=key, contact=contact, wall=wall, xi_imp=row["xi_imp"])


PRESETS = tuple(_TABLE3)
