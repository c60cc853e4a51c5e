"""The pointing-cone panel of the spm maps: a polar map drawn on plain axes.

Polar axes transform every mesh vertex non-affinely and take seconds per panel; here the
(tilt, azimuth) grid is resampled once onto a square image of the disk (x = psi2 cos psi1,
y = psi2 sin psi1), shown with ``imshow``, and the polar grid is drawn by hand. Angles
in degrees.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.colors import Colormap, Normalize
from matplotlib.patches import Circle
from matplotlib.ticker import MaxNLocator
from numpy.typing import NDArray

if TYPE_CHECKING:
    from matplotlib.axes import Axes

#: The spoke (deg) along which the tilt rings are labelled.
RING_LABEL_ANGLE_DEG = 100.0

__all__ = [
    "DISK_PIXELS",
    "RING_LABEL_ANGLE_DEG",
    "disk_image",
    "disk_panel",
]

FloatArray = NDArray[np.float64]
#: Pixels across the resampled disk.
DISK_PIXELS = 321
_SPOKES_DEG = np.arange(0.0, 360.0, 45.0)


def _bracket(grid: FloatArray, x: FloatArray) -> tuple[NDArray[np.intp], FloatArray]:
    """Cell index and fraction of x in the ascending nodes ``grid`` (clipped to it)."""
    cell = np.clip(np.searchsorted(grid, x, side="right") - 1, 0, grid.size - 2)
    width = grid[cell + 1] - grid[cell]
    fraction = np.clip((x - grid[cell]) / np.where(width > 0, width, 1.0), 0.0, 1.0)
    return cell, fraction


def disk_image(
    azimuth_deg: FloatArray, tilt_deg: FloatArray, values: FloatArray, pixels: int = DISK_PIXELS
) -> FloatArray:
    """values (nt, na) on tilt_deg x azimuth_deg (azimuth covering [0, 360]) resampled
    bilinearly onto a (pixels, pixels) image of the disk of radius tilt_deg[-1]
    (rows: y ascending). NaN outside the disk and next to a pose without a solution."""
    radius = float(tilt_deg[-1])
    axis = np.linspace(-radius, radius, pixels)
    x, y = np.meshgrid(axis, axis)
    r = np.hypot(x, y)
    a = np.mod(np.degrees(np.arctan2(y, x)) - azimuth_deg[0], 360.0) + azimuth_deg[0]
    i, fi = _bracket(tilt_deg, r)
    j, fj = _bracket(azimuth_deg, a)
    image = ((1 - fi) * (1 - fj) * values[i, j] + (1 - fi) * fj * values[i, j + 1]
             + fi * (1 - fj) * values[i + 1, j] + fi * fj * values[i + 1, j + 1])  # fmt: skip
    return np.where(r <= radius * (1.0 + 1e-9), image, np.nan)


def disk_panel(
    ax: Axes, image: FloatArray, radius: float, norm: Normalize, cmap: Colormap, background: str
) -> None:
    """The image on a ``background`` disk (shows through NaN), polar grid and labels."""
    ax.add_patch(Circle((0.0, 0.0), radius, color=background, zorder=0))
    clear = cmap.with_extremes(bad=(0.0, 0.0, 0.0, 0.0))  # NaN: the disk shows through
    ax.imshow(np.ma.masked_invalid(image), origin="lower", extent=(-radius, radius, -radius,
              radius), cmap=clear, norm=norm, interpolation="nearest", zorder=1)  # fmt: skip
    turn = np.linspace(0.0, 2.0 * np.pi, 361)
    for tick in MaxNLocator(nbins=5, steps=[1, 2, 2.5, 5, 10]).tick_values(0.0, radius):
        if 0.0 < tick < radius * 0.999:
            ax.plot(tick * np.cos(turn), tick * np.sin(turn), color="white", lw=0.5, alpha=0.5,
                    zorder=2)  # fmt: skip
            ring = np.radians(RING_LABEL_ANGLE_DEG)
            ax.text(tick * np.cos(ring), tick * np.sin(ring), f"{tick:g}°", fontsize=7.5,
                    color="white", ha="center", va="bottom", zorder=4)  # fmt: skip
    for spoke in np.radians(_SPOKES_DEG):
        ax.plot([0.0, radius * np.cos(spoke)], [0.0, radius * np.sin(spoke)], color="white",
                lw=0.5, alpha=0.5, zorder=2)  # fmt: skip
        ax.text(1.1 * radius * np.cos(spoke), 1.1 * radius * np.sin(spoke),
                f"{np.degrees(spoke):g}°", fontsize=8.5, ha="center", va="center")  # fmt: skip
    ax.plot(radius * np.cos(turn), radius * np.sin(turn), color="black", lw=1.0, zorder=3)
    ax.set_xlim(-1.2 * radius, 1.2 * radius)
    ax.set_ylim(-1.2 * radius, 1.2 * radius)
    ax.set_aspect("equal")
    ax.set_axis_off()
