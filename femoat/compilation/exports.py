"""The building solver's compiled entry points: the kernels it calls from Python.

One list, read by :func:`femoat.integration.solve.kernels` (the namespace handed to the
solver) and by the warm-up (:mod:`~femoat.startup.probe` calls every one). Modules are
named, not imported, so that importing this list imports neither numba nor the solver.
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
