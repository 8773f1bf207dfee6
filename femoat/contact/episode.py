"""The result of one simulated contact episode, shared by the single-impact solvers
(:mod:`femoat.impact.single` for rigid, SDOF and modal walls; :mod:`femoat.walls.fe.transient`
for a finite-element wall)."""

from dataclasses import dataclass, field

import numpy as np


class ContactDidNotEndError(RuntimeError):
    """The contact did not end within the simulated time."""


@dataclass(frozen=True)
class ImpactResult:
    """One contact episode. Units in brackets; histories sampled densely over the contact.

    Attributes
    ----------
    law : str                    contact law letter
    target : str                 "rigid", "sdof" or "modal"
    v0 : float                   impact speed [in/s]
    peak_force : float           largest contact force [kip]
    max_indentation : float      largest indentation δ [in]
    contact_duration : float     time from closure to separation [s]
    restitution : float          −(mass velocity at separation)/v0 [-]
    dissipated_energy : float    energy lost in the contact spring, ∫f·δ̇ dt [kip·in]
    wall_dissipated_energy : float  energy lost in the wall dashpot(s) [kip·in]
    wall_energy : float          kinetic + strain energy of the wall at separation [kip·in]
    peak_wall_displacement : float  largest wall displacement at the impact point during
                                 contact [in]
    energy_residual : float      |energy in − energy accounted| / energy in [-]
    damping : float or None      damping parameter used (ξ_KV, ξ_J, ξ_h or M's design e)
    time, indentation, indentation_rate, force, wall_displacement : arrays [s, in, in/s, kip, in]
    modal_displacement : array (n_samples, N) or None  modal coordinates q_i [in] of a modal wall
    """

    law: str
    target: str
    v0: float
    peak_force: float
    max_indentation: float
    contact_duration: float
    restitution: float
    dissipated_energy: float
    wall_dissipated_energy: float
    wall_energy: float
    peak_wall_displacement: float
    energy_residual: float
    damping: float | None
    time: np.ndarray = field(repr=False)
    indentation: np.ndarray = field(repr=False)
    indentation_rate: np.ndarray = field(repr=False)
    force: np.ndarray = field(repr=False)
    wall_displacement: np.ndarray = field(repr=False)
    modal_displacement: np.ndarray | None = field(default=None, repr=False)

    def summary(self):
        """The scalar results as a JSON-ready dict (stable keys, units in the docstring)."""
        return {
            "law": self.law,
            "target": self.target,
            "v0": self.v0,
            "peak_force": self.peak_force,
            "max_indentation": self.max_indentation,
            "contact_duration": self.contact_duration,
            "restitution": self.restitution,
            "dissipated_energy": self.dissipated_energy,
            "wall_dissipated_energy": self.wall_dissipated_energy,
            "wall_energy": self.wall_energy,
            "peak_wall_displacement": self.peak_wall_displacement,
            "energy_residual": self.energy_residual,
            "damping_parameter": self.damping,
        }
