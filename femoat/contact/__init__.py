"""Contact laws between the base mat and a moat wall (docs/paper.md §2).

One module per law (kernels, validated parameter dataclass, :class:`LawSpec`); the registries
are built in :mod:`femoat.contact.laws`, which also says how to add a law.
"""

from femoat.contact.hertzdamp import Hertzdamp, xi_hertzdamp
from femoat.contact.jankowski import Jankowski, xi_jankowski
from femoat.contact.kelvin_voigt import KelvinVoigt, xi_kelvin_voigt
from femoat.contact.laws import (
    DAMPING_NAMES,
    LAW_CODES,
    LAW_NAMES,
    LAW_SPECS,
    LAWS,
    PAPER_LAWS,
    ContactLaw,
    make_law,
    register,
    unregister,
)
from femoat.contact.linear import Linear
from femoat.contact.muthukumar import Muthukumar, muthukumar_stiffnesses
from femoat.contact.parameters import ContactParameters
from femoat.contact.spec import Bracket, KernelFamily, LawSpec

__all__ = [
    "Bracket",
    "ContactLaw",
    "ContactParameters",
    "DAMPING_NAMES",
    "Hertzdamp",
    "Jankowski",
    "KelvinVoigt",
    "KernelFamily",
    "LAWS",
    "LAW_CODES",
    "LAW_NAMES",
    "LAW_SPECS",
    "LawSpec",
    "Linear",
    "Muthukumar",
    "PAPER_LAWS",
    "make_law",
    "muthukumar_stiffnesses",
    "register",
    "unregister",
    "xi_hertzdamp",
    "xi_jankowski",
    "xi_kelvin_voigt",
]
