"""The reduced nonlinear building: a base mat on an isolator, stories as shear springs.

Default: the paper's quarter-scale, 3-story moment frame on single friction-pendulum bearings
(docs/paper.md §4; the paper gives no weights, stiffnesses or strengths, so these representative
values are femoat's, and every one is a parameter):

* weights [kip]: base mat 10.0; floors 8.0, 8.0, 7.0 (bottom to top);
* isolation: one friction pendulum, R = 30 in, W = 33 kip, μ = 0.06, u_y = 0.01 in;
* stories: bilinear shear springs k0 = 42.799 kip/in (fixed-base T1 = 0.30 s), Fy = 11.556 kip
  (yield drift 0.27 in), hardening 0.03;
* damping: a dashpot c = β·k0 in parallel with each story, β = 2·0.02/ω1, ω1 = 2π/0.30 s;
* story heights [in]: 39.0 each, an assumption (a 13 ft prototype story at quarter scale; the
  paper gives none); they turn drifts into drift ratios and set the P-Delta stiffness;
* P-Delta off (the paper's model); on, every story carries the gravity load of the floors above
  it as a negative geometric stiffness −P/h (exact linear P-Delta of a shear story);
* isolator displacement capacity 7.0 in (the test bearings', docs/paper.md §4).
"""

import math
from dataclasses import dataclass, field

from femoat.bearings import registry as bearing_registry
from femoat.structure.materials import Bilinear, Elastic, FrictionPendulum


DEFAULT_STORY_HEIGHT = 39.0
"""Story height of the quarter-scale frame [in] (assumed: a 13 ft story at 1:4)."""


def _default_stories():
    return (Bilinear(), Bilinear(), Bilinear())


def check_story(material, where="stories"):
    """Raise unless ``material`` can be a story spring: a story material answers its initial
    stiffness [kip/in] (the story dashpot is β times it)."""
    if not isinstance(getattr(type(material), "initial_stiffness", None), property):
        raise ValueError(f"{where}: {type(material).__name__} is not a story material "
                         "(use Elastic, Bilinear or IMKBilinear).")


class StoryBuilding:
    """What every building shares, on one axis or in plan: the weights, the story damping, the
    story heights, P-Delta and the isolator's capacity (their fields, parameters as
    :class:`Building`), their checks and what follows from them. :class:`Building` adds the
    stories of its one axis, :class:`femoat.plan.PlanBuilding` one set per direction; each
    checks its own isolator."""

    AXES = ("x",)
    """The axes the building moves along."""

    def _check_shared(self):
        """Raise, naming the parameter, unless the shared fields are valid."""
        if not (math.isfinite(self.base_weight) and self.base_weight > 0):
            raise ValueError(f"base_weight = {self.base_weight!r} must be a positive weight [kip].")
        for i, w in enumerate(self.floor_weights):
            if not (math.isfinite(w) and w > 0):
                raise ValueError(f"floor_weights[{i}] = {w!r} must be a positive weight [kip].")
        for axis in self.AXES:
            key = self._stories_field(axis)
            stories = getattr(self, key)
            if len(stories) != len(self.floor_weights):
                raise ValueError(f"{key}: {len(stories)} story springs for "
                                 f"{len(self.floor_weights)} floors; give one story material per "
                                 "floor.")
            for mat in stories:
                check_story(mat, key)
        if not (math.isfinite(self.story_damping_ratio) and self.story_damping_ratio >= 0):
            raise ValueError(f"story_damping_ratio = {self.story_damping_ratio!r} must be >= 0.")
        if not (math.isfinite(self.story_damping_period) and self.story_damping_period > 0):
            raise ValueError(
                f"story_damping_period = {self.story_damping_period!r} must be a positive period [s].")
        if self.story_heights is not None:
            if len(self.story_heights) != len(self.floor_weights):
                raise ValueError(f"story_heights: {len(self.story_heights)} heights for "
                                 f"{len(self.floor_weights)} floors; give one height [in] per story.")
            for i, h in enumerate(self.story_heights):
                if not (isinstance(h, (int, float)) and math.isfinite(h) and h > 0):
                    raise ValueError(f"story_heights[{i}] = {h!r} must be a positive height [in].")
        if not isinstance(self.p_delta, bool):
            raise ValueError(f"p_delta = {self.p_delta!r} must be true or false.")
        if not (isinstance(self.isolator_capacity, (int, float))
                and self.isolator_capacity > 0 and not math.isnan(self.isolator_capacity)):
            raise ValueError(f"isolator_capacity = {self.isolator_capacity!r} must be a positive "
                             "displacement [in] (math.inf for none).")

    def _stories_field(self, axis):
        """The field holding the stories along ``axis``."""
        return "stories"

    def stories_along(self, axis="x"):
        """The story materials along ``axis`` ("x" or "y"), bottom to top."""
        if axis not in self.AXES:
            raise ValueError(f"axis = {axis!r}: use {' or '.join(map(repr, self.AXES))}.")
        return getattr(self, self._stories_field(axis))

    @property
    def heights(self):
        """Story heights [in], bottom to top (the default where none were given)."""
        if self.story_heights is None:
            return tuple(DEFAULT_STORY_HEIGHT for _ in self.floor_weights)
        return tuple(float(h) for h in self.story_heights)

    def gravity_loads(self):
        """Axial (gravity) load on each story [kip]: the weight of its floor and those above."""
        w = self.floor_weights
        return tuple(float(sum(w[k:])) for k in range(len(w)))

    def geometric_stiffnesses(self):
        """P-Delta stiffness of each story [kip/in], in every direction: −P_k/h_k, or zeros
        without P-Delta."""
        if not self.p_delta:
            return tuple(0.0 for _ in self.floor_weights)
        return tuple(-p / h for p, h in zip(self.gravity_loads(), self.heights))

    @property
    def total_weight(self):
        """Weight above the isolators [kip]."""
        return self.base_weight + sum(self.floor_weights)

    @property
    def story_damping_beta(self):
        """Stiffness-proportional factor β = 2ξ/ω1 [s] (every direction)."""
        return 2.0 * self.story_damping_ratio * self.story_damping_period / (2.0 * math.pi)


@dataclass(frozen=True)
class Building(StoryBuilding):
    """A base-isolated shear building on one axis.

    Parameters
    ----------
    base_weight : float
        Weight of the base mat [kip], > 0.
    floor_weights : tuple of float
        Floor weights [kip], bottom to top; empty for a bare base mat.
    isolator : FrictionPendulum or Elastic or None
        The isolation layer lumped into one element between base mat and ground: a bearing
        kind's one-axis form (:mod:`femoat.bearings`), an Elastic spring, or ``None`` (the base
        mat free: no restoring force, no friction).
    stories : tuple of materials
        One shear spring per floor (Elastic, Bilinear or IMKBilinear), bottom to top.
    story_damping_ratio : float
        Viscous damping ratio ξ [-] at ``story_damping_period``: a dashpot c = β·k0 in parallel
        with each story, β = 2ξ/ω1, ω1 = 2π/T1.
    story_damping_period : float
        Fixed-base first period T1 [s] used for β.
    story_heights : tuple of float or None
        Story heights [in], bottom to top; None: 39.0 in per story (assumed, see module).
    p_delta : bool
        Add each story's geometric stiffness −P_k/h_k, P_k the weight of floors k and above
        [kip] (linear P-Delta; the buckling load of an elastic story is k·h).
    isolator_capacity : float
        Displacement capacity of the isolator [in]: a collapse criterion, and 10 × it a runaway
        bound that ends every run (femoat.collapse).
    """

    base_weight: float = 10.0
    floor_weights: tuple = (8.0, 8.0, 7.0)
    isolator: object = field(default_factory=FrictionPendulum)
    stories: tuple = field(default_factory=_default_stories)
    story_damping_ratio: float = 0.02
    story_damping_period: float = 0.30
    story_heights: tuple | None = None
    p_delta: bool = False
    isolator_capacity: float = 7.0

    def __post_init__(self):
        bearings = bearing_registry.axis_classes()
        if self.isolator is not None and not isinstance(self.isolator, (*bearings, Elastic)):
            if type(self.isolator) in bearing_registry.plan_classes():
                raise ValueError(f"isolator: a {type(self.isolator).__name__} is a plan bearing; "
                                 "a 1D building takes its one-axis form (.uniaxial()).")
            names = ", ".join(c.__name__ for c in bearings)
            raise ValueError(f"isolator must be a bearing ({names}), an Elastic spring or None.")
        self._check_shared()
