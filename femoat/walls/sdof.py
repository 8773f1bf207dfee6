"""The SDOF wall of the Masroor impact element: mass M1, spring K1 and dashpot C_imp."""

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class SdofWall:
    """A moat wall idealized by its first mode, in series behind the contact spring.

    Parameters
    ----------
    stiffness : float
        K1, first modal stiffness [kip/in], > 0.
    mass : float
        M1, first modal mass [kip·s²/in], > 0.
    damping : float
        C_imp, impact dashpot [kip·s/in], >= 0.
    damping_source : str
        How ``damping`` was obtained ("published", "consistent" or "user"); reported with results.
    """

    stiffness: float
    mass: float
    damping: float
    damping_source: str = "user"

    def __post_init__(self):
        for name, value, low in (("stiffness (K1)", self.stiffness, 0.0),
                                 ("mass (M1)", self.mass, 0.0)):
            if not (math.isfinite(value) and value > low):
                raise ValueError(f"{name} = {value!r} must be a positive finite number.")
        if not (math.isfinite(self.damping) and self.damping >= 0):
            raise ValueError(f"damping (C_imp) = {self.damping!r} must be >= 0 [kip·s/in].")

    @property
    def omega(self):
        """Natural circular frequency √(K1/M1) [rad/s]."""
        return math.sqrt(self.stiffness / self.mass)

    @property
    def period(self):
        """Natural period 2π/ω [s]."""
        return 2.0 * math.pi / self.omega

    @property
    def damping_ratio(self):
        """ξ = C_imp / (2√(K1·M1)) [-]."""
        return self.damping / (2.0 * math.sqrt(self.stiffness * self.mass))
