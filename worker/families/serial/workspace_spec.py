"""Validated inputs of ``serial-workspace-map``: an arm, the joint sampling and the grids."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from worker.common.field_errors import field_error
from worker.families.serial.arm_inputs import ArmInputs, characteristic_length_field, plots_field
from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.kinematics.voxel_grid import VoxelGrid, voxel_grid

__all__ = ["MAX_MAP_CELLS", "MAX_SAMPLES", "SerialWorkspaceMapSpec"]

#: The most joint samples one map draws.
MAX_SAMPLES = 20_000_000
#: The most voxels x orientation bins one map holds (a bit each, as bytes: 200 MB).
MAX_MAP_CELLS = 200_000_000
#: The most voxels (or pixels) of one grid.
MAX_VOXELS = 8_000_000


class SerialWorkspaceMapSpec(ArmInputs):
    """Inputs of ``serial-workspace-map``."""

    samples: int = Field(100_000, ge=64, le=MAX_SAMPLES, description="Joint samples to "
                         "draw within the joint limits (the grid sampler uses the largest "
                         "m**joints not above it).")  # fmt: skip
    sampler: Literal["sobol", "uniform", "grid"] = Field(
        "sobol", description="sobol: scrambled Sobol' points; uniform: seeded uniform "
        "random; grid: a tensor grid of cell-centred joint values in a seeded order."
    )  # fmt: skip
    seed: int = Field(0, ge=0, le=2**32 - 1, description="Seed of the sampler.")
    voxel_size: float = Field(..., gt=0.0, le=1e6, description="Edge of a voxel "
                              "(pixel), length_unit; nodes at its multiples.")  # fmt: skip
    orientation_bins: int = Field(36, ge=1, le=4096, description="Orientation bins: equal "
                                  "phi bins over [-180, 180) deg (planar arm) or equal-area "
                                  "tool-axis cells on the sphere.")  # fmt: skip
    bounds: tuple[tuple[float, float], ...] | None = Field(
        None, min_length=2, max_length=3, description="[[xmin, xmax], [ymin, ymax], "
        "[zmin, zmax]] (z ignored for a planar arm), length_unit; null: the arm's reach."
    )  # fmt: skip
    convergence_tolerance: float = Field(0.02, gt=0.0, le=1.0, description="Largest "
                                         "relative change of the reached volume and of the "
                                         "mean reachability index over the last doubling "
                                         "of the samples for convergence.met.")  # fmt: skip
    characteristic_length: float | None = characteristic_length_field()
    plots: bool = plots_field()

    @model_validator(mode="after")
    def _bounded_grid(self) -> SerialWorkspaceMapSpec:
        arm = self.arm()
        if self.bounds is not None:
            if len(self.bounds) < (2 if arm.planar else 3):
                raise field_error(self, ("bounds",), "a spatial arm needs x, y and z "
                                  "bounds", [list(b) for b in self.bounds])  # fmt: skip
            for k, (lo, hi) in enumerate(self.bounds):
                if not lo < hi:
                    raise field_error(self, ("bounds", k), "lower must be below upper",
                                      [lo, hi])  # fmt: skip
        for k, (lo, hi) in enumerate(zip(arm.lower, arm.upper, strict=True)):
            if not lo < hi:
                raise field_error(self, ("robot",), f"joint {arm.names[k]} has an empty "
                                  "range; the map samples within the limits", None)  # fmt: skip
        voxels = 1
        for axis in self.grid(arm).axes:
            voxels *= axis.shape[0]
        if voxels > MAX_VOXELS or voxels * self.orientation_bins > MAX_MAP_CELLS:
            raise field_error(self, ("voxel_size",), f"the grid would hold {voxels:,} "
                              f"voxels x {self.orientation_bins} bins; at most "
                              f"{MAX_VOXELS:,} voxels and {MAX_MAP_CELLS:,} voxel-bins: "
                              "use larger voxels, fewer bins or bounds",
                              self.voxel_size)  # fmt: skip
        return self

    def grid(self, arm: SerialArm) -> VoxelGrid:
        """The voxel (pixel) grid."""
        return voxel_grid(arm, self.voxel_size, self.bounds, arm.planar)
