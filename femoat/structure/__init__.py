"""The building: story and isolator materials, the shear building, and the pounding model."""
