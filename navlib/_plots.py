"""Unchecked cores of :mod:`navlib.plots`' schematic primitives: a plane frame and an angle arc.

The checked public functions live in :mod:`navlib.plots`; a function of another module that has already
checked its axes (e.g. :func:`navlib.papers.north_finding.draw_device`) calls the core here with navlib's own
constants, so that nothing is checked twice on one call. ``ax`` is a matplotlib Axes, angles in deg
(counter-clockwise from the plot's +x axis), lengths in data units.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ._typing import ArrayLike

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.typing import ColorType


def plane_frame(ax: Axes, origin: ArrayLike, angle_deg: float, labels: Sequence[str], length: float, color: ColorType) -> None:
    """Two perpendicular axes from ``origin``, the first at ``angle_deg``, named by ``labels``."""
    o, a = np.asarray(origin, dtype=float), np.deg2rad(angle_deg)
    for k, name in enumerate(labels):
        d = length * np.array([np.cos(a + k * np.pi / 2), np.sin(a + k * np.pi / 2)])
        ax.annotate("", tuple(o + d), tuple(o), arrowprops={"arrowstyle": "-|>", "color": color, "linewidth": 1.4})
        tip = o + 1.12 * d
        ax.text(tip[0], tip[1], name, color=color, ha="center", va="center")


def angle_arc(ax: Axes, center: ArrayLike, radius: float, start_deg: float, end_deg: float, label: str, color: ColorType) -> None:
    """An arc from ``start_deg`` to ``end_deg`` with ``label`` (if any) at its middle."""
    from matplotlib.patches import Arc  # noqa: PLC0415 -- navlib imports without matplotlib

    c = np.asarray(center, dtype=float)
    lo, hi = min(start_deg, end_deg), max(start_deg, end_deg)
    ax.add_patch(Arc(tuple(c), 2 * radius, 2 * radius, theta1=lo, theta2=hi, color=color, linewidth=1))
    if label:
        mid = np.deg2rad((lo + hi) / 2)
        ax.text(
            c[0] + 1.25 * radius * np.cos(mid), c[1] + 1.25 * radius * np.sin(mid), label, color=color, ha="center", va="center"
        )
