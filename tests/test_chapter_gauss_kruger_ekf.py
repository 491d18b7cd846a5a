"""Notebook 03's chapter helpers in navlib.papers.gauss_kruger_ekf: the textbook inverse series and the redrawn Figs. 1-2.

They are kept out of the module's ``__all__`` (they serve the notebook); tested here: the inverse against navlib's
Krüger inverse and the paper's forward series, figures drawn without error, bad input named.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from navlib import earth, geodesy  # noqa: E402
from navlib.papers import gauss_kruger_ekf as gk  # noqa: E402


def test_inverse_series_matches_kruger_inside_a_zone():
    lat, lon = np.meshgrid(np.linspace(0, 70, 36), 120 + np.linspace(-1.5, 1.5, 13))
    x, y = geodesy.geodetic2gk(lat, lon, zone=40, ellipsoid=earth.CGCS2000, deg=True)
    la, lo = gk.inverse_series(x, y, 120.0, deg=True)
    metres = 111_320 * np.hypot(la - lat, (lo - lon) * np.cos(np.radians(lat)))
    assert metres.max() < 5e-5  # the e^8 arc series' truncation near 70° N
    assert metres[:, lat[0] < 40].max() < 1e-5  # micrometres at the site's latitudes


def test_inverse_series_undoes_the_paper_series():
    lat, lon = np.radians(26.06), np.radians(119.2)
    x, y = gk.paper_series(lat, lon, np.radians(120.0))
    la, lo = gk.inverse_series(x, y, np.radians(120.0))
    assert abs(la - lat) < 1e-12 and abs(lo - lon) < 1e-12


def test_footpoint_latitude_inverts_the_meridian_arc():
    W = np.radians([0.0, 10.0, 26.06, 60.0, 85.0])
    np.testing.assert_allclose(gk.footpoint_latitude(gk.paper_meridian_arc(W)), W, atol=1e-13)


@pytest.mark.parametrize(
    "args, name",
    [
        ((0.0, 2e6, 120.0), "y"),
        ((2e7, 0.0, 120.0), "x"),
        ((np.nan, 0.0, 120.0), "x"),
        ((0.0, [1.0, 2.0], [120.0, 121.0, 122.0]), "lon0"),
        (([], 0.0, 120.0), "x"),
    ],
)
def test_inverse_series_names_bad_input(args, name):
    with pytest.raises(ValueError, match=f"^{name}"):
        gk.inverse_series(*args, deg=True)


def test_zone_figures_draw(ax):
    gk.draw_zones(ax, 112.5, 127.5, mark=(26.06, 119.2))
    assert [t.get_text() for t in ax.texts if t.get_text().startswith("zone")][:5] == [f"zone {n}" for n in range(38, 43)]
    fig, other = plt.subplots()
    gk.draw_zone_grid(other, 40, 60.0, mark=(26.06, 119.2))
    central = [ln for ln in other.lines if np.allclose(ln.get_xdata(), 0.0)]
    assert len(central) == 1  # the central meridian maps to the x axis
    plt.close(fig)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda a: gk.draw_zones(a, 120.0, 110.0), "lon_min"),
        (lambda a: gk.draw_zones(a, 0.0, 90.0), "lon_min"),
        (lambda a: gk.draw_zones(a, mark=(1.0,)), "mark"),
        (lambda a: gk.draw_zone_grid(a, 0), "zone"),
        (lambda a: gk.draw_zone_grid(a, 40.5), "zone"),
        (lambda a: gk.draw_zone_grid(a, 40, lat_max=5.0), "lat_max"),
        (lambda a: gk.draw_zone_grid(a, 40, step_deg=-1.0), "step_deg"),
    ],
)
def test_zone_figures_name_bad_input(ax, call, name):
    with pytest.raises(ValueError, match=f"^{name}"):
        call(ax)


def test_block_diagram_draws(ax):
    gk.draw_block_diagram(ax)
    assert len(ax.patches) == 9 and not ax.axison
    with pytest.raises(ValueError, match="^ax"):
        gk.draw_block_diagram(None)
