"""What every bearing kind's dataclass answers alike: its virgin states, of its kind's widths, and
its material code on one axis (:mod:`femoat.bearings.registry`)."""

import sys

import numpy as np

from femoat.bearings import registry


class BearingFaces:
    """Mixin of a bearing kind's dataclass (one class for both faces, or either face): the
    kind's module gives the widths ``N_STATE_AXIS`` and ``N_STATE_PLAN``."""

    def initial_state_axis(self) -> np.ndarray:
        """Virgin committed state on one axis: at rest, centred (zeros)."""
        return np.zeros(sys.modules[type(self).__module__].N_STATE_AXIS)

    def initial_state_plan(self) -> np.ndarray:
        """Virgin committed state in plan: at rest, centred (zeros)."""
        return np.zeros(sys.modules[type(self).__module__].N_STATE_PLAN)

    def initial_state(self) -> np.ndarray:
        """The material convention's virgin state: on one axis."""
        return self.initial_state_axis()

    @property
    def code(self):
        """The material code of this bearing on one axis (:mod:`femoat.bearings.registry`)."""
        return registry.axis_code(self)
