"""The contact-law registry: a law added from this file alone runs a single impact and a
building run; the registries agree; the generated dispatcher follows the registry."""

import math

import numpy as np
import pytest

from femoat.contact import (
    DAMPING_NAMES,
    LAW_CODES,
    LAW_NAMES,
    LAW_SPECS,
    LAWS,
    PAPER_LAWS,
    KernelFamily,
    LawSpec,
    Linear,
    generate,
    laws,
    linear,
    make_law,
    register,
    unregister,
)
from femoat.impact import simulate_impact
from femoat.impact.calibration import calibrate
from femoat.opensees.single_impact import opensees_contact_material
from femoat.paper import paper_model, paper_motion
from femoat.plotting.style import LAW_STYLE
from femoat.run import run
from femoat.units import G
from femoat.walls import wall_preset

STIFFNESS = 4.0  # the throwaway law's spring, in units of E's k_eff [-]
V0 = 10.0  # [in/s]


class StiffLinear(Linear):
    """A linear spring STIFFNESS times E's k_h·√δ_me: it runs on the linear kernels."""

    @classmethod
    def from_law(cls, law):
        return cls(STIFFNESS * law.params.k_eff)


STIFF = LawSpec("L", "stiff linear", linear.KERNELS, StiffLinear,
                style={"color": "black", "linestyle": "--"})


@pytest.fixture
def stiff():
    """The throwaway law L, registered for one test and taken out again."""
    before = {name: dict(d) for name, d in _registries().items()}
    register(STIFF)
    try:
        yield "L"
    finally:
        unregister("L")
        assert {name: dict(d) for name, d in _registries().items()} == before  # no trace


def _registries():
    return {"LAW_SPECS": LAW_SPECS, "LAWS": LAWS, "LAW_CODES": LAW_CODES,
            "LAW_NAMES": LAW_NAMES, "DAMPING_NAMES": DAMPING_NAMES}


def test_a_registered_law_runs_a_single_impact(stiff):
    pr = wall_preset("concrete").contact
    law = make_law(stiff, pr)
    r = simulate_impact(law, V0)
    m, k = pr.m_eff, STIFFNESS * pr.k_eff
    # A mass on a linear spring k: half a period π·√(m/k) in contact, f_max = v0·√(k·m), e = 1;
    # with k four times E's, half E's duration and twice its peak force.
    assert r.contact_duration == pytest.approx(math.pi * math.sqrt(m / k), rel=1e-4)
    assert r.peak_force == pytest.approx(V0 * math.sqrt(k * m), rel=1e-4)
    assert r.restitution == pytest.approx(1.0, abs=1e-6)
    assert r.law == "L"


def test_a_registered_law_runs_a_building_run(stiff):
    # The paper's building between concrete walls (consistent C_imp, so that the contact spring
    # and not the wall dashpot sets the impact), E against L on the first 4 s of Erzincan.
    motion = paper_motion(quick=True)
    runs = {k: run(paper_model("concrete", k, damping="consistent"), motion) for k in ("E", stiff)}
    first = {k: r.impacts[0] for k, r in runs.items()}
    # Until the first gap closure the two runs are the same run: same instant, same speed.
    assert first["L"]["start"] == first["E"]["start"]
    assert first["L"]["approach_velocity"] == first["E"]["approach_velocity"]
    # Over a contact of a few ms the base mat is a rigid mass m_base hitting the SDOF wall, the
    # single impact of femoat.impact with that mass: the first peak agrees with it (measured
    # 0.4 % for E, 0.2 % for L: the isolator and stories hardly move the base in 3 ms).
    preset = wall_preset("concrete", damping="consistent")
    m_base = paper_model("concrete", "E").building.base_weight / G
    for kind, impact in first.items():
        alone = simulate_impact(make_law(kind, preset.contact), impact["approach_velocity"],
                                wall=preset.wall, mass=m_base)
        assert impact["peak_force"] == pytest.approx(alone.peak_force, rel=0.02), kind
    # The wall mass M1 meets the spring: f_max ≈ v·√(k·M1), so four times the stiffness is
    # twice the force (the wall dashpot, ξ = C_imp/(2√(k·M1)) = 0.095 for E, trims it: 1.96).
    assert first["L"]["peak_force"] / first["E"]["peak_force"] == pytest.approx(2.0, rel=0.05)
    # and over the whole run the stiffer contact hits harder
    assert runs["L"].peaks["peak_impact_force"] > runs["E"].peaks["peak_impact_force"]


def test_a_registered_law_is_everywhere_a_letter_is_read(stiff):
    pr = wall_preset("concrete").contact
    law = make_law("stiff linear", pr)  # by its long name too
    assert (law.kind, law.code, law.name) == ("L", LAW_CODES["E"], "stiff linear")
    assert LAW_STYLE["L"] == {"color": "black", "linestyle": "--", "label": "L  stiff linear"}
    # its OpenSees twin is the linear law's, with its own stiffness
    name, k, *_ = opensees_contact_material(law, 1e-3)
    assert (name, k) == ("ElasticPPGap", pytest.approx(STIFFNESS * pr.k_eff, rel=1e-15))
    # undamped: nothing to calibrate, no damping to override
    assert not law.calibratable
    with pytest.raises(ValueError, match="no damping to calibrate"):
        calibrate(law, V0)
    with pytest.raises(ValueError, match="has no damping parameter"):
        make_law("L", pr, damping=0.1)


def test_after_unregister_the_law_is_gone():
    pr = wall_preset("concrete").contact
    register(STIFF)
    unregister("L")
    with pytest.raises(ValueError, match="law = 'L' is unknown"):
        make_law("L", pr)
    assert "L" not in LAW_STYLE


def test_register_refuses_what_it_cannot_run():
    # a taken letter or name
    with pytest.raises(ValueError, match="letter = 'E' is taken"):
        register(LawSpec("E", "other", linear.KERNELS, StiffLinear))
    with pytest.raises(ValueError, match="name = 'Hertzdamp' is taken"):
        register(LawSpec("Q", "Hertzdamp", linear.KERNELS, StiffLinear))
    # kernels the compiled dispatcher does not run: numba cannot add them at run time
    new = KernelFamily("fresh", linear.linear_force, linear.linear_energy, 1)
    with pytest.raises(ValueError, match=r"not compiled into the dispatcher.*generate"):
        register(LawSpec("Q", "fresh", new, StiffLinear))
    # the built-in laws stay
    with pytest.raises(ValueError, match="built-in law"):
        unregister("H")
    with pytest.raises(ValueError, match="'Q' is not registered"):
        unregister("Q")
    assert "Q" not in LAW_CODES


@pytest.mark.parametrize("kwargs, match", [
    ({"letter": "ee"}, "one capital letter"),
    ({"kernels": object()}, "must be a KernelFamily"),
    ({"parameters": object}, "needs from_law, params, separation_indicator"),
    ({"damping": "xi"}, "go together"),
    ({"options": ("tension",)}, "unknown option"),
])
def test_a_bad_law_spec_says_what_to_fix(kwargs, match):
    fields = {"letter": "Q", "name": "q", "kernels": linear.KERNELS, "parameters": StiffLinear}
    with pytest.raises(ValueError, match=match):
        LawSpec(**(fields | kwargs))


def test_registries_agree_and_the_builtin_codes_stand():
    assert list(LAW_SPECS) == list(LAWS) == list(LAW_CODES) == list(LAW_NAMES) == list(PAPER_LAWS)
    # the kernel families in registry order: E, V, J, H, M (the codes the models pack)
    assert LAW_CODES == {"E": 0, "V": 1, "J": 2, "H": 3, "M": 4}
    assert list(DAMPING_NAMES) == [k for k, s in LAW_SPECS.items() if s.damping is not None]
    assert [k for k, s in LAW_SPECS.items() if s.calibratable] == list("VJHM")


def test_the_dispatcher_is_generated_from_the_registry():
    # after a change to laws.MODULES or a KernelFamily: python -m femoat.contact.generate
    assert generate.main(["--check"]) == 0, "run: python -m femoat.contact.generate"


def test_a_new_kernel_family_gets_its_branches(monkeypatch):
    # A sixth family (here linear's kernels with a history commit and a dashpot at δ = 0⁺)
    # appended to the registry: the generated dispatcher calls its kernels under code 5.
    from femoat.contact import muthukumar

    fresh = KernelFamily("fresh", linear.linear_force, linear.linear_energy, 7,
                         commit=muthukumar.muthukumar_commit, acts_at_zero=True)
    monkeypatch.setattr(generate, "FAMILIES", laws.FAMILIES + (fresh,))
    text = generate.source()
    assert "    if code == 5:\n        return linear_force(p, h, d, v)" in text
    assert "    elif code == 5:\n        muthukumar_commit(h, d)" in text
    assert "return code == 1 or code == 5" in text
    assert "N_PARAMS = 7" in text
    namespace = {}
    exec(compile(text, "<generated>", "exec"), namespace)  # noqa: S102 (our own generated text)
    # run the generated Python (not compiled): code 5 is the linear spring f = k·δ
    p, h = np.array([2.0]), np.zeros(4)
    assert namespace["family_force"].py_func(5, p, h, 0.5, 1.0) == (1.0, 2.0, 0.0)
    assert math.isnan(namespace["family_force"].py_func(6, p, h, 0.5, 1.0)[0])
    namespace["family_commit"].py_func(5, h, 0.3)
    assert h[1] == 0.3  # the bilinear law's δ_m, advanced
