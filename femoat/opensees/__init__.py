"""Cross-checks against OpenSees (optional extra: ``pip install femoat[verify]``).

Nothing here imports openseespy at import time; the functions import it when called.
"""

from femoat.opensees.building import (
    OpenSeesFailure,
    opensees_commands,
    opensees_run,
    write_opensees_script,
)
from femoat.opensees.single_impact import opensees_contact_material, opensees_impact

__all__ = [
    "OpenSeesFailure",
    "opensees_commands",
    "opensees_contact_material",
    "opensees_impact",
    "opensees_run",
    "write_opensees_script",
]
