"""Modified Ibarra-Medina-Krawinkler (IMK) bilinear model with capping and cyclic deterioration.

The rules are those of OpenSees ``Bilin`` (Lignos & Krawinkler, 2011; Ibarra, Medina &
Krawinkler, 2005), written afresh for a translational spring (deformations in [in], forces in
[kip]); see the "Differences from OpenSees Bilin" list at the end.

Backbone (the same on both sides; u_y = My/K0):

* elastic, stiffness K0, up to (u_y, My);
* strain hardening, slope as·K0, up to the capping point u_cap = u_y + θp, f_cap = My + as·K0·θp;
* post-capping, slope K_pc = −f_cap/θpc (θpc is the deformation from the capping point to zero
  force along this slope);
* residual plateau Res·My;
* fracture at |u| ≥ θu: the force is zero from then on, in both directions.

Hysteresis: the force is the elastic predictor f_n + K0·(u − u_n) from the committed point
(u_n, f_n), clipped by the current backbone of the side the deformation is moving towards. The
hardening branches are fixed lines that extend across the origin (kinematic hardening, like
Steel01): without capping and deterioration the model is exactly the bilinear kinematic spring.
The unloading stiffness stays K0 (no unloading-stiffness deterioration).

Cyclic deterioration (energy based). Each time the force changes sign after the spring has been
on its backbone, the energy dissipated since the previous such event, E_i, sets

    β_i = (E_i / (E_t − ΣE))^c,  E_t = Λ·My,  (β_i = 1 once ΣE ≥ E_t)

and the side now being loaded deteriorates: its yield force and hardening ratio by (1 − β_i·D),
the intercept of its post-capping line (the line's force at u = 0) by (1 − β_i·D); its
post-capping slope is rescaled to K_pc·(fy − Res·My)/(My − Res·My) and its capping point moves to
where the new hardening line meets the post-capping line of the original slope. When the yield
force falls to Res·My that side becomes perfectly plastic at Res·My for good (the other side
keeps deteriorating).
Λ = math.inf switches deterioration off.

Params ``p`` (float64, length 10):

===  ========  ==============================================================
idx  name      meaning
===  ========  ==============================================================
0    K0        elastic stiffness [kip/in]
1    as        strain-hardening ratio [-]
2    My        effective yield force [kip]
3    Lambda    Λ: reference cumulative deformation, E_t = Λ·My [in] (inf: off)
4    c         exponent of the deterioration rate [-]
5    theta_p   pre-capping plastic deformation θp [in]
6    theta_pc  post-capping deformation θpc [in]
7    Res       residual force ratio [-]
8    theta_u   ultimate (fracture) deformation θu [in]
9    D         rate-of-deterioration factor [-]
===  ========  ==============================================================

State ``s`` (float64, length 20): 0 u, 1 f (committed deformation and force), 2 largest and
3 smallest deformation reached, 4 total and 5 current-excursion dissipated energy [kip·in],
6 armed (1 once on the backbone since the last deterioration), 7 fractured; then for the
positive (8..13) and the negative (14..19) side, in positive (mirrored) form: yield force, hardening ratio, post-capping slope [kip/in], post-capping line intercept at
u = 0 [kip], capping deformation [in] and capping force [kip].

Mapping to OpenSees ``uniaxialMaterial Bilin`` (OpenSees 3.x argument order)::

    Bilin tag K0 as as My -My  LamdaS LamdaD LamdaA LamdaK  Cs Cd Ca Ck
          theta_p theta_p theta_pc theta_pc Res Res theta_u theta_u D D
    with LamdaS = LamdaD = Λ (0 when Λ = inf), LamdaA = LamdaK = 0, Cs = Cd = c, Ca = Ck = 1.

Differences from OpenSees Bilin (checked against openseespy 3.7.1 and the OpenSees source;
with the mapping above the two agree to round-off on symmetric cyclic protocols with capping and
deterioration, tests/test_materials_opensees.py):

1. Residual reached through cyclic deterioration. Bilin resets the side to fy = Res·My, hardening
   ratio 1e-4, post-capping intercept fy, but recomputes its capping point with the *original*
   post-capping slope, which puts it on the elastic line at u = Res·My/(K0 − K_pc); the side's
   strength becomes Res·My·K0/(K0 − K_pc) (87 % of Res·My for θp = 0.6 in, θpc = 2 in) on a
   slope of 1e-4·K0. Bilin then also stops deteriorating the *other* side. Here the side
   becomes perfectly plastic at Res·My and the other side keeps deteriorating.
2. Fracture. Bilin (openseespy 3.7.1) returns zero force only while |u| ≥ θu and has its full
   strength back as soon as |u| < θu. Here fracture is permanent, in both directions.
3. Once-per-excursion guard. Bilin means to deteriorate once per excursion that reached the
   backbone (flag ``interup``), but at the deterioration step it overwrites its tangent with the
   opposite side's envelope tangent at that side's last peak and re-arms the flag when that is a
   hardening or post-capping slope; an elastic excursion after yielding then deteriorates the
   spring again by a tiny amount. Here a new event needs backbone contact since the last one
   (largest difference seen on partial cycles: 4e-5·My).
4. Tangent. At a deterioration step Bilin reports that overwritten tangent (e.g. −3.9 kip/in
   instead of K0 on the elastic branch); here the tangent is always that of the returned force.
5. Once ΣE ≥ E_t Bilin uses β = 1 for strength but β = 0 for the post-capping line; here both
   use β = 1. A negative E_i (elastic bookkeeping) makes Bilin's pow(E_i/…, c) NaN for
   non-integer c; here E_i is floored at 0.
6. Older Bilin sources set the negative side's hardening ratio to ``10^(-4)`` on reaching the
   residual, which C++ evaluates as the integer XOR 10 ^ −4 = −10; current sources (and
   openseespy 3.7.1) use 1e-4.

Not modelled: unloading-stiffness (Bilin LamdaK) and accelerated-reloading (LamdaA, meaningless
for a bilinear model) deterioration, and Bilin's nFactor stiffness amplification.
"""

import math
from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.compilation.jit import njit
from femoat.structure.materials.codes import IMK

N_PARAMS = 10
N_STATE = 20
K0, AS, MY, LAMBDA, C, THETA_P, THETA_PC, RES, THETA_U, D = range(N_PARAMS)

_U, _F, _UMAX, _UMIN, _ETOT, _EEXC, _ARMED, _FAILED = range(8)
_POS, _NEG = 8, 14
_FY, _AL, _KC, _FCR, _CP, _FCAP = range(6)


@njit(cache=True)
def _cap_slope0(p):
    """Original post-capping stiffness K_pc [kip/in] (< 0)."""
    return -(p[MY] + p[AS] * p[K0] * p[THETA_P]) / p[THETA_PC]


@njit(cache=True)
def _cap_point(p, fy, al, fcr):
    """Capping point where the hardening line of (fy, al) meets the original-slope cap line."""
    k = p[K0]
    kc0 = _cap_slope0(p)
    kh = al * k
    on_elastic = fcr / (k - kc0)
    on_hardening = (fcr + kh * fy / k - fy) / (kh - kc0)
    cp = max(on_elastic, on_hardening)
    return cp, fcr + kc0 * cp


@njit(cache=True)
def _backbone(p, fy, al, kc, cp, fcap, x):
    """Backbone of one side in mirrored (positive) form: (g, dg/dx) at x."""
    k = p[K0]
    if x <= cp:
        kh = al * k
        return fy + kh * (x - fy / k), kh
    g = fcap + kc * (x - cp)
    fr = p[RES] * p[MY]
    if g <= fr:
        return fr, 0.0
    return g, kc


@njit(cache=True)
def _clip(p, fy, al, kc, cp, fcap, sign, u, fe):
    """Elastic predictor fe clipped by one side's backbone (sign +1: upper, −1: lower)."""
    g, kg = _backbone(p, fy, al, kc, cp, fcap, sign * u)
    if sign * fe > g:
        return sign * g, kg, True
    return fe, p[K0], False


@njit(cache=True)
def _step(p, s, u, write):
    """Force and tangent at u from the committed state; with ``write`` commit u into s."""
    if s[_FAILED] != 0.0 or abs(u) >= p[THETA_U]:
        if write:
            s[_FAILED] = 1.0
            s[_ETOT] += 0.5 * s[_F] * (u - s[_U])
            s[_U] = u
            s[_F] = 0.0
        return 0.0, 0.0

    du = u - s[_U]
    fc = s[_F]
    fe = fc + p[K0] * du
    if du >= 0.0:
        o, sign = _POS, 1.0
    else:
        o, sign = _NEG, -1.0
    fy, al, kc, fcr, cp, fcap = (
        s[o + _FY], s[o + _AL], s[o + _KC], s[o + _FCR], s[o + _CP], s[o + _FCAP]
    )
    f, k, on_backbone = _clip(p, fy, al, kc, cp, fcap, sign, u, fe)

    # Deterioration event: the force changes sign while moving towards side o, after the spring
    # has been on its backbone since the last event and has yielded on the side it leaves.
    event = False
    if f * fc < 0.0 and s[_ARMED] != 0.0:
        if fc > 0.0:
            event = s[_UMAX] > s[_POS + _FY] / p[K0]
        else:
            event = s[_UMIN] < -s[_NEG + _FY] / p[K0]
    de = 0.5 * (f + fc) * du
    if not event and not write:
        return f, k

    if event:
        e_tot = s[_ETOT] + de
        e_t = p[LAMBDA] * p[MY]
        if e_tot >= e_t:
            beta = 1.0
        else:
            beta = min((max(s[_EEXC] + de, 0.0) / (e_t - e_tot)) ** p[C], 1.0)
        shrink = 1.0 - beta * p[D]
        fy *= shrink
        al *= shrink
        fcr *= shrink
        fr = p[RES] * p[MY]
        if fy <= fr:  # strength exhausted: perfectly plastic at the residual force for good
            fy, al, kc, fcr, cp, fcap = fr, 0.0, 0.0, fr, np.inf, fr
        else:
            kc = _cap_slope0(p) * abs((fr - fy) / (fr - p[MY]))
            if kc >= 0.0:
                kc = -1e-6 * p[K0]
            cp, fcap = _cap_point(p, fy, al, fcr)
        # the force of this step already respects the deteriorated backbone
        f, k, on_backbone = _clip(p, fy, al, kc, cp, fcap, sign, u, fe)
    if not write:
        return f, k

    s[_ETOT] += de
    s[_EEXC] = 0.0 if event else s[_EEXC] + de
    if event:
        s[_ARMED] = 0.0
        s[o + _FY], s[o + _AL], s[o + _KC] = fy, al, kc
        s[o + _FCR], s[o + _CP], s[o + _FCAP] = fcr, cp, fcap
    if on_backbone:
        s[_ARMED] = 1.0
    s[_UMAX] = max(s[_UMAX], u)
    s[_UMIN] = min(s[_UMIN], u)
    s[_U] = u
    s[_F] = f
    return f, k


@njit(cache=True)
def imk_trial(p, s, u):
    f, k = _step(p, s, u, False)
    return f, k, 0.0


@njit(cache=True)
def imk_commit(p, s, u):
    _step(p, s, u, True)


@njit(cache=True)
def imk_energy(p, s):
    return 0.5 * s[_F] * s[_F] / p[K0]


def imk_initial_state(p: np.ndarray) -> np.ndarray:
    """Virgin state for params ``p``."""
    s = np.zeros(N_STATE)
    k, my = p[K0], p[MY]
    uy = my / k
    s[_UMAX], s[_UMIN] = uy, -uy
    kc0 = -(my + p[AS] * k * p[THETA_P]) / p[THETA_PC]
    cp = uy + p[THETA_P]
    fcap = my + p[AS] * k * p[THETA_P]
    for o in (_POS, _NEG):
        s[o + _FY], s[o + _AL], s[o + _KC] = my, p[AS], kc0
        s[o + _FCR], s[o + _CP], s[o + _FCAP] = fcap - kc0 * cp, cp, fcap
    return s


@dataclass(frozen=True)
class IMKBilinear:
    """Modified Ibarra-Medina-Krawinkler bilinear spring (symmetric in tension and compression).

    Parameters
    ----------
    theta_p : float
        Pre-capping plastic deformation θp [in], > 0: capping at u_y + θp.
    theta_pc : float
        Post-capping deformation θpc [in], > 0: from the capping point to zero force.
    K0 : float
        Elastic stiffness [kip/in], > 0.
    My : float
        Effective yield force [kip], > 0.
    alpha_s : float
        Strain-hardening ratio as [-], in [0, 1).
    res : float
        Residual force ratio Res [-], in [0, 1): residual force Res·My.
    theta_u : float
        Ultimate deformation θu [in] (total, not plastic), > u_y; ``math.inf`` for no fracture.
    Lambda : float
        Reference cumulative deformation Λ [in], > 0: hysteretic energy capacity E_t = Λ·My
        [kip·in]; ``math.inf`` switches cyclic deterioration off.
    c : float
        Exponent of the cyclic deterioration rate [-], > 0 (usually 1).
    D : float
        Rate-of-deterioration factor [-], in [0, 1] (1 for symmetric deterioration).
    """

    theta_p: float
    theta_pc: float
    K0: float = 42.799
    My: float = 11.556
    alpha_s: float = 0.03
    res: float = 0.4
    theta_u: float = math.inf
    Lambda: float = math.inf
    c: float = 1.0
    D: float = 1.0

    def __post_init__(self):
        _checks.positive("theta_p", self.theta_p, "[in]")
        _checks.positive("theta_pc", self.theta_pc, "[in]")
        _checks.positive("K0", self.K0, "[kip/in]")
        _checks.positive("My", self.My, "[kip]")
        _checks.in_range("alpha_s", self.alpha_s, "[-]", 0.0, 1.0, hi_open=True)
        _checks.in_range("res", self.res, "[-]", 0.0, 1.0, hi_open=True)
        _checks.positive_or_inf("theta_u", self.theta_u, "[in]")
        if self.theta_u <= self.My / self.K0:
            raise ValueError(
                f"theta_u = {self.theta_u!r} [in]: must exceed the yield deformation "
                f"My/K0 = {self.My / self.K0:.6g} in."
            )
        _checks.positive_or_inf("Lambda", self.Lambda, "[in]")
        _checks.positive("c", self.c, "[-]")
        _checks.in_range("D", self.D, "[-]", 0.0, 1.0)

    code = IMK

    @property
    def uy(self) -> float:
        """Yield deformation My/K0 [in]."""
        return self.My / self.K0

    @property
    def initial_stiffness(self) -> float:
        """Initial (elastic) stiffness [kip/in]: K0; a story's dashpot is β times it."""
        return self.K0

    @property
    def yield_deformation(self) -> float:
        """Deformation at first yield [in]: u_y = My/K0."""
        return self.uy

    def params(self) -> np.ndarray:
        return np.array(
            [self.K0, self.alpha_s, self.My, self.Lambda, self.c, self.theta_p, self.theta_pc,
             self.res, self.theta_u, self.D],
            dtype=np.float64,
        )

    def initial_state(self) -> np.ndarray:
        return imk_initial_state(self.params())

    def opensees_bilin_args(self) -> list[float]:
        """The 23 numbers after the tag of the equivalent OpenSees ``uniaxialMaterial Bilin``."""
        lam = 0.0 if math.isinf(self.Lambda) else self.Lambda
        thu = 1e10 if math.isinf(self.theta_u) else self.theta_u
        return [
            self.K0, self.alpha_s, self.alpha_s, self.My, -self.My,
            lam, lam, 0.0, 0.0, self.c, self.c, 1.0, 1.0,
            self.theta_p, self.theta_p, self.theta_pc, self.theta_pc,
            self.res, self.res, thu, thu, self.D, self.D,
        ]
