"""The parameter set shared by all five contact laws (docs/paper.md §2, the paper's Table 2).

Sign convention: indentation δ [in] is positive in contact; δ̇ [in/s] is positive while the two
bodies approach. Contact forces are compressive and reported positive [kip].
"""

import math
from dataclasses import dataclass

from femoat.units import G


def _require(name, value, ok, accepted):
    if not (isinstance(value, (int, float)) and math.isfinite(value) and ok(value)):
        raise ValueError(f"{name} = {value!r} is invalid: {name} must be {accepted}.")


@dataclass(frozen=True)
class ContactParameters:
    """Parameters of a contact between the base mat and a moat wall.

    Parameters
    ----------
    k_h : float
        Hertz contact stiffness [kip/in^1.5], > 0.
    m_eff : float
        Effective mass of the impact [kip·s²/in], > 0. Use :meth:`from_weight` to give a weight.
    delta_me : float
        Maximum expected indentation δ_me [in], > 0; sets k_eff = k_h·√δ_me.
    e : float
        Target coefficient of restitution, in (0, 1].
    a : float
        Yield-indentation ratio of the Muthukumar bilinear law, in (0, 1): δ_y = a·δ_me.
    """

    k_h: float
    m_eff: float
    delta_me: float
    e: float
    a: float = 0.1

    def __post_init__(self):
        _require("k_h", self.k_h, lambda x: x > 0, "a positive stiffness [kip/in^1.5]")
        _require("m_eff", self.m_eff, lambda x: x > 0, "a positive mass [kip·s²/in] (weight/g)")
        _require("delta_me", self.delta_me, lambda x: x > 0, "a positive indentation [in]")
        _require("e", self.e, lambda x: 0 < x <= 1, "in (0, 1] (coefficient of restitution)")
        _require("a", self.a, lambda x: 0 < x < 1, "in (0, 1) (yield-indentation ratio)")

    @classmethod
    def from_weight(cls, k_h, w_eff, delta_me, e, a=0.1):
        """Build from the effective weight ``w_eff`` = m_eff·g [kip] as the paper tabulates it."""
        _require("w_eff", w_eff, lambda x: x > 0, "a positive weight [kip]")
        return cls(k_h=k_h, m_eff=w_eff / G, delta_me=delta_me, e=e, a=a)

    @property
    def k_eff(self):
        """Effective linear stiffness k_h·√δ_me [kip/in]."""
        return self.k_h * math.sqrt(self.delta_me)

    @property
    def delta_y(self):
        """Yield indentation of the bilinear law a·δ_me [in]."""
        return self.a * self.delta_me
