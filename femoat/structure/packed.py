"""The packed model: the plain arrays the compiled loop integrates, one type for a model on one
axis and a model in plan (:func:`femoat.structure.packing.pack` builds it).

A model on one axis is the plan model reduced to that axis: its layout has no y DOFs (a 1D run
carries none), its elements all act along x, it has no plan bearing (its isolator is one of its
elements), and its walls have no slip rows and no friction (zeros).
"""

from dataclasses import dataclass

import numpy as np

from femoat.structure.layout import AXES, Layout


@dataclass
class PackedModel:
    """Plain arrays of a model (mutable copies: the loop updates the states). n DOFs, ``k``
    axes (1 or 2), ne uniaxial elements, nb plan bearings (0 on one axis), nc walls.

    * ``M``, ``C``, ``K`` (n, n): the floors' masses on each axis [kip·s²/in], story dashpots
      c = β·k0 [kip·s/in] and P-Delta −P/h [kip/in] per axis, the walls' modal masses,
      dampings and stiffnesses;
    * ``R`` (n, k) [kip·s²/in]: the ground load is −R·a_g, a_g one acceleration per axis
      [in/s²]: the masses on their axis, a wall mode's participation L_i along its normal
      (signed: the mode points away from the building);
    * ``layout``: the :class:`~femoat.structure.layout.Layout` of the DOFs;
    * ``story_heights`` (stories,) [in];
    * uniaxial elements (stories; an isolator that is not a plan bearing, one per axis):
      DOFs ``el_i`` (top) and ``el_j`` (bottom, −1 the ground), ``el_axis`` (0 x, 1 y),
      material ``el_code``, params ``el_P``, state ``el_S``, ``el_roles``
      (:class:`~femoat.structure.roles.Role`), ``el_materials``;
    * the plan bearing (a kind of :mod:`femoat.bearings`): ``bearing_kind`` (nb,),
      ``bearing_dofs`` (nb, 2) (the base mat's x, y), params ``bearing_P`` and plan state
      ``bearing_S`` (nb, the registry's widest);
    * contacts, one row per wall: ``c_B`` (nc, n) (δ = c_B·u − gap [in]: n at the base mat,
      −φ_i on the wall's modes), ``c_T`` (nc, n) (the base mat's slip along the wall: t at the
      base mat), ``c_gap`` [in], law ``c_code``, params ``c_P``, history ``c_H``, friction
      coefficient ``c_friction`` [-], ``c_names`` (the layout's wall names), ``walls``.
    """

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    R: np.ndarray
    layout: Layout
    story_heights: np.ndarray
    el_i: np.ndarray
    el_j: np.ndarray
    el_axis: np.ndarray
    el_code: np.ndarray
    el_P: np.ndarray
    el_S: np.ndarray
    el_roles: tuple
    el_materials: list
    bearing_kind: np.ndarray
    bearing_dofs: np.ndarray
    bearing_P: np.ndarray
    bearing_S: np.ndarray
    c_B: np.ndarray
    c_T: np.ndarray
    c_gap: np.ndarray
    c_code: np.ndarray
    c_P: np.ndarray
    c_H: np.ndarray
    c_friction: np.ndarray
    c_names: list
    walls: tuple

    @property
    def n(self):
        """Number of DOFs."""
        return self.M.shape[0]

    @property
    def n_struct(self):
        """Number of building DOFs (the floors' translations), the first ones."""
        return self.layout.n_struct

    @property
    def dof_names(self):
        """One name per DOF (:class:`~femoat.structure.layout.Layout`)."""
        return list(self.layout.names)

    @property
    def r(self):
        """The ground load's influence [kip·s²/in]: on one axis R's column (n,), in plan
        ``R`` (n, 2)."""
        return self.R[:, 0] if self.R.shape[1] == 1 else self.R

    @property
    def el_names(self):
        """Each uniaxial element's name, from its role: on one axis ``"isolator"``,
        ``"story1"``, ...; in plan with its axis, ``"story1_x"``, ``"isolator_y"``, ..."""
        if len(self.layout.axes) == 1:
            return [role.name for role in self.el_roles]
        return [f"{role.name}_{AXES[a]}" for role, a in zip(self.el_roles, self.el_axis)]

    @property
    def dof_axis(self):
        """(n,) the axis (0 x, 1 y) each DOF moves along (a wall mode: its normal's)."""
        axis = np.zeros(self.n, dtype=np.int64)
        for a in range(len(self.layout.axes)):
            axis[self.layout.floor_dofs[:, a]] = a
        for w, cols in zip(self.walls, self.layout.wall_dofs):
            axis[list(cols)] = w.axis
        return axis
