"""Notebook 04 as a chapter: the redrawn fusion structure of paper 003 (its Fig. 3)."""

import matplotlib

matplotlib.use("Agg")
import pytest  # noqa: E402
from matplotlib.patches import FancyBboxPatch  # noqa: E402

from navlib.papers import mimu_mag_rtk  # noqa: E402


def test_fusion_structure_draws_the_four_blocks_and_the_sensors(ax):
    mimu_mag_rtk.draw_fusion_structure(ax)
    boxes = [p for p in ax.patches if isinstance(p, FancyBboxPatch)]
    texts = " ".join(t.get_text() for t in ax.texts)
    assert len(boxes) == 9  # 4 sensors, 4 blocks, the output
    for block in ("initial attitude", "PI correction", "quaternion KF", "heading fusion", "RTK", "magnetometer"):
        assert block in texts
    assert len([c for c in ax.get_children() if type(c).__name__ == "Annotation"]) == 12  # the arrows
    assert not ax.axison  # a schematic, no axes


def test_fusion_structure_renders(ax, tmp_path):
    mimu_mag_rtk.draw_fusion_structure(ax)
    ax.figure.savefig(tmp_path / "fusion.png")  # mathtext of every label parses
    assert (tmp_path / "fusion.png").stat().st_size > 0


@pytest.mark.parametrize("bad", [None, "axes", 3.0])
def test_fusion_structure_refuses_what_is_not_an_axes(bad):
    with pytest.raises(ValueError, match="ax"):
        mimu_mag_rtk.draw_fusion_structure(bad)
