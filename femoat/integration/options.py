"""The compiled loop's option slots, status codes and counters: one home for the indices that
the Python side (:mod:`femoat.integration.solve`) fills and the kernels read."""

# Status codes returned by run_chunk.
DONE, STOPPED, BUFFER_FULL, NEWTON_FAILED, STEP_TOO_SMALL, LIMIT_REACHED = 0, 1, 2, 3, 4, 5

# Float options (fopt)
F_BETA, F_GAMMA, F_ALPHA, F_RTOL, F_HMAX, F_HMIN, F_NTOL, F_TEND, F_DTREC, F_HCONTACT, \
    F_GAPTOL = range(11)
N_FOPT = 11
# Integer options (iopt)
I_MAXIT, I_RECORD_EVERY, I_N_COUPLED, I_STOP_AT_LIMIT, I_N_STRUCT, I_METHOD, \
    I_N_EXPLICIT, I_RING = range(8)
N_IOPT = 8
# I_STOP_AT_LIMIT: 1 ends the run at the first criterion row exceeded, 0 only records its time
# (a runaway row always ends it: femoat.integration.limits)
# I_METHOD: the method of the open phase (the contact phase is always Newmark/HHT)
METHOD_NEWMARK, METHOD_DP5 = 0, 1
# I_RING: 1 when the recorder is a ring of RING_ROWS samples (a run that keeps no history: the
# running peaks and the impact episodes read the last samples, row k modulo its length), 0
# when it keeps every sample (grown by the Python side on BUFFER_FULL)
RING_ROWS = 3
# Stats (stats), integer
S_STEPS, S_REJECT_ERR, S_REJECT_NEWTON, S_NEWTON, S_NOUT, S_EVENTS, S_IMPACTS = range(7)
N_STATS = 7
# Energies (energy), float
E_INPUT, E_VISCOUS = 0, 1
N_ENERGY = 2
