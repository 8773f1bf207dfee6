"""Accuracy of every peak at the default rtol, convergence in rtol, and kinks landed on.

The converged reference is femoat itself at rtol = 1e-8 with steps of at most 1e-4 s: its peaks
agree with the OpenSees twin at dt = 2e-5 s to ≤ 3e-4 (base acceleration) and ≤ 4e-5 for every
other peak (benchmarks/peak_accuracy.py), well inside the tolerances asserted here; the slow
tests check the same targets against OpenSees directly.
"""

import functools
from types import SimpleNamespace

import numpy as np
import pytest

from femoat.contact.laws import make_law
from femoat.ground_motions import GroundMotion, fema_p695_record
from femoat.integration import Integrator
from femoat.paper import paper_model, paper_motion
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.materials import FrictionPendulum
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.units import G
from femoat.walls.presets import wall_preset

CONVERGED = Integrator(method="newmark", rtol=1e-8, max_step=1e-4)


def peaks(result):
    """Every peak a user reads: impact force, base and wall displacement, story drifts, floor
    and base accelerations (absent ones, e.g. no impact, are left out)."""
    p = result.peaks
    out = dict(F=p["peak_impact_force"], base=p["peak_base_displacement"],
               wall=p["peak_wall_displacement"], a0=p["peak_base_acceleration"])
    out.update({f"d{k + 1}": d for k, d in enumerate(p["peak_drift"])})
    out.update({f"a{k + 1}": a for k, a in enumerate(p["peak_floor_acceleration"])})
    return {k: v for k, v in out.items() if v}


def relative_errors(p, ref):
    return {k: abs(p[k] - ref[k]) / abs(ref[k]) for k in ref}


def fema_case(record_id, component, pga=0.6):
    """A FEMA P695 far-field record (dt = 0.01 s) at PGA ``pga`` [g] and time scale 0.5 on the
    paper building, concrete wall, law E (the 4 in gap stays open: no impact)."""
    gm = fema_p695_record("farfield", record_id, component).scaled_to_pga(pga).time_scaled(0.5)
    return paper_model("concrete", "E"), gm


def twin_model(wall, law):
    """The paper model with the law OpenSees has too (V pulls in tension, as OpenSees' gap)."""
    preset = wall_preset(wall, damping="published")
    contact = make_law(law, preset.contact, **({"allow_tension": True} if law == "V" else {}))
    return PoundingModel(Building(), tuple(MoatWall(contact, preset.wall, 4.0, side)
                                           for side in (1, -1)))


@functools.lru_cache(maxsize=None)
def converged(case):
    model, motion = case_inputs(case)
    return peaks(run(model, motion, CONVERGED))


def case_inputs(case):
    kind, *args = case
    if kind == "fema":
        return fema_case(*args)
    return twin_model(*args), paper_motion()


# ---- the default rtol against a converged run -------------------------------------------------

@pytest.mark.parametrize("record_id, component, pga",
                         [(1, "a", 0.6), (5, "a", 0.6), (21, "a", 0.6), (5, "a", 0.15),
                          (1, "a", 1.2)])
def test_default_rtol_gives_every_peak_of_a_fema_record_within_1e_3(record_id, component, pga):
    # Issue 9's target: on FEMA P695 records (samples every 0.01 s) every peak within 1e-3 of a
    # converged run. FF1a/5a/21a were the worst of seven records at 0.6 g before drifts and
    # accelerations had their own error scales (up to 9e-3 at the old default); measured now
    # ≤ 4e-4. The acceleration scale is proportional to the record's PGA, so a weak (0.15 g)
    # and a strong (1.2 g) record are as accurate (measured 3.5e-4 and 1.8e-4).
    case = ("fema", record_id, component, pga)
    model, motion = case_inputs(case)
    errors = relative_errors(peaks(run(model, motion)), converged(case))
    assert max(errors.values()) < 1e-3, errors


@pytest.mark.parametrize("case", [("fema", 1, "a", 0.6), ("fema", 5, "a", 0.6),
                                  ("paper", "steel", "J")])
def test_tsit5_at_its_default_rtol_gives_every_peak_within_1e_3(case):
    # Tsitouras' pair on dp5's step at the same default rtol: the same target as dp5's above
    # (benchmarks/explicit_pairs.py: worst peak 7.3e-4 on the 20 paper runs, 2.7e-4 on the 66
    # far-field x components, as dp5's), here on the two FEMA records above and a paper run
    # with three impacts.
    model, motion = case_inputs(case)
    res = run(model, motion, Integrator(method="tsit5"))
    # the loop really ran Tsitouras' tableau: its steps are not dp5's (measured on these three:
    # 3,811 against 4,201, 12,608 against 13,919, 7,440 against 7,505)
    assert res.meta["stats"]["steps"] != run(model, motion).meta["stats"]["steps"]
    errors = relative_errors(peaks(res), converged(case))
    assert max(errors.values()) < 1e-3, errors


@pytest.mark.parametrize("wall, law", [("concrete", "E"), ("steel", "J")])
def test_default_rtol_gives_paper_drifts_within_3e_4(wall, law):
    # Issue 9's target for the paper runs: peak story drifts within 3e-4 (measured ≤ 1e-4 at the
    # default; every other peak ≤ 3e-4); the slow test checks all eight against OpenSees.
    case = ("paper", wall, law)
    model, motion = case_inputs(case)
    errors = relative_errors(peaks(run(model, motion)), converged(case))
    drifts = {k: e for k, e in errors.items() if k.startswith("d")}
    assert len(drifts) == 3
    assert max(drifts.values()) < 3e-4, errors
    assert max(errors.values()) < 1e-3, errors


def test_rtol_converges_every_peak_with_newmark():
    # rtol is the knob: each peak's error falls about as rtol^0.6 (local error O(h³) per step,
    # global O(h²); measured 1e-3 → 1e-7: the largest error 7.8e-3 → 2.4e-5). Errors of single
    # peaks are not strictly monotone (a peak's error can cross zero between two settings, e.g.
    # a1: 1.2e-4 at 1e-5, 1.3e-4 at 1e-6), so the assertion is on the envelope: two decades
    # finer than any setting, every peak's error is at most half the largest error seen up to
    # that setting, unless below 2e-5 (the reference's own uncertainty for accelerations read
    # at 1e-4 s steps); over the four decades the largest error falls by 100.
    case = ("fema", 1, "a", 0.6)
    model, motion = case_inputs(case)
    ref = converged(case)
    rtols = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7)
    errs = [relative_errors(peaks(run(model, motion, Integrator(method="newmark", rtol=rtol))),
                            ref) for rtol in rtols]
    assert max(errs[-1].values()) < max(errs[0].values()) / 100
    for key in ref:
        seq = [e[key] for e in errs]
        for k in range(2, len(seq)):
            assert seq[k] < max(max(seq[:k - 1]) / 2, 2e-5), (key, seq)


def test_dp5_open_phase_is_converged_at_every_rtol():
    # The fifth-order open phase on FF1a (no impact): every peak within 5e-5 of the converged
    # Newmark run from rtol 1e-3 to 1e-6 (measured ≤ 1.6e-5, the reference's own uncertainty for
    # accelerations read at 1e-4 s steps being ~1e-5): one step per record sample is already
    # converged, so rtol barely matters while the gaps are open.
    case = ("fema", 1, "a", 0.6)
    model, motion = case_inputs(case)
    ref = converged(case)
    for rtol in (1e-3, 1e-4, 1e-5, 1e-6):
        errors = relative_errors(peaks(run(model, motion, Integrator(method="dp5", rtol=rtol))),
                                 ref)
        assert max(errors.values()) < 5e-5, (rtol, errors)


def test_dp5_contact_phase_converges_with_rtol():
    # With impacts (paper concrete/H) the contact phase is Newmark's: the largest peak error
    # falls with rtol (measured 1.3e-3 at 1e-3, 2.4e-5 at 1e-6) and the default is within 1e-3.
    case = ("paper", "concrete", "H")
    model, motion = case_inputs(case)
    ref = converged(case)
    worst = [max(relative_errors(peaks(run(model, motion, Integrator(method="dp5", rtol=rtol))),
                                 ref).values()) for rtol in (1e-3, 1e-5, 1e-6)]
    assert worst[2] < worst[0] / 10, worst
    assert worst[1] < 1e-3, worst


# ---- kinks --------------------------------------------------------------------------------

def test_steps_land_on_the_stick_slip_kink_of_a_friction_bearing():
    # A bare base mat (W = 33 kip) on a friction pendulum (R = 30 in, μ = 0.06, u_y = 0.01 in)
    # pushed from rest at v0 = 10 in/s: it sticks (z = u/u_y) until u = u_y, then slides. At that
    # instant the force has a corner, f = (W/R)·u_y + μ·W = 2.0 kip, and the acceleration jumps
    # in slope. The step that contains it is shortened to end at most 2^-12 of its length past
    # it: some sample has u − u_y in [0, v0·h·2^-12] (h ≤ 1 ms here).
    iso = FrictionPendulum(W=33.0, R=30.0, u_y=0.01, mu=0.06)
    model = PoundingModel(Building(base_weight=33.0, floor_weights=(), isolator=iso,
                                   stories=()), ())
    quiet = GroundMotion(np.zeros(101), 1e-3, name="quiet")
    r = run(model, quiet, Integrator(rtol=1e-3), duration=0.05, u0=[0.0], v0=[10.0])
    u = r.base_displacement
    past = u - iso.u_y
    first_past = past[past >= 0.0].min()
    assert 0.0 <= first_past < 10.0 * 1e-3 * 2.0 ** -12 * 1.01
    f = r.element_force[:, 0]
    k = int(np.argmin(np.where(past >= 0.0, past, np.inf)))
    corner = 33.0 / 30.0 * iso.u_y + 0.06 * 33.0
    assert f[k] == pytest.approx(corner, rel=1e-4)
    # the absolute acceleration there is the corner's, −f/m (no ground motion)
    assert r.absolute_acceleration()[k, 0] == pytest.approx(-corner / (33.0 / G), rel=1e-4)


# ---- against OpenSees (slow) --------------------------------------------------------------

@pytest.mark.slow
@pytest.mark.parametrize("wall", ["concrete", "steel"])
@pytest.mark.parametrize("law", ["E", "V", "J", "H"])
def test_default_rtol_paper_drifts_match_opensees(wall, law):
    # Issue 9's "done when": on the paper runs of E, V, J, H femoat's peak drifts at the default
    # rtol agree with the OpenSees twin at dt = 2e-5 s within 3e-4.
    from conftest import opensees_or_skip

    opensees_or_skip()
    from femoat.opensees import opensees_run

    model, motion = twin_model(wall, law), paper_motion()
    # OpenSees' Newton test on the displacement increment: 1e-10 in (the twin's default) cannot
    # be met at t = 2.129 s of concrete/V (round-off with the stiff Kelvin-Voigt contact: the
    # increments stagnate); at 1e-8 in it converges, and the drift peaks of E, J and H are the
    # same at both tolerances to 1e-7.
    twin = opensees_run(model, motion, 2e-5, tol=1e-8 if law == "V" else 1e-10)["peaks"]
    ours = run(model, motion).peaks
    for d, d_os in zip(ours["peak_drift"], twin["peak_drift"]):
        assert d == pytest.approx(d_os, rel=3e-4)


@pytest.mark.slow
@pytest.mark.parametrize("record_id, component", [(1, "a"), (5, "a"), (12, "a")])
def test_default_rtol_fema_peaks_match_opensees(record_id, component):
    # Issue 9's "done when": on FEMA P695 records with dt = 0.01 s every peak within 1e-3 of
    # the OpenSees twin at dt = 2e-5 s.
    from conftest import opensees_or_skip

    opensees_or_skip()
    from femoat.opensees import opensees_run

    model, motion = fema_case(record_id, component)
    theirs = peaks(SimpleNamespace(peaks=opensees_run(model, motion, 2e-5)["peaks"]))
    ours = peaks(run(model, motion))
    assert set(theirs) == set(ours)
    errors = relative_errors(ours, theirs)
    assert max(errors.values()) < 1e-3, errors


def test_a_tiny_record_does_not_ask_for_unbounded_steps():
    # The acceleration scale is 0.15 × PGA but never below 0.15 × 0.1 g: a run driven by its
    # initial conditions under a record of zeros, or of one 1e-6 g sample, takes the same steps
    # (without the floor the steps grew as PGA^(-1/3): 1.7e5 steps for 2 s at 1e-6 g).
    model = PoundingModel(Building(), ())
    steps = []
    for blip in (0.0, 1e-6):
        a = np.zeros(201)
        a[100] = blip
        r = run(model, GroundMotion(a, 0.01, name="quiet"), duration=2.0, v0=[10.0] * 4)
        steps.append(r.meta["stats"]["steps"])
    assert steps[1] == pytest.approx(steps[0], rel=0.01)
    assert steps[0] < 10000


@pytest.mark.parametrize("wall, law", [("steel", "M"), ("concrete", "M"), ("concrete", "J")])
def test_every_impact_of_a_chattering_paper_run_is_within_1e_3(wall, law):
    # The consistent-damping paper runs chatter: 6-13 impacts of 1.7 to 48 kip, most of them a
    # tenth to a third of δ_me deep. Measured against δ_me in contact, their wall DOFs' errors
    # were a large part of such an indentation: 13.2 and 12.3 kip impacts of steel/M 3.0e-3
    # and 2.9e-3 off, concrete/M's first 1.7e-3, concrete/J 1.2e-3 (benchmarks/README.md, issue
    # 26 item 2). With the contact error measured on each episode's own indentation
    # (solve.episode_scaling), every impact of at least 5 kip (the threshold) is within
    # 1e-3 of the converged run (measured 5.7e-4, 7.3e-4, 4.2e-4), one by one, and the count
    # is the same. The first 4 s of the record hold every impact of these runs (1.6-2.9 s).
    model = paper_model(wall, law, damping="consistent")
    motion = paper_motion(quick=True)
    got, ref = run(model, motion).impacts, run(model, motion, CONVERGED).impacts
    assert len(got) == len(ref) >= 6
    strong = [(g, r) for g, r in zip(got, ref) if r["peak_force"] >= 5.0]
    assert len(strong) >= 5
    for g, r in strong:
        assert g["side"] == r["side"]
        assert g["peak_force"] == pytest.approx(r["peak_force"], rel=1e-3)
        assert g["start"] == pytest.approx(r["start"], abs=1e-4)
