"""Work-precision of integrator families on the paper model made elastic (issue 15). A script,
not a test.

    python benchmarks/method_families.py            # rtol 1e-3 .. 1e-8
    python benchmarks/method_families.py --quick    # rtol 1e-3, 1e-5, 1e-7 only
    python benchmarks/method_families.py --check-references   # + Radau at 1e-12 as a check

(the run times are printed at the end of the report).

Which family should femoat's higher-order integrator come from? The paper building (femoat's own
``paper_model("concrete", "E")``, packed) is made linear so that every method integrates a smooth
ODE y' = f(t, y), y = (u, v):

* isolator: the friction pendulum as a secant spring W/R + mu*W/D at D = 3 in, with the
  friction's equivalent viscous damping (Jacobsen: xi = 2 mu / (pi (mu + D/R)) of the isolated
  mass on the secant stiffness) as a dashpot to ground; stories: linear at their initial
  stiffness k0; the packed damping C (story dashpots c = beta*k0, the walls' C_imp) and masses
  unchanged;
* ground motion: ``paper_motion()`` (Erzincan N-S, 0.91 g, time-scaled by 0.5), a_g linear between
  samples as in the kernel; the run ends with the record (no free vibration after it).

Problems:

* P1  open phase, the real model: building + both SDOF walls (published C_imp), no contact
      (walls far away). The walls' dashpot makes the wall DOF overdamped: an eigenvalue near
      -C_imp/M1, which bounds an explicit method's step by stability, not accuracy.
* P1b open phase, building alone (the walls removed): the non-stiff problem of the issue's probe.
* P2  contact phase: P1 with the paper's 4 in gap (the elastic building's peak base displacement
      exceeds it, so the base mat hits both walls), contact a linear spring k_eff (the wall
      preset's contact law E, k_h*sqrt(delta_me)) in compression only, published C_imp: the
      overdamped wall clings to the base mat, few long contacts.
* P2c the same with the consistent C_imp (2 xi sqrt(K1 M1)): the wall is not stiff in the open
      phase, the contact is a ~1,200 rad/s oscillation, many short contacts: the stiff contact
      phase of the issue.
      k_eff*max(delta, 0) is only C0 at delta = 0, so P2 and P2c run with events: each contact
      closing/opening is located with the method's own dense output, the step redone to end on
      it, and the method restarted with the other (linear, smooth) right-hand side; every segment
      is smooth. (No run integrates the C0 force across contact changes.)

Steps and samples. "land": every step ends on a record sample (the solvers' t_bound is moved to
the next sample; the one-step methods keep their step size, FSAL stage and Jacobian across it;
BDF and LSODA keep their history, which then spans the slope jump of a_g). "cross": steps may
step over samples; states at the samples come from each method's dense output.

Peaks (every run, reference alike): max |base displacement|, max |story drift| per story, max
|absolute acceleration| of the base and of each floor, evaluated at the record samples; in P2 also
max |wall displacement| per wall and the peak contact force per wall, located at the zero of the
indentation rate inside contact with the dense output. A run's error is the worst relative peak
error, max_k |x_k - ref_k| / |ref_k|. Reference: DOP853 at rtol 1e-12 landing on samples;
``--check-references`` also runs Radau at rtol 1e-12 and prints the difference.

Tolerances: rtol as in the grid; atol = rtol * scale per component, scale 0.01 in for
displacements and 1 in/s for velocities; error norm: RMS of err / (atol + rtol*max(|y0|, |y1|))
(scipy's, used by the hand-written methods too).

Methods: scipy's RK23 (Bogacki-Shampine 3(2)), RK45 (Dormand-Prince 5(4)), DOP853, Radau
(Radau IIA, order 5), BDF, LSODA (Adams/BDF switching), each given the exact (constant per segment) Jacobian where it takes one;
hand-written here: Rodas4 (Hairer & Wanner's Rosenbrock method, 6 stages, order 4(3), stiffly
accurate, exact df/dt) and ESDIRK4(3)6L[2]SA (Kennedy & Carpenter 2003, "KenCarp4"'s implicit
part), both with the exact Jacobian, one LU of (I/(h*gamma) - J) resp. (I - h*gamma*J) per step
size (the step size kept while a change would be within [1, 1.2], and a sample interval divided
into equal steps, so the LU is reused), cubic Hermite dense output (f at the step end is the next
step's first stage: free). ESDIRK: one Newton iteration per stage with the exact Jacobian, exact
for this problem because it is linear in every segment (as the real kernel's open phase is with
element branches frozen during a step; a Hertz contact would need more); stage derivatives from
the stage equation, not from extra f evaluations.

Counts: steps (accepted), rejected (attempts - accepted; LSODA does not report attempts), f
evaluations (including those for dense output, and for df/dt: none, it is analytic), Jacobian
evaluations, LU factorizations, LU solves (Radau's complex solves counted as one each), CPU time
(time.process_time of the Python run: Python overhead dominates; it is not the kernel's cost).

Cost model: the numba-compiled cost of one f evaluation, one LU factorization and one LU solve of
this system (measured here), turning the counts into an expected kernel CPU per run.

Order checks (fixed steps): the hand-written methods on a damped 3-DOF linear system, free and
forced by a sine, against the closed form (expm of the augmented matrix); measured log-log slope
of the final error against the step size. DP5 with fixed steps on P1b, steps ending on every
sample vs stepping over them (h = 1.5 dt/N), against DP5 at dt/16: measured slope. And adaptive
RK45 landing vs crossing at equal rtol.

Writes benchmarks/results/method_families.txt (the printed report).
"""

import argparse
import io
import math
import os
import sys
import time

import numpy as np
from scipy.integrate import BDF, DOP853, LSODA, RK23, RK45, Radau
from scipy.integrate._ivp import bdf as _bdf
from scipy.integrate._ivp import radau as _radau
from scipy.integrate._ivp import rk as _rk
from scipy.linalg import expm, lu_factor, lu_solve
from scipy.optimize import brentq

from femoat.paper import paper_model, paper_motion
from femoat.structure.materials import FrictionPendulum
from femoat.structure.pounding import PoundingModel
from femoat.units import G

D_SECANT = 3.0  # representative isolator displacement for the secant stiffness [in]
U_SCALE, V_SCALE = 0.01, 1.0  # atol = rtol * scale: displacements [in], velocities [in/s]
FIRST_STEP = 1e-4  # every method's first step [s]

# ---------------------------------------------------------------------------------------------
# attempt counters (scipy does not report rejected steps)
ATTEMPTS = [0]


def _counting(fn):
    def wrapped(*a, **k):
        ATTEMPTS[0] += 1
        return fn(*a, **k)
    return wrapped


_rk.rk_step = _counting(_rk.rk_step)
_radau.solve_collocation_system = _counting(_radau.solve_collocation_system)
_bdf.solve_bdf_system = _counting(_bdf.solve_bdf_system)


# ---------------------------------------------------------------------------------------------
# the model
class Problem:
    """y' = A_m y + e a_g(t) + g_m for contact mode m (a tuple of closed flags)."""

    def __init__(self, name, packed, contacts, ag, dt, T):
        self.name, self.ag, self.dt, self.T = name, ag, dt, T
        p = packed
        n = p.n
        self.n = n
        K = p.K.copy()
        for i, j, mat in zip(p.el_i, p.el_j, p.el_materials):
            if isinstance(mat, FrictionPendulum):
                k = mat.W / mat.R + mat.mu * mat.W / D_SECANT
            else:
                k = mat.initial_stiffness
            K[i, i] += k
            if j >= 0:
                K[j, j] += k
                K[i, j] -= k
                K[j, i] -= k
        C = p.C.copy()
        for i, j, mat in zip(p.el_i, p.el_j, p.el_materials):
            if isinstance(mat, FrictionPendulum) and j < 0:
                # the friction's equivalent viscous damping (Jacobsen) at D: a dashpot to ground
                k_sec = mat.W / mat.R + mat.mu * mat.W / D_SECANT
                xi = 2 * mat.mu / (math.pi * (mat.mu + D_SECANT / mat.R))
                C[i, i] += 2 * xi * math.sqrt(k_sec * mat.W / G)
        self.M, self.C, self.K, self.r = p.M, C, K, p.r
        self.Minv = np.linalg.inv(p.M)
        self.contacts = contacts  # list of (b, gap, k)
        self.e = np.concatenate([np.zeros(n), -self.Minv @ p.r])
        self.scale = np.concatenate([np.full(n, U_SCALE), np.full(n, V_SCALE)])
        self.n_struct = p.n_struct
        self.wall_dofs = list(range(p.n_struct, n)) if contacts else []
        self._modes = {}
        self.samples = np.arange(int(math.floor(T / dt + 1e-9)) + 1) * dt
        self.samples[-1] = min(self.samples[-1], T)

    def mode(self, closed):
        if closed not in self._modes:
            n = self.n
            Ks = self.K.copy()
            force = np.zeros(n)
            for (b, gap, k), c in zip(self.contacts, closed):
                if c:
                    Ks += k * np.outer(b, b)
                    force += k * gap * b
            A = np.zeros((2 * n, 2 * n))
            A[:n, n:] = np.eye(n)
            A[n:, :n] = -self.Minv @ Ks
            A[n:, n:] = -self.Minv @ self.C
            g = np.concatenate([np.zeros(n), self.Minv @ force])
            self._modes[closed] = (A, g)
        return self._modes[closed]

    def ag_at(self, t):
        x = t / self.dt
        i = int(x)
        ag = self.ag
        if i >= ag.size - 1:
            return ag[-1] if i == ag.size - 1 and x - i < 1e-9 else 0.0
        w = x - i
        return (1.0 - w) * ag[i] + w * ag[i + 1]

    def ag_slope(self, t):
        """Right derivative of a_g at t."""
        i = int(t / self.dt + 1e-9)
        if i >= self.ag.size - 1:
            return 0.0
        return (self.ag[i + 1] - self.ag[i]) / self.dt

    def rhs(self, closed):
        A, g = self.mode(closed)
        e, ag_at = self.e, self.ag_at

        def f(t, y):
            return A @ y + e * ag_at(t) + g

        def ft(t, y):
            return e * self.ag_slope(t)
        return f, ft, A

    def indentation(self, y):
        n = self.n
        return np.array([b @ y[:n] - gap for b, gap, _ in self.contacts])

    def indentation_rate(self, y):
        n = self.n
        return np.array([b @ y[n:] for b, _, _ in self.contacts])

    def peak_values(self, Y, ts, closed):
        """Peak channels of states Y (rows) at times ts under contact mode ``closed``."""
        n = self.n
        A, g = self.mode(closed)
        ag = np.array([self.ag_at(t) for t in ts])
        acc = (Y @ A.T)[:, n:] + (self.e[n:][None, :] * ag[:, None]) + g[n:][None, :]
        u = Y[:, :n]
        ns = self.n_struct
        out = [np.abs(u[:, 0])]
        out += [np.abs(u[:, k + 1] - u[:, k]) for k in range(ns - 1)]
        out += [np.abs(acc[:, k] + ag) for k in range(ns)]
        out += [np.abs(u[:, j]) for j in self.wall_dofs]
        return np.array([o.max() for o in out])

    def channel_names(self):
        ns = self.n_struct
        names = ["u_base"] + [f"drift{k + 1}" for k in range(ns - 1)]
        names += ["a_base"] + [f"a_floor{k}" for k in range(1, ns)]
        names += [f"u_wall{j - ns + 1}" for j in self.wall_dofs]
        names += [f"F_contact{c + 1}" for c in range(len(self.contacts))]
        return names


def make_problems(quick=False):
    gm = paper_motion()
    ag = np.asarray(gm.accel_g, float) * G
    dt = gm.dt
    T = (ag.size - 1) * dt
    model = paper_model("concrete", "E")
    p1 = Problem("P1", model.pack(), [], ag, dt, T)
    bare = PoundingModel(model.building, ())
    p1b = Problem("P1b", bare.pack(), [], ag, dt, T)
    return p1, p1b, model, ag, dt, T


def make_contact_problem(model, ag, dt, T, gap):
    packed = model.pack()
    contacts = []
    for row, w, k in zip(packed.c_B, model.walls, packed.c_P[:, 0]):
        contacts.append((row.copy(), gap, float(k)))
    return Problem("P2", packed, contacts, ag, dt, T)


# ---------------------------------------------------------------------------------------------
# hand-written methods (same interface as scipy's OdeSolver, the parts the driver uses)
class _Hermite:
    def __init__(self, t0, y0, f0, t1, y1, f1):
        self.t0, self.h = t0, t1 - t0
        self.y0, self.y1, self.f0, self.f1 = y0, y1, f0, f1

    def __call__(self, t):
        t = np.asarray(t, float)
        s = (t - self.t0) / self.h
        h00 = (1 + 2 * s) * (1 - s) ** 2
        h10 = s * (1 - s) ** 2
        h01 = s * s * (3 - 2 * s)
        h11 = s * s * (s - 1)
        if s.ndim == 0:
            return h00 * self.y0 + h10 * self.h * self.f0 + h01 * self.y1 + h11 * self.h * self.f1
        return (np.outer(self.y0, h00) + np.outer(self.h * self.f0, h10)
                + np.outer(self.y1, h01) + np.outer(self.h * self.f1, h11))


class _OneStep:
    """Adaptive one-step driver with the exact constant Jacobian J and LU caching by step size."""

    order_err = 3  # order of the embedded solution: error ~ h^(q+1)

    def __init__(self, fun, t0, y0, t_bound, first_step, rtol, atol, jac, ft, fixed=False):
        self.nfev = 0
        self._f = fun
        self.ft = ft
        self.t, self.y = t0, np.array(y0, float)
        self.t_bound = t_bound
        self.rtol, self.atol = rtol, atol
        self.J = jac
        self.njev, self.nlu, self.nsolve, self.attempts = 1, 0, 0, 0
        self.h = first_step
        self.step_size = first_step
        self.status = "running"
        self.fixed = fixed
        self.fy = self.fun(t0, self.y)
        self._lu_h = None
        self._lu = None
        self.t_old = None
        self._dense = None

    def fun(self, t, y):
        self.nfev += 1
        return self._f(t, y)

    def _factor(self, h):
        if self._lu_h is None or abs(h - self._lu_h) > 1e-9 * h:  # sample ends round off
            self._lu = lu_factor(self._matrix(h))
            self._lu_h = h
            self.nlu += 1
        return self._lu

    def _solve(self, b):
        self.nsolve += 1
        return lu_solve(self._lu, b)

    def step(self):
        t, y = self.t, self.y
        remaining = self.t_bound - t
        while True:
            h = self.h
            if h >= remaining * (1 - 1e-12):
                hs = remaining
            else:
                hs = remaining / math.ceil(remaining / h - 1e-9)
            self.attempts += 1
            y1, err = self._attempt(t, y, hs)
            if self.fixed:
                en = 0.0
            else:
                sc = self.atol + self.rtol * np.maximum(np.abs(y), np.abs(y1))
                en = np.sqrt(np.mean((err / sc) ** 2))
            if en <= 1.0:
                break
            self.h = hs * max(0.2, 0.9 * en ** (-1.0 / (self.order_err + 1)))
        if not self.fixed:
            fac = 5.0 if en == 0 else min(5.0, max(0.2, 0.9 * en ** (-1.0 / (self.order_err + 1))))
            hn = hs * fac
            # keep the step size (and its LU) unless a change is worth it
            if not (1.0 <= hn / self.h <= 1.2):
                self.h = hn
        f1 = self._f1
        self._dense = (t, y, self.fy, t + hs, y1, f1)
        self.t_old = t
        self.t = t + hs if hs != remaining else self.t_bound
        self.y = y1
        self.fy = f1
        self.step_size = hs
        if self.t >= self.t_bound:
            self.status = "finished"
        return None

    def dense_output(self):
        return _Hermite(*self._dense)


class Rodas4(_OneStep):
    """Hairer & Wanner's Rodas4 (RODAS, E. Hairer, G. Wanner: Solving ODEs II, Sec. IV.7),
    transformed form: (I/(h*gamma) - J) k_i = f(t + c_i h, y + sum a_ij k_j)
    + sum (C_ij/h) k_j + h d_i f_t; y1 = y + sum a_6j k_j + k5 + k6 (stiffly accurate), error k6."""

    gamma = 0.25
    c = (0.0, 0.386, 0.21, 0.63, 1.0, 1.0)
    d = (0.25, -0.1043, 0.1035, -0.0362, 0.0, 0.0)
    a = ((),
         (1.544,),
         (0.9466785280815826, 0.2557011698983284),
         (3.314825187068521, 2.896124015972201, 0.9986419139977817),
         (1.221224509226641, 6.019134481288629, 12.53708332932087, -0.6878860361058950))
    C = ((),
         (-5.6688,),
         (-2.430093356833875, -0.2063599157091915),
         (-0.1073529058151375, -9.594562251023355, -20.47028614809616),
         (7.496443313967647, -10.24680431464352, -33.99990352819905, 11.70890893206160),
         (8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136,
          -6.058818238834054))

    def _matrix(self, h):
        return np.eye(self.J.shape[0]) / (h * self.gamma) - self.J

    def _attempt(self, t, y, h):
        self._factor(h)
        ft = self.ft(t, y)
        k = []
        for i in range(6):
            if i == 0:
                rhs = self.fy + h * self.d[0] * ft
            else:
                if i < 5:
                    yi = y + sum(aij * kj for aij, kj in zip(self.a[i], k))
                else:
                    yi = y5 + k[4]
                if i == 4:
                    y5 = yi
                rhs = self.fun(t + self.c[i] * h, yi) + sum(cij / h * kj for cij, kj in zip(self.C[i], k))
                if self.d[i]:
                    rhs = rhs + h * self.d[i] * ft
            k.append(self._solve(rhs))
        y1 = y5 + k[4] + k[5]
        self._f1 = self.fun(t + h, y1)
        return y1, k[5]


class ESDIRK43(_OneStep):
    """Kennedy & Carpenter (2003) ESDIRK4(3)6L[2]SA, the implicit part of ARK4(3)6L[2]SA:
    gamma = 1/4, stiffly accurate, L-stable."""

    gamma = 0.25
    c = (0.0, 0.5, 83 / 250, 31 / 50, 17 / 20, 1.0)
    A = ((),
         (0.25,),
         (8611 / 62500, -1743 / 31250),
         (5012029 / 34652500, -654441 / 2922500, 174375 / 388108),
         (15267082809 / 155376265600, -71443401 / 120774400, 730878875 / 902184768,
          2285395 / 8070912),
         (82889 / 524892, 0.0, 15625 / 83664, 69875 / 102672, -2260 / 8211))
    bhat = (4586570599 / 29645900160, 0.0, 178811875 / 945068544, 814220225 / 1159782912,
            -3700637 / 11593932, 61727 / 225920)

    def _matrix(self, h):
        return np.eye(self.J.shape[0]) - h * self.gamma * self.J

    def _attempt(self, t, y, h):
        self._factor(h)
        F = [self.fy]
        hg = h * self.gamma
        for i in range(1, 6):
            base = y + h * sum(aij * Fj for aij, Fj in zip(self.A[i], F))
            Y = base + hg * F[-1]  # predictor
            res = Y - base - hg * self.fun(t + self.c[i] * h, Y)
            Y = Y - self._solve(res)  # one Newton iteration: exact for a linear f
            F.append((Y - base) / hg)
        b = self.A[5] + (self.gamma,)
        err = h * sum((bj - bh) * Fj for bj, bh, Fj in zip(b, self.bhat, F))
        self._f1 = F[5]
        return Y, err


# ---------------------------------------------------------------------------------------------
# the driver
SCIPY = {"RK23": RK23, "RK45": RK45, "DOP853": DOP853, "Radau": Radau, "BDF": BDF, "LSODA": LSODA}
HAND = {"Rodas4": Rodas4, "ESDIRK43": ESDIRK43}
IMPLICIT = ("Radau", "BDF", "LSODA", "Rodas4", "ESDIRK43")


def _new_solver(method, prob, closed, t0, y0, t_bound, first_step, rtol):
    f, ft, A = prob.rhs(closed)
    atol = rtol * prob.scale
    first_step = min(first_step, t_bound - t0)
    if method in HAND:
        return HAND[method](f, t0, y0, t_bound, first_step, rtol, atol, A, ft)
    kw = {}
    if method in ("Radau", "BDF"):
        kw["jac"] = A
    elif method == "LSODA":
        kw["jac"] = lambda t, y: A
    s = SCIPY[method](f, t0, y0, t_bound, first_step=first_step, rtol=rtol, atol=atol, **kw)
    s.nsolve = 0
    if hasattr(s, "solve_lu"):
        inner = s.solve_lu

        def counted(LU, b, _s=s, _inner=inner):
            _s.nsolve += 1
            return _inner(LU, b)
        s.solve_lu = counted
    return s


def _set_bound(s, t_bound):
    s.t_bound = t_bound
    s.status = "running"
    if isinstance(s, LSODA):
        s._lsoda_solver._integrator.rwork[0] = t_bound
        s._lsoda_solver._integrator.call_args[4] = s._lsoda_solver._integrator.rwork


def integrate(prob, method, rtol, land=True):
    """Run one method; returns (peaks, stats)."""
    ATTEMPTS[0] = 0
    cpu0 = time.process_time()
    n2 = 2 * prob.n
    samples, T = prob.samples, prob.T
    nc = len(prob.contacts)
    closed = tuple(False for _ in range(nc))
    peaks = np.zeros(len(prob.channel_names()) - nc)
    fpeak = np.zeros(nc)
    solvers = []
    accepted = [0]
    in_contact = [0]
    events = [0]
    k_next = [1]  # index of the next sample not yet recorded

    def next_bound(t):
        if not land:
            return T
        i = int(math.floor(t / prob.dt + 1e-7)) + 1
        if i < samples.size and samples[i] - t < 1e-9 * prob.dt:
            i += 1
        return samples[i] if i < samples.size else T

    def handle(s, t0, y0, closed):
        """Peaks of an accepted step [t0, s.t]."""
        t1, y1 = s.t, s.y
        accepted[0] += 1
        in_contact[0] += any(closed)
        sol = None
        k = k_next[0]
        j = k
        while j < samples.size and samples[j] <= t1 + 1e-12:
            j += 1
        if j > k:
            ts = samples[k:j]
            if land or abs(ts[-1] - t1) < 1e-12 and j - k == 1:
                Y = y1[None, :]
            else:
                sol = s.dense_output()
                Y = np.asarray(sol(ts)).T
                if abs(ts[-1] - t1) < 1e-12:
                    Y[-1] = y1
            np.maximum(peaks, prob.peak_values(Y, ts, closed), out=peaks)
            k_next[0] = j
        for c in range(nc):
            if closed[c]:
                b = prob.contacts[c][0]
                kc, gap = prob.contacts[c][2], prob.contacts[c][1]
                n = prob.n
                r0, r1 = b @ y0[n:], b @ y1[n:]
                fpeak[c] = max(fpeak[c], kc * (b @ y1[:n] - gap))
                if r0 > 0 >= r1:
                    if sol is None:
                        sol = s.dense_output()
                    tr = brentq(lambda t: b @ sol(t)[n:], t0, t1, xtol=1e-13)
                    fpeak[c] = max(fpeak[c], kc * (b @ sol(tr)[:n] - gap))

    t, y = 0.0, np.zeros(n2)
    h = FIRST_STEP
    s = _new_solver(method, prob, closed, t, y, next_bound(t), h, rtol)
    solvers.append(s)
    while True:
        t0, y0 = s.t, s.y.copy()
        msg = s.step()
        if s.status == "failed":
            raise RuntimeError(f"{method} failed at t = {t0}: {msg}")
        if s.status == "running" and 0 < s.t_bound - s.t < 1e-9 * prob.dt:
            s.t, s.status = s.t_bound, "finished"  # t + (t_bound - t) rounded below t_bound
        t1, y1 = s.t, s.y
        if nc:
            d0, d1 = prob.indentation(y0), prob.indentation(y1)
            hit = [c for c in range(nc) if (d1[c] < 0 if closed[c] else d1[c] >= 0)]
        else:
            hit = []
        if hit:
            sol = s.dense_output()
            n = prob.n
            te, ce = t1, None
            for c in hit:
                b, gap, _ = prob.contacts[c]
                g = lambda tt: b @ sol(tt)[:n] - gap  # noqa: E731
                if (g(t0) < 0) == (g(t1) < 0):
                    tc = t0  # no bracket: a graze at the segment's start
                else:
                    tc = brentq(g, t0, t1, xtol=1e-13)
                if tc < te:
                    te, ce = tc, c
            h_last = s.step_size
            if te - t0 > 1e-12:
                # redo the step to end on the event
                r = _new_solver(method, prob, closed, t0, y0, te, te - t0, rtol)
                solvers.append(r)
                while r.status == "running":
                    ta, ya = r.t, r.y.copy()
                    r.step()
                    if r.status == "running" and 0 < r.t_bound - r.t < 1e-9 * prob.dt:
                        r.t, r.status = r.t_bound, "finished"
                    if r.status == "failed":
                        raise RuntimeError(f"{method} failed at t = {ta}")
                    handle(r, ta, ya, closed)
                t, y = r.t, r.y.copy()
            else:
                t, y = t0, y0
            events[0] += 1
            closed = tuple((not cl) if c == ce else cl for c, cl in enumerate(closed))
            s = _new_solver(method, prob, closed, t, y, next_bound(t), max(h_last, 1e-9), rtol)
            solvers.append(s)
            continue
        handle(s, t0, y0, closed)
        if s.status == "finished":
            if t1 >= T - 1e-12:
                break
            _set_bound(s, next_bound(t1))
    cpu = time.process_time() - cpu0
    nfev = sum(x.nfev for x in solvers)
    njev = sum(getattr(x, "njev", 0) or 0 for x in solvers)
    if method in ("Radau", "BDF"):
        njev = len(solvers)  # the constant Jacobian of each segment, given once
    nlu = sum(getattr(x, "nlu", 0) or 0 for x in solvers)
    nsolve = sum(getattr(x, "nsolve", 0) for x in solvers)
    if method in HAND:
        attempts = sum(x.attempts for x in solvers)
    elif method == "LSODA":
        attempts = None
    else:
        attempts = ATTEMPTS[0]
    if method in ("RK23", "RK45", "DOP853"):
        njev = nlu = nsolve = 0
    stats = dict(steps=accepted[0], rejected=None if attempts is None else attempts - accepted[0],
                 nfev=nfev, njev=njev, nlu=nlu, nsolve=nsolve, cpu=cpu, events=events[0],
                 contact_steps=in_contact[0], y_end=s.y.copy())
    return np.concatenate([peaks, fpeak]), stats


# ---------------------------------------------------------------------------------------------
# order checks
def order_check(method_cls, forced):
    """Fixed-step final error on a damped 3-DOF system (forced: + e*sin(w t)); returns
    (hs, errors, slope)."""
    Mm = np.diag([1.0, 1.5, 2.0])
    Kk = np.array([[300.0, -150.0, 0.0], [-150.0, 400.0, -250.0], [0.0, -250.0, 250.0]])
    Cc = 0.02 * Kk + 0.1 * Mm
    n = 3
    Mi = np.linalg.inv(Mm)
    A = np.zeros((6, 6))
    A[:3, 3:] = np.eye(3)
    A[3:, :3] = -Mi @ Kk
    A[3:, 3:] = -Mi @ Cc
    e = np.concatenate([np.zeros(n), Mi @ np.array([1.0, 0.5, -0.3])]) * 50.0
    w = 7.0
    y0 = np.array([0.1, -0.05, 0.2, 0.0, 1.0, -0.5])
    T = 1.0
    if forced:
        Aa = np.zeros((8, 8))
        Aa[:6, :6] = A
        Aa[:6, 6] = e
        Aa[6, 7] = w
        Aa[7, 6] = -w
        exact = (expm(Aa * T) @ np.concatenate([y0, [0.0, 1.0]]))[:6]

        def f(t, y):
            return A @ y + e * math.sin(w * t)

        def ft(t, y):
            return e * w * math.cos(w * t)
    else:
        exact = expm(A * T) @ y0

        def f(t, y):
            return A @ y

        def ft(t, y):
            return np.zeros(6)
    Ns = [20, 40, 80, 160, 320]
    errs = []
    for N in Ns:
        s = method_cls(f, 0.0, y0, T, T / N, 1.0, np.ones(6), A, ft, fixed=True)
        while s.status == "running":
            s.step()
        errs.append(np.max(np.abs(s.y - exact)))
    hs = [T / N for N in Ns]
    slope = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    return hs, errs, slope


# ---------------------------------------------------------------------------------------------
def dp5_fixed(prob, num, den):
    """Fixed-step Dormand-Prince 5 (scipy's RK45 tableau) on an open problem, h = (num/den)*dt
    from t = 0 (den/num integer: steps end on every sample; else they step over samples);
    returns the displacements at the step ends, (steps, n)."""
    f, _, _ = prob.rhs(())
    y = np.zeros(2 * prob.n)
    K = np.empty((RK45.n_stages + 1, y.size))
    steps = int(math.floor((prob.samples.size - 1) * den / num + 1e-9))
    h = num * prob.dt / den
    t, fy = 0.0, f(0.0, y)
    out = np.empty((steps, prob.n))
    for k in range(steps):
        t1 = (k + 1) * h
        y, fy = _rk.rk_step(f, t, y, fy, t1 - t, RK45.A, RK45.B, RK45.C, K)
        t = t1
        out[k] = y[:prob.n]
    return out

# ---------------------------------------------------------------------------------------------
# cost model (numba)
def cost_model(n2):
    import numba

    @numba.njit(cache=False)
    def rhs(t, y, A, e, g, ag, dt, out):
        x = t / dt
        i = int(x)
        a = 0.0
        if i < ag.size - 1:
            w = x - i
            a = (1.0 - w) * ag[i] + w * ag[i + 1]
        m = y.size
        for r in range(m):
            s = e[r] * a + g[r]
            for c in range(m):
                s += A[r, c] * y[c]
            out[r] = s

    @numba.njit(cache=False)
    def lu(Ain, LUm, piv):
        m = Ain.shape[0]
        LUm[:, :] = Ain
        for k in range(m):
            p = k
            for r in range(k + 1, m):
                if abs(LUm[r, k]) > abs(LUm[p, k]):
                    p = r
            piv[k] = p
            if p != k:
                for c in range(m):
                    tmp = LUm[k, c]
                    LUm[k, c] = LUm[p, c]
                    LUm[p, c] = tmp
            for r in range(k + 1, m):
                LUm[r, k] /= LUm[k, k]
                lrk = LUm[r, k]
                for c in range(k + 1, m):
                    LUm[r, c] -= lrk * LUm[k, c]

    @numba.njit(cache=False)
    def lusolve(LUm, piv, b):
        m = b.size
        for k in range(m):
            p = piv[k]
            if p != k:
                tmp = b[k]
                b[k] = b[p]
                b[p] = tmp
        for r in range(m):
            for c in range(r):
                b[r] -= LUm[r, c] * b[c]
        for r in range(m - 1, -1, -1):
            for c in range(r + 1, m):
                b[r] -= LUm[r, c] * b[c]
            b[r] /= LUm[r, r]

    @numba.njit(cache=False)
    def bench_rhs(N, y, A, e, g, ag, dt, out):
        acc = 0.0
        for k in range(N):
            rhs(1e-3 * (k % 1000), y, A, e, g, ag, dt, out)
            acc += out[0]
            y[0] = out[0] * 1e-12
        return acc

    @numba.njit(cache=False)
    def bench_lu(N, Ain, LUm, piv):
        acc = 0.0
        for k in range(N):
            Ain[0, 0] += 1e-12
            lu(Ain, LUm, piv)
            acc += LUm[0, 0]
        return acc

    @numba.njit(cache=False)
    def bench_solve(N, LUm, piv, b):
        acc = 0.0
        for k in range(N):
            b[0] += 1.0
            lusolve(LUm, piv, b)
            acc += b[0]
        return acc

    rng = np.random.default_rng(0)
    A = rng.standard_normal((n2, n2))
    e, g = rng.standard_normal(n2), rng.standard_normal(n2)
    ag = rng.standard_normal(5000)
    y, out = rng.standard_normal(n2), np.zeros(n2)
    W = np.eye(n2) * 10 + A
    LUm, piv = np.zeros((n2, n2)), np.zeros(n2, np.int64)
    b = rng.standard_normal(n2)
    bench_rhs(10, y, A, e, g, ag, 2.5e-3, out)
    bench_lu(10, W, LUm, piv)
    bench_solve(10, LUm, piv, b)
    res = {}
    for name, fn, args in (("rhs", bench_rhs, (y, A, e, g, ag, 2.5e-3, out)),
                           ("lu", bench_lu, (W, LUm, piv)),
                           ("solve", bench_solve, (LUm, piv, b))):
        N = 200000
        best = math.inf
        for _ in range(3):
            c0 = time.process_time()
            fn(N, *args)
            best = min(best, (time.process_time() - c0) / N)
        res[name] = best
    return res


# ---------------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="rtol 1e-3, 1e-5, 1e-7 only")
    ap.add_argument("--check-references", action="store_true",
                    help="also run Radau at rtol 1e-12 (several minutes) and print its worst "
                         "relative peak difference from the reference")
    args = ap.parse_args()
    out = io.StringIO()
    t_start = time.time()

    def say(*a):
        print(*a)
        print(*a, file=out)
        sys.stdout.flush()

    rtols = [1e-3, 1e-5, 1e-7] if args.quick else [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
    methods = ["RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA", "Rodas4", "ESDIRK43"]
    say("method_families.py: integrator families on the paper model made elastic (issue 15)")
    say(f"rtol grid {rtols}; atol = rtol*[{U_SCALE} in, {V_SCALE} in/s]; isolator secant at "
        f"D = {D_SECANT} in; first step {FIRST_STEP} s")

    # order checks
    say("\n== Measured order of the hand-written methods (fixed steps, h = 1/20 .. 1/320) ==")
    for cls in (Rodas4, ESDIRK43):
        for forced in (False, True):
            hs, errs, slope = order_check(cls, forced)
            say(f"{cls.__name__:9s} {'forced (sin)' if forced else 'free        '}: max-norm errors at "
                "T = 1: " + " ".join(f"{x:.2e}" for x in errs) + f"  slope {slope:.2f}")

    p1, p1b, model, ag, dt, T = make_problems()
    gap = 4.0
    p2 = make_contact_problem(model, ag, dt, T, gap)
    model_c = paper_model("concrete", "E", damping="consistent")
    p2c = make_contact_problem(model_c, ag, dt, T, gap)
    p2c.name = "P2c"
    problems = {"P1": p1, "P1b": p1b, "P2": p2, "P2c": p2c}
    say(f"\nrecord: {ag.size} samples, dt = {dt} s, T = {T:.4f} s (record only); P2/P2c gap "
        f"{gap} in, k_eff = {p2.contacts[0][2]:.1f} kip/in; P2 published C_imp "
        f"{model.walls[0].wall.damping} kip s/in, P2c consistent C_imp "
        f"{model_c.walls[0].wall.damping:.3f} kip s/in")
    for p in problems.values():
        for closed in ((), (True, False)) if p.contacts else ((),):
            if p.contacts and not closed:
                closed = (False, False)
            A, _ = p.mode(closed)
            ev = np.linalg.eigvals(A)
            say(f"{p.name:4s}: n = {p.n} DOF, {'one contact closed' if any(closed) else 'open'}: "
                f"max |lambda| = {np.abs(ev).max():6.0f} 1/s, most negative real part "
                f"{ev.real.min():6.0f} 1/s, max |Im| = {np.abs(ev.imag).max():5.0f} rad/s")

    # references
    refs = {}
    say("")
    for p in problems.values():
        rm, cm_ = "DOP853", "Radau"
        pk, st = integrate(p, rm, 1e-12)
        refs[p.name] = (pk, st["y_end"])
        check = ""
        if args.check_references:
            pkc, _ = integrate(p, cm_, 1e-12)
            check = f"{cm_} at 1e-12 differs by {np.max(np.abs(pkc - pk) / np.abs(pk)):.1e}; "
        say(f"{p.name:4s} reference {rm} rtol 1e-12: {st['steps']} steps ({st['contact_steps']} in "
            f"contact), {st['events']} contact events; {check}peaks "
            + ", ".join(f"{n}={v:.5g}" for n, v in zip(p.channel_names(), pk)))

    rows = []
    runs = [(pn, m, True) for pn in problems for m in methods]
    runs += [(pn, m, False) for pn in ("P1b", "P2c") for m in ("RK45", "DOP853", "Radau", "Rodas4")]
    runs += [("P1", "RK45", False)]
    for pn, m, land in runs:
        p = problems[pn]
        for rt in rtols:
            try:
                pk, st = integrate(p, m, rt, land)
                rel = np.abs(pk - refs[pn][0]) / np.abs(refs[pn][0])
                err, worst = float(rel.max()), p.channel_names()[int(rel.argmax())]
            except Exception as exc:  # a failed run is a result too
                st, err, worst = dict(error=str(exc)), math.nan, "-"
            rows.append(dict(problem=pn, method=m, land=land, rtol=rt, err=err, worst=worst, **st))
            r = rows[-1]
            if "error" in r:
                say(f"{pn:4s} {m:8s} {'land' if land else 'cross'} rtol {rt:.0e}: FAILED {r['error']}")

    cm = cost_model(2 * p2.n)

    def kernel_us(r):
        return 1e6 * (r["nfev"] * cm["rhs"] + r["nlu"] * cm["lu"] + r["nsolve"] * cm["solve"])

    say("\n== All runs (err: worst relative peak error; worst: its channel; c-steps: steps in "
        "contact; kernel us: f*X + LU*Y + solves*Z of the cost model) ==")
    say(f"{'prob':4s} {'method':8s} {'mode':5s} {'rtol':>6s} {'err':>8s} {'worst':>10s} "
        f"{'steps':>6s} {'rej':>5s} {'f':>7s} {'jac':>5s} {'LU':>6s} {'solves':>7s} "
        f"{'events':>6s} {'c-steps':>7s} {'kern us':>7s} {'cpu s':>6s}")
    for r in rows:
        if "error" in r:
            continue
        rej = "-" if r["rejected"] is None else str(r["rejected"])
        say(f"{r['problem']:4s} {r['method']:8s} {'land' if r['land'] else 'cross':5s} "
            f"{r['rtol']:6.0e} {r['err']:8.1e} {r['worst']:>10s} {r['steps']:6d} {rej:>5s} "
            f"{r['nfev']:7d} {int(r['njev']):5d} {int(r['nlu']):6d} {r['nsolve']:7d} "
            f"{r['events']:6d} {r['contact_steps']:7d} {kernel_us(r):7.0f} {r['cpu']:6.2f}")

    say(f"\n== Cost model (numba, a dense y' = A y + e a_g(t) + g of size {2 * p2.n}, the n = "
        f"{p2.n} DOF model; best of 3 x 200000 calls) ==")
    say(f"X = one f evaluation {cm['rhs'] * 1e9:.0f} ns; Y = one LU factorization "
        f"{cm['lu'] * 1e9:.0f} ns; Z = one LU solve {cm['solve'] * 1e9:.0f} ns (Radau's complex "
        "LU and solves cost ~4x these; step overhead, error norm, events and peaks not included)")

    say("\n== Work-precision: the cheapest run (by kernel estimate) with every peak within the "
        "target ==")
    say("cell: steps / f evals / LU / kernel us @rtol; '-': no rtol of the grid reached it")
    for pn in problems:
        for land in (True, False):
            sub = [r for r in rows if r["problem"] == pn and r["land"] == land and "error" not in r]
            if not sub:
                continue
            say(f"-- {pn} ({'steps end on samples' if land else 'steps cross samples'})")
            for m in methods:
                mr = [r for r in sub if r["method"] == m]
                if not mr:
                    continue
                cells = []
                for tgt in (1e-3, 1e-4):
                    ok = [r for r in mr if r["err"] <= tgt]
                    if not ok:
                        cells.append(f"{'-':>38s}")
                        continue
                    b = min(ok, key=kernel_us)
                    cells.append(f"{b['steps']:6d} / {b['nfev']:6d} / {int(b['nlu']):5d} / "
                                 f"{kernel_us(b):6.0f} @{b['rtol']:.0e}")
                say(f"  {m:8s} err<=1e-3: {cells[0]:>38s}   err<=1e-4: {cells[1]:>38s}")

    # DP5: steps on samples or over them
    say("\n== DP5 (RK45 tableau) with fixed steps on P1b: max over the run of |u - u_ref| [in] at "
        "the step ends (u_ref: DP5 at h = dt/16, landing) ==")
    uref = dp5_fixed(p1b, 1, 16)
    for label, hs_ in (("land  (h = dt/N)  ", ((1, 1), (1, 2), (1, 4), (1, 8))),
                       ("cross (h = 1.5dt/N)", ((3, 2), (3, 4), (3, 8), (3, 16)))):
        hs, es = [], []
        for num, den in hs_:
            u = dp5_fixed(p1b, num, den)
            idx = (np.arange(1, u.shape[0] + 1) * num * 16) // den - 1
            hs.append(num * dt / den)
            es.append(np.max(np.abs(u - uref[idx])))
        sl = np.polyfit(np.log(hs), np.log(es), 1)[0]
        say(f"{label}: " + "; ".join(f"h={h * 1e3:.4g} ms err {e:.1e}" for h, e in zip(hs, es))
            + f"  slope {sl:.2f}")
    say("\n== RK45 adaptive: steps end on samples vs step over them (error vs f evals) ==")
    for pn in problems:
        for land in (True, False):
            mr = [r for r in rows if r["problem"] == pn and r["method"] == "RK45"
                  and r["land"] == land and "error" not in r]
            if mr and not (pn in ("P2", "P1") and land):
                say(f"{pn:4s} {'land ' if land else 'cross'}: "
                    + "; ".join(f"rtol {r['rtol']:.0e}: err {r['err']:.1e} ({r['steps']} steps, "
                                f"{r['rejected']} rej, {r['nfev']} f)" for r in mr))

    say("\n== Summary (steps end on samples; target: every peak within 1e-3, then 1e-4) ==")
    for pn in problems:
        for tgt in (1e-3, 1e-4):
            sub = [r for r in rows if r["problem"] == pn and r["land"] and "error" not in r
                   and r["err"] <= tgt]
            if not sub:
                continue
            best = {}
            for m in methods:
                mr = [r for r in sub if r["method"] == m]
                if mr:
                    best[m] = min(mr, key=kernel_us)
            order = sorted(best.values(), key=kernel_us)
            fs = min(best.values(), key=lambda r: r["steps"])
            ff = min(best.values(), key=lambda r: r["nfev"])
            line = (f"{pn:4s} <= {tgt:.0e}: fewest steps {fs['method']} ({fs['steps']}), fewest f "
                    f"{ff['method']} ({ff['nfev']}); by kernel estimate: "
                    + ", ".join(f"{r['method']} {kernel_us(r) / 1e3:.1f} ms" for r in order))
            if problems[pn].contacts:
                line += "; steps in contact: " + ", ".join(
                    f"{r['method']} {r['contact_steps']}" for r in order)
            say(line)
        imp = [r for r in rows if r["problem"] == pn and r["land"] and "error" not in r
               and r["err"] <= 1e-3 and r["method"] in IMPLICIT]
        if imp:
            cells = []
            for m in IMPLICIT:
                mr = [r for r in imp if r["method"] == m]
                if mr:
                    b = min(mr, key=kernel_us)
                    cells.append(f"{m} {int(b['njev'])} J / {int(b['nlu'])} LU / {b['nsolve']} "
                                 f"solves = {1e6 * (b['nlu'] * cm['lu'] + b['nsolve'] * cm['solve']) / 1e3:.1f} ms")
            say(f"{pn:4s} implicit methods' linear algebra at <= 1e-3: " + "; ".join(cells))

    say(f"\nwall time of this script: {time.time() - t_start:.0f} s")
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results",
                        "method_families_quick.txt" if args.quick else "method_families.txt")
    tmp = path + ".tmp"
    with open(tmp, "w") as fh:
        fh.write(out.getvalue())
    os.replace(tmp, path)
    print(f"wrote {os.path.relpath(path)}")


if __name__ == "__main__":
    main()
