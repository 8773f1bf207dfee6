"""Modal analysis of a wall model and its reduction to the paper's SDOF (K1, M1).

Units: frequencies [Hz], angular frequencies [rad/s], masses [kip·s²/in], stiffnesses [kip/in],
flexibilities [in/kip]. Mode shapes are stored mass-normalised (φᵀMφ = 1) as full DOF vectors
(zero at the supports). The impact participation of mode i is p_i = cᵀφ_i, with c the model's
impact interpolation vector; mode i normalised to unit impact displacement, ψ_i = φ_i/p_i, has
modal mass m_i = ψ_iᵀMψ_i = 1/p_i² and modal stiffness k_i = ω_i²·m_i. The paper's SDOF wall is
the fundamental impact mode: M1 = m_1, K1 = k_1.
"""

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
import scipy.sparse.linalg as sla

from femoat.units import G

NEGLIGIBLE = 1e-6
"""A mode whose |p_i| is below this fraction of the largest |p| does not move the impact point
(an antisymmetric or torsional mode of a symmetric wall: zero up to round-off)."""


@dataclass(frozen=True, eq=False)
class ModalResult:
    """Modes of a wall and the SDOF idealisation of its fundamental impact mode.

    kind : str  the name of the wall kind (:mod:`femoat.walls.kinds`)
    frequencies : ndarray  [Hz], ascending
    angular_frequencies : ndarray  [rad/s]
    shapes : ndarray (n_dofs, n_modes)  mass-normalised mode shapes [in/√(kip·s²/in)]
    impact_participation : ndarray  p_i = cᵀφ_i [1/√(kip·s²/in)]
    participation_factors : ndarray  Γ_i = φ_iᵀ·(M·r)_free for a horizontal ground motion, r
        the rigid-body influence vector on all DOFs (supports included: with a consistent mass
        the moving base also drags the free DOFs) [√(kip·s²/in)]
    effective_masses : ndarray  Γ_i² [kip·s²/in]
    total_mass : float  rᵀMr over all DOFs, the wall's translating mass [kip·s²/in]; the
        effective masses of all modes add up to the part not carried by the supports
    static_flexibility : float  impact displacement per unit impact force cᵀK⁻¹c [in/kip]
    static_stiffness : float  its inverse [kip/in]
    sdof_mode : int  index of the fundamental impact mode (the lowest mode with p ≠ 0)
    K1 : float  modal stiffness of that mode at unit impact displacement [kip/in]
    M1 : float  its modal mass [kip·s²/in]
    static_shape : ndarray or None  the static deflection under a unit impact force, K⁻¹c, as a
        full DOF vector [in/kip] (for the residual-flexibility vector, :func:`residual_mode`)
    model : WallModel or None  the model the modes belong to (its mass matrix is needed by
        :func:`residual_mode`)
    """

    kind: str
    frequencies: np.ndarray
    angular_frequencies: np.ndarray
    shapes: np.ndarray
    impact_participation: np.ndarray
    participation_factors: np.ndarray
    effective_masses: np.ndarray
    total_mass: float
    static_flexibility: float
    static_stiffness: float
    sdof_mode: int
    K1: float
    M1: float
    static_shape: np.ndarray | None = field(default=None, repr=False)
    model: object = field(default=None, repr=False)

    @property
    def modal_weight(self):
        """M1·g [kip], the paper's 'modal weight'."""
        return self.M1 * G


@dataclass(frozen=True, eq=False)
class ImpactModes:
    """The first modes that move the impact point, each normalised to unit impact displacement.

    A modal wall in the solver is a set of uncoupled oscillators driven by the impact force F
    (positive pushing the wall toward the backfill) and the ground acceleration ü_g:
    u_impact = Σ q_i,  m_i·q̈_i + k_i·q_i = F − L_i·ü_g  (q_i relative to the ground).

    mode_numbers : ndarray[int]  indices into the ModalResult modes
    frequencies : ndarray  [Hz]
    modal_masses : ndarray  m_i = 1/p_i² [kip·s²/in]
    modal_stiffnesses : ndarray  k_i = ω_i²·m_i [kip/in]
    impact_participation : ndarray  p_i of the mass-normalised modes [1/√(kip·s²/in)]
    ground_factors : ndarray  L_i = ψ_iᵀ·M·r = Γ_i/p_i [kip·s²/in]
    shapes : ndarray (n_dofs, n)  ψ_i = φ_i/p_i, unit displacement at the impact point [in/in]
    flexibility_fraction : float  Σ 1/k_i over these modes / static flexibility [-]
    """

    mode_numbers: np.ndarray
    frequencies: np.ndarray
    modal_masses: np.ndarray
    modal_stiffnesses: np.ndarray
    impact_participation: np.ndarray
    ground_factors: np.ndarray
    shapes: np.ndarray
    flexibility_fraction: float


def _reduced(model):
    free = model.free
    K = model.stiffness[free][:, free].tocsc()
    M = model.mass[free][:, free].tocsc()
    return free, K, M


def _factor(K):
    try:
        # A symmetric ordering: 30-50 % less fill than COLAMD on these meshes.
        return sla.splu(K, permc_spec="MMD_AT_PLUS_A")
    except RuntimeError as err:
        raise ValueError(f"the wall stiffness matrix is singular ({err}): the supports do not "
                         "hold the wall; use base='fixed' or add a backfill") from None


def static_stiffness(model):
    """Force per unit impact-point displacement under a static impact load [kip/in]."""
    free, K, _ = _reduced(model)
    c = model.impact[free]
    return 1.0 / (c @ _factor(K).solve(c))


def modal_analysis(model, n_modes=6):
    """The lowest ``n_modes`` modes (eigsh, shift-invert about σ = 0) and the SDOF wall.

    model : WallModel
    n_modes : int  number of modes (all of them if the model has fewer DOFs)
    """
    if int(n_modes) != n_modes or n_modes < 1:
        raise ValueError(f"n_modes must be a positive integer, got {n_modes!r}")
    free, K, M = _reduced(model)
    n_free = len(free)
    lu = _factor(K)
    if n_modes >= n_free - 1:
        lam, phi = scipy.linalg.eigh(K.toarray(), M.toarray())
        lam, phi = lam[:n_modes], phi[:, :n_modes]
    else:
        op = sla.LinearOperator(K.shape, matvec=lu.solve, dtype=float)
        # ARPACK's own random start continues one generator through the process, so the modes
        # would differ in their last bits with the calls made before; a fixed start (random,
        # so that no symmetry hides a mode from it) makes them the same bits in every process
        v0 = np.random.default_rng(0).standard_normal(K.shape[0])
        lam, phi = sla.eigsh(K, k=int(n_modes), M=M, sigma=0.0, which="LM", OPinv=op, v0=v0)
    order = np.argsort(lam)
    lam, phi = lam[order], phi[:, order]
    if lam[0] <= 0:
        raise ValueError(f"non-positive eigenvalue {lam[0]:.3g}: the wall is not stable on its "
                         "supports; use base='fixed' or add a backfill")
    phi = phi / np.sqrt(np.einsum("im,im->m", phi, M @ phi))
    c = model.impact[free]
    mass_r = model.mass @ model.ground
    p = c @ phi
    big = np.abs(p) > NEGLIGIBLE * np.abs(p).max()
    # Sign: unit impact displacement positive; other modes: largest component positive.
    sign = np.where(big, np.sign(p), np.sign(phi[np.abs(phi).argmax(axis=0), np.arange(phi.shape[1])]))
    phi, p = phi * sign, p * sign
    gamma = phi.T @ mass_r[free]
    static = lu.solve(c)
    flex = c @ static
    omega = np.sqrt(lam)
    if not big.any():
        raise ValueError("no computed mode moves the impact point; raise n_modes")
    first = int(np.argmax(big))
    shapes = np.zeros((model.n_dofs, phi.shape[1]))
    shapes[free] = phi
    return ModalResult(
        kind=model.kind,
        frequencies=omega / (2 * np.pi),
        angular_frequencies=omega,
        shapes=shapes,
        impact_participation=p,
        participation_factors=gamma,
        effective_masses=gamma**2,
        total_mass=float(model.ground @ mass_r),
        static_flexibility=float(flex),
        static_stiffness=float(1.0 / flex),
        sdof_mode=first,
        K1=float(lam[first] / p[first] ** 2),
        M1=float(1.0 / p[first] ** 2),
        static_shape=_full(model, free, static),
        model=model,
    )


def _full(model, free, values):
    out = np.zeros(model.n_dofs)
    out[free] = values
    return out


def flexibility_fraction(result, n):
    """Share of the static impact flexibility captured by the first ``n`` modes [-].

    Σ_{i<n} p_i²/ω_i² / cᵀK⁻¹c; it tends to 1 as n grows to all modes (spectral expansion of K⁻¹).
    """
    if not 1 <= n <= len(result.frequencies):
        raise ValueError(f"n must be in [1, {len(result.frequencies)}] (the modes computed), got {n}")
    p, w = result.impact_participation[:n], result.angular_frequencies[:n]
    return float(np.sum(p**2 / w**2) / result.static_flexibility)


def impact_modes(result, n=None):
    """The modes among the first ``n`` (default: all computed) that move the impact point."""
    n = len(result.frequencies) if n is None else n
    frac = flexibility_fraction(result, n)
    p = result.impact_participation[:n]
    keep = np.nonzero(np.abs(p) > NEGLIGIBLE * np.abs(result.impact_participation).max())[0]
    m = 1.0 / p[keep] ** 2
    return ImpactModes(
        mode_numbers=keep,
        frequencies=result.frequencies[keep],
        modal_masses=m,
        modal_stiffnesses=result.angular_frequencies[keep] ** 2 * m,
        impact_participation=p[keep],
        ground_factors=result.participation_factors[keep] / p[keep],
        shapes=result.shapes[:, keep] / p[keep],
        flexibility_fraction=frac,
    )


def modes_for_flexibility(result, target):
    """Smallest number of modes whose flexibility fraction reaches ``target`` (0 < target < 1)."""
    if not 0 < target < 1:
        raise ValueError(f"target flexibility fraction must be in (0, 1), got {target!r}")
    p, w = result.impact_participation, result.angular_frequencies
    cumulative = np.cumsum(p**2 / w**2) / result.static_flexibility
    reached = np.nonzero(cumulative >= target)[0]
    if len(reached) == 0:
        raise ValueError(f"the {len(p)} computed modes capture only {cumulative[-1]:.4f} of the "
                         f"impact flexibility (< {target}): run modal_analysis with more n_modes")
    return int(reached[0]) + 1


@dataclass(frozen=True, eq=False)
class ResidualMode:
    """The static part of the modes left out, as one more (Ritz) mode at the impact point.

    shape : ndarray (n_dofs,)  ψ_r, normalised to unit impact displacement [in/in]
    modal_mass : float  m_r = ψ_rᵀMψ_r [kip·s²/in]
    modal_stiffness : float  k_r = ψ_rᵀKψ_r = 1/r_N [kip/in]
    ground_factor : float  L_r = ψ_rᵀ·M·r [kip·s²/in]
    frequency : float  its Rayleigh-quotient frequency √(k_r/m_r)/2π [Hz]
    flexibility : float  r_N, the impact flexibility the kept modes miss [in/kip]
    """

    shape: np.ndarray
    modal_mass: float
    modal_stiffness: float
    ground_factor: float
    frequency: float
    flexibility: float


def residual_mode(result, kept):
    """The residual-flexibility vector of the modes ``kept`` (modal truncation augmentation).

    A modal wall of N modes misses the impact flexibility r_N = cᵀK⁻¹c − Σ_{i≤N} p_i²/ω_i² of
    the modes above them. Those modes respond quasi-statically to a contact force that is slow
    for them, so their sum is the static deflection x_r = K⁻¹c − Σ_{i≤N} φ_i·p_i/ω_i² (Dickens,
    Nakagawa & Wittbrodt 1997, "A critique of mode acceleration and modal truncation
    augmentation methods"). x_r is M- and K-orthogonal to every kept mode (φ_iᵀMK⁻¹c = p_i/ω_i²
    and φ_iᵀc = p_i), so it is one more uncoupled oscillator; normalised to unit impact
    displacement it has stiffness 1/r_N, and the N + 1 oscillators reproduce the full static
    impact flexibility exactly. Returns None when nothing is missing (all modes kept, r_N ≤ 1e-12
    of the static flexibility).

    result : ModalResult  from :func:`modal_analysis` (carries K⁻¹c and the model)
    kept : sequence[int]  indices of the kept modes in ``result``
    """
    if result.static_shape is None or result.model is None:
        raise ValueError("this ModalResult carries no static deflection and model (built by "
                         "hand?): run femoat.walls.fe.modal_analysis on the WallModel")
    kept = np.asarray(kept, dtype=int)
    model = result.model
    free = model.free
    lam = result.angular_frequencies[kept] ** 2
    p = result.impact_participation[kept]
    x = result.static_shape[free] - result.shapes[free][:, kept] @ (p / lam)
    c = model.impact[free]
    r = float(c @ x)
    if r <= 1e-12 * result.static_flexibility:
        return None
    psi = x / r
    M = model.mass[free][:, free]
    m = float(psi @ (M @ psi))
    ground = float(psi @ (model.mass @ model.ground)[free])
    return ResidualMode(shape=_full(model, free, psi), modal_mass=m, modal_stiffness=1.0 / r,
                        ground_factor=ground, frequency=float(np.sqrt(1.0 / (r * m)) / (2 * np.pi)),
                        flexibility=r)
