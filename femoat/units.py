"""Units and conventions used everywhere in femoat.

femoat works in **kip, in, s**. Masses are therefore in kip·s²/in, stiffnesses in kip/in,
damping coefficients in kip·s/in, energies in kip·in, accelerations in in/s². Users think in
weights [kip] and in g; the helpers here are the only place the conversion happens.
"""

G = 386.09
"""Standard gravity [in/s²]."""


def weight_to_mass(weight):
    """Mass [kip·s²/in] of a weight [kip]."""
    return weight / G


def mass_to_weight(mass):
    """Weight [kip] of a mass [kip·s²/in]."""
    return mass * G


def accel_to_g(accel):
    """Acceleration [in/s²] expressed in g."""
    return accel / G


def g_to_accel(accel_g):
    """Acceleration [g] expressed in in/s²."""
    return accel_g * G
