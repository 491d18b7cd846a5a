"""Notebook 05 as a chapter: the redrawn system block diagram of paper 004 (its Fig. 2)."""

import matplotlib

matplotlib.use("Agg")
import pytest  # noqa: E402
from matplotlib.patches import FancyBboxPatch  # noqa: E402

from navlib.papers import pedestrian_ins  # noqa: E402


def test_system_diagram_draws_sensors_blocks_and_the_feedback_loop(ax):
    pedestrian_ins.draw_system(ax)
    boxes = [p for p in ax.patches if isinstance(p, FancyBboxPatch)]
    texts = " ".join(t.get_text() for t in ax.texts)
    assert len(boxes) == 10  # 3 sensors, detector, INS, KF, compass, height, reset, output
    for block in (
        "MPU-6050",
        "HMC5983",
        "BMP180",
        "static detector",
        "strapdown INS",
        "ZUPT/ZARU",
        "Eqs. (4)–(6)",
        "direct binding",
        "feedback",
    ):
        assert block in texts
    arrows = [c for c in ax.get_children() if type(c).__name__ == "Annotation"]
    assert len(arrows) == 9 + 2  # the block arrows and the INS <-> filter pair
    assert not ax.axison


def test_system_diagram_renders(ax, tmp_path):
    pedestrian_ins.draw_system(ax)
    ax.figure.savefig(tmp_path / "system.png")  # mathtext of every label parses
    assert (tmp_path / "system.png").stat().st_size > 0


@pytest.mark.parametrize("bad", [None, "axes", 3.0])
def test_system_diagram_refuses_what_is_not_an_axes(bad):
    with pytest.raises(ValueError, match="ax"):
        pedestrian_ins.draw_system(bad)
