"""The OpenSees twins' command lists, pinned: the one builder (femoat.opensees.twin) writes, for
a model on one axis and a model in plan, exactly the commands the two separate builders wrote
before they became one (issue 25).

``tests/data/opensees_twin_commands.json`` holds the command lists of the four models of
:func:`cases` under short made-up records (five samples, so the file stays small), written by the
two builders of commit 5273f72 (``python tests/test_opensees_twin_commands.py`` writes it anew:
only when the twin's model changes on purpose, and say why in the commit). Each command is
compared as JSON text, so an int stays an int, a float a float, and every float is compared to
the bit (JSON writes a float's shortest round-trip repr). The tests below also derive a few of
the stored numbers from the model's parameters, so that the file is not taken on trust.
"""

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from femoat.bearings.lead_rubber import LeadRubberBearing
from femoat.contact import make_law
from femoat.ground_motions import GroundMotion, RecordPair
from femoat.opensees import opensees_commands
from femoat.opensees.plan import opensees_plan_commands
from femoat.plan import PlanBuilding, PlanModel, PlanWall
from femoat.structure.building import Building
from femoat.structure.materials import Elastic
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.units import G
from femoat.walls import ModalWall, wall_preset

DATA = Path(__file__).resolve().parent / "data" / "opensees_twin_commands.json"


def two_mode_wall():
    """A made-up wall of two modes, φ = (1, −0.5) and L ≠ m, so that its chain has an inerter,
    rescaled masses and ground-load corrections on both nodes."""
    return ModalWall(np.array([2e-3, 1e-3]), np.array([900.0, 4000.0]), np.array([0.05, 0.02]),
                     np.array([1.0, -0.5]), np.array([2.5e-3, 4e-4]))


def cases():
    """name -> (builder, model, ground motion): two models on one axis, two in plan."""
    steel, concrete = wall_preset("steel"), wall_preset("concrete")
    jank = make_law("J", steel.contact)
    hertz = make_law("H", concrete.contact)
    x = GroundMotion(np.array([0.0, 0.1, -0.25, 0.3, 0.05]), 0.01, name="x")
    y = GroundMotion(np.array([0.0, -0.2, 0.15, 0.1, -0.3]), 0.01, name="y")
    return {
        # the paper building (constant-μ friction pendulum, three bilinear stories with their
        # dashpots) between an SDOF steel wall at +gap and the two-mode wall at −gap
        "1d_friction_pendulum_sdof_and_modal_walls": (
            opensees_commands,
            PoundingModel(Building(), (MoatWall(jank, steel.wall, 4.0, 1),
                                       MoatWall(hertz, two_mode_wall(), 3.0, -1))), x),
        # a lead-rubber bearing under one undamped elastic story, a linear-law wall at −gap only
        "1d_lead_rubber_one_wall": (
            opensees_commands,
            PoundingModel(Building(floor_weights=(8.0,), isolator=LeadRubberBearing(),
                                   stories=(Elastic(30.0),), story_damping_ratio=0.0),
                          (MoatWall(make_law("E", concrete.contact), concrete.wall, 2.0, -1),)),
            x),
        # the paper building in plan on its bidirectional slider (a gravity step), P-Delta on,
        # the two-mode wall at +x and a viscoelastic-gap wall at −y, under a turned, scaled pair
        "plan_slider_p_delta_two_walls": (
            opensees_plan_commands,
            PlanModel(PlanBuilding(p_delta=True),
                      (PlanWall(hertz, two_mode_wall(), 3.0, "+x"),
                       PlanWall(make_law("V", steel.contact), steel.wall, 4.0, "-y"))),
            RecordPair(x, y, angle=30.0, scale=1.5)),
        # an Elastic isolator (one spring in x and y), other stories in y, no walls
        "plan_elastic_isolator_no_walls": (
            opensees_plan_commands,
            PlanModel(PlanBuilding(isolator=Elastic(2.0), stories_y=(Elastic(40.0),) * 3), ()),
            RecordPair(x, y)),
    }


def built(name):
    builder, model, ground = cases()[name]
    return builder(model, ground)


def as_json(cmd):
    return json.dumps(list(cmd))


@pytest.mark.parametrize("name", sorted(cases()))
def test_commands_are_the_pinned_ones(name):
    stored = json.loads(DATA.read_text())[name]
    cmds = built(name)
    assert len(cmds) == len(stored)
    for k, (cmd, pinned) in enumerate(zip(cmds, stored)):
        assert as_json(cmd) == json.dumps(pinned), f"command {k}"


def test_pinned_numbers_follow_from_the_model():
    stored = json.loads(DATA.read_text())
    one_axis = stored["1d_friction_pendulum_sdof_and_modal_walls"]
    b = Building()
    # the friction pendulum's 1D twin: W/R = 33/30 = 1.1 kip/in in parallel with ElasticPP
    # (μW/u_y = 0.06·33/0.01 = 198 kip/in, u_y = 0.01 in), element 1 from the ground (node 1)
    first = [c[0] for c in one_axis].index("uniaxialMaterial")
    assert one_axis[first:first + 4] == [["uniaxialMaterial", "Elastic", 1, 33.0 / 30.0],
                              ["uniaxialMaterial", "ElasticPP", 2, 0.06 * 33.0 / 0.01, 0.01],
                              ["uniaxialMaterial", "Parallel", 3, 1, 2],
                              ["element", "zeroLength", 1, 1, 2, "-mat", 3, "-dir", 1]]
    # each story's dashpot is Elastic(0, c = β·k0): β = 2ξ·T1/2π = 2·0.02·0.30/2π
    beta = 2.0 * 0.02 * 0.30 / (2.0 * math.pi)
    dashpots = [c for c in one_axis if c[:2] == ["uniaxialMaterial", "Elastic"] and c[3] == 0.0]
    assert [c[4] for c in dashpots] == [beta * s.initial_stiffness for s in b.stories]
    # the two-mode wall at −gap (wall 1): chain nodes 101 and 1000 + 100 + 1 = 1101; masses
    # m/φ² = 2e-3 and 1e-3/0.25 = 4e-3 (the second an inerter); the ground-load corrections
    # P_1 = L_2/φ_2 − L_1/φ_1 + m_1/φ_1² = −8e-4 − 2.5e-3 + 2e-3 and P_2 = −L_2/φ_2 = 8e-4
    assert ["mass", 101, 2e-3] in one_axis
    assert ["element", "InertiaTruss", 100101, 101, 1101, 1e-3 / 0.25] in one_axis
    loads = [c for c in one_axis if c[0] == "load"]
    assert loads == [["load", 101, 4e-4 / -0.5 - 2.5e-3 + 2e-3], ["load", 1101, 8e-4]]
    # the excitation: the record in in/s² (a_g·G) at its dt, one UniformExcitation along x
    assert one_axis[-6] == ["timeSeries", "Path", 1, "-dt", 0.01, "-values",
                            *[a * G for a in (0.0, 0.1, -0.25, 0.3, 0.05)]]

    plan = stored["plan_slider_p_delta_two_walls"]
    # the slider's normal force: a static load −W = −33 kip on the base mat's free z
    assert ["load", 2, 0.0, 0.0, -33.0, 0.0, 0.0, 0.0] in plan
    assert ["fix", 2, 0, 0, 0, 1, 1, 1] in plan and ["fix", 3, 0, 0, 1, 1, 1, 1] in plan
    # P-Delta: story k carries the floors above it, P = 23, 15, 7 kip over h = 39 in, a spring
    # Elastic(−P/h, 0) in x and in y
    geometric = [c[3] for c in plan if c[:2] == ["uniaxialMaterial", "Elastic"] and c[3] < 0.0]
    assert geometric == [-p / 39.0 for p in (23.0, 23.0, 15.0, 15.0, 7.0, 7.0)]
    # the −y wall (wall 1): its contact goes from the impact node 101 to the base mat 2 along y
    contact = next(c for c in plan if c[:3] == ["element", "zeroLength", 201])
    assert (contact[3], contact[4], contact[-2:]) == (101, 2, ["-dir", 2])

if __name__ == "__main__":  # write the pinned lists anew (module docstring)
    DATA.write_text(json.dumps({name: [list(c) for c in built(name)] for name in sorted(cases())},
                               indent=None).replace("], [", "],\n ["))
    print(f"wrote {DATA}", file=sys.stderr)
