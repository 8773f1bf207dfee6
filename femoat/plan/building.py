"""The building in plan: a base mat and floors that translate in x and y, no torsion.

Every floor (the base mat included) has two horizontal translations; floors do not rotate in
plan (no torsion in issue 18: the centres of mass and stiffness coincide, so a plan model is two
shear buildings, one per direction, coupled only by the isolator and the corner walls). The DOF
layout keeps a column for a rotation per floor (:mod:`femoat.plan.model`).

Stories: one 1D story material per floor and per direction (``stories_x``, ``stories_y``),
uncoupled: a story's x spring sees only the x drift. Default: the paper's building
(:class:`femoat.structure.building.Building`) in both directions. Story dashpots c = β·k0 per
story and direction, one β = 2ξ/ω1 for both (ω1 = 2π/T1 with T1 = ``story_damping_period``: the
damping matrix is β times the initial story stiffness in each direction). P-Delta, when on, adds
the linear geometric stiffness −P_k/h_k of each story in x and in y, as the 1D Building does.

The isolator is the bidirectional friction pendulum
(:class:`~femoat.plan.bearing.BidirectionalFrictionPendulum`, friction coupled in plan), an
:class:`~femoat.structure.materials.Elastic` spring (the same stiffness in x and y) or ``None``.
"""

from dataclasses import dataclass, field, fields

from femoat.bearings import registry as bearing_registry
from femoat.plan.bearing import BidirectionalFrictionPendulum
from femoat.structure.building import Building, StoryBuilding
from femoat.structure.layout import AXES
from femoat.structure.materials import Bilinear, Elastic, FrictionPendulum


def _paper_stories():
    return (Bilinear(), Bilinear(), Bilinear())


@dataclass(frozen=True)
class PlanBuilding(StoryBuilding):
    """A base-isolated shear building in plan (x, y translations per floor, no torsion).

    Parameters as :class:`~femoat.structure.building.Building` (weights [kip], story damping,
    story heights [in], P-Delta, isolator capacity [in], measured in plan: |u| of the base mat),
    but for:

    isolator : BidirectionalFrictionPendulum or Elastic or None
        A bearing kind's plan form (:mod:`femoat.bearings`: friction coupled in plan), an
        Elastic spring (alike in x and y), or ``None`` (the base mat free).
    stories_x, stories_y : tuple of materials
        One story material per floor (Elastic, Bilinear or IMKBilinear), bottom to top, for the
        x and the y direction.
    """

    base_weight: float = 10.0
    floor_weights: tuple = (8.0, 8.0, 7.0)
    isolator: object = field(default_factory=BidirectionalFrictionPendulum)
    stories_x: tuple = field(default_factory=_paper_stories)
    stories_y: tuple = field(default_factory=_paper_stories)
    story_damping_ratio: float = 0.02
    story_damping_period: float = 0.30
    story_heights: tuple | None = None
    p_delta: bool = False
    isolator_capacity: float = 7.0

    AXES = AXES

    def __post_init__(self):
        if isinstance(self.isolator, FrictionPendulum):
            raise ValueError("isolator: a FrictionPendulum is the 1D bearing; in plan use "
                             "femoat.plan.BidirectionalFrictionPendulum with the same parameters "
                             "(friction coupled in plan).")
        bearings = bearing_registry.plan_classes()
        if self.isolator is not None and not isinstance(self.isolator, (*bearings, Elastic)):
            names = ", ".join(c.__name__ for c in bearings)
            raise ValueError(f"isolator must be a {names}, an Elastic spring or None.")
        for axis in AXES:
            key = self._stories_field(axis)
            if not isinstance(getattr(self, key), tuple):
                raise ValueError(f"{key} must be a tuple of story materials, one per floor.")
        self._check_shared()

    def _stories_field(self, axis):
        return f"stories_{axis}"

    def along(self, axis):
        """The 1D :class:`~femoat.structure.building.Building` along ``axis`` ("x" or "y"): the
        stories of that direction, the isolator as its 1D bearing. Exactly this building when
        the motion stays on that axis."""
        if axis not in AXES:
            raise ValueError(f"axis = {axis!r}: use 'x' or 'y'.")
        iso = self.isolator
        kind = None if iso is None else bearing_registry.kind_of(iso)
        if kind is not None and bearing_registry.module(kind).AXIS_CLASS is not type(iso):
            iso = iso.uniaxial()
        return Building(
            base_weight=self.base_weight, floor_weights=tuple(self.floor_weights), isolator=iso,
            stories=self.stories_along(axis),
            story_damping_ratio=self.story_damping_ratio,
            story_damping_period=self.story_damping_period, story_heights=self.story_heights,
            p_delta=self.p_delta, isolator_capacity=self.isolator_capacity)

    @classmethod
    def from_building(cls, building, stories_y=None):
        """The plan building of a 1D ``building``: its stories in x (and in y unless
        ``stories_y`` is given), its friction pendulum made bidirectional."""
        if not isinstance(building, Building):
            raise ValueError("building must be a femoat.structure.building.Building.")
        iso = building.isolator
        kind = None if iso is None else bearing_registry.kind_of(iso)
        if kind is not None:  # the bearing's plan face, the same parameters
            plan_class = bearing_registry.module(kind).PLAN_CLASS
            if plan_class is not type(iso):
                iso = plan_class(**{f.name: getattr(iso, f.name) for f in fields(iso)})
        return cls(base_weight=building.base_weight, floor_weights=tuple(building.floor_weights),
                   isolator=iso, stories_x=tuple(building.stories),
                   stories_y=tuple(building.stories if stories_y is None else stories_y),
                   story_damping_ratio=building.story_damping_ratio,
                   story_damping_period=building.story_damping_period,
                   story_heights=building.story_heights, p_delta=building.p_delta,
                   isolator_capacity=building.isolator_capacity)
