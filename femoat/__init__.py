"""femoat: a base-isolated building pounding its moat wall.

Units are kip, in, s throughout (see :mod:`femoat.units`).
"""

__version__ = "0.1.0"
