"""Moat walls: the SDOF idealization of the paper and its presets."""

from femoat.walls.presets import DAMPING_CHOICES, PRESETS, WallPreset, wall_preset
from femoat.walls.modal import ModalWall
from femoat.walls.sdof import SdofWall

__all__ = ["DAMPING_CHOICES", "PRESETS", "ModalWall", "SdofWall", "WallPreset", "wall_preset"]
