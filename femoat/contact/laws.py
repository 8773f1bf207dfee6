"""The five contact laws of the paper as small frozen objects (docs/paper.md §2).

======  ==============================  ===========================================
symbol  law                             damping parameter (from e unless calibrated)
======  ==============================  ===========================================
E       linear elastic                  none
V       Kelvin-Voigt (viscoelastic)     ξ_KV, dashpot c_eff = 2ξ_KV√(m_eff·k_eff)
J       Jankowski (nonlinear viscoel.)  ξ_J
H       Hertzdamp                       ξ_h
M       Muthukumar bilinear             loss factor λ = 0.4(1−e²) in k1, k2
======  ==============================  ===========================================

A law's ``damping`` is ``None`` for the paper's closed form from ``params.e``, or a number that
replaces it (what :func:`femoat.impact.calibration.calibrate` finds so that a simulated impact
reaches ``e`` exactly).
"""

import math
from dataclasses import dataclass, replace

import numpy as np

from femoat.contact import kernels
from femoat.contact.codes import H_DMAX, H_V0
from femoat.contact.damping import (
    muthukumar_loss_factor,
    muthukumar_stiffnesses,
    xi_hertzdamp,
    xi_jankowski,
    xi_kelvin_voigt,
)
from femoat.contact.hertzdamp import Hertzdamp
from femoat.contact.jankowski import Jankowski
from femoat.contact.kelvin_voigt import KelvinVoigt
from femoat.contact.linear import Linear
from femoat.contact.muthukumar import Muthukumar
from femoat.contact.parameters import ContactParameters

LAWS = {"E": Linear, "V": KelvinVoigt, "J": Jankowski, "H": Hertzdamp, "M": Muthukumar}
"""The law of each letter: a frozen dataclass of its kernel parameters (with units), in its own
module with its compiled kernels (dispatched by :mod:`femoat.contact.kernels`)."""
LAW_CODES = {kind: law.code for kind, law in LAWS.items()}
LAW_NAMES = {
    "E": "linear elastic",
    "V": "Kelvin-Voigt",
    "J": "Jankowski",
    "H": "Hertzdamp",
    "M": "Muthukumar bilinear",
}
DAMPING_NAMES = {"V": "xi_KV", "J": "xi_J", "H": "xi_h", "M": "loss_factor"}


@dataclass(frozen=True)
class ContactLaw:
    """One contact law with its parameters.

    Parameters
    ----------
    kind : str
        One of ``"E", "V", "J", "H", "M"``.
    params : ContactParameters
        The shared parameter set (k_h, m_eff, δ_me, e, a).
    damping : float or None
        Override of the damping parameter named in :data:`DAMPING_NAMES` (ξ_KV, ξ_J, ξ_h or, for
        M, the loss factor λ in [0, 1−a)) [-]; ``None`` uses the paper's closed form from e.
    allow_tension : bool
        Kelvin-Voigt only: keep contact (and pull) until δ = 0 instead of cutting the force at zero.
    v0_min : float
        Smallest approach velocity [in/s] Hertzdamp divides by; guards a gap closing at zero speed.
    """

    kind: str
    params: ContactParameters
    damping: float | None = None
    allow_tension: bool = False
    v0_min: float = 1e-3

    def __post_init__(self):
        if self.kind not in LAW_CODES:
            raise ValueError(
                f"law = {self.kind!r} is unknown: choose one of {', '.join(LAW_CODES)} "
                f"({', '.join(f'{k} = {v}' for k, v in LAW_NAMES.items())})."
            )
        if not isinstance(self.params, ContactParameters):
            raise ValueError("params must be a ContactParameters instance.")
        if self.damping is not None:
            if self.kind == "E":
                raise ValueError("damping: the linear elastic law (E) has no damping parameter.")
            ok = math.isfinite(self.damping) and self.damping >= 0
            if self.kind == "M":
                ok = ok and self.damping < 1 - self.params.a
            if not ok:
                rng = "in [0, 1 - a)" if self.kind == "M" else "a finite number >= 0"
                raise ValueError(
                    f"damping ({DAMPING_NAMES[self.kind]}) = {self.damping!r} must be {rng}."
                )
        if self.allow_tension and self.kind != "V":
            raise ValueError("allow_tension applies to the Kelvin-Voigt law (V) only.")
        if not (math.isfinite(self.v0_min) and self.v0_min > 0):
            raise ValueError(f"v0_min = {self.v0_min!r} must be a positive velocity [in/s].")
        if self.kind == "M":
            self.stiffnesses()  # raises if k2 <= 0

    @property
    def code(self):
        """Integer code used by the compiled kernels."""
        return LAW_CODES[self.kind]

    @property
    def name(self):
        return LAW_NAMES[self.kind]

    def damping_parameter(self):
        """The damping parameter in use (ξ_KV, ξ_J, ξ_h, or M's loss factor λ); None for E."""
        if self.kind == "E":
            return None
        if self.damping is not None:
            return self.damping
        e = self.params.e
        return {"V": xi_kelvin_voigt, "J": xi_jankowski, "H": xi_hertzdamp,
                "M": muthukumar_loss_factor}[self.kind](e)

    @property
    def c_eff(self):
        """Kelvin-Voigt dashpot 2ξ_KV√(m_eff·k_eff) [kip·s/in] (0 for other laws)."""
        if self.kind != "V":
            return 0.0
        pr = self.params
        return 2.0 * self.damping_parameter() * math.sqrt(pr.m_eff * pr.k_eff)

    def stiffnesses(self):
        """Muthukumar (k1, k2) [kip/in] for this law's loss factor."""
        pr = self.params
        return muthukumar_stiffnesses(pr.k_eff, pr.e, pr.a, loss=self.damping_parameter())

    def with_damping(self, value):
        """A copy with the damping parameter replaced (``None`` restores the closed form)."""
        return replace(self, damping=value)

    def resolved(self):
        """This law's kernel parameters (its damping resolved to numbers): a :class:`Linear`,
        :class:`KelvinVoigt`, :class:`Jankowski`, :class:`Hertzdamp` or :class:`Muthukumar`."""
        return LAWS[self.kind].from_law(self)

    def packed(self):
        """Float array of the parameters in the layout of the law's module (see
        :mod:`femoat.contact.kernels`)."""
        return self.resolved().params()

    def force(self, d, v, v0=None, delta_max=0.0):
        """Force [kip] and tangents at indentation d [in] and rate v [in/s] (for plots and tests).

        ``v0`` is Hertzdamp's approach velocity [in/s] (defaults to ``v``); ``delta_max`` the
        largest past indentation [in] for the bilinear law.
        """
        h = np.zeros(kernels.N_HISTORY)
        h[H_V0], h[H_DMAX] = v if v0 is None else v0, delta_max
        return kernels.contact_force(self.code, self.packed(), h, float(d), float(v))


def make_law(kind, params, **options):
    """Build a :class:`ContactLaw` from its letter (E, V, J, H, M) or its name."""
    key = str(kind).strip()
    by_name = {v.lower(): k for k, v in LAW_NAMES.items()}
    key = by_name.get(key.lower(), key.upper() if len(key) == 1 else key)
    return ContactLaw(key, params, **options)
