"""A throwaway bearing kind for the registry's tests: a linear spring beside a friction cap, the
cap uncoupled per axis (a square yield surface in plan, unlike the friction pendulum's disk).

    f_a = k·u_a + clip(q_a + k_f·(u_a − w_a), −F, F)       for each axis a of x, y

with the restoring stiffness ``k`` [kip/in], the cap's elastic stiffness ``k_f`` [kip/in] and
its force ``F`` [kip] (the yield displacement u_y = F/k_f); the committed state per axis holds
the displacement w_a [in] and the cap's force q_a [kip] at the last commit.

Closed forms the tests use: on one axis this is the friction pendulum with W/R = k, μW = F and
u_y = F/k_f (the same elastic-perfectly-plastic rule written in force instead of z); a cycle of
amplitude u0 > u_y dissipates 4·F·(u0 − u_y). In plan the two axes do not interact, so a plan
run of a building whose stories are uncoupled is the sum of two 1D runs.

It lives in the tests, not in femoat: registering it from here is what proves that a bearing kind
is one module and one registry line (``femoat.bearings.registry.register``).
"""

from dataclasses import dataclass

import numpy as np

from femoat import checks
from femoat.bearings import registry
from femoat.compilation.jit import njit

KEY = "capped_spring"
N_PARAMS = 3
N_STATE_AXIS = 4
N_STATE_PLAN = 4
_K, _KF, _F = range(N_PARAMS)


@njit(cache=True)
def _axis(p, w, q, u):
    """Cap force, its derivative and the spring force on one axis from the committed (w, q)."""
    t = q + p[_KF] * (u - w)
    if t > p[_F]:
        return p[_F], 0.0
    if t < -p[_F]:
        return -p[_F], 0.0
    return t, p[_KF]


@njit(cache=True)
def axis_trial(p, s, u, v):
    cap, dcap = _axis(p, s[0], s[1], u)
    return p[_K] * u + cap, p[_K] + dcap, 0.0


@njit(cache=True)
def axis_commit(p, s, u, v):
    s[1] = _axis(p, s[0], s[1], u)[0]
    s[0] = u


@njit(cache=True)
def axis_energy(p, s):
    return 0.5 * p[_K] * s[0] * s[0] + 0.5 * s[1] * s[1] / p[_KF]


@njit(cache=True)
def plan_trial(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau, f, k, c):
    fx, kx = _axis(p, s[0], s[1], ux)
    fy, ky = _axis(p, s[2], s[3], uy)
    f[0] = p[_K] * ux + fx
    f[1] = p[_K] * uy + fy
    k[0, 0] = p[_K] + kx
    k[1, 1] = p[_K] + ky
    k[0, 1] = 0.0
    k[1, 0] = 0.0
    c[0, 0] = 0.0
    c[0, 1] = 0.0
    c[1, 0] = 0.0
    c[1, 1] = 0.0


@njit(cache=True)
def plan_commit(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau):
    s[1] = _axis(p, s[0], s[1], ux)[0]
    s[0] = ux
    s[3] = _axis(p, s[2], s[3], uy)[0]
    s[2] = uy


@njit(cache=True)
def plan_energy(p, s):
    return (0.5 * p[_K] * (s[0] * s[0] + s[2] * s[2])
            + 0.5 * (s[1] * s[1] + s[3] * s[3]) / p[_KF])


@njit(cache=True)
def plan_branch(p, s, ux, uy):
    """0 elastic on both axes, 1 x capped, 2 y capped, 3 both (a change lands the step)."""
    bx = abs(s[1] + p[_KF] * (ux - s[0])) > p[_F]
    by = abs(s[3] + p[_KF] * (uy - s[2])) > p[_F]
    return (1 if bx else 0) + (2 if by else 0)


@njit(cache=True)
def plan_turn_direction(s):
    return 0.0, 0.0


@dataclass(frozen=True)
class CappedSpring:
    """Linear spring ``k`` [kip/in] beside a friction cap of force ``F`` [kip] and elastic
    stiffness ``k_f`` [kip/in], per axis (module docstring); one class on one axis and in plan."""

    k: float = 1.1
    k_f: float = 198.0
    F: float = 1.98

    def __post_init__(self):
        checks.positive("k", self.k, "[kip/in]")
        checks.positive("k_f", self.k_f, "[kip/in]")
        checks.positive("F", self.F, "[kip]")

    @property
    def yield_deformation(self):
        """The cap's yield displacement F/k_f [in]."""
        return self.F / self.k_f

    @property
    def capacity(self):
        return float("inf")

    @property
    def code(self):
        return registry.axis_code(self)

    def params(self):
        return np.array([self.k, self.k_f, self.F], dtype=np.float64)

    def initial_state(self):
        return np.zeros(N_STATE_AXIS)

    def initial_state_axis(self):
        return np.zeros(N_STATE_AXIS)

    def initial_state_plan(self):
        return np.zeros(N_STATE_PLAN)


AXIS_CLASS = CappedSpring
PLAN_CLASS = CappedSpring
