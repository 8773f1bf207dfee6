"""Wall meshes on disk: .vtu (femoat's format) and gmsh .msh (a user's mesh), through meshio.

Named boundaries travel as scikit-fem's cell-data tags: for each name, ``skfem:b:<name>`` holds
one integer per cell whose bits flag the cell's facets on that boundary (scikit-fem's own
encoding, decoded by :func:`skfem.io.meshio.from_meshio`). A gmsh file's physical groups of
facets (lines in 2D, triangles/quads in 3D) become boundaries under their physical names.

Coordinates on disk are 3D in the wall frame (x normal to the wall, y along the moat, z up),
each mesh coordinate on its axis of the wall kind the mesh makes (:mod:`femoat.walls.kinds`): a
beam mesh is written along z at x = y = 0 and a 2D section in the x-z plane. On reading, a
1D mesh takes the coordinate with the largest extent as z; a 2D mesh takes x and, as vertical,
z if the points span z, else y (gmsh draws in the x-y plane).
"""

from pathlib import Path

import numpy as np

from femoat.atomic import atomic_path

READABLE = (".vtu", ".vtk", ".msh", ".xdmf")
CELL_DIM = {"line": 1, "triangle": 2, "quad": 2, "triangle6": 2, "quad9": 2, "tetra": 3,
            "hexahedron": 3, "tetra10": 3, "hexahedron27": 3}


def wall_frame_points(mesh):
    """The mesh vertices as 3D wall-frame points (n, 3) [in]: each mesh coordinate on its axis
    of the kind the mesh makes."""
    from femoat.walls.kinds import kind_of_mesh

    out = np.zeros((mesh.p.shape[1], 3))
    out[:, list(kind_of_mesh(mesh).axes)] = mesh.p.T
    return out


def write_mesh(path, mesh, point_data=None, cell_data=None):
    """Write a scikit-fem mesh with its named boundaries (and optional data) atomically.

    path : str or Path  .vtu (or any meshio format chosen by the suffix; .msh writes gmsh)
    point_data : dict of name → array (n_vertices, ...) e.g. mode shapes [in]
    cell_data : dict of name → [array (n_cells, ...)]
    """
    import meshio
    from skfem.io.meshio import to_meshio

    mio = to_meshio(mesh, point_data=dict(point_data or {}), cell_data=dict(cell_data or {}))
    mio.points = wall_frame_points(mesh)
    path = Path(path)
    kwargs = {"file_format": "gmsh"} if path.suffix == ".msh" else {}
    with atomic_path(path) as tmp:
        meshio.write(tmp, mio, **kwargs)
    return path


def _read_meshio(path):
    import meshio

    path = Path(path)
    if not path.is_file():
        raise ValueError(f"mesh file {path} does not exist")
    if path.suffix.lower() not in READABLE:
        raise ValueError(f"mesh file {path} has suffix {path.suffix!r}; femoat reads "
                         f"{', '.join(READABLE)}")
    try:
        return meshio.read(path)
    except SystemExit:  # meshio prints the reason and calls sys.exit(1) on unreadable files
        raise ValueError(f"meshio could not read {path}: the file is damaged or not a "
                         f"{path.suffix} mesh") from None
    except Exception as err:
        raise ValueError(f"meshio could not read {path}: {err}") from err


def read_mesh(path):
    """Read a wall mesh (scikit-fem Mesh with named boundaries) from .vtu, .msh, ...

    Raises ValueError if the file is missing, unreadable or holds no supported cells.
    """
    import meshio
    from skfem.io.meshio import from_meshio

    mio = _read_meshio(path)
    dims = [CELL_DIM[block.type] for block in mio.cells if block.type in CELL_DIM]
    if not dims:
        raise ValueError(f"mesh file {path} holds no line, triangle, quad, tetra or hexahedron "
                         f"cells (found {sorted({b.type for b in mio.cells})})")
    dim = max(dims)
    pts = np.asarray(mio.points, dtype=float)
    if pts.shape[1] == 2:
        pts = np.column_stack([pts, np.zeros(len(pts))])
    extent = np.ptp(pts, axis=0)
    if dim == 1:
        columns = [int(np.argmax(extent))]
    elif dim == 2:
        columns = [0, 2] if extent[2] > 0 else [0, 1]
    else:
        columns = [0, 1, 2]
    reduced = meshio.Mesh(pts[:, columns], mio.cells, cell_data=mio.cell_data,
                          field_data=mio.field_data, cell_sets=mio.cell_sets)
    try:
        mesh = from_meshio(reduced)
    except Exception as err:
        raise ValueError(f"scikit-fem could not build a mesh from {path}: {err}") from err
    return mesh
