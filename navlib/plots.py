"""Plot helpers shared by the notebooks (matplotlib; axes labelled with units)."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from . import attitude, units
from ._typing import Angles, Array, ArrayLike, Dcm
from ._validate import as_dcm, euler_angles, positive, same_shape, text

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.typing import ColorType
    from mpl_toolkits.mplot3d import Axes3D

__all__ = ["body_axes", "allan", "heading_deg"]

_AXIS_STYLE = (("x right", "tab:red"), ("y forward", "tab:green"), ("z up", "tab:blue"))


def body_axes(ax: Axes3D, C_bn: Dcm, title: str = "") -> None:
    """Draw the ENU frame (grey) and the body axes of ``C_bn`` on a 3-D axes.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    C_bn : array_like, shape (3, 3)
        Body-to-ENU rotation; its columns are the body axes in ENU.
    """
    if not hasattr(ax, "quiver") or not hasattr(ax, "set_zlim"):
        raise ValueError(f"ax: expected a 3-D matplotlib Axes (projection='3d'), got {type(ax).__name__}")
    C = as_dcm(C_bn, "C_bn")
    text(title, "title")
    for v, name in zip(np.eye(3), "ENU", strict=True):
        ax.quiver(0, 0, 0, *v, color="0.6", arrow_length_ratio=0.08, linewidth=1)
        ax.text(*(1.12 * v), name, color="0.4")
    for i, (name, color) in enumerate(_AXIS_STYLE):
        ax.quiver(0, 0, 0, *C[:, i], color=color, arrow_length_ratio=0.1, linewidth=2)
        ax.text(*(1.15 * C[:, i]), name, color=color)
    ax.set(xlim=(-1, 1), ylim=(-1, 1), zlim=(-1, 1), xlabel="East", ylabel="North", zlabel="Up")
    ax.set_box_aspect((1, 1, 1))
    if title:
        ax.set_title(title)


def allan(ax: Axes, taus: ArrayLike, adev_rad_s: ArrayLike, theory: ArrayLike | None = None, label: str = "",
          color: ColorType | None = None) -> None:
    """Log-log Allan deviation of a gyro in deg/h against averaging time in s.

    Parameters
    ----------
    taus : array_like, shape (M,)  (s)
    adev_rad_s : array_like, shape (M,) or (M, k)
        Allan deviation (rad/s); several columns are drawn thin.
    theory : array_like, shape (M,), optional
        Model curve (rad/s), drawn dashed.
    """
    if not hasattr(ax, "loglog"):
        raise ValueError(f"ax: expected a matplotlib Axes, got {type(ax).__name__}")
    taus = positive(taus, "taus")
    if taus.size == 0:
        raise ValueError("taus: expected at least one averaging time, got an empty array")
    a = units.to_deg_per_h(positive(adev_rad_s, "adev_rad_s"))
    if taus.ndim != 1:
        raise ValueError(f"taus: expected a 1-D array of averaging times, got shape {taus.shape}")
    if a.ndim not in (1, 2) or a.shape[0] != taus.size:
        raise ValueError(f"adev_rad_s: expected shape ({taus.size},) or ({taus.size}, k) (one row per tau), got {a.shape}")
    if theory is not None:
        theory = same_shape(positive(theory, "theory"), "theory", taus.shape, of="taus")
    text(label, "label")
    from matplotlib.colors import is_color_like  # noqa: PLC0415 -- navlib imports without matplotlib
    if color is not None and not is_color_like(color):
        raise ValueError(f"color: expected a matplotlib color, got {color!r:.40}")
    lines = ax.loglog(taus, a, color=color, linewidth=1 if a.ndim > 1 else 1.5, alpha=0.8)
    lines[0].set_label(label)
    if theory is not None:
        ax.loglog(taus, units.to_deg_per_h(theory), "--", color=lines[0].get_color(), linewidth=1.5,
                  label=f"{label} model" if label else "model")
    ax.set(xlabel="averaging time τ (s)", ylabel="Allan deviation (°/h)")
    ax.grid(True, which="both", alpha=0.3)


def heading_deg(hpr: Angles) -> Array:
    """Heading in degrees in [0, 360) from an ``hpr`` array (..., 3)."""
    return units.to_deg(attitude.wrap_2pi(euler_angles(hpr, "hpr")[..., 0]))
