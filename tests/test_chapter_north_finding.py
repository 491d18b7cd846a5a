"""The schematics notebook 01 redraws from paper 000 (Figs. 2 and 3): drawn without error, inputs validated."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from navlib.papers import north_finding as nf  # noqa: E402


@pytest.mark.parametrize("heading", [0.0, 30.0, 179.0, 181.0, 359.9, -45.0, 725.0])
def test_device_is_drawn_at_any_heading(ax, heading):
    nf.draw_device(ax, heading)
    assert len(ax.patches) >= 4 and ax.texts  # robot, nose, gyro, IMU, the arc; the labels
    assert ax.get_aspect() == 1.0 and not ax.axison


def test_device_projection_is_the_gyro_reading(ax):
    """The orange segment along the forward axis has length r cos psi (Eq. 8, level): zero at 90 deg."""
    nf.draw_device(ax, 90.0)
    segment = [line for line in ax.lines if line.get_linewidth() == 4][0]
    x, y = segment.get_data()
    assert np.hypot(x[1] - x[0], y[1] - y[0]) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("h1, h2", [(60.0, 130.0), (122.0, 191.47), (0.0, 180.0), (350.0, 10.0)])
def test_candidate_pairs_are_mirror_images(ax, h1, h2):
    nf.draw_candidate_pairs(ax, h1, h2, dpsi_ins_error_deg=3.0)
    labels = [t.get_text() for t in ax.texts]
    assert "stop 1" in labels and "stop 2" in labels
    # each stop labels its two candidates, alpha (beta) and 2 pi - alpha (2 pi - beta): they sum to 360 deg;
    # at 0 and 180 deg the two coincide and one label names both
    for name, heading in (("α", h1), ("β", h2)):
        values = [float(t.split("= ")[-1].rstrip("°")) for t in labels if t.endswith("°") and name in t]
        if heading % 180.0 == 0.0:
            assert len(values) == 1 and values[0] == pytest.approx(heading % 360.0)
        else:
            assert len(values) == 2 and sum(values) == pytest.approx(360.0, abs=1.0)
    legend = {h.get_label() for h in ax.get_legend_handles_labels()[0]}
    assert any("mirror" in label for label in legend)


@pytest.mark.parametrize(
    "call",
    [
        lambda: nf.draw_device("not an axes"),
        lambda: nf.draw_candidate_pairs(None, 10.0, 20.0),
    ],
)
def test_refuses_a_non_axes(call):
    with pytest.raises(ValueError, match="ax"):
        call()


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(heading_deg=np.nan), "heading_deg"),
        (dict(heading_deg="30"), "heading_deg"),
        (dict(heading_deg=[10.0, 20.0]), "heading_deg"),
    ],
)
def test_device_validates_the_heading(ax, kwargs, name):
    with pytest.raises((ValueError, TypeError), match=name):
        nf.draw_device(ax, **kwargs)


@pytest.mark.parametrize(
    "args, name",
    [
        ((np.inf, 10.0), "heading1_deg"),
        ((10.0, np.nan), "heading2_deg"),
        ((10.0, 20.0, np.nan), "dpsi_ins_error_deg"),
    ],
)
def test_candidate_pairs_validate_their_angles(ax, args, name):
    with pytest.raises((ValueError, TypeError), match=name):
        nf.draw_candidate_pairs(ax, *args)
