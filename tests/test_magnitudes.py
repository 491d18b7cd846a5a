"""Extreme magnitudes and out-of-range raw values give a clear error or the right answer (issue 15, items 7-8)."""

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from navlib import (  # noqa: E402
    alignment,
    analysis,
    atmosphere,
    attitude,
    earth,
    euler,
    kalman,
    plots,
    sensors,
    strapdown,
    trajectory,
    units,
)
from navlib.filters import mahony  # noqa: E402
from navlib.imu import ImuSamples  # noqa: E402
from navlib.papers import gauss_kruger_ekf, rotation_bias  # noqa: E402


@pytest.mark.parametrize("scale", [1e155, 1e300, 1e-9])
def test_quaternions_of_any_finite_magnitude_normalise(scale):
    q = np.array([1.0, 2.0, -2.0, 4.0])
    np.testing.assert_allclose(attitude.quat_normalize(scale * q), q / 5.0, rtol=1e-15)
    np.testing.assert_allclose(attitude.quat_to_dcm(scale * q), attitude.quat_to_dcm(q), atol=1e-15)


def test_rotation_vector_beyond_float_resolution_is_refused():
    with pytest.raises(ValueError, match="^rv: rotation angle"):
        attitude.rotvec_to_quat([1e300, 0.0, 0.0])
    assert np.all(np.isfinite(attitude.rotvec_to_quat([1e9, 0.0, 0.0])))


def test_transport_rate_and_error_model_are_refused_at_the_poles():
    with pytest.raises(ValueError, match="^lat: the ENU transport rate is singular"):
        earth.transport_rate_n(np.pi / 2, 0.0, [1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="^lat: the local-level"):
        strapdown.error_model(-np.pi / 2, 0.0, [1.0, 0.0, 0.0], [0.0, 0.0, 9.8])
    assert np.all(np.isfinite(earth.transport_rate_n(np.deg2rad(89.9), 0.0, [1.0, 0.0, 0.0])))


@pytest.mark.parametrize("UT, UP, arg", [(-1, 23843, "UT"), (27898, -5, "UP"), (1 << 16, 23843, "UT"), (27898, 1 << 16, "UP")])
def test_bmp180_raw_counts_outside_the_adc_range_are_refused(UT, UP, arg):
    calib = dict(AC1=408, AC2=-72, AC3=-14383, AC4=32741, AC5=32757, AC6=23153, B1=6190, B2=4, MB=-32768, MC=-8711, MD=2868)
    with pytest.raises(ValueError, match=f"^{arg}: "):
        atmosphere.bmp180_compensate(UT, UP, calib)


def test_a_path_with_too_many_steps_is_refused_naming_T():
    with pytest.raises(ValueError, match="^T: "):
        gauss_kruger_ekf.waypoint_path([[0.0, 0.0], [100.0, 0.0], [100.0, 100.0]], 5.0, 0.2, 1e-300)


@pytest.mark.parametrize(
    "taus, adev, theory, arg",
    [
        ([[1.0, 2.0]], [1.0, 2.0], None, "taus"),
        ([1.0, 2.0], np.ones((2, 3, 2)), None, "adev_rad_s"),
        ([1.0, 2.0], [1.0, 2.0], [1.0], "theory"),
    ],
)
def test_allan_plot_shapes_name_the_argument(taus, adev, theory, arg):
    fig, ax = plt.subplots()
    with pytest.raises(ValueError, match=f"^{arg}: "):
        plots.allan(ax, taus, adev, theory=theory)
    plt.close(fig)


def _static_marg(n=200, seed=0):
    rng = np.random.default_rng(seed)
    w = 1e-3 * rng.standard_normal((n, 3))
    f = np.array([0.0, 0.0, 9.8]) + 0.01 * rng.standard_normal((n, 3))
    return w, f, np.tile([0.0, 20.0, -40.0], (n, 1))


@pytest.mark.parametrize("filt", ["mahony", "quaternion_kf", "run_filter"])
def test_sample_intervals_below_a_nanosecond_are_refused(filt):
    from navlib.filters import mahony, quaternion_kf, zupt_ins

    w, f, m = _static_marg()
    q0 = [1.0, 0.0, 0.0, 0.0]
    call = {
        "mahony": lambda: mahony.mahony(ImuSamples(w, f, 1e-300), q0, m_b=m),
        "quaternion_kf": lambda: quaternion_kf.quaternion_kf(ImuSamples(w, f, 1e-300), q0, m_b=m, B_n=[0.0, 20.0, -40.0]),
        "run_filter": lambda: zupt_ins.run_filter(
            ImuSamples(w, f, 1e-300), zupt_ins.Start([0.5, 0.1, 0.0], q0), np.ones(len(w), bool)
        ),
    }[filt]
    with pytest.raises(ValueError, match="^dt: expected intervals of at least"):  # was a numba TypingError
        call()


def test_attitude_filters_refuse_intervals_the_first_order_update_cannot_integrate():
    from navlib.filters import mahony, quaternion_kf

    w, f, m = _static_marg()
    with pytest.raises(ValueError, match="^dt: the gyro turns up to"):
        quaternion_kf.quaternion_kf(ImuSamples(w, f, 1e6), [1.0, 0.0, 0.0, 0.0], m_b=m, B_n=[0.0, 20.0, -40.0])  # was LinAlgError
    with pytest.raises(ValueError, match="^dt: the gyro turns up to"):
        mahony.mahony(ImuSamples(w, f, 1e6), [1.0, 0.0, 0.0, 0.0], m_b=m)


def test_static_means_names_a_latitude_that_does_not_match_the_trials():
    from navlib import alignment

    w, f, _ = _static_marg()
    with pytest.raises(ValueError, match="^lat, h: "):  # was IndexError
        alignment.static_means(w, f, [0.6, 0.6])
    assert alignment.static_means(np.stack([w, w]), np.stack([f, f]), [0.6, 0.6]).faults["window", "refused"].shape == (2,)


def test_strapdown_refuses_what_it_cannot_integrate():
    w = 1e-3 * np.ones((10, 3))
    f = np.tile([0.0, 0.0, 9.8], (10, 1))
    with pytest.raises(ValueError, match="^dt: the gyro turns up to"):  # was silent NaN
        strapdown.integrate_attitude([1.0, 0.0, 0.0, 0.0], w, 1e300)
    with pytest.raises(ValueError, match="^dt: the gyro turns up to"):
        strapdown.integrate([0.5, 0.1, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], w, f, 1e300)
    with pytest.raises(ValueError, match="^w_ib_b, f_b, dt: the integrated position diverges"):  # was "lla: ..."
        strapdown.integrate([0.5, 0.1, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], np.zeros((10, 3)), 0 * f, 1e3)


def test_settling_time_refuses_time_that_goes_backwards_and_floors_take_whole_numbers():
    from navlib import analysis

    with pytest.raises(ValueError, match="^time: expected strictly increasing"):  # was accepted
        analysis.settling_time([0.0, 2.0, 1.0, 3.0], [1.0, 1.0, 0.0, 0.0], 0.0, 0.5)
    with pytest.raises(ValueError, match="^ref_floor: "):  # 1.5 was truncated to 1
        atmosphere.classify_floor([0.0, 3.0], ref_floor=1.5)
    assert list(atmosphere.classify_floor([0.0, 3.1], ref_floor=np.int64(2))) == [2, 3]


# Found by tools/fuzz.py (issue 15, item 4). A value whose square overflows float64 (navlib._validate.MAX_MAGNITUDE)
# is refused naming the argument: these calls returned inf or a finite wrong answer, or raised an error that
# named no argument (OverflowError, ZeroDivisionError, numpy's "Maximum allowed size exceeded").
@pytest.mark.parametrize(
    "arg, call",
    [
        ("err", lambda: analysis.rmse([1e300, 1.0])),  # was inf
        ("x", lambda: kalman.predict([1e300, 0.0], np.eye(2), np.eye(2), np.eye(2))),
        ("noise_density", lambda: sensors.TriadErrors(noise_density=1e300)),
        ("f_b", lambda: alignment.level([0.0, 1e300, 9.8])),
        ("vel_n", lambda: earth.transport_rate_n(0.5, 0.0, [1e300, 0.0, 0.0])),
        ("duration", lambda: trajectory.static(1e300, 0.1, [0.5, 0.1, 0.0], [0.0, 0.0, 0.0])),
        (
            "max_cond",
            lambda: analysis.cramer_rao_bound(
                np.stack([np.eye(3)[:2], np.eye(3)[1:]]), np.tile(np.eye(2), (2, 1, 1)), max_cond=1e300
            ),
        ),
        (
            "kp",
            lambda: mahony.mahony(ImuSamples(*_static_marg()[:2], 0.01), [1.0, 0.0, 0.0, 0.0], kp=1e300),
        ),  # was ZeroDivisionError
    ],
)
def test_values_whose_square_overflows_are_refused_naming_the_argument(arg, call):
    with pytest.raises(ValueError, match=f"^{arg}: expected magnitudes up to 1e\\+150"):
        call()


def test_functions_exact_at_any_magnitude_still_take_huge_values():
    assert units.deg(1e300) == pytest.approx(np.deg2rad(1e300))  # a linear conversion
    np.testing.assert_allclose(attitude.ned_to_enu_quat([1e300, 0.0, 0.0, 0.0]), [1.0, 0.0, 0.0, 0.0])


def test_integrators_name_an_interval_they_cannot_integrate():
    w = np.full((40, 3), 1e-3)
    f = np.tile([0.0, 0.0, 9.8], (40, 1))
    with pytest.raises(ValueError, match="^dt: the gyro turns up to"):  # was "w_ib_b: the integrated pitch ..."
        euler.integrate_euler([0.0, 0.0, 0.0], w, 1e300)
    with pytest.raises(ValueError, match="^dt: the gyro turns up to"):  # was accepted: residuals of 1e297 rad
        rotation_bias.tilt_residuals(w, f, 1e300, [0, 20], 10)


@pytest.mark.parametrize("options", [{}, {"allow_nan": True}, {"finite": False}, {"huge": True}])
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf, 1e200, -1e200, None])
def test_large_arrays_take_the_min_max_shortcut_with_the_same_outcome(options, bad):
    # as_array skips its element-wise checks on arrays whose min and max are in range: the outcome
    # (accepted, or the same message) must be that of the small array with the same bad value, wherever
    # the value sits (first or last element, a NaN beside an inf), contiguous or not
    from navlib._validate import as_array

    def outcome(n, where, step=1):
        x = np.linspace(-1.0, 1.0, n * step)[::step]
        if bad is not None:
            x[where(n)] = bad
            x[where(n) - 1] = np.nan if bad == np.inf else x[where(n) - 1]
        try:
            as_array(x, "x", **options)
        except ValueError as exc:
            return str(exc)
        return "accepted"

    for where in (lambda n: n // 2, lambda n: 1, lambda n: n - 1):
        small = outcome(5, where)
        assert outcome(1 << 14, where) == small
        assert outcome((1 << 20) + 7, where) == small
        assert outcome((1 << 20) + 7, where, step=2) == small
