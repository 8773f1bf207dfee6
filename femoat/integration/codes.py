"""The compiled loop's status codes and the indices of its counters and energies: one home for
the numbers the Python side (:mod:`femoat.integration.solve`) reads back from the kernels."""

# Status codes returned by run_chunk.
DONE, STOPPED, BUFFER_FULL, NEWTON_FAILED, STEP_TOO_SMALL, LIMIT_REACHED = 0, 1, 2, 3, 4, 5

# Counters (State.stats), integer
S_STEPS, S_REJECT_ERR, S_REJECT_NEWTON, S_NEWTON, S_NOUT, S_EVENTS, S_IMPACTS = range(7)
N_STATS = 7
# Energies (State.energy, Work.de), float
E_INPUT, E_VISCOUS = 0, 1
N_ENERGY = 2
