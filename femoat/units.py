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

