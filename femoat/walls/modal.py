"""A modal wall: N modes of a finite-element wall coupled at the impact point.

Units kip, in, s. Each mode ψ_i is normalised to unit displacement at the impact point
(``impact_shape`` = 1), so the impact-point displacement is w = Σ q_i and mode i obeys

    m_i·q̈_i + c_i·q̇_i + k_i·q_i = F − L_i·ü_g,

with F the contact force (positive pushing the wall away from the building), m_i = ψ_iᵀMψ_i,
k_i = ω_i²·m_i, L_i = ψ_iᵀ·M·ι the ground participation, and q_i relative to the ground. One mode
with L_1 = M1 is the paper's SDOF wall (M1, K1, C_imp); :func:`femoat.structure.pounding.wall_modes`
reads these arrays, so a ModalWall goes wherever an :class:`~femoat.walls.sdof.SdofWall` goes.

How many modes. The impact-point static flexibility is Σ_all 1/k_i (the spectral expansion of
cᵀK⁻¹c); the first N modes capture the fraction Σ_{i≤N} 1/k_i / cᵀK⁻¹c. Without ``n_modes``,
:meth:`ModalWall.from_fe` keeps the fewest modes that reach ``flexibility_target`` and, when a
contact time t_c is given, also every mode with frequency up to ``4/t_c`` (a force pulse of
length t_c has little content above 2/t_c; twice that is the margin). The flexibility alone is
not enough for impacts: it is a static measure, and a 2-3 ms contact on the paper's concrete wall
needs its modes up to ~1.5 kHz (8 beam modes) for 1 % where 99 % of the flexibility is in 2
modes. The right t_c is the contact's shortest time scale, :func:`contact_time`: the half period
π√(m_r/k_eff) of the impacting mass and the wall's first modal mass (reduced mass m_r) on the
law's linearised stiffness; a heavy base mat stays in contact for many such periods, but its
force history still oscillates at this rate. Modes that do not move the impact point (torsion of
a symmetric wall) are never kept.

The modes left out. Above the cut-off the modes respond quasi-statically, but together they are
a spring: the impact flexibility r_N they carry sits in series with the contact, and with
k_eff·r_N ≈ 0.08 (3D solid wall at its automatic N = 36) dropping it errs by 1.7 % in the force
history. By default (``residual=True``) :meth:`ModalWall.from_fe` adds it back as one more
oscillator, the residual-flexibility vector of
:func:`femoat.walls.fe.modal.residual_mode` (modal truncation augmentation): stiffness 1/r_N, the
mass of the static residual shape, M- and K-orthogonal to the kept modes. The static impact
flexibility is then exact (``flexibility_fraction`` = 1) and the solid wall's history error at
N = 36 falls to 0.7 %. It is the last mode, ``mode_numbers`` −1.

Damping: C_imp onto the modes. femoat gives every mode the same damping ratio ξ,
c_i = 2ξ·√(k_i·m_i) (``damping_ratio``); with ξ = ξ_imp = C_imp/(2√(K1·M1)) mode 1 has exactly
the SDOF wall's dashpot C_imp. Why not stiffness-proportional damping (c_i = (C_imp/K1)·k_i,
i.e. C = βK with β = C_imp/K1)? ξ_imp is a ratio (Table 3 prints 200 % and 40 %), and
stiffness-proportional damping multiplies it by ω_i/ω_1: for the concrete wall (9, 56, 155 Hz)
ξ_imp = 200 % becomes 1240 % and 3450 % in modes 2 and 3, which locks exactly the modes the
modal wall is meant to add (an overdamped mode barely moves in a 2 ms contact) and makes the
equations stiff (fast roots ≈ β·ω_i², which average-acceleration Newmark does not damp).
Rayleigh damping (c_i = α·m_i + β·k_i, ``rayleigh=(α, β)``) is offered for comparison with a
finite-element model damped by C = αM + βK (see :mod:`femoat.walls.fe.transient`).
"""

import math
from dataclasses import dataclass, field, replace

import numpy as np

from femoat.walls.reduction import CUTOFF_FACTOR  # noqa: F401  (its home before)


def _array(name, value, unit, positive):
    a = np.array(value, dtype=float).reshape(-1)
    if a.size == 0:
        raise ValueError(f"ModalWall.{name} is empty: give one value per mode [{unit}]")
    ok = a > 0 if positive else a >= 0
    if not (np.all(np.isfinite(a)) and np.all(ok)):
        rel = "> 0" if positive else ">= 0"
        raise ValueError(f"ModalWall.{name} = {a.tolist()} must be finite and {rel} [{unit}]")
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class ModalWall:
    """N wall modes coupled at the impact point (see the module docstring for the equations).

    Parameters
    ----------
    modal_masses : array  m_i [kip·s²/in], > 0
    modal_stiffnesses : array  k_i [kip/in], > 0
    modal_dampings : array  c_i [kip·s/in], >= 0
    impact_shape : array  φ_i, mode displacement at the impact point [in/in] (1 for modes
        normalised to unit impact displacement)
    ground_participation : array  L_i = ψ_iᵀ·M·ι [kip·s²/in] (the load of a unit ground
        acceleration is −L_i·ü_g)
    frequencies : array  undamped frequencies √(k_i/m_i)/2π [Hz]; computed when omitted
    source : str  where the modes came from (model, mode numbers, how N was chosen)
    damping_source : str  how the dashpots were set (reported with building results)
    mode_numbers : array[int] or None  indices of the modes in the finite-element modal result
    shapes : array (n_dofs, N) or None  the finite-element shapes ψ_i [in/in] (for renders)
    flexibility_fraction : float or None  Σ φ_i²/k_i over the static impact flexibility [-]
    residual : bool  the last mode is a residual-flexibility vector, not an eigenmode (it
        completes the impact flexibility of the modes before it)
    """

    modal_masses: np.ndarray
    modal_stiffnesses: np.ndarray
    modal_dampings: np.ndarray
    impact_shape: np.ndarray
    ground_participation: np.ndarray
    frequencies: np.ndarray | None = None
    source: str = "user"
    damping_source: str = "user"
    mode_numbers: np.ndarray | None = field(default=None, repr=False)
    shapes: np.ndarray | None = field(default=None, repr=False)
    flexibility_fraction: float | None = None
    residual: bool = False

    def __post_init__(self):
        units = {"modal_masses": "kip·s²/in", "modal_stiffnesses": "kip/in",
                 "modal_dampings": "kip·s/in"}
        for name, unit in units.items():
            object.__setattr__(self, name, _array(name, getattr(self, name), unit,
                                                  name != "modal_dampings"))
        n = self.modal_masses.size
        for name in ("impact_shape", "ground_participation"):
            a = np.array(getattr(self, name), dtype=float).reshape(-1)
            if not np.all(np.isfinite(a)):
                raise ValueError(f"ModalWall.{name} must be finite")
            a.flags.writeable = False
            object.__setattr__(self, name, a)
        for name in ("modal_stiffnesses", "modal_dampings", "impact_shape", "ground_participation"):
            if getattr(self, name).size != n:
                raise ValueError(f"ModalWall.{name} has {getattr(self, name).size} values for "
                                 f"{n} modal masses: give one value per mode")
        if not np.all(self.impact_shape != 0):
            raise ValueError("ModalWall.impact_shape has a zero: a mode that does not move the "
                             "impact point cannot be hit; drop it")
        f = np.sqrt(self.modal_stiffnesses / self.modal_masses) / (2 * np.pi)
        if self.frequencies is None:
            object.__setattr__(self, "frequencies", f)
        else:
            given = np.array(self.frequencies, dtype=float).reshape(-1)
            if given.shape != f.shape or not np.allclose(given, f, rtol=1e-6):
                raise ValueError("ModalWall.frequencies disagree with √(k_i/m_i)/2π: omit them "
                                 "to have them computed")
            object.__setattr__(self, "frequencies", given)
        self.frequencies.flags.writeable = False

    # ---- derived -----------------------------------------------------------------------
    @property
    def n_modes(self):
        return int(self.modal_masses.size)

    @property
    def angular_frequencies(self):
        """ω_i [rad/s]."""
        return 2 * np.pi * self.frequencies

    @property
    def periods(self):
        """T_i = 1/f_i [s]."""
        return 1.0 / self.frequencies

    @property
    def damping_ratios(self):
        """ξ_i = c_i / (2√(k_i·m_i)) [-]."""
        return self.modal_dampings / (2 * np.sqrt(self.modal_stiffnesses * self.modal_masses))

    @property
    def flexibility(self):
        """Impact-point static flexibility of the retained modes Σ φ_i²/k_i [in/kip]."""
        return float(np.sum(self.impact_shape**2 / self.modal_stiffnesses))

    @property
    def stiffness(self):
        """Impact-point static stiffness of the retained modes [kip/in]."""
        return 1.0 / self.flexibility

    def truncated(self, n):
        """The first ``n`` modes as a new ModalWall.

        A residual-flexibility vector completes the flexibility of exactly the modes before it,
        so it is kept only when all of them are (``n`` = n_modes); otherwise it is dropped.
        """
        if int(n) != n or not 1 <= n <= self.n_modes:
            raise ValueError(f"n = {n!r} must be an integer in [1, {self.n_modes}] (this wall's "
                             "modes)")
        n = int(n)
        if n == self.n_modes:
            return self
        if self.residual:
            n = min(n, self.n_modes - 1)
        def cut(a):
            return None if a is None else a[..., :n]

        return replace(self, modal_masses=self.modal_masses[:n],
                       modal_stiffnesses=self.modal_stiffnesses[:n],
                       modal_dampings=self.modal_dampings[:n], impact_shape=self.impact_shape[:n],
                       ground_participation=self.ground_participation[:n],
                       frequencies=self.frequencies[:n], mode_numbers=cut(self.mode_numbers),
                       shapes=cut(self.shapes), flexibility_fraction=None, residual=False,
                       source=f"{self.source}; first {n} modes")

    # ---- constructors ------------------------------------------------------------------
    @classmethod
    def from_sdof(cls, wall):
        """The paper's SDOF wall as a one-mode ModalWall (L_1 = M1, as the SDOF mass feels the
        ground acceleration in the building model)."""
        from femoat.walls.sdof import SdofWall

        if not isinstance(wall, SdofWall):
            raise ValueError("wall must be an SdofWall (femoat.walls.SdofWall)")
        return cls([wall.mass], [wall.stiffness], [wall.damping], [1.0], [wall.mass],
                   source="SDOF wall", damping_source=wall.damping_source)

    @classmethod
    def from_fe(cls, source, n_modes=None, flexibility_target=0.99, contact_duration=None,
                damping_ratio=0.0, rayleigh=None, computed_modes=None, residual=True):
        """Modal wall from a finite-element wall.

        Parameters
        ----------
        source : WallModel or ModalResult
            The wall model (its modes are computed here) or a modal analysis of it.
        n_modes : int or None
            Number N of impact modes to keep; ``None`` chooses N from the targets below.
        flexibility_target : float
            Fraction of the impact-point static flexibility the kept modes must capture, in
            (0, 1) [-] (used when ``n_modes`` is None).
        contact_duration : float, callable or None
            Contact time scale t_c [s], e.g. :func:`contact_time`; with ``n_modes`` None, also
            keep every mode up to CUTOFF_FACTOR/t_c [Hz]. A callable gets the wall's modal
            analysis and returns t_c (e.g. from its M1), so the modes are solved once.
        damping_ratio : float
            ξ [-] of every mode: c_i = 2ξ·√(k_i·m_i). Use the SDOF wall's
            ``damping_ratio`` (ξ_imp = C_imp/(2√(K1·M1))) to carry C_imp over.
        rayleigh : (float, float) or None
            (α [1/s], β [s]): c_i = α·m_i + β·k_i instead of ``damping_ratio``.
        computed_modes : int or None
            Modes to compute from a WallModel (default: enough for the targets, doubling from 12).
        residual : bool
            Add the residual-flexibility vector of the modes left out as one more mode (see the
            module docstring); needs a ModalResult from ``modal_analysis`` (it carries K⁻¹c).
        """
        from femoat.walls.reduction import reduce_fe_wall

        return cls(**reduce_fe_wall(source, n_modes, flexibility_target, contact_duration,
                                    damping_ratio, rayleigh, computed_modes, residual))

def contact_time(law, mass=None, wall_mass=None):
    """The contact's shortest time scale π·√(m_r/k_eff) [s], for choosing the modes.

    law : ContactLaw  (its k_eff = k_h·√δ_me [kip/in] is the linearised contact stiffness)
    mass : float or None  impacting mass [kip·s²/in]; default the law's m_eff
    wall_mass : float or None  the wall's first modal mass M1 [kip·s²/in] (e.g. ModalResult.M1,
        or ``ModalWall.modal_masses[0]``); None for a rigid stop
    m_r = m·M1/(m + M1) is the reduced mass of the two bodies the contact spring sits between.
    """
    from femoat.contact.laws import ContactLaw

    if not isinstance(law, ContactLaw):
        raise ValueError("law must be a ContactLaw (see femoat.contact.make_law)")
    m = law.params.m_eff if mass is None else mass
    for name, value in (("mass", m), ("wall_mass", 1.0 if wall_mass is None else wall_mass)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r} must be a positive mass [kip·s²/in]")
    m_r = m if wall_mass is None else m * wall_mass / (m + wall_mass)
    return math.pi * math.sqrt(m_r / law.params.k_eff)

