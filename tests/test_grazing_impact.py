"""A grazing impact (a gap closed at a small approach velocity) against its exact solution: the
linear contact law E, in 1D and in plan, at femoat's default integrator settings (1D "dp5",
plan "ark5").

The model is linear, so the whole run has a closed form. A bare base mat (no floors) of mass
m = W/g = 1 kip·s²/in on an Elastic isolator k_b = m·ω² (ω = 2 rad/s, T_b = π s), undamped; the
moat walls at ±GAP (1D sides ±1; in plan ±x and ±y) are the paper's concrete SDOF wall (K1,
M1 of Table 3) behind the linear contact spring f = k_eff·δ for δ > 0 (femoat/contact/linear.py:
``linear_force`` returns p[K_EFF]·d, k_eff = k_h·√δ_me = 1059.36 kip/in).

Ground: a rectangular pulse, every sample a0 [g] at DT for T = (N − 1)·DT = 0.1 s. Between
samples the ground is linear (constant here), and after the last one it is zero: femoat's
explicit methods restart at the record's last sample with the ground's right limit
(femoat/integration/driver.py, ``_record_end``/``_after_the_record``), a step drop at exactly T.

Open phase (no contact). y = side·u is the base's displacement toward the wall it reaches
first; with a0 > 0 the ground load −m·a_g pushes the base toward −x, so side = −1 (1D ``neg``,
plan ``-y``), and m·ÿ + k_b·y = m·a0·g during the pulse. From rest:
    y = (a0·g/ω²)·(1 − cos ωt)                         (0 ≤ t ≤ T),
    y = (a0·g/ω²)·(cos ω(t−T) − cos ωt) = A·sin ω(t − T/2)   (t ≥ T),
    A = 2·(a0·g/ω²)·|sin(ωT/2)|.
With ωT = 0.2 < π, y(T) < A and the crest y = A comes after the pulse, at T/2 + π/(2ω). The pulse
is chosen so that A = GAP·(1 + EPS): the base reaches the wall shortly before its crest, at
    t_c = T/2 + asin(GAP/A)/ω,   ẏ(t_c) = v0 = ω·√(A² − GAP²) = ω·GAP·√(2·EPS + EPS²),
a graze: v0 = 0.62 in/s against the base's peak velocity ω·A = 8.02 in/s.

The wall (femoat/structure/pounding.py, ``PoundingModel.pack``): its modal coordinate q points
away from the building and its mass feels the ground (r = L·side, L = M1), so on the side −1
wall M1·q̈ + C1·q̇ + K1·q = M1·a_g. Its indentation is δ = side·u_base − GAP − q = y − GAP − q,
and the contact force k_eff·δ pushes the base back (−side) and the wall away (+q).

Choice of C1 (the wall at rest at the closure). The preset's published C_imp = 3.3 kip·s/in
(c/M1 = 4393 1/s) does not do it: an overdamped wall has a fast root ≈ −C1/M1 but also a slow
one ≈ −K1/C1 = −0.73 1/s, along which the ground-driven creep (≈ 1e-3 in here) dies out only
over tens of seconds. The fastest decay of a free SDOF wall is at critical damping,
C1 = 2·√(K1·M1) = 0.0849 kip·s/in, both roots −ω1, ω1 = √(K1/M1) = 56.5 rad/s. During the
pulse (step response from rest) q = q_s·(1 − (1 + ω1·t)·e^(−ω1·t)), q_s = a0·g/ω1² = 0.025 in,
so |q(T)| ≤ q_s and |q̇(T)| = q_s·ω1²·T·e^(−ω1·T) ≤ q_s·ω1/e; after it, with τ = t − T,
    q = (q(T) + (q̇(T) + ω1·q(T))·τ)·e^(−ω1·τ),   |q| ≤ q_s·(1 + 2·ω1·τ)·e^(−ω1·τ).
The closure comes τ = t_c − T = 0.697 s after the pulse: ω1·τ = 39.4 and |q| ≤ 0.025·79.8·
7.8e-18 = 1.6e-17 in, |q̇| ≤ 1e-15 in/s: the wall is at rest (below 1e-14 in) at the closure.
(The exact open-phase solution below confirms both bounds.)

Contact phase (from the closure on, a_g = 0). With x = (y, q, ẏ, q̇, 1) — the constant 1 carries
the gap, which makes the closed system affine — x' = A_c·x with
    m·ÿ   = −k_b·y − k_eff·(y − GAP − q),
    M1·q̈ = −K1·q − C1·q̇ + k_eff·(y − GAP − q),
so x(t_c + s) = expm(A_c·s)·x(t_c), x(t_c) = (GAP, 0, v0, 0, 1), exactly. The contact force
k_eff·δ(s) is sampled densely (steps of 1e-6 s, the fast mode's period being 5.3 ms), its
largest sample refined by ``minimize_scalar`` (bounded to the samples either side), and the
contact ends at the first root of δ after the closure (``brentq`` between samples). The first
contact is a bounce of the light wall: the base (m = 1) drives the wall mass (M1 = 7.5e-4) on the
stiff contact spring, δ returns to zero after 2.78 ms; the base, barely slowed, touches again
later (the second row of the impact table), which this test does not look at.

What the run must give (``result.impacts[0]``): side −1, start = t_c, approach velocity = v0 =
δ̇(t_c), the peak force and the contact duration of the exact solution. The open phase is the
same exact construction with the pulse's A_open (both the base and the wall, the ground as the
constant column), so the closure state (t_c, v0, q, q̇) it finds is checked against the closed
forms above.

Measured (default rtol 1e-5; rtol 1e-7 in brackets), the same in 1D and in plan (bit for bit):
peak force +6.6e-5 (+4.3e-6) relative, approach velocity −2.2e-10 (−2.2e-10), start +7.8e-12 s,
duration +5.2e-4 (+2.5e-5) relative.
"""

import functools
import math

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.optimize import brentq, minimize_scalar

from femoat.contact import make_law
from femoat.ground_motions import GroundMotion, RecordPair
from femoat.plan import PlanBuilding, PlanModel, PlanWall
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.materials import Elastic
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.units import G
from femoat.walls import SdofWall, wall_preset

W = G                      # [kip] base mat weight: m = W/g = 1 kip·s²/in
M = W / G                  # [kip·s²/in]
OMEGA = 2.0                # [rad/s] isolated frequency (T_b = π s)
K_B = M * OMEGA ** 2       # [kip/in] the Elastic isolator
GAP = 4.0                  # [in] clearance on every side
EPS = 3e-3                 # [-] A = GAP·(1 + EPS): the crest passes the wall by 0.012 in
DT, N = 0.01, 11           # [s], samples: the pulse lasts T = (N − 1)·DT = 0.1 s
T = (N - 1) * DT
A_FREE = GAP * (1.0 + EPS)                                   # [in] free-vibration amplitude
A0 = A_FREE * OMEGA ** 2 / (2.0 * G * math.sin(OMEGA * T / 2.0))   # [g] pulse, 0.2082 g

PRESET = wall_preset("concrete")
LAW = make_law("E", PRESET.contact)
K_EFF = LAW.params.k_eff   # [kip/in]
K1, M1 = PRESET.wall.stiffness, PRESET.wall.mass
C1 = 2.0 * math.sqrt(K1 * M1)   # [kip·s/in] critical: the wall at rest at the closure (docstring)
WALL = SdofWall(stiffness=K1, mass=M1, damping=C1)

# closed forms of the open phase (docstring)
T_CLOSE = T / 2.0 + math.asin(GAP / A_FREE) / OMEGA           # [s] 0.79672
V0 = OMEGA * math.sqrt(A_FREE ** 2 - GAP ** 2)                 # [in/s] 0.62014

H_SAMPLE = 1e-6            # [s] dense sampling of the exact contact phase
REL = 1e-3                 # [-] the accuracy asked of the peak force and the approach velocity
START_TOL = 1e-8           # [s] the closure time (measured 7.8e-12 s at the default)


def _matrix(ag, contact):
    """A of x' = A·x, x = (y, q, ẏ, q̇, 1): base toward the wall and the wall's coordinate, under
    the constant ground acceleration ``ag`` [in/s²] (both masses are pushed toward the wall by
    m·a_g and M1·a_g), with or without the contact spring."""
    a = np.zeros((5, 5))
    a[0, 2] = a[1, 3] = 1.0
    a[2, 0] = -K_B / M
    a[2, 4] = ag
    a[3, 1] = -K1 / M1
    a[3, 3] = -C1 / M1
    a[3, 4] = ag
    if contact:  # k_eff·δ, δ = y − GAP − q: on the base −k_eff·δ, on the wall +k_eff·δ
        a[2, :] += np.array([-K_EFF, K_EFF, 0.0, 0.0, K_EFF * GAP]) / M
        a[3, :] += np.array([K_EFF, -K_EFF, 0.0, 0.0, -K_EFF * GAP]) / M1
    return a


def _indentation(x):
    return x[0] - GAP - x[1]


def _first_root(f, times, values):
    """The first root of f after times[0], between the samples where ``values`` turns
    positive (closure) or negative (separation)."""
    sign = values[0] <= 0.0
    i = int(np.flatnonzero((values[1:] > 0.0) if sign else (values[1:] < 0.0))[0]) + 1
    return brentq(f, times[i - 1], times[i], xtol=1e-15, rtol=4 * np.finfo(float).eps)


@functools.lru_cache(maxsize=1)
def exact():
    """The exact first impact: closure (time, state) from the open phase, then the contact
    phase's peak force and duration."""
    x_pulse = expm(_matrix(A0 * G, False) * T) @ np.array([0.0, 0.0, 0.0, 0.0, 1.0])
    a_free = _matrix(0.0, False)

    def d_open(t):
        return _indentation(expm(a_free * (t - T)) @ x_pulse)

    times = np.linspace(T, T_CLOSE + 0.05, 5001)
    t_close = _first_root(d_open, times, np.array([d_open(t) for t in times]))
    x_close = expm(a_free * (t_close - T)) @ x_pulse

    a_contact = _matrix(0.0, True)

    def force(s):
        return K_EFF * _indentation(expm(a_contact * s) @ x_close)

    step = expm(a_contact * H_SAMPLE)
    xs, x = [], x_close
    while True:  # sample until δ has turned negative (the separation)
        xs.append(x)
        if len(xs) > 2 and _indentation(x) < 0.0:
            break
        x = step @ x
    s = H_SAMPLE * np.arange(len(xs))
    f = K_EFF * np.array([_indentation(x) for x in xs])
    k = int(np.argmax(f))
    best = minimize_scalar(lambda t: -force(t), bounds=(s[k - 1], s[k + 1]), method="bounded",
                           options={"xatol": 1e-13})
    t_peak, peak = (best.x, -best.fun) if -best.fun > f[k] else (s[k], f[k])
    duration = _first_root(force, s[1:], f[1:])
    return {"start": t_close, "approach_velocity": x_close[2] - x_close[3], "peak_force": peak,
            "t_peak": t_peak, "duration": duration, "y": x_close[0], "v": x_close[2],
            "q": x_close[1], "q_rate": x_close[3]}


def _duration():
    """Run to just after the first contact (the second touch starts 17 ms after the first)."""
    e = exact()
    return e["start"] + e["duration"] + 0.005


def model_1d():
    building = Building(base_weight=W, floor_weights=(), isolator=Elastic(K_B), stories=())
    return PoundingModel(building, (MoatWall(LAW, WALL, GAP, 1), MoatWall(LAW, WALL, GAP, -1)))


def model_plan():
    building = PlanBuilding(base_weight=W, floor_weights=(), isolator=Elastic(K_B),
                            stories_x=(), stories_y=())
    return PlanModel(building, tuple(PlanWall(LAW, WALL, GAP, side)
                                     for side in ("+x", "-x", "+y", "-y")))


def pulse():
    return GroundMotion(np.full(N, A0), DT, name="pulse")


@functools.cache
def run_1d(integrator=None):
    return run(model_1d(), pulse(), integrator, duration=_duration())


@functools.cache
def run_plan(integrator=None):
    # the pulse along y only: x is zero
    pair = RecordPair(GroundMotion(np.zeros(N), DT, name="zero"), pulse())
    return run(model_plan(), pair, integrator, duration=_duration())


def test_the_exact_closure_is_the_closed_form_with_the_wall_at_rest():
    e = exact()
    # the open phase's matrix exponentials reproduce the closed forms of the docstring
    assert e["start"] == pytest.approx(T_CLOSE, abs=1e-12)
    assert e["y"] == pytest.approx(GAP, abs=1e-12)
    assert e["v"] == pytest.approx(V0, rel=1e-10)
    # the critically damped wall has forgotten the pulse: |q| ≤ 1.6e-17 in, |q̇| ≤ 1e-15 in/s
    assert abs(e["q"]) < 1e-14 and abs(e["q_rate"]) < 1e-12
    assert e["approach_velocity"] == pytest.approx(V0, rel=1e-12)


def test_the_configuration_is_a_graze():
    e = exact()
    # the approach velocity is a small fraction of the base's peak velocity ω·A
    # (√(2·EPS + EPS²) = 0.077), and the first impact is light (0.55 kip) and short (2.8 ms)
    assert V0 < 0.1 * OMEGA * A_FREE
    assert 0.1 < e["peak_force"] < 2.0
    assert 0.0 < e["t_peak"] < e["duration"] < 0.01
    # the closure is after the pulse and before the free crest T/2 + π/(2ω)
    assert T < e["start"] < T / 2.0 + math.pi / (2.0 * OMEGA)


@pytest.mark.parametrize("where", ["1d", "plan"])
def test_the_first_impact_matches_the_exact_graze_at_the_default_settings(where):
    result = run_1d() if where == "1d" else run_plan()
    assert result.meta["info"]["method"] == ("dp5" if where == "1d" else "ark5")
    e = exact()
    first = result.impacts[0]
    assert first["side"] == ("neg" if where == "1d" else "-y")
    assert first["start"] == pytest.approx(e["start"], abs=START_TOL)
    assert first["approach_velocity"] == pytest.approx(e["approach_velocity"], rel=REL)
    assert first["peak_force"] == pytest.approx(e["peak_force"], rel=REL)
    # the separation (measured +5.2e-4 relative at the default): the sample where δ ≤ 0 again
    assert first["duration"] == pytest.approx(e["duration"], rel=1e-2)
    # only the −1 / −y wall is touched
    assert {row["side"] for row in result.impacts} == {first["side"]}


def test_the_plan_run_repeats_the_1d_run():
    # the pulse along y on a bare mat with an Elastic isolator: the plan model is the 1D one
    # along y (ark5 is dp5 where no plan bearing's friction state moves); measured bit for bit
    a, b = run_1d().impacts[0], run_plan().impacts[0]
    for key in ("start", "approach_velocity", "peak_force", "duration", "max_indentation",
                "impulse"):
        assert b[key] == pytest.approx(a[key], rel=1e-6, abs=1e-12), key
