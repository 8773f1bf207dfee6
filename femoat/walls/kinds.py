"""The finite-element wall models by name: the one registry the scenario files, the command line
and the library read.

``beam`` (:func:`~femoat.walls.fe.beam.beam_model`), ``plane``
(:func:`~femoat.walls.fe.plane_stress.plane_model`) and ``solid``
(:func:`~femoat.walls.fe.solid.solid_model`); a mesh of dimension 1, 2 or 3 makes the model of
:data:`KIND_OF_DIMENSION`. Nothing heavy is imported here (the command line reads :data:`KINDS`).
"""

KINDS = ("beam", "plane", "solid")
KIND_OF_DIMENSION = {1: "beam", 2: "plane", 3: "solid"}


def build_model(kind, geometry, mesh=None, **options):
    """The wall model ``kind`` of ``geometry`` (on ``mesh`` when given); ``options`` go to the
    builder (the beam's ``timoshenko``)."""
    from femoat.walls.fe.beam import beam_model
    from femoat.walls.fe.plane_stress import plane_model
    from femoat.walls.fe.solid import solid_model

    builders = {"beam": beam_model, "plane": plane_model, "solid": solid_model}
    if kind not in builders:
        raise ValueError(f"model = {kind!r}: use {', '.join(repr(k) for k in KINDS)}.")
    return builders[kind](geometry, mesh=mesh, **options)


def kind_of_mesh(mesh):
    """The model a mesh makes, from its dimension."""
    return KIND_OF_DIMENSION[mesh.dim()]
