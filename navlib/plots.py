"""Plot helpers shared by the notebooks (matplotlib; axes labelled with units).

Besides data plots, primitives for the schematics the chapters redraw (block diagrams, plane frames,
angles) and one style for a paper's value on a figure (:data:`PAPER_STYLE`), so that "the paper says"
looks the same on every figure of every notebook.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Annotated, Any

import numpy as np

from . import _plots, attitude, units
from ._typing import Angles, Array, ArrayLike, Dcm
from ._validate import (
    Check,
    Fraction,
    Positive,
    Real,
    Text,
    as_array,
    as_dcm,
    axes,
    boundary,
    euler_angles,
    instance,
    positive,
    same_shape,
    scalar,
    text,
)

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.typing import ColorType
    from mpl_toolkits.mplot3d import Axes3D

__all__ = ["body_axes", "allan", "heading_deg", "PAPER_STYLE", "paper_value", "block_diagram", "plane_frame", "angle_arc"]

PAPER_STYLE: dict[str, Any] = {"color": "black", "linestyle": (0, (5, 3)), "linewidth": 1.2}
"""How a paper's printed value or curve is drawn: black, long dashes (markers: black open symbols)."""

_AXIS_STYLE = (("x right", "tab:red"), ("y forward", "tab:green"), ("z up", "tab:blue"))


@boundary
def body_axes(ax: Axes3D, C_bn: Dcm, title: Text = "") -> None:
    """Draw the ENU frame (grey) and the body axes of ``C_bn`` on a 3-D axes.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    C_bn : array_like, shape (3, 3)
        Body-to-ENU rotation; its columns are the body axes in ENU.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> import numpy as np
    >>> from navlib import attitude, plots
    >>> fig = plt.figure()
    >>> ax = fig.add_subplot(projection="3d")
    >>> plots.body_axes(ax, attitude.euler_to_dcm(np.deg2rad([30.0, 0.0, 0.0])), title="heading 30 deg")
    >>> ax.get_title()
    'heading 30 deg'
    >>> plt.close(fig)
    """
    if not hasattr(ax, "quiver") or not hasattr(ax, "set_zlim"):
        raise ValueError(f"ax: expected a 3-D matplotlib Axes (projection='3d'), got {type(ax).__name__}")
    C = as_dcm(C_bn, "C_bn")
    # E, N, U labelled beyond the body axes' labels (a level body's z axis lies on U)
    for v, at, name in zip(np.eye(3), [(1.3, 0, -0.18), (0, 1.3, -0.18), (0, 0, 1.38)], "ENU", strict=True):
        ax.quiver(0, 0, 0, *v, color="0.6", arrow_length_ratio=0.08, linewidth=1)
        ax.text(*at, name, color="0.4")
    for i, (name, color) in enumerate(_AXIS_STYLE):
        ax.quiver(0, 0, 0, *C[:, i], color=color, arrow_length_ratio=0.1, linewidth=2)
        ax.text(*(1.15 * C[:, i]), name, color=color)
    ax.set(xlim=(-1, 1), ylim=(-1, 1), zlim=(-1, 1), xlabel="East", ylabel="North", zlabel="Up")
    ax.set_box_aspect((1, 1, 1))
    if title:
        ax.set_title(title)


@boundary
def allan(
    ax: Axes,
    taus: ArrayLike,
    adev_rad_s: ArrayLike,
    theory: ArrayLike | None = None,
    label: Text = "",
    color: ColorType | None = None,
) -> None:
    """Log-log Allan deviation of a gyro in deg/h against averaging time in s.

    Parameters
    ----------
    taus : array_like, shape (M,)  (s)
    adev_rad_s : array_like, shape (M,) or (M, k)
        Allan deviation (rad/s); several columns are drawn thin.
    theory : array_like, shape (M,), optional
        Model curve (rad/s), drawn dashed.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> import numpy as np
    >>> from navlib import analysis, plots
    >>> taus = np.geomspace(0.1, 100.0, 10)
    >>> fig, ax = plt.subplots()
    >>> plots.allan(ax, taus, analysis.allan_deviation_theory(taus, white=1e-4), label="white noise")
    >>> ax.get_xscale(), ax.get_ylabel()
    ('log', 'Allan deviation (°/h)')
    >>> plt.close(fig)
    """
    axes(ax)
    taus = positive(taus, "taus", shape=(None,), nonempty=True)
    a = units.to_deg_per_h(positive(adev_rad_s, "adev_rad_s"))
    if a.ndim not in (1, 2) or a.shape[0] != taus.size:
        raise ValueError(f"adev_rad_s: expected shape ({taus.size},) or ({taus.size}, k) (one row per tau), got {a.shape}")
    if theory is not None:
        theory = same_shape(positive(theory, "theory"), "theory", taus.shape, of="taus")
    if color is not None:
        _color(color, "color")
    lines = ax.loglog(taus, a, color=color, linewidth=1 if a.ndim > 1 else 1.5, alpha=0.8)
    lines[0].set_label(label)
    if theory is not None:
        ax.loglog(
            taus,
            units.to_deg_per_h(theory),
            "--",
            color=lines[0].get_color(),
            linewidth=1.5,
            label=f"{label} model" if label else "model",
        )
    ax.set(xlabel="averaging time τ (s)", ylabel="Allan deviation (°/h)")
    ax.grid(True, which="both", alpha=0.3)


def heading_deg(hpr: Angles) -> Array:
    """Heading in degrees in [0, 360) from an ``hpr`` array (..., 3).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import plots
    >>> np.round(plots.heading_deg(np.array([[-0.1, 0.0, 0.0], [np.pi, 0.0, 0.0]])), 3)
    array([354.27, 180.  ])
    """
    return units.to_deg(attitude.wrap_2pi(euler_angles(hpr, "hpr")[..., 0]))


def _color(c: object, name: str) -> None:
    from matplotlib.colors import is_color_like  # noqa: PLC0415 -- navlib imports without matplotlib

    if c is None or not is_color_like(c):
        raise ValueError(f"{name}: expected a matplotlib color, got {c!r:.40}")


@boundary
def paper_value(
    ax: Axes,
    value: Real,
    label: Text,
    *,
    axis: Annotated[str, Check("choice", options=("x", "y"))] = "y",
    text_at: Annotated[float, Check("scalar", within=(0.0, 1.0))] = 0.02,
) -> None:
    """Mark a paper's printed value on ``ax``: a line in :data:`PAPER_STYLE` with its label written on it.

    Parameters
    ----------
    value : float
        The printed value, in the units of the axis it is drawn on.
    label : str
        e.g. ``"paper: 1.25°"``; also the legend entry.
    axis : {"y", "x"}
        ``"y"``: a horizontal line at y = value; ``"x"``: a vertical line at x = value.
    text_at : float
        Where along the line the label sits, as a fraction of the axes in [0, 1] (0 = left/bottom).

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib import plots
    >>> fig, ax = plt.subplots()
    >>> plots.paper_value(ax, 0.5, "paper: 0.5 deg")
    >>> len(ax.lines), ax.texts[0].get_text()
    (1, 'paper: 0.5 deg')
    >>> plt.close(fig)
    """
    axes(ax)
    if axis == "y":
        ax.axhline(value, label=label, **PAPER_STYLE)
        ax.annotate(
            label,
            (text_at, value),
            xycoords=("axes fraction", "data"),
            xytext=(0, 3),
            textcoords="offset points",
            fontsize=8,
            va="bottom",
        )
    else:
        ax.axvline(value, label=label, **PAPER_STYLE)
        ax.annotate(
            label,
            (value, text_at),
            xycoords=("data", "axes fraction"),
            xytext=(3, 0),
            textcoords="offset points",
            fontsize=8,
            rotation=90,
            va="bottom",
        )


@boundary
def block_diagram(
    ax: Axes,
    blocks: Mapping[str, Sequence[object]],
    arrows: Sequence[Sequence[str]],
    *,
    width: Fraction = 0.18,
    height: Fraction = 0.11,
    colors: Mapping[str, ColorType] | None = None,
) -> None:
    """Draw a block diagram (signal flow) on ``ax`` in axes coordinates [0, 1] x [0, 1].

    Parameters
    ----------
    blocks : dict
        ``name -> (x, y, text)``: a rounded box centred at (x, y) (axes fractions) holding ``text``
        (may contain newlines and mathtext).
    arrows : list
        ``(from, to)`` or ``(from, to, label)``: a straight arrow between the two boxes, labelled at
        its middle. Route around a box with an extra (empty-text) block.
    width, height : float
        Box size as a fraction of the axes, in (0, 1].
    colors : dict, optional
        ``name -> face colour`` for boxes to set apart (e.g. the sensors); default light grey.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib import plots
    >>> fig, ax = plt.subplots()
    >>> plots.block_diagram(ax, {"imu": (0.2, 0.5, "IMU"), "ins": (0.6, 0.5, "INS")}, [("imu", "ins", "w, f")])
    >>> sorted(t.get_text() for t in ax.texts)
    ['', 'IMU', 'INS', 'w, f']
    >>> plt.close(fig)
    """
    axes(ax)
    instance(blocks, "blocks", dict, "a dict name -> (x, y, text)")
    instance(arrows, "arrows", (list, tuple), "a list of (from, to[, label])")
    colors = {} if colors is None else dict(instance(colors, "colors", dict, "a dict name -> colour"))
    boxes = {}
    for name, spec in blocks.items():
        if not isinstance(spec, (tuple, list)) or len(spec) != 3:
            raise ValueError(f"blocks: expected (x, y, text) for {name!r}, got {spec!r:.60}")
        boxes[name] = (*as_array(spec[:2], f"blocks[{name!r}]", shape=(2,)), text(spec[2], f"blocks[{name!r}] text"))
    for arrow in arrows:
        if not isinstance(arrow, (tuple, list)) or len(arrow) not in (2, 3) or arrow[0] not in boxes or arrow[1] not in boxes:
            raise ValueError(f"arrows: expected (from, to[, label]) between blocks {sorted(boxes)}, got {arrow!r:.60}")
    for name, c in colors.items():
        _color(c, f"colors[{name!r}]")
    from matplotlib.patches import FancyBboxPatch  # noqa: PLC0415 -- navlib imports without matplotlib

    for name, (x, y, label) in boxes.items():
        ax.add_patch(
            FancyBboxPatch(
                (x - width / 2, y - height / 2),
                width,
                height,
                transform=ax.transAxes,
                boxstyle="round,pad=0.01",
                facecolor=colors.get(name, "0.93"),
                edgecolor="0.3",
                linewidth=1,
            )
        )
        ax.text(x, y, label, transform=ax.transAxes, ha="center", va="center", fontsize=8.5)
    for arrow in arrows:
        (x0, y0, _), (x1, y1, _) = boxes[arrow[0]], boxes[arrow[1]]
        # leave each box where the line from centre to centre crosses its edge
        dx, dy = x1 - x0, y1 - y0
        s = min((width / 2 + 0.01) / abs(dx) if dx else np.inf, (height / 2 + 0.01) / abs(dy) if dy else np.inf, 0.5)
        start, end = (x0 + s * dx, y0 + s * dy), (x1 - s * dx, y1 - s * dy)
        ax.annotate("", end, start, xycoords="axes fraction", arrowprops={"arrowstyle": "-|>", "color": "0.25", "linewidth": 1.1})
        if len(arrow) == 3:
            ax.text(
                (start[0] + end[0]) / 2,
                (start[1] + end[1]) / 2,
                text(arrow[2], "arrows label"),
                transform=ax.transAxes,
                ha="center",
                va="bottom",
                fontsize=7.5,
                color="0.2",
                bbox={"facecolor": "white", "edgecolor": "none", "pad": 0.5},
            )
    ax.set(xlim=(0, 1), ylim=(0, 1))
    ax.set_axis_off()


@boundary
def plane_frame(
    ax: Axes,
    origin: tuple[float, float],
    angle_deg: Real,
    labels: Sequence[str],
    *,
    length: Positive = 1.0,
    color: ColorType = "0.2",
) -> None:
    """Draw a 2-D frame: two perpendicular axes from ``origin``, the first at ``angle_deg``.

    ``angle_deg`` is measured counter-clockwise from the plot's +x axis (for a map with x east and
    y north, a body forward axis at heading psi has angle 90° - psi). ``labels`` name the first
    and second axis (the second is 90° counter-clockwise of the first). ``length`` in data units.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib import plots
    >>> fig, ax = plt.subplots()
    >>> plots.plane_frame(ax, (0.0, 0.0), 90.0, ("x_b", "y_b"))
    >>> sorted(t.get_text() for t in ax.texts)
    ['', '', 'x_b', 'y_b']
    >>> plt.close(fig)
    """
    axes(ax)
    o = as_array(origin, "origin", shape=(2,))
    if not isinstance(labels, (tuple, list)) or len(labels) != 2:
        raise ValueError(f"labels: expected two axis names, got {labels!r:.60}")
    names = [text(n, "labels") for n in labels]
    _color(color, "color")
    _plots.plane_frame(ax, o, angle_deg, names, length, color)


@boundary
def angle_arc(
    ax: Axes,
    center: tuple[float, float],
    radius: Positive,
    start_deg: float,
    end_deg: float,
    label: Text = "",
    *,
    color: ColorType = "0.2",
) -> None:
    """An arc from ``start_deg`` to ``end_deg`` (counter-clockwise from +x) with ``label`` at its middle.

    ``center`` and ``radius`` in data units (use an equal aspect ratio for a circular arc).

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib import plots
    >>> fig, ax = plt.subplots()
    >>> plots.angle_arc(ax, (0.0, 0.0), 1.0, 0.0, 60.0, "60 deg")
    >>> [t.get_text() for t in ax.texts]
    ['60 deg']
    >>> plt.close(fig)
    """
    axes(ax)
    c = as_array(center, "center", shape=(2,))
    t0, t1 = scalar(start_deg, "start_deg"), scalar(end_deg, "end_deg")
    _color(color, "color")
    _plots.angle_arc(ax, c, radius, t0, t1, label, color)
