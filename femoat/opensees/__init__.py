"""Cross-checks against OpenSees (optional extra: ``pip install femoat[verify]``).

Nothing here imports openseespy at import time; the functions import it when called.
"""

from femoat.opensees.single_impact import opensees_contact_material, opensees_impact

__all__ = ["opensees_contact_material", "opensees_impact"]
