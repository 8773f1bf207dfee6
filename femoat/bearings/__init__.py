"""Isolation bearings: one module per bearing kind, one line each in the registry.

A bearing kind is one module (the single friction pendulum, :mod:`femoat.bearings.friction_pendulum`,
is the first), listed in :data:`femoat.bearings.registry.KINDS`. It provides

* on the Python side: ``KEY`` (its name in scenario and suite files, ``[building.isolator] type``),
  ``N_PARAMS``, ``N_STATE_AXIS``, ``N_STATE_PLAN`` (its params and committed-state widths on one
  axis and in plan), ``AXIS_CLASS`` and ``PLAN_CLASS`` (its validated frozen dataclasses, with
  units; they may be one class), each with ``params()``, ``initial_state_axis()``,
  ``initial_state_plan()``, ``yield_deformation`` [in] and ``capacity`` [in]; optionally
  ``GEOMETRY_KEYS``, scenario keys that may replace its fields ``GEOMETRY_REPLACES``, read by
  ``AXIS_CLASS.from_geometry`` (the triple friction pendulum's manufacturer geometry);
* compiled kernels (numba, no allocation), each from the committed state ``s``, which only the
  commits modify (a kind may keep scratch slots after it in ``s``, which its plan trials write
  while they walk a step's path: the triple friction pendulum's):

  - ``axis_trial(p, s, u, v) -> (f, df/du, df/dv)``, ``axis_commit(p, s, u, v)``,
    ``axis_energy(p, s)``: the bearing on one axis (u [in], v [in/s], f [kip]);
  - ``plan_trial(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau, f, k, c)``: force ``f`` (2,),
    ∂f/∂u ``k`` and ∂f/∂v ``c`` (2, 2) in place at the end (ux, uy), (vx, vy) of a step of
    duration ``tau`` [s] from the committed state (start velocity (v0x, v0y)); ``tau = 0``: a
    path of no duration; ``plan_commit(...)`` with the same path arguments, ``plan_energy(p, s)``;
  - ``plan_branch(p, s, ux, uy) -> int``: the branch of a trial point (the solver lands a step
    where it changes) and ``plan_turn_direction(s) -> (dx, dy)``: the committed direction along
    which a velocity turning negative unloads the bearing ((0, 0): none);

optionally a **rate form** for the coupled-friction step (:mod:`femoat.integration.methods.ark5`;
all or none but the two with defaults, :data:`femoat.bearings.registry.RATE_KERNELS`): ``N_RATE_PLAN``, the width of its
friction state z (a vector the step carries while the kind says so), and

  - ``plan_rate_active(p, s, vx, vy) -> bool``: whether a step from the committed state at the
    velocity (vx, vy) carries z (the pendulum: it slides and keeps loading);
  - ``plan_rate_state(p, s, z) -> n``: the committed z into ``z``, its width n;
  - ``plan_rate(p, s, ux, uy, vx, vy, z, g, J)``: the rate ż = g(z; u, v) [1/s] into ``g`` and
    ∂g/∂z into ``J`` (the step solves each stage's z implicitly with it); z's first two entries
    are the committed direction of sliding (the kink search's test of a straight step);
  - ``plan_rate_turn(p, s, ux, uy, vx, vy, ax, ay, z, g, J) -> (r, ṙ)``: the loading measure
    whose crossing of zero downwards unloads the bearing and its time rate at the acceleration
    (ax, ay) (the turn search lands a step where it crosses, z moving); optional: without it,
    a bearing whose z is one sliding direction, r = z·v and ṙ = g·v + z·a
    (:func:`femoat.bearings.rate_form.turn_along`, the pendulum's and the lead-rubber
    bearing's);
  - ``plan_rate_branch(p, s, ux, uy, z) -> int``: the branch at a trial point of a step that
    carries z, z given there (the kink search follows z along the step); optional: without
    it, ``plan_branch`` (z's value does not change the branch while it is carried);
  - ``plan_rate_force(p, s, ux, uy, vx, vy, z, f, k, c)``: force and tangents at a stage whose z
    is given; ``plan_rate_commit(p, s, ux, uy, vx, vy, z)``: commit the step's end.

and, for its OpenSees twins (:mod:`femoat.opensees`), ``opensees_plan_element(bearing, ele_tag,
i_node, j_node, mat_tag) -> (commands, next_mat_tag)`` (the 3D element between two nodes, shear in
global x, y) with ``OPENSEES_AXIAL_LOAD`` (whether it needs the normal force W from a gravity
step), and where OpenSees has a uniaxial twin ``opensees_axis_material(bearing, mat_tag)`` (its
last material is the bearing; without it the 1D twin is the 3D one driven along x).

The kinds: ``fp`` :mod:`~femoat.bearings.friction_pendulum`, ``lrb``
:mod:`~femoat.bearings.lead_rubber`, ``tfp`` :mod:`~femoat.bearings.triple_friction_pendulum`.

Along one axis the plan kernels equal the one-axis kernels (each kind's tests hold it). Energy:
the recoverable energy at the committed state; the loop integrates the work, their difference is
the bearing's dissipation.
"""
