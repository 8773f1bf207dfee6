"""The tags of the OpenSees twins' nodes, elements and load patterns, on one axis and in plan
(:mod:`femoat.opensees.twin` writes the model with them; the runs read their results by them).

Nodes: :data:`GROUND`, the base mat :data:`BASE`, floor k at ``BASE + k``; wall i's chain
(:mod:`femoat.opensees.wall_chain`) from ``WALL_NODE + i``, its later modes at
``MODE_TAG + 100·i + j``. Time series and patterns: the ground components 1 (x) and 2 (y),
:data:`GRAVITY` (a slider's normal force), ``WALL_SERIES + i`` (wall i's ground-load
correction).
"""

GROUND, BASE, WALL_NODE = 1, 2, 100
"""The ground node (fixed), the base mat (floor k: ``BASE + k``) and wall i's first chain node
(``WALL_NODE + i``)."""

BEARING_ELE = 1
"""The isolator's element: a bearing kind's twin (its further elements, a slider's W/R spring,
the next tags), or on one axis any isolator."""

ELASTIC_SPRING_ELE = 2
"""An Elastic isolator's element in plan (one spring in x and y; the tag of a slider's W/R
spring)."""

STORY_ELE, WALL_ELE, CONTACT_ELE = 10, 100, 200
"""Story k's element ``STORY_ELE + k``, wall i's first mode ``WALL_ELE + i``, its contact
``CONTACT_ELE + i``."""

MODE_TAG = 1000
"""Nodes and elements of a wall's second and later modes: ``MODE_TAG + 100·wall + mode``."""

INERTER_TAG = 100000
"""The inerter of wall i's mode j >= 2: ``INERTER_TAG + 100·i + j``."""

WALL_SERIES = 100
"""Time series and pattern of wall i's ground-load correction: ``WALL_SERIES + i``."""

GRAVITY = 10
"""Time series and pattern of a slider's gravity step (the base mat's load −W in z)."""
