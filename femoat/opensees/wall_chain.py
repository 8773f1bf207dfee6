"""A moat wall in the OpenSees twins (1D and 3D): its modes as a chain of nodes along the wall's
axis, and the maps between the chain's node displacements and femoat's modal coordinates.

The chain (written once here)
-----------------------------
A wall of N modes (m_i, k_i, c_i, impact shape φ_i, ground participation L_i; an SDOF wall is
one mode with φ = 1 and L = m) is a chain of N nodes along its axis (:func:`wall_chain`), the
first ``WALL_NODE + i`` for wall i of ``model.walls``, the later ones ``MODE_TAG + 100·i + j``
(:mod:`femoat.opensees.tags`). With s_i = φ_i·q_i the mode's displacement at the impact point
(q_i positive away from the building), chain node j moves X_j = side·Σ_{i≤j} s_i along the axis,
so the last node is the impact point (an SDOF wall's node: X = side·q). Mode i's equation divided
by φ_i, (m_i/φ_i²)·s̈_i + (c_i/φ_i²)·ṡ_i + (k_i/φ_i²)·s_i = −(L_i/φ_i)·a_g + F, is a spring and
dashpot (``zeroLength``, ``Elastic k/φ² c/φ²``) between nodes j−1 and j (the ground for the
first) and the mass m/φ² on the relative motion: lumped on the first node, an ``InertiaTruss``
(inerter: force m·(ẍ_j − ẍ_{j−1})) for later modes. The ground excitation loads only the lumped
mass, so a ``Plain`` pattern of the same a_g (the wall axis' component) adds the difference on
each chain node (P_j = L_{j+1}/φ_{j+1} − L_j/φ_j, plus m_1/φ_1² on the first; none for an SDOF
wall). This is femoat's modal wall exactly (the contact force F acts on every s_i, i.e. φ_i·F on
q_i); ``InertiaTruss`` prints its inertance on every step (to the captured stderr).
"""

import numpy as np

from femoat.opensees.tags import GROUND, INERTER_TAG, MODE_TAG, WALL_ELE, WALL_NODE, WALL_SERIES
from femoat.structure.moat_wall import wall_modes


def wall_chain(wall):
    """A wall's modes as the twin's chain of nodes (module docstring): per mode i the chain
    mass m_i/φ_i² [kip·s²/in], stiffness k_i/φ_i² [kip/in] and damping c_i/φ_i² [kip·s/in], and
    the ground-load correction P_i [kip·s²/in] on chain node i (the load P_i·a_g that turns the
    excitation's −m·a_g on the first node into the modes' −L·a_g)."""
    m, k, c, phi, L = wall_modes(wall)
    scale = phi * phi
    masses = m / scale
    participation = L / phi  # the load −L_i·a_g on q_i is −(L_i/φ_i)·a_g on s_i = φ_i·q_i
    correction = np.append(participation[1:], 0.0) - participation
    correction[0] += masses[0]
    return masses, k / scale, c / scale, correction


def wall_chain_nodes(i, wall):
    """Node tags of wall i's chain, first mode first; the last is the impact point."""
    n = len(wall_modes(wall)[0])
    if n > 99:  # the tags MODE_TAG + 100·i + j would collide
        raise ValueError(f"walls: a wall of {n} modes; the OpenSees twins take at most 99 "
                         "(ModalWall.from_fe(..., n_modes=...) chooses fewer).")
    return [WALL_NODE + i] + [MODE_TAG + 100 * i + j for j in range(1, n)]


def wall_chain_transform(wall, side):
    """T (modes × modes): chain node displacements X = T·q from the modal coordinates q (each
    positive away from the building): X_j = side·Σ_{i≤j} φ_i·q_i."""
    phi = wall_modes(wall)[3]
    return side * np.tril(np.ones((phi.size, phi.size))) * phi[None, :]


def wall_chain_commands(i, wall, frame, axis, mat):
    """Commands of wall i's chain along ``axis`` (0 x, 1 y) in the model space ``frame``
    (:mod:`femoat.opensees.frame`) from the material tag ``mat``: returns (commands, impact
    node, next material tag, load corrections).

    Chain node j sits at j along the axis (the inerters need a length; the zero-length
    springs between nodes apart only warn), free along the axis only; its displacement is
    Σ_{i≤j} s_i with s_i = φ_i·q_i the mode's displacement at the impact point. Mode 1 is a
    lumped mass m_1/φ_1² on node 1 and a spring and dashpot to the ground; mode j ≥ 2 is a
    spring and dashpot and an ``InertiaTruss`` of inertance m_j/φ_j² (force m·(ẍ_j − ẍ_{j−1}))
    between nodes j−1 and j, so each mode's equation is the modal one. A one-mode wall with
    φ = 1 and L = m (an SDOF wall) is one node with its mass and spring.
    """
    masses, stiffs, damps, correction = wall_chain(wall)
    nodes = wall_chain_nodes(i, wall)
    cmds, prev = [], GROUND
    for j, node in enumerate(nodes):
        cmds += [frame.node(node, float(j), axis), *frame.fix(node, free=(axis,))]
        if j == 0:
            cmds.append(("mass", node, *frame.vector({axis: float(masses[0])})))
        ele = WALL_ELE + i if j == 0 else MODE_TAG + 100 * i + j
        cmds += [("uniaxialMaterial", "Elastic", mat, float(stiffs[j]), float(damps[j])),
                 ("element", "zeroLength", ele, prev, node, "-mat", mat, "-dir", axis + 1)]
        if j > 0:
            cmds.append(("element", "InertiaTruss", INERTER_TAG + 100 * i + j, prev, node,
                         float(masses[j])))
        mat += 1
        prev = node
    return cmds, nodes[-1], mat, correction


def wall_load_commands(i, correction, accel, dt, frame, axis):
    """The ground-load corrections of wall i (:func:`wall_chain`): a ``Plain`` pattern of the
    ground acceleration ``accel`` [in/s²] along the wall's axis; none when all are zero."""
    nodes_loads = [(j, p) for j, p in enumerate(correction) if p != 0.0]
    if not nodes_loads:
        return []
    tag = WALL_SERIES + i
    cmds = [("timeSeries", "Path", tag, "-dt", float(dt), "-values", *accel),
            ("pattern", "Plain", tag, tag)]
    nodes = [WALL_NODE + i] + [MODE_TAG + 100 * i + j for j in range(1, len(correction))]
    for j, p in nodes_loads:
        cmds.append(("load", nodes[j], *frame.vector({axis: float(p)})))
    return cmds


def chain_to_modes(X, wall, side):
    """Modal coordinates q [in] (..., modes) of a wall from its chain node displacements X [in]
    (..., modes), inverting :func:`wall_chain_transform`: q_j = side·(X_j − X_{j−1})/φ_j."""
    phi = wall_modes(wall)[3]
    X = np.asarray(X, dtype=float)
    s = np.diff(X, axis=-1, prepend=0.0) if phi.size > 1 else X
    return side * s / phi
