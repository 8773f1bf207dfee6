"""Contact laws between the base mat and a moat wall (PAPER.md §2)."""

from femoat.contact.damping import (
    muthukumar_stiffnesses,
    xi_hertzdamp,
    xi_jankowski,
    xi_kelvin_voigt,
)
from femoat.contact.laws import LAW_CODES, LAW_NAMES, ContactLaw, make_law
from femoat.contact.parameters import ContactParameters

__all__ = [
    "ContactLaw",
    "ContactParameters",
    "LAW_CODES",
    "LAW_NAMES",
    "make_law",
    "muthukumar_stiffnesses",
    "xi_hertzdamp",
    "xi_jankowski",
    "xi_kelvin_voigt",
]
