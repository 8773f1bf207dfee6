"""Shared plotting conventions: one colour and line style per contact law, each declared by the
law's own module (its ``LAW.style``, :mod:`femoat.contact.laws`)."""

from collections.abc import Mapping

from femoat.contact.laws import LAW_SPECS


class _LawStyles(Mapping):
    """Letter → matplotlib keywords (colour, line style, label "E  linear elastic"), read from
    the registry when asked, so a law added with :func:`femoat.contact.register` has its own."""

    def __getitem__(self, letter):
        spec = LAW_SPECS[letter]
        return dict(spec.style, label=f"{letter}  {spec.name}")

    def __iter__(self):
        return iter(LAW_SPECS)

    def __len__(self):
        return len(LAW_SPECS)


LAW_STYLE = _LawStyles()


def pyplot():
    """matplotlib.pyplot on the off-screen Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
