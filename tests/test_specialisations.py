"""Read-only inputs do not make numba compile a kernel twice (issue 16: redundant specialisations).

numba types a read-only array (``np.broadcast_to`` views, pandas 3 columns) differently from a writable
one; every such input reaching a kernel used to cost a second compilation of the whole kernel (measured
in notebooks 02, 04 and 05: 2-5 signatures of kernels that take 5-40 s each to compile). The wrappers
pass kernels ``_validate.kernel_array`` copies; these tests call public functions with read-only
inputs and check that no kernel signature holds a read-only array.
"""

import os

import numpy as np
import pytest
from numba.core import types

from navlib import _kernels, alignment, earth, euler, strapdown, trajectory, units
from navlib.filters import mahony, quaternion_kf
from navlib.filters.observations import RtkHeading
from navlib.imu import ImuSamples
from navlib.papers import rotation_bias


def readonly(a):
    a = np.array(a, dtype=float)
    a.flags.writeable = False
    return a


def _calls():
    traj = trajectory.static(2.0, 0.1, [0.5, 0.0, 0.0], [0.1, 0.0, 0.0])
    w, f = trajectory.ideal_imu(traj)
    return [
        ("earth.gravity", lambda: earth.gravity(readonly(0.5), readonly(10.0)), _kernels.normal_gravity),
        (
            "alignment.magnetic_heading",
            lambda: alignment.magnetic_heading(readonly([20.0, 1.0, 40.0]), readonly(0.1), readonly(0.0)),
            _kernels.tilt_heading,
        ),
        (
            "euler.integrate_euler",
            lambda: euler.integrate_euler(np.broadcast_to(units.deg([10.0, 5.0, 0.0]), (3,)), readonly(w), 0.1),
            euler._euler_kernel,
        ),
        (
            "strapdown.integrate",
            lambda: strapdown.integrate(
                readonly(traj.lla[0]), readonly(traj.vel_n[0]), readonly(traj.q_bn[0]), readonly(w), readonly(f), 0.1
            ),
            strapdown._nav_kernel,
        ),
        (
            "quaternion_kf, RTK heading",
            lambda: quaternion_kf.quaternion_kf(
                ImuSamples(readonly([w, w]), readonly([f, f]), 0.1),
                readonly([1.0, 0, 0, 0]),
                rtk=RtkHeading(readonly(np.full((2, len(w)), 0.1)), np.ones((2, len(w)), dtype=bool)),
            ),
            quaternion_kf._kernel,
        ),
        (
            "mahony, RTK heading",
            lambda: mahony.mahony(
                ImuSamples(readonly([w, w]), readonly([f, f]), 0.1),
                readonly([1.0, 0, 0, 0]),
                rtk=RtkHeading(readonly(np.full((2, len(w)), 0.1)), np.ones((2, len(w)), dtype=bool)),
            ),
            mahony._kernel,
        ),
        (
            "rotation_bias.tilt_residuals",
            lambda: rotation_bias.tilt_residuals(readonly(w), readonly(f), 0.1, [0], 10),
            rotation_bias._residual_kernel,
        ),
    ]


def _readonly(t) -> bool:
    """A read-only array type, also inside a tuple or named tuple argument (the attitude filters' inputs)."""
    if isinstance(t, types.BaseTuple):
        return any(_readonly(x) for x in t.types)
    return isinstance(t, types.Array) and not t.mutable


@pytest.mark.parametrize("name, call, kernel", _calls(), ids=lambda x: x if isinstance(x, str) else "")
def test_read_only_inputs_reach_kernels_writable(name, call, kernel):
    call()
    readonly_sigs = [s for s in kernel.signatures if any(_readonly(t) for t in s)]
    assert kernel.signatures and not readonly_sigs, f"{name}: read-only specialisations {readonly_sigs}"


def test_compilations_are_logged_where_navlib_compile_log_says(tmp_path):
    """tools/reproduce.py plans a warm run from a cold one's times less the seconds logged here."""
    import subprocess
    import sys

    log = tmp_path / "compile.log"
    code = (
        "import numpy as np; from numba import njit; import navlib._kernels; "
        "f = njit(lambda x: x.sum() + 1.0); f(np.ones(3)); f(np.ones(3))"
    )  # compiled once, then reused
    subprocess.run([sys.executable, "-c", code], check=True, env={**os.environ, "NAVLIB_COMPILE_LOG": str(log)})
    lines = [line.split() for line in log.read_text().splitlines()]  # "<seconds> <module.function>"
    assert len(lines) == 1 and 0 < float(lines[0][0]) < 60 and lines[0][1] == "__main__.<lambda>"


def test_compilation_garbage_is_collected_at_once(tmp_path):
    """A compilation's reference cycles (typing objects, llvmlite modules holding native memory) are freed
    when it ends (navlib._kernels' compile listener, registered where NAVLIB_COMPILE_LOG is set, as
    tools/reproduce.py does), not at the collector's next full pass: they kept notebook 02's first run
    0.5 GB above its warm peak."""
    import subprocess
    import sys

    code = (
        "import gc, numpy as np; from numba import njit; import navlib._kernels; "
        "fresh = njit(lambda A: A @ A); "  # a new function: compiled by this call (a BLAS call, ~1 s: solve took 4 s)
        "fresh(np.eye(3)); print(gc.collect())"
    )
    out = subprocess.run(
        [sys.executable, "-c", code],
        check=True,
        capture_output=True,
        text=True,
        env={**os.environ, "NAVLIB_COMPILE_LOG": str(tmp_path / "compile.log")},
    ).stdout
    assert int(out.split()[-1]) < 100  # without the listener: ~10,000 objects
