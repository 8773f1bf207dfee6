"""The one pack path: a building and its moat walls as the arrays of a
:class:`~femoat.structure.packed.PackedModel`, on the DOFs of a layout with one axis (a
:class:`~femoat.structure.pounding.PoundingModel`) or two (a :class:`~femoat.plan.model.PlanModel`).

Every uniaxial element (a story, an Elastic isolator) acts on its axis between two DOFs; a wall
acts through its rows b (δ = b·u − gap) and t (the slip along it) at the base mat's DOFs. Along
one axis, the plan pack is the 1D pack of that axis's model to the bit: the same numbers,
assembled in the same order (tests/test_plan_model.py).
"""

import numpy as np

from femoat.bearings import registry as bearing_registry
from femoat.contact.kernels import N_HISTORY, N_PARAMS
from femoat.structure.materials.kernels import DURATION, DURATION_COLUMNS
from femoat.structure.moat_wall import wall_modes
from femoat.structure.packed import PackedModel
from femoat.structure.roles import ISOLATOR, STORY, Role
from femoat.units import G


def pack(building, stories, layout, walls, bearing=None):
    """The :class:`PackedModel` of ``building`` and ``walls`` on ``layout``.

    Parameters
    ----------
    building : Building or PlanBuilding
        Its weights [kip], story damping β [s], P-Delta stiffnesses [kip/in], story heights
        [in] and isolator are read.
    stories : tuple of tuple
        One entry per axis of ``layout``: the story materials along it, bottom to top.
    layout : Layout
        The DOFs (:func:`femoat.structure.layout.dof_layout`), walls in the order of ``walls``.
    walls : tuple of MoatWall
        The moat's walls.
    bearing : int or None
        The isolator's bearing kind (:mod:`femoat.bearings.registry`) when it acts in plan as
        one bearing on the base mat's (x, y); None: the isolator (if any) is one uniaxial
        element per axis.
    """
    b = building
    n, dofs, axes = layout.n, layout.floor_dofs, range(len(layout.axes))
    if len(stories) != len(axes):
        raise ValueError(f"stories: one tuple per axis of the layout ({len(axes)}), "
                         f"got {len(stories)}.")
    if bearing is not None and len(axes) != 2:
        raise ValueError("a plan bearing acts on the base mat's x and y: the layout has one "
                         "axis (make the isolator one element along it).")
    M, C, K, R = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, len(axes)))
    for k, w in enumerate([b.base_weight, *b.floor_weights]):
        for a in axes:
            M[dofs[k, a], dofs[k, a]] = w / G
            R[dofs[k, a], a] = w / G
    beta = b.story_damping_beta
    geometric = b.geometric_stiffnesses()
    elements = []
    for a in axes:
        for k, mat in enumerate(stories[a]):
            i, j = dofs[k + 1, a], dofs[k, a]
            _add_spring(C, i, j, beta * mat.initial_stiffness)
            _add_spring(K, i, j, geometric[k])
            elements.append((i, j, a, mat, Role(STORY, k + 1)))
    iso = b.isolator
    if iso is not None and bearing is None:
        elements = [(dofs[0, a], -1, a, iso, Role(ISOLATOR)) for a in axes] + elements
    contacts = []
    for w, cols in zip(walls, layout.wall_dofs):
        mm, kk, cc, phi, L = wall_modes(w.wall)
        row, slip = np.zeros(n), np.zeros(n)
        for a in axes:
            row[dofs[0, a]] = w.normal[a]
            slip[dofs[0, a]] = w.tangent[a]
        for i, col in enumerate(cols):
            M[col, col], K[col, col], C[col, col] = mm[i], kk[i], cc[i]
            R[col, w.axis] = L[i] * w.sign  # the mode points away from the building
            row[col] = -phi[i]
        contacts.append((row, slip, w))
    bearings = [] if bearing is None else [bearing]
    p_width, _, s_width = bearing_registry.widths()
    return PackedModel(
        M=M, C=C, K=K, R=R, layout=layout,
        story_heights=np.array(b.heights, dtype=float),
        el_i=np.array([e[0] for e in elements], dtype=np.int64),
        el_j=np.array([e[1] for e in elements], dtype=np.int64),
        el_axis=np.array([e[2] for e in elements], dtype=np.int64),
        el_code=np.array([e[3].code for e in elements], dtype=np.int64),
        el_P=_stack([e[3].params() for e in elements]),
        el_S=_element_states([e[3] for e in elements]),
        el_roles=tuple(e[4] for e in elements),
        el_materials=[e[3] for e in elements],
        bearing_kind=np.array(bearings, dtype=np.int64),
        bearing_dofs=np.array([dofs[0, :2] for _ in bearings], dtype=np.int64).reshape(-1, 2),
        bearing_P=_stack([iso.params() for _ in bearings], width=p_width),
        bearing_S=_stack([iso.initial_state_plan() for _ in bearings], width=s_width),
        c_B=np.array([c[0] for c in contacts]).reshape(len(contacts), n),
        c_T=np.array([c[1] for c in contacts]).reshape(len(contacts), n),
        c_gap=np.array([c[2].gap for c in contacts], dtype=float),
        c_code=np.array([c[2].law.code for c in contacts], dtype=np.int64),
        c_P=_stack([c[2].law.packed() for c in contacts], width=N_PARAMS),
        c_H=np.zeros((len(contacts), N_HISTORY)),
        c_friction=np.array([c[2].friction for c in contacts], dtype=float),
        c_names=list(layout.wall_names),
        walls=walls,
    )


def _add_spring(A, i, j, value):
    """Add a spring ``value`` between DOFs i and j (j = −1: the ground) to the matrix A."""
    A[i, i] += value
    if j >= 0:
        A[j, j] += value
        A[i, j] -= value
        A[j, i] -= value


def _element_states(materials):
    """The elements' initial states, one row each, with the duration column last
    (:data:`~femoat.structure.materials.kernels.DURATION`): 0 for a material that reads each
    step's duration, −1 for one that does not (the loop then neither writes it nor lets the
    one-axis kink search skip the element)."""
    out = _stack([m.initial_state() for m in materials], extra=DURATION_COLUMNS)
    for row, m in zip(out, materials):
        row[DURATION] = 0.0 if _reads_duration(m) else -1.0
    return out


def _reads_duration(material):
    """Whether ``material`` (a story material or a bearing on one axis) reads each step's
    duration (:func:`femoat.bearings.registry.reads_duration`)."""
    kind = bearing_registry.kind_of(material)
    return kind is not None and bearing_registry.reads_duration(bearing_registry.kinds()[kind],
                                                                material.params())


def _stack(rows, width=None, extra=0):
    """The rows (sequences of floats) as one array, zero-padded to the longest and ``extra``
    columns more (at least ``width`` columns when there is no row)."""
    if not rows:
        return np.zeros((0, width or 1))
    w = max(len(r) for r in rows) + extra
    out = np.zeros((len(rows), w))
    for i, row in enumerate(rows):
        out[i, : len(row)] = row
    return out
