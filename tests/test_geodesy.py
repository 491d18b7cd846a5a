"""Tests of navlib.geodesy: PROJ reference vectors, pyproj cross-checks, round trips, paper 002 values.

The paper's own equations (printed zone number, radii, e^8 arc, sixth-order series) are the companion's:
tests/test_planar.py. navlib.geodesy defaults to WGS84; CGCS2000 references pass ``ellipsoid=CGCS2000``.
"""

import inspect
import re

import numpy as np
import pytest
from helpers import read_vectors
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from navlib import earth, geodesy
from navlib.papers import gauss_kruger_ekf

pyproj = pytest.importorskip("pyproj")

ELLIPSOIDS = [earth.CGCS2000, earth.WGS84, earth.KRASSOVSKY]
M_PER_DEG = 111_320.0  # metres per degree of arc, to express angular errors as distances
CGCS = dict(ellipsoid=earth.CGCS2000)  # China's datum (EPSG:4490 grids); geodesy defaults to WGS84


def tolerance_m(text):
    """'50 nm', '0.1 mm', '0.01 m', 'printed to 1e-6 m' -> metres."""
    value, unit = re.search(r"([0-9.e-]+)\s*(nm|mm|m)\b", text).groups()
    return float(value) * {"nm": 1e-9, "mm": 1e-3, "m": 1.0}[unit]


def proj_tmerc(ell, lon0, k0=1.0):
    return pyproj.Proj(
        f"+proj=tmerc +a={ell.a} +rf={1 / ell.f!r} +lon_0={lon0} +k={k0} +x_0=0 +y_0=0 +algo=poder_engsager +units=m"
    )


# --------------------------------------------------------------------------
# PROJ reference vectors
# --------------------------------------------------------------------------


def vector_rows():
    return read_vectors("tmerc_gauss_kruger.csv")


def test_proj_vectors_within_stated_tolerances():
    rows = vector_rows()
    assert len(rows) >= 25
    for r in rows:
        ell = earth.Ellipsoid(r["ellps"], float(r["a_m"]), 1 / float(r["rf"]), earth.WGS84.GM, earth.OMEGA_IE)
        k0 = float(r["k_0"])
        fn = float(r["y_0"]) - k0 * geodesy.meridian_arc(float(r["lat_0"]), ell, deg=True)
        kw = dict(
            lon0=float(r["lon_0"]),
            ellipsoid=ell,
            deg=True,
            k0=k0,
            false_easting=float(r["x_0"]),
            false_northing=fn,
            max_offset_deg=60.0,
        )
        tol = tolerance_m(r["tolerance"])
        lon, lat, east, north = (float(r[k]) for k in ("lon_deg", "lat_deg", "x_m", "y_m"))
        if r["direction"] == "forward":
            x, y = geodesy.geodetic2gk(lat, lon, **kw)
            assert abs(y - east) <= tol and abs(x - north) <= tol, (r["case_id"], y - east, x - north)
        else:
            kw.pop("max_offset_deg")
            la, lo = geodesy.gk2geodetic(north, east, **kw)
            err = M_PER_DEG * max(abs(la - lat), abs(lo - lon) * np.cos(np.deg2rad(lat)))
            assert err <= tol, (r["case_id"], err)


def test_paper_test_vector_and_epsg_grids():
    """Paper 002 site (assumed): 119.20° E, 26.06° N -> zone 40, x = 2 883 727.417 m, y = -80 055.050 m (PROJ, EPSG:4549/4528)."""
    assert geodesy.zone(119.2, deg=True) == 40
    assert geodesy.central_meridian(40, deg=True) == 120
    x, y = geodesy.geodetic2gk(26.06, 119.20, deg=True, **CGCS)
    assert abs(x - 2_883_727.417) < 1e-3 and abs(y + 80_055.050) < 1e-3
    e4549, n4549 = pyproj.Transformer.from_crs("EPSG:4490", "EPSG:4549", always_xy=True).transform(119.2, 26.06)
    e4528, n4528 = pyproj.Transformer.from_crs("EPSG:4490", "EPSG:4528", always_xy=True).transform(119.2, 26.06)
    x1, y1 = geodesy.geodetic2gk(26.06, 119.2, deg=True, false_easting=500e3, **CGCS)
    x2, y2 = geodesy.geodetic2gk(26.06, 119.2, deg=True, false_easting=500e3, zone_prefix=True, **CGCS)
    assert_allclose([x1, y1, x2, y2], [n4549, e4549, n4528, e4528], rtol=0, atol=1e-6)
    la, lo = geodesy.gk2geodetic(x2, y2, deg=True, false_easting=500e3, zone_prefix=True, **CGCS)
    assert_allclose([la, lo], [26.06, 119.2], rtol=0, atol=1e-11)
    assert abs(geodesy.meridian_arc(26.06, deg=True, **CGCS) - 2_883_481.880) < 1e-3


# --------------------------------------------------------------------------
# pyproj cross-check inside zones
# --------------------------------------------------------------------------


@pytest.mark.parametrize("width", [3, 6])
@pytest.mark.parametrize("ell", ELLIPSOIDS, ids=lambda e: e.name)
def test_matches_pyproj_inside_zones(width, ell):
    """Random points inside each zone at 0-70° latitude agree with PROJ's exact tmerc to 1e-5 mm (a few ulps of
    the northing: both evaluate Krüger's n^6 series; the largest difference is about 5e-6 mm)."""
    rng = np.random.default_rng(width)
    zones = np.arange(1, 360 // width + 1)
    for zn in zones:
        lon0 = float(geodesy.central_meridian(zn, width, deg=True))
        lat = rng.uniform(0.0, 70.0, 200)
        lon = lon0 + rng.uniform(-width / 2, width / 2, 200)
        x, y = geodesy.geodetic2gk(lat, lon, zone=zn, width=width, ellipsoid=ell, deg=True)
        east, north = proj_tmerc(ell, lon0).transform(lon, lat)
        assert np.abs(x - north).max() <= 1e-8 and np.abs(y - east).max() <= 1e-8, zn


def test_grid_convergence_and_scale_match_pyproj():
    rng = np.random.default_rng(7)
    lat, lon = rng.uniform(-70, 70, 2000), 120 + rng.uniform(-3, 3, 2000)
    f = proj_tmerc(earth.CGCS2000, 120).get_factors(lon, lat)
    gamma = geodesy.convergence(lat, lon, lon0=120, width=6, deg=True, **CGCS)
    k = geodesy.scale_factor(lat, lon, lon0=120, width=6, deg=True, **CGCS)
    assert_allclose(gamma, f.meridian_convergence, rtol=0, atol=1e-8)
    assert_allclose(k, f.meridional_scale, rtol=0, atol=1e-9)
    # Erratum E002-09: -0.3515° at Fuzhou (PROJ); l sin(lat) to first order
    assert abs(geodesy.convergence(26.06, 119.2, deg=True, **CGCS) + 0.3515) < 1e-3


def test_grid_convergence_is_the_grid_bearing_of_true_north():
    """A step due (true) north has grid bearing -gamma: heading_grid = heading_true - gamma."""
    lat, lon, d = 26.06, 121.3, 1e-6
    x0, y0 = geodesy.geodetic2gk(lat, lon, zone=40, deg=True)
    x1, y1 = geodesy.geodetic2gk(lat + d, lon, zone=40, deg=True)
    bearing = np.degrees(np.arctan2(y1 - y0, x1 - x0))
    assert abs(bearing + geodesy.convergence(lat, lon, zone=40, deg=True)) < 1e-6


# --------------------------------------------------------------------------
# Round trips and the paper's equations
# --------------------------------------------------------------------------


@settings(max_examples=300, deadline=None)
@given(lat=st.floats(-89.0, 89.0), offset=st.floats(-3.0, 3.0), zn=st.integers(1, 60), ell=st.sampled_from(ELLIPSOIDS))
def test_round_trip_inverse_of_forward(lat, offset, zn, ell):
    lon0 = float(geodesy.central_meridian(zn, 6, deg=True))
    lon = lon0 + offset
    x, y = geodesy.geodetic2gk(lat, lon, zone=zn, width=6, ellipsoid=ell, deg=True)
    la, lo = geodesy.gk2geodetic(x, y, zone=zn, width=6, ellipsoid=ell, deg=True)
    assert abs(la - lat) < 1e-9
    assert abs((lo - lon + 180) % 360 - 180) < 1e-9


def test_zone_numbers_corrected_formula():
    """Erratum E002-01: n = floor((L + 1.5)/3) (the printed (L - 1.5)/3: tests/test_planar.py)."""
    lon = [1.5, 4.49, 4.5, 117.0, 118.5, 119.2, 121.49, 121.5, 0.5, 359.0, -1.0]
    assert geodesy.zone(lon, deg=True).tolist() == [1, 1, 2, 39, 40, 40, 40, 41, 120, 120, 120]
    assert geodesy.central_meridian(120, deg=True) == 0
    assert geodesy.zone([117.0, 0.5, -3.0], width=6, deg=True).tolist() == [20, 1, 60]
    assert_allclose(geodesy.central_meridian([20, 60], 6, deg=True), [117, -3])
    assert geodesy.zone(np.deg2rad(119.2)) == 40  # radians by default


def test_per_point_zones_and_prefix():
    x, y = geodesy.geodetic2gk([26.0, 26.0], [121.4, 121.6], deg=True, false_easting=500e3, zone_prefix=True)
    assert int(y[0] // 1e6) == 40 and int(y[1] // 1e6) == 41
    la, lo = geodesy.gk2geodetic(x, y, deg=True, false_easting=500e3, zone_prefix=True)
    assert_allclose(lo, [121.4, 121.6], atol=1e-11)


def arc_by_quadrature(lat, ell, order=64):
    """Integral of R_M from 0 to lat by Gauss-Legendre (exact to rounding for this smooth integrand)."""
    nodes, weights = np.polynomial.legendre.leggauss(order)
    w = lat / 2 * (nodes + 1)
    return lat / 2 * np.sum(weights * earth.radii(w, ellipsoid=ell)[0])


@pytest.mark.parametrize("ell", ELLIPSOIDS, ids=lambda e: e.name)
def test_meridian_arc_against_quadrature(ell):
    """Krüger's series equals the integral of R_M to 1e-8 m from the equator to the pole."""
    for lat_deg in (26.0, 45.0, 89.9):
        exact = arc_by_quadrature(np.deg2rad(lat_deg), ell)
        assert abs(geodesy.meridian_arc(lat_deg, ell, deg=True) - exact) < 1e-8


def test_default_ellipsoid_is_wgs84():
    """Every ``ellipsoid`` of navlib.geodesy defaults to WGS84 (CGCS2000 differs by 0.1 mm in b)."""
    defaults = {name: inspect.signature(getattr(geodesy, name)).parameters.get("ellipsoid") for name in geodesy.__all__}
    defaults = {name: p.default for name, p in defaults.items() if p is not None}
    assert len(defaults) == 12 and all(d is earth.WGS84 for d in defaults.values()), defaults
    x, y = geodesy.geodetic2gk(26.06, 119.2, deg=True)
    assert (x, y) == geodesy.geodetic2gk(26.06, 119.2, deg=True, ellipsoid=earth.WGS84)
    x_c, _ = geodesy.geodetic2gk(26.06, 119.2, deg=True, **CGCS)
    assert 0 < abs(x - x_c) < 1e-3
    assert geodesy.geodetic2ecef(26.06, 119.2, 0.0, deg=True) == geodesy.geodetic2ecef(26.06, 119.2, 0.0, earth.WGS84, True)


@pytest.mark.parametrize("name", ["printed_zone_number", "printed_meridian_radius", "paper_radii", "paper_series"])
def test_paper_functions_live_in_the_companion(name):
    """Paper 002's own equations live in navlib.papers.gauss_kruger_ekf, not in geodesy."""
    assert not hasattr(geodesy, name)
    assert name not in geodesy.__all__ and name in gauss_kruger_ekf.__all__
    with pytest.raises(TypeError):
        geodesy.meridian_arc(0.45, series="paper")  # the e^8 series: gauss_kruger_ekf.paper_meridian_arc


def test_local_scales_of_any_projection():
    """``project`` replaces geodetic2gk: UTM's k0 scales h and k (1e-9, central differences); plate carrée is not conformal."""
    lat, lon = 0.45, 2.08

    def utm(la, lo, lo0, ell):
        return geodesy.geodetic2gk(la, lo, lon0=lo0, ellipsoid=ell, k0=0.9996)

    def plate_carree(la, lo, lo0, ell):
        return ell.a * la, ell.a * (lo - lo0)

    h, k, angle = geodesy.local_scales(lat, lon, 2.094, project=utm)
    h1, k1, angle1 = geodesy.local_scales(lat, lon, 2.094)
    assert abs(h / h1 - 0.9996) < 1e-9 and abs(k / k1 - 0.9996) < 1e-9 and abs(angle - angle1) < 1e-9
    h, k, angle = geodesy.local_scales(lat, lon, 2.094, project=plate_carree)
    R_M, R_N = earth.radii(lat)
    assert abs(h - earth.WGS84.a / R_M) < 1e-9 and abs(k - earth.WGS84.a / (R_N * np.cos(lat))) < 1e-9
    assert abs(angle - np.pi / 2) < 1e-12 and k / h > 1.1


# --------------------------------------------------------------------------
# Geodetic <-> ECEF <-> ENU
# --------------------------------------------------------------------------


def test_ecef_matches_pyproj_and_round_trips():
    rng = np.random.default_rng(3)
    lat, lon, h = rng.uniform(-89, 89, 500), rng.uniform(-180, 180, 500), rng.uniform(-100, 9000, 500)
    x, y, z = geodesy.geodetic2ecef(lat, lon, h, earth.WGS84, deg=True)
    X, Y, Z = pyproj.Transformer.from_crs("EPSG:4979", "EPSG:4978", always_xy=True).transform(lon, lat, h)
    assert_allclose(np.stack([x, y, z]), np.stack([X, Y, Z]), rtol=0, atol=1e-6)
    la, lo, hh = geodesy.ecef2geodetic(x, y, z, earth.WGS84, deg=True)
    assert np.abs(la - lat).max() < 1e-10 and np.abs(lo - lon).max() < 1e-10 and np.abs(hh - h).max() < 1e-6


def test_enu_round_trip_and_axes():
    lat0, lon0, h0 = 26.06, 119.2, 10.0
    e, n, u = geodesy.geodetic2enu(lat0 + 1e-3, lon0, h0, lat0, lon0, h0, deg=True)
    assert abs(e) < 1e-6 and 100 < n < 120 and abs(u) < 0.01  # a step north is +n
    e, n, u = geodesy.geodetic2enu(lat0, lon0 + 1e-3, h0, lat0, lon0, h0, deg=True)
    assert e > 90 and abs(n) < 0.01
    enu = np.array([[100.0, -250.0, 3.0], [5e3, 2e3, -40.0]])
    la, lo, h = geodesy.enu2geodetic(enu[:, 0], enu[:, 1], enu[:, 2], lat0, lon0, h0, deg=True)
    back = geodesy.geodetic2enu(la, lo, h, lat0, lon0, h0, deg=True)
    assert_allclose(np.stack(back, -1), enu, rtol=0, atol=1e-7)


def test_broadcasting():
    x, y = geodesy.geodetic2gk(np.array([[20.0], [30.0], [40.0]]), 120 + np.array([-1.0, 0.0, 0.5, 1.0]), zone=40, deg=True)
    assert x.shape == y.shape == (3, 4)
    la, lo = geodesy.gk2geodetic(x, y, zone=40, deg=True)
    assert la.shape == (3, 4)


# --------------------------------------------------------------------------
# Bad input: the registry tools/fuzz_calls.py (the rows of navlib.geodesy), run by tests/test_bad_input.py
# --------------------------------------------------------------------------

# --------------------------------------------------------------------------
# Properties (issue 9): every conversion and projection, by hypothesis
# --------------------------------------------------------------------------

LATS = st.floats(-85.0, 85.0)


@settings(max_examples=150, deadline=None)
@given(lat=LATS, offset=st.floats(-3.0, 3.0), ell=st.sampled_from(ELLIPSOIDS))
def test_gk_is_conformal_and_scale_factor_matches_the_local_scales(lat, offset, ell):
    """Conformal: meridian and parallel scales equal, their images at right angles (central
    differences of step 1e-6 rad: 1e-8 relative); ``scale_factor`` equals that scale (1e-8)."""
    lon0 = 120.0
    h, k, angle = geodesy.local_scales(lat, lon0 + offset, lon0, ell, deg=True)
    assert abs(h / k - 1) < 1e-8 and abs(angle - np.pi / 2) < 1e-8
    kk = geodesy.scale_factor(lat, lon0 + offset, lon0=lon0, ellipsoid=ell, deg=True)
    assert abs(kk / h - 1) < 1e-8 and kk >= 1 - 1e-12  # GK: k0 = 1 on the meridian


@settings(max_examples=150, deadline=None)
@given(lat=LATS, offset=st.floats(-3.0, 3.0), ell=st.sampled_from(ELLIPSOIDS))
def test_gk_symmetries(lat, offset, ell):
    """Easting odd and northing even in the longitude offset; northing odd in latitude (1e-6 m)."""
    kw = dict(lon0=120.0, ellipsoid=ell, deg=True)
    x1, y1 = geodesy.geodetic2gk(lat, 120.0 + offset, **kw)
    x2, y2 = geodesy.geodetic2gk(lat, 120.0 - offset, **kw)
    x3, y3 = geodesy.geodetic2gk(-lat, 120.0 + offset, **kw)
    assert abs(x1 - x2) < 1e-6 and abs(y1 + y2) < 1e-6
    assert abs(x1 + x3) < 1e-6 and abs(y1 - y3) < 1e-6


@settings(max_examples=150, deadline=None)
@given(lat=st.floats(-80.0, 80.0), offset=st.floats(-3.0, 3.0), ell=st.sampled_from(ELLIPSOIDS))
def test_convergence_is_the_grid_bearing_of_true_north(lat, offset, ell):
    """A step north on the ellipsoid points at grid bearing -gamma (1e-6 rad, from 1e-7 deg steps)."""
    kw = dict(lon0=120.0, ellipsoid=ell, deg=True)
    d = 1e-7
    xa, ya = geodesy.geodetic2gk(lat - d, 120.0 + offset, **kw)
    xb, yb = geodesy.geodetic2gk(lat + d, 120.0 + offset, **kw)
    gamma = np.radians(geodesy.convergence(lat, 120.0 + offset, **kw))  # deg=True: degrees
    bearing = np.arctan2(yb - ya, xb - xa)
    assert abs(np.angle(np.exp(1j * (bearing + gamma)))) < 1e-6


@settings(max_examples=200, deadline=None)
@given(lon=st.floats(-180.0, 360.0), width=st.sampled_from([3, 6]))
def test_every_longitude_lies_in_its_zone(lon, width):
    """|lon - central_meridian(zone(lon))| <= width/2 (mod 360; 1e-9 deg)."""
    zn = geodesy.zone(lon, width, deg=True)
    assert 1 <= zn <= 360 // width
    off = (lon - geodesy.central_meridian(zn, width, deg=True) + 180.0) % 360.0 - 180.0
    assert abs(off) <= width / 2 + 1e-9


@settings(max_examples=200, deadline=None)
@given(lat=st.floats(-89.9, 89.9), lon=st.floats(-180.0, 180.0), h=st.floats(-500.0, 1e5), ell=st.sampled_from(ELLIPSOIDS))
def test_ecef_round_trip(lat, lon, h, ell):
    """geodetic -> ECEF -> geodetic: 1e-9 deg and 1e-6 m up to 100 km height."""
    la, lo, hh = geodesy.ecef2geodetic(*geodesy.geodetic2ecef(lat, lon, h, ell, deg=True), ell, deg=True)
    assert abs(la - lat) < 1e-9 and abs((lo - lon + 180) % 360 - 180) * np.cos(np.radians(lat)) < 1e-9
    assert abs(hh - h) < 1e-6


@settings(max_examples=200, deadline=None)
@given(
    lat0=st.floats(-85.0, 85.0), lon0=st.floats(-180.0, 180.0), enu=st.tuples(*[st.floats(-5e4, 5e4)] * 2, st.floats(-1e3, 1e3))
)
def test_enu_round_trip_and_isometry(lat0, lon0, enu):
    """ENU -> geodetic -> ENU to 1e-6 m within 50 km; the ENU frame is a rotation: |enu| equals
    the ECEF distance to the origin (1e-6 m)."""
    la, lo, h = geodesy.enu2geodetic(*enu, lat0, lon0, 0.0, deg=True)
    back = geodesy.geodetic2enu(la, lo, h, lat0, lon0, 0.0, deg=True)
    assert_allclose(np.array(back, dtype=float), enu, rtol=0, atol=1e-6)
    p = np.array(geodesy.geodetic2ecef(la, lo, h, deg=True)) - np.array(geodesy.geodetic2ecef(lat0, lon0, 0.0, deg=True))
    assert abs(np.linalg.norm(p) - np.linalg.norm(enu)) < 1e-6


@settings(max_examples=200, deadline=None)
@given(a=st.floats(-89.0, 89.0), b=st.floats(-89.0, 89.0), ell=st.sampled_from(ELLIPSOIDS))
def test_meridian_arc_odd_and_monotonic(a, b, ell):
    """S(-lat) = -S(lat); S increases with lat."""
    Sa, Sb = (geodesy.meridian_arc(v, ell, deg=True) for v in (a, b))
    assert abs(geodesy.meridian_arc(-a, ell, deg=True) + Sa) < 1e-6
    if a < b:
        assert Sa < Sb
