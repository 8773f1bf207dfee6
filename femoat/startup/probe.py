"""A tiny building run that makes every solver entry point compile (or load): the default
building between two concrete walls with Hertzdamp contact, 4 in away, under 0.2 s of a 1 g sine
(no contact needed: every entry point is called by every run).
:mod:`~femoat.startup.warmup` pays the start-up with it (``femoat compile``, the paper
study, a run and a suite's client before its workers start).
"""

import numpy as np


def probe_model():
    """The default building between two concrete moat walls (Hertzdamp, published damping)."""
    from femoat.contact.laws import make_law
    from femoat.structure.building import Building
    from femoat.structure.pounding import MoatWall, PoundingModel
    from femoat.walls.presets import wall_preset

    preset = wall_preset("concrete", damping="published")
    law = make_law("H", preset.contact)
    return PoundingModel(Building(), tuple(MoatWall(law, preset.wall, 4.0, side)
                                           for side in (1, -1)))


def probe_motion():
    """(ground acceleration [in/s²], sample interval [s]): 0.2 s of a 1 g, 1 Hz sine."""
    from femoat.units import G

    t = np.arange(0.0, 0.2, 0.01)
    return np.sin(2.0 * np.pi * t) * G, 0.01


def run_probe():
    """Run the probe through :func:`femoat.integration.solve.solve` (every entry point is
    called by every run); return the namespace of entry points used."""
    from femoat.integration.solve import kernels, solve

    accel, dt = probe_motion()
    solve(probe_model().pack(), accel, dt, dt * (accel.size - 1))
    return kernels()
