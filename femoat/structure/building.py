"""The reduced nonlinear building: a base mat on an isolator, stories as shear springs.

Default: the paper's quarter-scale, 3-story moment frame on single friction-pendulum bearings
(PAPER.md §4; the paper gives no weights, stiffnesses or strengths, so these representative
values are femoat's, and every one is a parameter):

* weights [kip]: base mat 10.0; floors 8.0, 8.0, 7.0 (bottom to top);
* isolation: one friction pendulum, R = 30 in, W = 33 kip, μ = 0.06, u_y = 0.01 in;
* stories: bilinear shear springs k0 = 42.799 kip/in (fixed-base T1 = 0.30 s), Fy = 11.556 kip
  (yield drift 0.27 in), hardening 0.03;
* damping: a dashpot c = β·k0 in parallel with each story, β = 2·0.02/ω1, ω1 = 2π/0.30 s.
"""

import math
from dataclasses import dataclass, field

from femoat.structure.materials import Bilinear, Elastic, FrictionPendulum, IMKBilinear


def _default_stories():
    return (Bilinear(), Bilinear(), Bilinear())


def initial_stiffness(material):
    """Initial stiffness [kip/in] of a story material."""
    if isinstance(material, Elastic):
        return material.k
    if isinstance(material, Bilinear):
        return material.k0
    if isinstance(material, IMKBilinear):
        return material.K0
    raise ValueError(f"stories: {type(material).__name__} is not a story material "
                     "(use Elastic, Bilinear or IMKBilinear).")


@dataclass(frozen=True)
class Building:
    """A base-isolated shear building.

    Parameters
    ----------
    base_weight : float
        Weight of the base mat [kip], > 0.
    floor_weights : tuple of float
        Floor weights [kip], bottom to top; empty for a bare base mat.
    isolator : FrictionPendulum or Elastic or None
        The isolation layer lumped into one element between base mat and ground; ``None`` leaves
        the base mat free (no restoring force, no friction).
    stories : tuple of materials
        One shear spring per floor (Elastic, Bilinear or IMKBilinear), bottom to top.
    story_damping_ratio : float
        Viscous damping ratio ξ [-] at ``story_damping_period``: a dashpot c = β·k0 in parallel
        with each story, β = 2ξ/ω1, ω1 = 2π/T1.
    story_damping_period : float
        Fixed-base first period T1 [s] used for β.
    """

    base_weight: float = 10.0
    floor_weights: tuple = (8.0, 8.0, 7.0)
    isolator: object = field(default_factory=FrictionPendulum)
    stories: tuple = field(default_factory=_default_stories)
    story_damping_ratio: float = 0.02
    story_damping_period: float = 0.30

    def __post_init__(self):
        if not (math.isfinite(self.base_weight) and self.base_weight > 0):
            raise ValueError(f"base_weight = {self.base_weight!r} must be a positive weight [kip].")
        for i, w in enumerate(self.floor_weights):
            if not (math.isfinite(w) and w > 0):
                raise ValueError(f"floor_weights[{i}] = {w!r} must be a positive weight [kip].")
        if len(self.stories) != len(self.floor_weights):
            raise ValueError(
                f"stories: {len(self.stories)} story springs for {len(self.floor_weights)} floors; "
                "give one story material per floor."
            )
        for s in self.stories:
            initial_stiffness(s)
        if self.isolator is not None and not isinstance(self.isolator, (FrictionPendulum, Elastic)):
            raise ValueError("isolator must be a FrictionPendulum, an Elastic spring or None.")
        if not (math.isfinite(self.story_damping_ratio) and self.story_damping_ratio >= 0):
            raise ValueError(f"story_damping_ratio = {self.story_damping_ratio!r} must be >= 0.")
        if not (math.isfinite(self.story_damping_period) and self.story_damping_period > 0):
            raise ValueError(
                f"story_damping_period = {self.story_damping_period!r} must be a positive period [s].")

    @property
    def total_weight(self):
        """Weight above the isolators [kip]."""
        return self.base_weight + sum(self.floor_weights)

    @property
    def story_damping_beta(self):
        """Stiffness-proportional factor β = 2ξ/ω1 [s]."""
        return 2.0 * self.story_damping_ratio * self.story_damping_period / (2.0 * math.pi)
