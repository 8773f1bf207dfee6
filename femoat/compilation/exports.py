"""The building solver's compiled entry points: the kernels it calls from Python.

One list for the three places that must agree on it: the JIT namespace
(:func:`femoat.integration.solve.kernels` with ``backend="jit"``), the ahead-of-time build
(:mod:`~femoat.compilation.aot_build` exports exactly these) and the loader
(:func:`femoat.compilation.aot.load` accepts a module only when it has them all). Modules are
named, not imported, so that the loader stays free of numba and of the solver.
"""

EXPORTS = {
    "run_chunk": "femoat.integration.driver",
    "ground_accel": "femoat.integration.forces",
    "internal_force": "femoat.integration.forces",
    "start_peaks": "femoat.integration.recording.peaks",
    "finish_peaks": "femoat.integration.recording.peaks",
    "start_episodes": "femoat.integration.recording.episodes",
    "finish_episodes": "femoat.integration.recording.episodes",
    "initial_element_energies": "femoat.integration.energy",
    "stored_energies": "femoat.integration.energy",
}
"""{name: module defining the kernel of that name}."""
