"""What each nonlinear element of a building is for: the isolator or story k.

:meth:`~femoat.structure.pounding.PoundingModel.pack` gives every element a :class:`Role`; the
solver (error scales, energy split), the collapse criteria and the results ask the role's
``kind`` (an integer code), never the element's name. The names (``"isolator"``,
``"story1"``, ...) are written and read here only: a result file stores them
(``meta["element_names"]``) and :func:`role_of` turns them back into roles.
"""

from dataclasses import dataclass

ISOLATOR, STORY = 0, 1
"""Role kinds: the isolation layer (base mat to ground) and a story spring (floor k to the
floor or base below)."""


@dataclass(frozen=True)
class Role:
    """The role of one element.

    Parameters
    ----------
    kind : int
        :data:`ISOLATOR` or :data:`STORY`.
    story : int
        Story number, 1 for the bottom story; 0 for the isolator.
    """

    kind: int
    story: int = 0

    def __post_init__(self):
        if self.kind not in (ISOLATOR, STORY):
            raise ValueError(f"kind = {self.kind!r}: use roles.ISOLATOR or roles.STORY.")
        if (self.kind == STORY) != (isinstance(self.story, int) and self.story >= 1):
            raise ValueError(f"story = {self.story!r}: a story element has a story number "
                             ">= 1 (bottom story 1), the isolator 0.")

    @property
    def name(self):
        """The element's name in results: ``"isolator"`` or ``"story{k}"``."""
        return "isolator" if self.kind == ISOLATOR else f"story{self.story}"


def role_of(name):
    """The :class:`Role` of an element named ``name`` (the inverse of :attr:`Role.name`)."""
    if name == "isolator":
        return Role(ISOLATOR)
    if name.startswith("story") and name[5:].isdigit():
        return Role(STORY, int(name[5:]))
    raise ValueError(f"element name {name!r} is neither 'isolator' nor 'story<k>'.")
