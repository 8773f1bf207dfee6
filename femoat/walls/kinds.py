"""The finite-element wall models, one row each: the registry that the scenario reader, the
command line, the continuum assembly, the mesh files and the renders read.

A kind is its name (the ``model`` of a scenario's ``[walls.fe]`` table and of ``femoat wall
--model``), the wall-frame axes of its mesh coordinates (and so its mesh dimension: a mesh of
that dimension makes the first kind of the dimension), the builder of its
:class:`~femoat.walls.fe.model.WallModel`, its structured mesher and how it is drawn. Adding a
kind is its builder's module and one row in :data:`KINDS`; nothing else names the kinds.

Nothing heavy is imported here (the command line reads the names): a builder's module is
imported at its first call.
"""

import importlib
from dataclasses import dataclass

VIEWS = ("elevation", "moat", "backfill")
"""Camera views of a wall picture: "elevation" looks along y at the x-z plane (a 1D or 2D
model); "moat" and "backfill" look at a 3D wall from either side."""


@dataclass(frozen=True)
class WallKind:
    """One finite-element wall model.

    name : str  the ``model`` key's value, e.g. "beam"
    axes : tuple of int  the wall-frame axes (0: x, normal to the wall; 1: y, along the moat;
        2: z, up; see :mod:`femoat.walls.fe.geometry`) of the mesh coordinates, in order. Their
        number is the mesh dimension; the displacement components of a continuum kind follow
        the same axes (a continuum kind starts with x, the direction of the impact).
    builder : callable  ``builder(geometry, mesh=None, **options)``: the kind's WallModel
    options : tuple of str  builder options the command line passes on (the beam's
        "timoshenko"); other kinds refuse them by name
    mesher : callable or None  ``mesher(geometry, **divisions)``: a structured mesh with the
        named boundaries "base", "impact" and "back", to write to a file; None when the builder
        makes its own
    views : tuple of str  the camera views of a picture (from :data:`VIEWS`); a one-panel
        picture uses the first
    line_width : float  [px] drawn width of the elements of a 1D model, of the cell edges of a
        2D or 3D one
    """

    name: str
    axes: tuple
    builder: object
    options: tuple = ()
    mesher: object = None
    views: tuple = ("elevation",)
    line_width: float = 1.0

    def __post_init__(self):
        if not (isinstance(self.name, str) and self.name.isidentifier()):
            raise ValueError(f"WallKind name = {self.name!r}: use a short identifier, e.g. "
                             "'plane_strain'.")
        axes = tuple(self.axes)
        if not (1 <= len(axes) <= 3 and list(axes) == sorted(set(axes))
                and set(axes) <= {0, 1, 2}):
            raise ValueError(f"WallKind {self.name!r} axes = {self.axes!r}: give the wall-frame "
                             "axes of the mesh coordinates in order, from 0 (x), 1 (y), 2 (z), "
                             "e.g. (0, 2) for a section in the x-z plane.")
        if not callable(self.builder) or not (self.mesher is None or callable(self.mesher)):
            raise ValueError(f"WallKind {self.name!r}: builder (and mesher, if any) must be "
                             "callable: builder(geometry, mesh=None, **options).")
        if not self.views or not set(self.views) <= set(VIEWS):
            raise ValueError(f"WallKind {self.name!r} views = {self.views!r}: choose from "
                             f"{VIEWS}.")
        if not (isinstance(self.line_width, (int, float)) and self.line_width > 0):
            raise ValueError(f"WallKind {self.name!r} line_width = {self.line_width!r}: a "
                             "positive width [px].")
        object.__setattr__(self, "axes", axes)

    @property
    def dimension(self):
        """The mesh dimension (1, 2 or 3)."""
        return len(self.axes)

    def build(self, geometry, mesh=None, **options):
        """The kind's WallModel of ``geometry`` (on ``mesh`` when given)."""
        model = self.builder(geometry, mesh=mesh, **options)
        if model.kind != self.name:  # the renders and the files read the model's kind
            raise ValueError(f"wall kind {self.name!r}: its builder made a {model.kind!r} "
                             f"model; build the WallModel with kind {self.name!r}")
        return model


def _lazy(module, function):
    """``module.function``, imported at its first call."""

    def call(*args, **kwargs):
        return getattr(importlib.import_module(module), function)(*args, **kwargs)

    call.__name__ = function
    call.__qualname__ = f"{module}.{function}"
    return call


KINDS = (
    WallKind("beam", axes=(2,), builder=_lazy("femoat.walls.fe.beam", "beam_model"),
             options=("timoshenko",), line_width=6.0),
    WallKind("plane", axes=(0, 2), builder=_lazy("femoat.walls.fe.plane_stress", "plane_model"),
             mesher=_lazy("femoat.walls.fe.plane_stress", "plane_mesh")),
    WallKind("solid", axes=(0, 1, 2), builder=_lazy("femoat.walls.fe.solid", "solid_model"),
             mesher=_lazy("femoat.walls.fe.solid", "solid_mesh"), views=("moat", "backfill")),
)
"""Every wall kind; the first is the model of a geometry without a mesh."""


def registered():
    """Every kind, in registry order (:data:`KINDS`, read at each call)."""
    names = [k.name for k in KINDS]
    if len(set(names)) != len(names) or not all(isinstance(k, WallKind) for k in KINDS):
        raise ValueError(f"femoat.walls.kinds.KINDS must hold WallKind rows with distinct "
                         f"names, got {names}")
    return KINDS


def names():
    """The kinds' names, in registry order."""
    return tuple(k.name for k in registered())


def _listed(kinds):
    quoted = [repr(k.name) for k in kinds]
    return quoted[0] if len(quoted) == 1 else f"{', '.join(quoted[:-1])} or {quoted[-1]}"


def wall_kind(name):
    """The kind called ``name``; a ValueError lists the kinds."""
    for kind in registered():
        if kind.name == name:
            return kind
    raise ValueError(f"model = {name!r}: use {_listed(registered())}.")


def default_kind():
    """The model of a geometry without a mesh (the first kind)."""
    return registered()[0]


def kind_of_mesh(mesh, name=None):
    """The kind a mesh makes: ``name`` if given (it must take a mesh of this dimension), else the
    first kind of the mesh's dimension."""
    dim = mesh.dim()
    of_dim = [k for k in registered() if k.dimension == dim]
    if not of_dim:
        raise ValueError(f"no wall model takes a {dim}D mesh: the kinds take "
                         f"{sorted({k.dimension for k in registered()})}D meshes.")
    if name is None:
        return of_dim[0]
    kind = wall_kind(name)
    if kind.dimension != dim:
        raise ValueError(f"mesh is {dim}D, which makes a {' or '.join(k.name for k in of_dim)} "
                         f"model, not model = {name!r}.")
    return kind


def build_model(kind, geometry, mesh=None, **options):
    """The wall model ``kind`` (a name) of ``geometry`` (on ``mesh`` when given); ``options`` go
    to the builder (the beam's ``timoshenko``)."""
    return wall_kind(kind).build(geometry, mesh=mesh, **options)
