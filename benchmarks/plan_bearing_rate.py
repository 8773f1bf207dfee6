"""The plan friction pendulum's friction state carried through a Runge-Kutta step: which
formulation reaches fourth order on a curved orbit, and at what cost (issue 26).

    python benchmarks/plan_bearing_rate.py [--full]

Prints, in one run (about a minute on an idle core; --full adds h = 0.3125 ms):

1. the Butcher tableaus used (Dormand-Prince 5(4) from femoat's dp5 module; Kennedy & Carpenter's
   ARK3(2)4L[2]SA, ARK4(3)6L[2]SA, ARK5(4)8L[2]SA (2003) and ARK4(3)7L[2]SA1 (2019), transcribed
   from SUNDIALS ARKODE's ``arkode_butcher_erk.def`` / ``arkode_butcher_dirk.def``) with their
   order conditions checked numerically: every (bicoloured, for a pair) rooted tree up to the
   claimed order, the embedded weights one order lower, stiff accuracy and R(-inf);
2. the bearing alone: a rigid mass m = W/g on femoat's default plan bearing (W = 33 kip, R = 30 in,
   u_y = 0.01 in, mu = 0.06), driven by a smooth two-component ground acceleration so that the base
   orbit is (a) a circle (steady sliding, no event), (b) an ellipse with reversals (stick phases),
   (c) a figure-eight; and the imposed-displacement variant (u(t) prescribed, only z integrated);
   each against a converged reference (scipy DOP853 at rtol 1e-13 with the stick/slip switches
   located as events), the steps landed on the reference's switches (as femoat's kink search
   lands a step where ``plan_branch`` changes), so that the orders are those between events;
3. per formulation and step: the error of the end state (u, v, z) and of the bearing force at the
   end and at every landed switch, the observed order (log2 of successive error ratios), the
   evaluations of the structure's force (f_E), of the bearing rate and the 2x2 Newton solves;
4. along a straight line (y at rest): the new step against the 1D step of the x component.

Formulations (the friction state z is part of the stage state in all but the first):

* ``path``: dp5 stages with z from the committed state along the cubic Hermite path to the
  stage (:func:`femoat.bearings.friction_pendulum._path_z`): the step femoat refuses today;
* ``newmark+path``: Newmark (average acceleration) with femoat's ``plan_trial`` along the step's
  path: the plan run's method today;
* ``dp5-z``: dp5 on (u, v, z), z's slip rate explicit (stable only for h·|v|/u_y below ~3);
* ``dp5-X``: dp5 on (u, v, X), X = (X0, x) the homogeneous coordinates of z = x/X0 (the Lorentz
  group form of perfect plasticity, Hong & Liu 1999): while sliding X' = (x.v, X0 v)/u_y is
  *linear* in X, explicit;
* ``ark3/ark4/ark437/ark5``: the additive pairs, the structure (u, v) explicit and z's rate
  implicit (one 2x2 Newton solve per bearing and stage);
* ``dp5+I``: dp5 for the structure with an implicit companion for z in GARK form, found here
  (coupled order 4, L-stable; unoptimized): on a line it is the 1D dp5 step bit for bit.

Units: kip, in, s.  Findings: docs/coupled_friction.md.
"""

import argparse
import itertools
import math
import time
from fractions import Fraction as Fr

import numpy as np
from scipy.integrate import solve_ivp

from femoat.bearings import friction_pendulum as fp
from femoat.integration.methods import dp5 as _dp5
from femoat.units import G as GRAV

# ================================================================================================
# 1. Tableaus
# ================================================================================================


def _f(x):
    return float(Fr(x)) if isinstance(x, str) else float(x)


class Tableau:
    """An additive pair (A_E, b_E, c), (A_I, b_I) with shared embedded weights d (ARK), or one
    explicit method (A_I = A_E)."""

    def __init__(self, name, order, AE, b, d, c, AI=None, bI=None, dI=None):
        self.name, self.order = name, order
        self.AE = np.array(AE, float)
        self.b = np.array(b, float)
        self.d = np.array(d, float)
        self.c = np.array(c, float)
        self.AI = self.AE if AI is None else np.array(AI, float)
        self.bI = self.b if bI is None else np.array(bI, float)
        self.dI = self.d if dI is None else np.array(dI, float)
        self.s = self.b.size
        self.explicit = not np.any(np.diag(self.AI))
        # first same as last: the last explicit stage is the step's solution
        self.fsal = bool(np.allclose(self.AE[-1], self.b, atol=0, rtol=0) and self.c[-1] == 1.0)
        self.B = None  # GARK: the velocity rows of the implicit stages (None: the explicit rows)


def _lower(rows, s):
    A = np.zeros((s, s))
    for i, row in rows.items():
        for j, v in row.items():
            A[i, j] = _f(v)
    return A


def dp5_tableau():
    """femoat's own dp5 coefficients (femoat.integration.methods.dp5)."""
    s = _dp5.N_STAGES
    A = np.zeros((s, s))
    for i in range(s):
        A[i, :s - 1] = _dp5.DP_A[i]
    b = np.zeros(s)
    b[:s - 1] = _dp5.DP_A[s - 1]
    d = b - _dp5.DP_E
    return Tableau("dp5", 5, A, b, d, _dp5.DP_C)


G324 = "0.4358665215084589994160194511935568425293"


def ark324():
    """ARK3(2)4L[2]SA (Kennedy & Carpenter 2003), ARKODE_ARK324L2SA_{ERK,DIRK}_4_2_3."""
    AE = _lower({1: {0: "0.8717330430169179988320389023871136850586"},
                 2: {0: "0.52758901197630041156180797140291790433",
                     1: "0.07241098802369958843819202859708209566999"},
                 3: {0: "0.3990960076760701320627260736092142797856",
                     1: "-0.437557654613519443722846363831022571942",
                     2: "1.038461646937449311660120290221808292156"}}, 4)
    b = [_f(x) for x in ("0.1876410243467238251612921441668043913795",
                         "-0.5952974735769549480478230275858851737782",
                         "0.9717899277217721234705114322255239398694", G324)]
    d = [_f(x) for x in ("0.2147402862233891404862383406484193714659",
                         "-0.4851622638849390928209050808398155895845",
                         "0.86872500252038755116621237682951240796",
                         "0.4016969751411624011684543633618838101586")]
    c = [0.0, _f("0.8717330430169179988320389023871136850586"), 0.6, 1.0]
    AI = _lower({1: {0: G324, 1: G324},
                 2: {0: "0.2576482460664272457999960162840797092643",
                     1: "-0.09351476757488624521601546747763655179361", 2: G324}}, 4)
    AI[3] = b
    return Tableau("ark3", 3, AE, b, d, c, AI)


def ark436():
    """ARK4(3)6L[2]SA (Kennedy & Carpenter 2003) = OrdinaryDiffEq's KenCarp4."""
    AE = _lower({1: {0: "1/2"},
                 2: {0: "13861/62500", 1: "6889/62500"},
                 3: {0: "-116923316275/2393684061468", 1: "-2731218467317/15368042101831",
                     2: "9408046702089/11113171139209"},
                 4: {0: "-451086348788/2902428689909", 1: "-2682348792572/7519795681897",
                     2: "12662868775082/11960479115383", 3: "3355817975965/11060851509271"},
                 5: {0: "647845179188/3216320057751", 1: "73281519250/8382639484533",
                     2: "552539513391/3454668386233", 3: "3354512671639/8306763924573",
                     4: "4040/17871"}}, 6)
    b = [_f(x) for x in ("82889/524892", "0", "15625/83664", "69875/102672", "-2260/8211",
                         "1/4")]
    d = [_f(x) for x in ("4586570599/29645900160", "0", "178811875/945068544",
                         "814220225/1159782912", "-3700637/11593932", "61727/225920")]
    c = [_f(x) for x in ("0", "1/2", "83/250", "31/50", "17/20", "1")]
    AI = _lower({1: {0: "1/4", 1: "1/4"},
                 2: {0: "8611/62500", 1: "-1743/31250", 2: "1/4"},
                 3: {0: "5012029/34652500", 1: "-654441/2922500", 2: "174375/388108",
                     3: "1/4"},
                 4: {0: "15267082809/155376265600", 1: "-71443401/120774400",
                     2: "730878875/902184768", 3: "2285395/8070912", 4: "1/4"}}, 6)
    AI[5] = b
    return Tableau("ark4", 4, AE, b, d, c, AI)


def ark437():
    """ARK4(3)7L[2]SA1 (Kennedy & Carpenter 2019) = OrdinaryDiffEq's KenCarp47."""
    g = "1235/10000"
    AE = _lower({1: {0: "247/1000"},
                 2: {0: "247/4000", 1: "2694949928731/7487940209513"},
                 3: {0: "464650059369/8764239774964", 1: "878889893998/2444806327765",
                     2: "-952945855348/12294611323341"},
                 4: {0: "476636172619/8159180917465", 1: "-1271469283451/7793814740893",
                     2: "-859560642026/4356155882851", 3: "1723805262919/4571918432560"},
                 5: {0: "6338158500785/11769362343261", 1: "-4970555480458/10924838743837",
                     2: "3326578051521/2647936831840", 3: "-880713585975/1841400956686",
                     4: "-1428733748635/8843423958496"},
                 6: {0: "760814592956/3276306540349", 1: "760814592956/3276306540349",
                     2: "-47223648122716/6934462133451", 3: "71187472546993/9669769126921",
                     4: "-13330509492149/9695768672337", 5: "11565764226357/8513123442827"}}, 7)
    b = [_f(x) for x in ("0", "0", "9164257142617/17756377923965",
                         "-10812980402763/74029279521829", "1335994250573/5691609445217",
                         "2273837961795/8368240463276", "247/2000")]
    d = [_f(x) for x in ("0", "0", "4469248916618/8635866897933",
                         "-621260224600/4094290005349", "696572312987/2942599194819",
                         "1532940081127/5565293938103", "2441/20000")]
    c = [_f(x) for x in ("0", "247/1000", "4276536705230/10142255878289", "67/200", "3/40",
                         "7/10", "1")]
    AI = _lower({1: {0: g, 1: g},
                 2: {0: "624185399699/4186980696204", 1: "624185399699/4186980696204", 2: g},
                 3: {0: "1258591069120/10082082980243", 1: "1258591069120/10082082980243",
                     2: "-322722984531/8455138723562", 3: g},
                 4: {0: "-436103496990/5971407786587", 1: "-436103496990/5971407786587",
                     2: "-2689175662187/11046760208243", 3: "4431412449334/12995360898505",
                     4: g},
                 5: {0: "-2207373168298/14430576638973", 1: "-2207373168298/14430576638973",
                     2: "242511121179/3358618340039", 3: "3145666661981/7780404714551",
                     4: "5882073923981/14490790706663", 5: g}}, 7)
    AI[6] = b
    return Tableau("ark437", 4, AE, b, d, c, AI)


def ark548():
    """ARK5(4)8L[2]SA (Kennedy & Carpenter 2003) = OrdinaryDiffEq's KenCarp5: femoat's own
    coefficients (femoat.integration.methods.ark5, transcribed from ARKODE's tables; section 1
    checks their order conditions)."""
    from femoat.integration.methods import ark5

    return Tableau("ark5", 5, ark5.ARK_AE, ark5.ARK_B, ark5.ARK_BHAT, ark5.ARK_C, ark5.ARK_AI)


# ---- order conditions: Butcher's rooted trees, bicoloured for a pair ---------------------------


def _canon(t):
    return tuple(sorted(_canon(c) for c in t))


def _grow(t):
    out = [_canon(t + ((),))]
    for i, ch in enumerate(t):
        for g in _grow(ch):
            out.append(_canon(t[:i] + (g,) + t[i + 1:]))
    return out


def rooted_trees(pmax):
    """{order: [tree]}, a tree the sorted tuple of its children's trees."""
    trees = {1: [()]}
    for n in range(2, pmax + 1):
        trees[n] = sorted({g for t in trees[n - 1] for g in _grow(t)})
    return trees


def _size(t):
    return 1 + sum(_size(c) for c in t)


def _density(t):
    return _size(t) * math.prod(_density(c) for c in t)


def _colourings(t):
    """Every colouring of tree t: (colour, (children...)), colour 0 explicit, 1 implicit."""
    kids = [list(_colourings(c)) for c in t]
    for col in (0, 1):
        for combo in itertools.product(*kids):
            yield (col, combo)


def _stage_weight(ct, M):
    """The stage weights of coloured tree ct: M[(parent colour, child colour)] is the matrix
    of an edge (an ARK: the child's A whatever the parent; a GARK: its own coupling blocks)."""
    col, kids = ct
    g = np.ones(M[(col, col)].shape[0])
    for k in kids:
        g = g * (M[(col, k[0])] @ _stage_weight(k, M))
    return g


def order_residual(tab, p, weights=None, coupled=True):
    """Largest |Phi(t) - 1/gamma(t)| over the (bicoloured if ``coupled``) trees of order <= p."""
    M = {(0, 0): tab.AE, (1, 0): tab.AE if tab.B is None else tab.B, (0, 1): tab.AI,
         (1, 1): tab.AI}
    bw = (tab.b, tab.bI) if weights is None else weights
    worst = 0.0
    for ts in rooted_trees(p).values():
        for t in ts:
            for ct in _colourings(t):
                if not coupled and _has_mixed(ct):
                    continue
                phi = bw[ct[0]] @ _stage_weight(ct, M)
                worst = max(worst, abs(phi - 1.0 / _density(t)))
    return worst


def _has_mixed(ct):
    cols = set()

    def walk(x):
        cols.add(x[0])
        for k in x[1]:
            walk(k)
    walk(ct)
    return len(cols) > 1


def stability(A, b, z):
    s = b.size
    return 1.0 + z * b @ np.linalg.solve(np.eye(s) - z * A, np.ones(s))


def check_tableaus(tabs):
    print("\n## 1. Tableaus: order conditions checked numerically\n")
    print("| method | stages | order p | max residual, trees <= p (coupled) | order p+1 residual "
          "| embedded, trees <= p-1 | stiffly accurate | |R_I(-1e8)| | FSAL |")
    print("|---|---|---|---|---|---|---|---|---|")
    for tab in tabs:
        p = tab.order
        res = order_residual(tab, p)
        nxt = order_residual(tab, p + 1)
        emb = order_residual(tab, p - 1, weights=(tab.d, tab.dI)) if tab.B is None else None
        sa = "-" if tab.explicit else ("yes" if np.array_equal(tab.AI[-1], tab.bI) else "no")
        rinf = "-" if tab.explicit else f"{abs(stability(tab.AI, tab.bI, -1e8)):.1e}"
        emb = "none yet" if emb is None else f"{emb:.1e}"
        print(f"| {tab.name} | {tab.s} | {p} | {res:.1e} | {nxt:.1e} | {emb} | {sa} | {rinf}"
              f" | {'yes' if tab.fsal else 'no'} |")
    return True


# ================================================================================================
# 2. The bearing alone: a rigid mass on femoat's plan friction pendulum
# ================================================================================================

BEARING = fp.BidirectionalFrictionPendulum()
W, R, UY, MU = BEARING.W, BEARING.R, BEARING.u_y, BEARING.mu
KR = GRAV / R          # (W/R)/m [1/s²]
MUG = MU * GRAV        # mu·W/m [in/s²]
STICK, SLIP = 0, 1


def force(ux, uy, zx, zy):
    """The bearing force (f_x, f_y) [kip], in fp.axis_trial's arithmetic (k_r·u + (mu·W)·z)."""
    kr, muw = W / R, MU * W
    return kr * ux + muw * zx, kr * uy + muw * zy


def slip_rate(zx, zy, vx, vy):
    """z' on the rim while sliding, (v - (z.v) z)/u_y, written for every z near the rim: the
    radial direction is then attracted to |z| = 1 at the rate 2(z.v)/u_y."""
    zv = zx * vx + zy * vy
    return (vx - zv * zx) / UY, (vy - zv * zy) / UY


def slip_rate_tangent(zx, zy, vx, vy):
    """d(z')/dz = -((z.v) I + z v^T)/u_y (2x2, by rows)."""
    zv = zx * vx + zy * vy
    return (-(zv + zx * vx) / UY, -(zx * vy) / UY, -(zy * vx) / UY, -(zv + zy * vy) / UY)


def stick_z(zx0, zy0, ux0, uy0, ux, uy):
    """z while sticking: femoat's radial return from the committed state (fp._z): on a branch
    that does not change inside the step it is exact, and it is the 1D clip along a line."""
    zx = zx0 + (ux - ux0) / UY
    zy = zy0 + (uy - uy0) / UY
    n = math.sqrt(zx * zx + zy * zy)
    if n > 1.0:
        return zx / n, zy / n
    return zx, zy


class Scenario:
    """A ground acceleration (a_x, a_y) [in/s²] of time, an interval and a start state
    (ux, uy, vx, vy, zx, zy) with its branch; or, ``imposed``, a prescribed bearing displacement
    u(t) with its velocity (only z is integrated)."""

    def __init__(self, name, t0, t1, ag=None, y0=None, mode0=STICK, imposed=None):
        self.name, self.t0, self.t1 = name, t0, t1
        self.ag, self.y0, self.mode0, self.imposed = ag, y0, mode0, imposed


def circle_scenario(t1=2.0, r=3.0, period=1.0):
    """Steady sliding on a circle of radius r: a_g = A(cos wt, sin wt) and the start state on
    the rotating steady solution (z lags the velocity by asin(u_y/r)): no stick/slip event."""
    w = 2 * math.pi / period
    delta = -math.asin(UY / r)
    C = (KR - w * w) * r + 1j * MUG * complex(math.cos(delta), math.sin(delta))
    amp, psi = abs(C), math.pi - math.atan2(C.imag, C.real)
    th = psi + math.pi / 2 + delta
    y0 = [r * math.cos(psi), r * math.sin(psi), -r * w * math.sin(psi), r * w * math.cos(psi),
          math.cos(th), math.sin(th)]
    return Scenario("circle", 0.0, t1, lambda t: (amp * math.cos(w * t), amp * math.sin(w * t)),
                    y0, SLIP)


def ellipse_scenario(t1=3.0, ax=0.20, ay=0.005, period=1.2):
    """a_g = (ax cos wt, ay sin wt)·g from rest: an elongated orbit whose ends are reversals
    (the friction direction turns against the velocity: stick phases)."""
    w = 2 * math.pi / period
    return Scenario("ellipse", 0.0, t1,
                    lambda t: (ax * GRAV * math.cos(w * t), ay * GRAV * math.sin(w * t)),
                    [0.0] * 6, STICK)


def eight_scenario(t1=3.0, ax=0.08, ay=0.20, period=2.0):
    """a_g = (ax sin wt, ay sin 2wt)·g from rest: a figure-eight orbit."""
    w = 2 * math.pi / period
    return Scenario("eight", 0.0, t1,
                    lambda t: (ax * GRAV * math.sin(w * t), ay * GRAV * math.sin(2 * w * t)),
                    [0.0] * 6, STICK)


def imposed_scenario(kind, t1=2.0):
    """u(t) prescribed (in): the friction law alone. 'circle' r = 3 in, period 1 s;
    'eight' (3 sin wt, 2 sin 2wt), period 1.5 s; both from rest in z (a start at z = 0)."""
    if kind == "circle":
        w = 2 * math.pi
        path = lambda t: (3 * math.cos(w * t) - 3, 3 * math.sin(w * t),
                          -3 * w * math.sin(w * t), 3 * w * math.cos(w * t))
    else:
        w = 2 * math.pi / 1.5
        path = lambda t: (3 * math.sin(w * t), 2 * math.sin(2 * w * t),
                          3 * w * math.cos(w * t), 4 * w * math.cos(2 * w * t))
    return Scenario(f"imposed-{kind}", 0.0, t1, y0=[0.0] * 6, mode0=STICK, imposed=path)


# ---- the converged reference: DOP853, the switches as events -----------------------------------


def _ref_rhs(sc, mode):
    def rhs(t, y):
        if sc.imposed is not None:
            ux, uy, vx, vy = sc.imposed(t)
            ax = ay = 0.0
        else:
            ux, uy, vx, vy = y[0], y[1], y[2], y[3]
            gx, gy = sc.ag(t)
            ax = -gx - KR * ux - MUG * y[4]
            ay = -gy - KR * uy - MUG * y[5]
        if mode == STICK:
            zdx, zdy = vx / UY, vy / UY
        else:
            zdx, zdy = slip_rate(y[4], y[5], vx, vy)
        return [vx, vy, ax, ay, zdx, zdy]
    return rhs


def _ref_events(sc, mode):
    def to_slip(t, y):
        return y[4] * y[4] + y[5] * y[5] - 1.0
    to_slip.terminal, to_slip.direction = True, 1.0

    def to_stick(t, y):
        if sc.imposed is not None:
            _, _, vx, vy = sc.imposed(t)
        else:
            vx, vy = y[2], y[3]
        return y[4] * vx + y[5] * vy
    to_stick.terminal, to_stick.direction = True, -1.0
    return [to_slip] if mode == STICK else [to_stick]


def reference(sc, rtol=1e-13, atol=1e-14):
    """(segments [(ta, tb, mode)], states at the segment ends, the solver's RHS evaluations)."""
    t, y, mode = sc.t0, np.array(sc.y0, float), sc.mode0
    if sc.imposed is not None:
        y[:4] = sc.imposed(t)
    segs, states, nfev = [], [y.copy()], 0
    while t < sc.t1 - 1e-12:
        sol = solve_ivp(_ref_rhs(sc, mode), (t, sc.t1), y, method="DOP853", rtol=rtol, atol=atol,
                        events=_ref_events(sc, mode))
        nfev += sol.nfev
        if sc.imposed is None:
            sc.vmax = max(getattr(sc, "vmax", 0.0), float(np.max(np.hypot(sol.y[2], sol.y[3]))))
        if sol.status == 1 and sol.t_events[0].size:
            tb, yb = sol.t_events[0][0], sol.y_events[0][0].copy()
        else:
            tb, yb = sol.t[-1], sol.y[:, -1].copy()
        segs.append((t, tb, mode))
        if mode == STICK and tb < sc.t1 - 1e-12:
            n = math.hypot(yb[4], yb[5])
            yb[4:] /= n
        states.append(yb.copy())
        t, y = tb, yb
        mode = SLIP if mode == STICK else STICK
    return segs, states, nfev


# ================================================================================================
# 3. The formulations: one step each, from a state (ux, uy, vx, vy, zx, zy) on a known branch
# ================================================================================================


class Count:
    def __init__(self):
        self.steps = self.f_e = self.rate = self.newton = self.guard = 0


def _stage_uv(sc, t, h, y, i, tab, Vx, Vy, Ax, Ay):
    """The stage's (u, v): the explicit combination (femoat's dp5 arithmetic: u0 + h·Σ a·k), or
    the prescribed path at the stage's time."""
    if sc.imposed is not None:
        return sc.imposed(t + tab.c[i] * h)
    A = tab.AE_rows[i]
    su_x = su_y = sv_x = sv_y = 0.0
    for j in range(i):
        a = A[j]
        su_x += a * Vx[j]
        su_y += a * Vy[j]
        sv_x += a * Ax[j]
        sv_y += a * Ay[j]
    return y[0] + h * su_x, y[1] + h * su_y, y[2] + h * sv_x, y[3] + h * sv_y


MASS = W / GRAV


def _accel(sc, t, ux, uy, zx, zy):
    """a = -a_g - f/m, the force as femoat's kernels compute it (fp.axis_trial's arithmetic)."""
    gx, gy = sc.ag(t)
    fx, fy = force(ux, uy, zx, zy)
    return -gx - fx / MASS, -gy - fy / MASS


def _prepare(tab):
    if not hasattr(tab, "AE_rows"):
        tab.AE_rows = [list(r) for r in tab.AE]
        tab.AI_rows = [list(r) for r in tab.AI]
        tab.bl, tab.bIl, tab.cl = list(tab.b), list(tab.bI), list(tab.c)
        tab.B_rows = None if tab.B is None else [list(r) for r in tab.B]
    return tab


def step_z(tab, sc, t, h, y, mode, cnt):
    """One step of the pair ``tab`` with z in the stage state: (u, v) by the explicit tableau,
    z's slip rate by the implicit one (a 2x2 Newton solve per stage with a_ii != 0; an explicit
    tableau is then the plain Runge-Kutta method on (u, v, z)); while sticking z is the radial
    return from the committed state (algebraic, femoat's fp._z)."""
    s = tab.s
    Vx, Vy, Ax, Ay, Gx, Gy = ([0.0] * s for _ in range(6))
    zx0, zy0 = y[4], y[5]
    zx, zy = zx0, zy0
    AI = tab.AI_rows
    for i in range(s):
        ux, uy, vx, vy = _stage_uv(sc, t, h, y, i, tab, Vx, Vy, Ax, Ay)
        Vx[i], Vy[i] = vx, vy
        if tab.B is not None and sc.imposed is None:  # GARK: the z-solve's own velocity row
            svx = svy = 0.0
            for j in range(i):
                svx += tab.B_rows[i][j] * Ax[j]
                svy += tab.B_rows[i][j] * Ay[j]
            vx, vy = y[2] + h * svx, y[3] + h * svy
        if mode == SLIP:
            wx, wy = 0.0, 0.0
            for j in range(i):
                a = AI[i][j]
                wx += a * Gx[j]
                wy += a * Gy[j]
            wx, wy = zx0 + h * wx, zy0 + h * wy
            gam = AI[i][i]
            if gam == 0.0:
                zx, zy = wx, wy
            else:
                for _ in range(20):  # Newton on z - w - h·γ·z'(z, v) = 0 from the last stage's z
                    gx, gy = slip_rate(zx, zy, vx, vy)
                    rx, ry = zx - wx - h * gam * gx, zy - wy - h * gam * gy
                    t00, t01, t10, t11 = slip_rate_tangent(zx, zy, vx, vy)
                    j00, j01 = 1.0 - h * gam * t00, -h * gam * t01
                    j10, j11 = -h * gam * t10, 1.0 - h * gam * t11
                    det = j00 * j11 - j01 * j10
                    dx = (j11 * rx - j01 * ry) / det
                    dy = (j00 * ry - j10 * rx) / det
                    zx, zy = zx - dx, zy - dy
                    cnt.newton += 1
                    cnt.rate += 1
                    if abs(dx) + abs(dy) <= 1e-15:
                        break
            Gx[i], Gy[i] = slip_rate(zx, zy, vx, vy)
            cnt.rate += 1
            zx, zy = _guard(zx, zy, zx0, zy0, y[0], y[1], ux, uy, cnt)
        else:
            zx, zy = stick_z(zx0, zy0, y[0], y[1], ux, uy)
        if sc.imposed is None:
            Ax[i], Ay[i] = _accel(sc, t + tab.c[i] * h, ux, uy, zx, zy)
    return _finish(tab, sc, t, h, y, mode, cnt, Vx, Vy, Ax, Ay, Gx, Gy)


def _guard(zx, zy, zx0, zy0, ux0, uy0, ux, uy, cnt):
    """A sliding stage whose trial from the committed state is inside the disk (the stage moved
    back, unloading) reads the trial instead, as the 1D clip does: the 1D step along a line,
    bit for bit, whatever the signs of a stage's coefficients. (Never met on a smooth slip
    branch; counted.)"""
    tx = zx0 + (ux - ux0) / UY
    ty = zy0 + (uy - uy0) / UY
    if tx * tx + ty * ty <= 1.0:
        if (tx, ty) != (zx, zy):
            cnt.guard += 1
        return tx, ty
    return zx, zy


def _finish(tab, sc, t, h, y, mode, cnt, Vx, Vy, Ax, Ay, Gx, Gy, zend=None):
    s = tab.s
    cnt.steps += 1
    cnt.f_e += (s - 1) if tab.fsal else s
    if sc.imposed is not None:
        ux, uy, vx, vy = sc.imposed(t + h)
    else:
        b = tab.bl
        ux = y[0] + h * sum(b[j] * Vx[j] for j in range(s))
        uy = y[1] + h * sum(b[j] * Vy[j] for j in range(s))
        vx = y[2] + h * sum(b[j] * Ax[j] for j in range(s))
        vy = y[3] + h * sum(b[j] * Ay[j] for j in range(s))
    if zend is not None:
        zx, zy = zend
    elif mode == SLIP:
        bI = tab.bIl
        zx = y[4] + h * sum(bI[j] * Gx[j] for j in range(s))
        zy = y[5] + h * sum(bI[j] * Gy[j] for j in range(s))
        zx, zy = _guard(zx, zy, y[4], y[5], y[0], y[1], ux, uy, cnt)
    else:
        zx, zy = stick_z(y[4], y[5], y[0], y[1], ux, uy)
    return [ux, uy, vx, vy, zx, zy]


def step_x(tab, sc, t, h, y, mode, cnt):
    """dp5 on the homogeneous coordinates X = (X0, x) of z = x/X0 while sliding:
    X0' = (x.v)/u_y, x' = X0·v/u_y (linear in X; along a line x = X0·z stays proportional)."""
    if mode == STICK:
        return step_z(tab, sc, t, h, y, mode, cnt)
    s = tab.s
    Vx, Vy, Ax, Ay, P, Qx, Qy = ([0.0] * s for _ in range(7))
    A = tab.AE_rows
    for i in range(s):
        ux, uy, vx, vy = _stage_uv(sc, t, h, y, i, tab, Vx, Vy, Ax, Ay)
        X0, xx, xy = 0.0, 0.0, 0.0
        for j in range(i):
            a = A[j] if False else A[i][j]
            X0 += a * P[j]
            xx += a * Qx[j]
            xy += a * Qy[j]
        X0, xx, xy = 1.0 + h * X0, y[4] + h * xx, y[5] + h * xy
        zx, zy = xx / X0, xy / X0
        P[i] = (xx * vx + xy * vy) / UY
        Qx[i], Qy[i] = X0 * vx / UY, X0 * vy / UY
        cnt.rate += 1
        Vx[i], Vy[i] = vx, vy
        if sc.imposed is None:
            Ax[i], Ay[i] = _accel(sc, t + tab.c[i] * h, ux, uy, zx, zy)
    b = tab.bl
    X0 = 1.0 + h * sum(b[j] * P[j] for j in range(s))
    xx = y[4] + h * sum(b[j] * Qx[j] for j in range(s))
    xy = y[5] + h * sum(b[j] * Qy[j] for j in range(s))
    return _finish(tab, sc, t, h, y, mode, cnt, Vx, Vy, Ax, Ay, None, None, (xx / X0, xy / X0))


_P = BEARING.params()


def step_path(tab, sc, t, h, y, mode, cnt):
    """femoat's current plan step: each stage's z from the committed state along the cubic
    Hermite path to the stage (fp._path_z, femoat's own compiled kernel)."""
    s = tab.s
    Vx, Vy, Ax, Ay = ([0.0] * s for _ in range(4))
    sc_state = np.array([y[0], y[1], y[4], y[5], y[2], y[3]])
    for i in range(s):
        ux, uy, vx, vy = _stage_uv(sc, t, h, y, i, tab, Vx, Vy, Ax, Ay)
        zx, zy, _ = fp._path_z(_P, sc_state, y[0], y[1], y[2], y[3], ux, uy, vx, vy,
                               tab.c[i] * h)
        cnt.rate += 1
        Vx[i], Vy[i] = vx, vy
        if sc.imposed is None:
            Ax[i], Ay[i] = _accel(sc, t + tab.c[i] * h, ux, uy, zx, zy)
    out = _finish(tab, sc, t, h, y, STICK, cnt, Vx, Vy, Ax, Ay, None, None, (0.0, 0.0))
    zx, zy, _ = fp._path_z(_P, sc_state, y[0], y[1], y[2], y[3], out[0], out[1], out[2], out[3],
                           h)
    out[4], out[5] = zx, zy
    return out


STEPS = {"z": step_z, "X": step_x, "path": step_path}


def integrate(tab, form, sc, segs, h, cnt=None):
    """Fixed steps of at most ``h`` inside each reference segment (the steps land on every
    stick/slip switch); the states at the segments' ends."""
    _prepare(tab)
    cnt = Count() if cnt is None else cnt
    step = STEPS[form]
    y = list(sc.y0)
    if sc.imposed is not None:
        y[:4] = sc.imposed(sc.t0)
    out = [list(y)]
    for k, (ta, tb, mode) in enumerate(segs):
        n = max(1, math.ceil((tb - ta) / h - 1e-9))
        hh = (tb - ta) / n
        for m in range(n):
            y = step(tab, sc, ta + m * hh, hh, y, mode, cnt)
        if mode == STICK and k + 1 < len(segs):  # the landing step's commit: a radial return
            nz = math.hypot(y[4], y[5])
            y[4], y[5] = y[4] / nz, y[5] / nz
        out.append(list(y))
    return out, cnt


# ================================================================================================
# 4. Along a line: the plan step against the 1D step (femoat's axis kernel) of the x component
# ================================================================================================


def step_axis(tab, sc, t, h, y, mode, cnt):
    """The 1D step of the x component: the explicit tableau, every stage's force from
    femoat's own fp.axis_trial (z the clip from the committed state), the commit fp._z_axis."""
    s = tab.s
    p = _P
    st = np.array([y[0], y[4], y[2]])
    V, A = [0.0] * s, [0.0] * s
    for i in range(s):
        su = sv = 0.0
        for j in range(i):
            a = tab.AE_rows[i][j]
            su += a * V[j]
            sv += a * A[j]
        u, v = y[0] + h * su, y[2] + h * sv
        f, _, _ = fp.axis_trial(p, st, u, v)
        V[i] = v
        A[i] = -sc.ag(t + tab.c[i] * h)[0] - f / MASS
    cnt.steps += 1
    u1 = y[0] + h * sum(tab.bl[j] * V[j] for j in range(s))
    v1 = y[2] + h * sum(tab.bl[j] * A[j] for j in range(s))
    z1, _ = fp._z_axis(p, st, u1)
    return [u1, 0.0, v1, 0.0, z1, 0.0]


STEPS["axis"] = step_axis


def line_scenario(t1=3.0, ax=0.25, period=1.2):
    """a_g = (ax·g·sin wt, 0) from rest: a straight orbit with reversals (stick phases)."""
    w = 2 * math.pi / period
    return Scenario("line", 0.0, t1, lambda t: (ax * GRAV * math.sin(w * t), 0.0), [0.0] * 6,
                    STICK)


def line_check(methods, h=0.005):
    """Every step's state of the plan step along x against the 1D step (the same explicit
    tableau, and dp5: femoat's 1D default)."""
    sc = line_scenario()
    segs, _, _ = reference(sc)
    print(f"\n## 4. Along a line (a_g along x only, y at rest; {len(segs)} stick/slip segments, "
          f"h = {h * 1e3:g} ms)\n")
    print("| plan step | 1D step compared | max |x difference| over the run | y exactly 0 "
          "| stages inside the disk while sliding (guard) |")
    print("|---|---|---|---|---|")
    dp = _prepare(dp5_tableau())
    base = _trace(dp, "axis", sc, segs, h)[0]
    for name, tab, form in methods:
        tab = _prepare(tab)
        trace, cnt = _trace(tab, form, sc, segs, h)
        own = base if tab.name == "dp5" else _trace(tab, "axis", sc, segs, h)[0]
        for label, other in (("same tableau, 1D", own), ("dp5, 1D (femoat's default)", base)):
            if label.startswith("same") and np.array_equal(tab.AE, dp.AE):
                continue
            d = max(max(abs(a[k] - b[k]) for k in (0, 2, 4)) for a, b in zip(trace, other))
            y0 = all(a[1] == 0.0 and a[3] == 0.0 and a[5] == 0.0 for a in trace)
            print(f"| {name} | {label} | {'0 (bit for bit)' if d == 0 else f'{d:.1e}'} "
                  f"| {'yes' if y0 else 'no'} | {cnt.guard} |")


def _trace(tab, form, sc, segs, h):
    """Every step's state (the run of :func:`integrate`, all steps kept)."""
    _prepare(tab)
    cnt = Count()
    step = STEPS[form]
    y = list(sc.y0)
    out = [list(y)]
    for k, (ta, tb, mode) in enumerate(segs):
        n = max(1, math.ceil((tb - ta) / h - 1e-9))
        hh = (tb - ta) / n
        for m in range(n):
            y = step(tab, sc, ta + m * hh, hh, y, mode, cnt)
            out.append(list(y))
        if mode == STICK and k + 1 < len(segs) and form != "axis":
            nz = math.hypot(y[4], y[5])
            y[4], y[5] = y[4] / nz, y[5] / nz
        elif mode == STICK and k + 1 < len(segs):
            y[4] = 1.0 if y[4] > 0 else -1.0  # the 1D commit just past the kink: the clip
    return out, cnt


# ---- femoat's plan default today: Newmark (average acceleration) with the path z ------------


def step_newmark(tab, sc, t, h, y, mode, cnt):
    """Newmark gamma = 1/2, beta = 1/4 on the rigid mass, Newton on u1, the force and its
    tangents from femoat's fp.plan_trial along the step's path (tau = h): the plan run's
    method today. The state carries the acceleration (y[6:8])."""
    p = _P
    st = np.array([y[0], y[1], y[4], y[5], y[2], y[3]])
    gx, gy = sc.ag(t + h)
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    ux, uy = y[0] + h * y[2] + 0.5 * h * h * y[6], y[1] + h * y[3] + 0.5 * h * h * y[7]
    for _ in range(50):
        ax = 4 * (ux - y[0]) / (h * h) - 4 * y[2] / h - y[6]
        ay = 4 * (uy - y[1]) / (h * h) - 4 * y[3] / h - y[7]
        vx, vy = y[2] + 0.5 * h * (y[6] + ax), y[3] + 0.5 * h * (y[7] + ay)
        fp.plan_trial(p, st, y[0], y[1], y[2], y[3], ux, uy, vx, vy, h, f, k, c)
        cnt.f_e += 1
        rx, ry = MASS * (ax + gx) + f[0], MASS * (ay + gy) + f[1]
        m4 = 4 * MASS / (h * h)
        K00, K01 = m4 + k[0, 0] + 2 / h * c[0, 0], k[0, 1] + 2 / h * c[0, 1]
        K10, K11 = k[1, 0] + 2 / h * c[1, 0], m4 + k[1, 1] + 2 / h * c[1, 1]
        det = K00 * K11 - K01 * K10
        dx, dy = -(K11 * rx - K01 * ry) / det, -(K00 * ry - K10 * rx) / det
        ux, uy = ux + dx, uy + dy
        if abs(dx) + abs(dy) <= 1e-13 * (1.0 + abs(ux) + abs(uy)):
            break
    ax = 4 * (ux - y[0]) / (h * h) - 4 * y[2] / h - y[6]
    ay = 4 * (uy - y[1]) / (h * h) - 4 * y[3] / h - y[7]
    vx, vy = y[2] + 0.5 * h * (y[6] + ax), y[3] + 0.5 * h * (y[7] + ay)
    zx, zy, _ = fp._path_z(p, st, y[0], y[1], y[2], y[3], ux, uy, vx, vy, h)
    cnt.steps += 1
    return [ux, uy, vx, vy, zx, zy, ax, ay]


STEPS["newmark"] = step_newmark


# ================================================================================================
# 5. Measurements
# ================================================================================================


def gark_tableau():
    """dp5 + an implicit companion for z in GARK form (section 6 of the docs): see DP5_GARK."""
    tab = dp5_tableau()
    tab.name, tab.order = "dp5+I", 4
    tab.AI = np.array(DP5_GARK_A)
    tab.bI = tab.AI[-1].copy()
    tab.B = np.array(DP5_GARK_B)
    tab.explicit = False
    return tab


def run_case(tab, form, sc, segs, states, h):
    """Errors against the reference: end displacement, velocity, z; the force at every landed
    switch and at the end; and the counts."""
    y0 = list(sc.y0)
    if form == "newmark":
        sc_y = list(sc.y0)
        ax, ay = _accel(sc, sc.t0, sc_y[0], sc_y[1], sc_y[4], sc_y[5])
        y0 = sc_y + [ax, ay]
    t0 = time.perf_counter()
    with np.errstate(all="ignore"):
        out, cnt = _integrate_from(tab, form, sc, segs, h, y0)
    wall = time.perf_counter() - t0
    ref = states
    e_f = 0.0
    for a, b in zip(out[1:], ref[1:]):
        fa, fb = force(a[0], a[1], a[4], a[5]), force(b[0], b[1], b[4], b[5])
        e_f = max(e_f, math.hypot(fa[0] - fb[0], fa[1] - fb[1]))
    a, b = out[-1], ref[-1]
    e_u = math.hypot(a[0] - b[0], a[1] - b[1])
    e_v = math.hypot(a[2] - b[2], a[3] - b[3])
    e_z = math.hypot(a[4] - b[4], a[5] - b[5])
    bad = not all(math.isfinite(x) for x in a[:6]) or e_u > 1.0
    nan = float("nan")
    return {"e_u": nan if bad else e_u, "e_v": nan if bad else e_v,
            "e_z": nan if bad else e_z, "e_f": nan if bad else e_f, "cnt": cnt, "wall": wall}


def _integrate_from(tab, form, sc, segs, h, y0):
    _prepare(tab)
    cnt = Count()
    step = STEPS[form]
    y = list(y0)
    if sc.imposed is not None:
        y[:4] = sc.imposed(sc.t0)
    out = [list(y)]
    for k, (ta, tb, mode) in enumerate(segs):
        n = max(1, math.ceil((tb - ta) / h - 1e-9))
        hh = (tb - ta) / n
        for m in range(n):
            y = step(tab, sc, ta + m * hh, hh, y, mode, cnt)
        if mode == STICK and k + 1 < len(segs):
            nz = math.hypot(y[4], y[5])
            y[4], y[5] = y[4] / nz, y[5] / nz
        out.append(list(y))
    return out, cnt


def _fmt(e):
    return "unstable" if not math.isfinite(e) else f"{e:.1e}"


def _orders(errs):
    out = []
    for a, b in itertools.pairwise(errs):
        out.append(math.log2(a / b) if (math.isfinite(a) and math.isfinite(b) and a > 0 and b > 0)
                   else float("nan"))
    return out


def fitted_order(hs, errs, lo, hi):
    """Least-squares slope of log(err) on log(h) over lo <= h <= hi (finite errors only)."""
    pts = [(math.log(h), math.log(e)) for h, e in zip(hs, errs)
           if lo <= h * (1 + 1e-9) and h <= hi * (1 + 1e-9) and math.isfinite(e) and e > 0]
    if len(pts) < 2:
        return float("nan")
    x, y = np.array(pts).T
    return float(np.polyfit(x, y, 1)[0])


def scenario_table(sc, segs, states, methods, hs, results, key, unit):
    key, title = key.split(": ", 1)
    print(f"\n{key}: {title} [{unit}] (log2 ratio to the next step in brackets)\n")
    print("| method | " + " | ".join(f"h = {h * 1e3:g} ms" for h in hs) + " |")
    print("|---|" + "---|" * len(hs))
    for name, _, _ in methods:
        errs = [results[(sc.name, name, h)][key] for h in hs]
        od = _orders(errs)
        cells = []
        for i, e in enumerate(errs):
            o = f" ({od[i]:.1f})" if i < len(od) and math.isfinite(od[i]) else ""
            cells.append(_fmt(e) + o)
        print(f"| {name} | " + " | ".join(cells) + " |")


def methods_list():
    dp = dp5_tableau()
    out = [("path (femoat today, dp5)", dp, "path"), ("newmark+path (plan default)", dp, "newmark"),
           ("dp5-z (explicit)", dp, "z"), ("dp5-X (explicit)", dp, "X"),
           ("ark3 (KenCarp3)", ark324(), "z"), ("ark4 (KenCarp4)", ark436(), "z"),
           ("ark437 (KenCarp47)", ark437(), "z"), ("ark5 (KenCarp5)", ark548(), "z")]
    if DP5_GARK_A is not None:
        out.append(("dp5+I (GARK, here)", gark_tableau(), "z"))
    return out


# dp5 + an implicit companion for z in GARK form (Sandu & Günther 2015): the explicit stages
# are dp5's; implicit stage i (at dp5's c_i) solves z with the velocity v0 + h·Σ B_ij·a_j and
# gives explicit stage i its z; z_{n+1} is the last implicit stage (stiffly accurate). Found
# here by least squares (coupled order 4 on every bicoloured tree, checked in section 1;
# L-stable, A-stable on the imaginary axis, gamma = 0.275). A feasibility demonstration: not
# optimized (stage order 1, error constants free).
DP5_GARK_A = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [-0.07500000000000001, 0.275, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.1970591272403296, -0.17205912724032962, 0.275, 0.0, 0.0, 0.0, 0.0],
    [0.2679872769271119, 0.07568299436719945, 0.18132972870568861, 0.275, 0.0, 0.0, 0.0],
    [0.7742654933418114, 0.12450418333825802, -0.5399813552184215, 0.25510056742724085, 0.275, 0.0, 0.0],
    [0.7058328110793359, -0.11702251941534288, -0.1693460802636497, 0.4207046278702161, -0.11516883927055942, 0.275, 0.0],
    [0.05820185610049233, 0.10031805779525398, 0.40195592863872665, 0.2846943080120302, 0.20912117412410833, -0.32929132467061145, 0.275],
]
DP5_GARK_B = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [-0.1562487245463633, 0.4562487245463633, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.3242601995372946, -0.04106312428778795, 0.5168029247504934, 0.0, 0.0, 0.0, 0.0],
    [0.3727940627055134, -0.09481174083714378, 0.28264226179761126, 0.32826430522290795, 0.0, 0.0, 0.0],
    [0.28791373656496233, 0.3315691090474519, -0.17164922904881652, 0.2121983241903888, 0.3399680592460135, 0.0, 0.0],
    [0.15189524113964215, -0.15524170294051465, 0.32583966968981265, 0.3094296422177163, 0.2567970654466062, 0.11128008444673743, 0.0],
]


def main(full=False):
    t_start = time.perf_counter()
    tabs = [dp5_tableau(), ark324(), ark436(), ark437(), ark548()]
    if DP5_GARK_A is not None:
        tabs.append(gark_tableau())
    check_tableaus(tabs)
    hs = [0.01, 0.005, 0.0025, 0.00125, 0.000625] + ([0.0003125] if full else [])
    scens = [circle_scenario(), ellipse_scenario(), eight_scenario(),
             imposed_scenario("circle"), imposed_scenario("eight")]
    methods = methods_list()
    print("\n## 2. Scenarios (the bearing alone; reference DOP853 rtol 1e-13, switches located)\n")
    print("| scenario | interval [s] | stick/slip segments | max |v| [in/s] | max h·|v|/u_y at "
          "h = 5 ms | reference RHS evaluations |")
    print("|---|---|---|---|---|---|")
    refs = {}
    for sc in scens:
        segs, states, nfev = reference(sc)
        refs[sc.name] = (segs, states)
        vmax = _max_speed(sc, segs, states)
        print(f"| {sc.name} | {sc.t0:g}-{sc.t1:g} | {len(segs)} | {vmax:.1f} | "
              f"{0.005 * vmax / UY:.1f} | {nfev} |")
    results = {}
    print("\n## 3. Errors against the reference, fixed steps landed on the switches")
    for sc in scens:
        segs, states = refs[sc.name]
        meths = [m for m in methods if not (sc.imposed is not None and m[2] == "newmark")]
        for name, tab, form in meths:
            for h in hs:
                results[(sc.name, name, h)] = run_case(tab, form, sc, segs, states, h)
        print(f"\n### {sc.name}")
        scenario_table(sc, segs, states, meths, hs, results, "e_u: end displacement error", "in")
        scenario_table(sc, segs, states, meths, hs, results,
                       "e_f: force error, max over the switches and the end", "kip")
        if sc.imposed is not None:
            scenario_table(sc, segs, states, meths, hs, results, "e_z: end z error", "-")
    summary(scens, methods, hs, results)
    costs(scens, methods, hs, results)
    line_check([(n, t, f) for n, t, f in methods if f in ("z", "X")])
    print(f"\n(total {time.perf_counter() - t_start:.0f} s)")


def _max_speed(sc, segs, states):
    """The largest bearing speed |v| [in/s]: the prescribed path's, or over the reference's
    own steps."""
    if sc.imposed is not None:
        return max(math.hypot(*sc.imposed(t)[2:]) for t in np.linspace(sc.t0, sc.t1, 2001))
    return sc.vmax


def summary(scens, methods, hs, results):
    print("\n## 3b. Observed orders: least-squares slope of the force error e_f (and of e_u)\n")
    print("Stiff range: 0.625 <= h <= 5 ms (h·|v|/u_y ~ 1-15); asymptotic: the two smallest "
          "steps.\n")
    print("| method | " + " | ".join(sc.name for sc in scens) + " |")
    print("|---|" + "---|" * len(scens))
    for name, _, form in methods:
        cells = []
        for sc in scens:
            if (sc.name, name, hs[0]) not in results:
                cells.append("-")
                continue
            ef = [results[(sc.name, name, h)]["e_f"] for h in hs]
            eu = [results[(sc.name, name, h)]["e_u"] for h in hs]
            o1 = fitted_order(hs, ef, 0.000625, 0.005)
            o2 = _orders(ef)[-1]
            ou = fitted_order(hs, eu, 0.000625, 0.005)
            cells.append(f"{o1:.1f} / {o2:.1f} (u {ou:.1f})" if sc.imposed is None
                         else f"{o1:.1f} / {o2:.1f}")
        print(f"| {name} | " + " | ".join(cells) + " |")


def costs(scens, methods, hs, results):
    print("\n## 3c. Cost: evaluations per step, and the structure's force evaluations per "
          "simulated second for a given force error (log-log interpolation over h)\n")
    sc = next(s for s in scens if s.name == "eight")
    print(f"On '{sc.name}'.\n")
    print("| method | f_E / step | bearing rates / step | 2x2 Newton solves / step "
          "| f_E per s for e_f <= 1e-3 kip | <= 1e-5 kip | <= 1e-7 kip |")
    print("|---|---|---|---|---|---|---|")
    dur = sc.t1 - sc.t0
    for name, tab, form in methods:
        r = results[(sc.name, name, hs[2])]
        cnt = r["cnt"]
        per = []
        for target in (1e-3, 1e-5, 1e-7):
            per.append(_work_for(sc, name, hs, results, target, dur))
        print(f"| {name} | {cnt.f_e / cnt.steps:.1f} | {cnt.rate / cnt.steps:.1f} | "
              f"{cnt.newton / cnt.steps:.1f} | " + " | ".join(per) + " |")


def _work_for(sc, name, hs, results, target, dur):
    pts = []
    for h in hs:
        r = results[(sc.name, name, h)]
        if math.isfinite(r["e_f"]) and r["e_f"] > 0:
            pts.append((r["cnt"].f_e / dur, r["e_f"]))
    for (w1, e1), (w2, e2) in itertools.pairwise(pts):
        if e1 >= target >= e2 and e1 > e2:
            lw = math.log(w1) + (math.log(target) - math.log(e1)) * (
                math.log(w2) - math.log(w1)) / (math.log(e2) - math.log(e1))
            return f"{math.exp(lw):.0f}"
    if pts and pts[0][1] <= target:
        return f"<= {pts[0][0]:.0f}"
    return "> " + (f"{pts[-1][0]:.0f}" if pts else "-")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--full", action="store_true", help="also h = 0.3125 ms (twice the time)")
    main(ap.parse_args().full)
