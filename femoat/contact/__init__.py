"""Contact laws between the base mat and a moat wall (docs/paper.md §2)."""

from femoat.contact.damping import (
    muthukumar_stiffnesses,
    xi_hertzdamp,
    xi_jankowski,
    xi_kelvin_voigt,
)
from femoat.contact.hertzdamp import Hertzdamp
from femoat.contact.jankowski import Jankowski
from femoat.contact.kelvin_voigt import KelvinVoigt
from femoat.contact.laws import LAW_CODES, LAW_NAMES, LAWS, ContactLaw, make_law
from femoat.contact.linear import Linear
from femoat.contact.muthukumar import Muthukumar
from femoat.contact.parameters import ContactParameters

__all__ = [
    "ContactLaw",
    "ContactParameters",
    "Hertzdamp",
    "Jankowski",
    "KelvinVoigt",
    "LAWS",
    "LAW_CODES",
    "LAW_NAMES",
    "Linear",
    "Muthukumar",
    "make_law",
    "muthukumar_stiffnesses",
    "xi_hertzdamp",
    "xi_jankowski",
    "xi_kelvin_voigt",
]
