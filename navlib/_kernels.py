"""Compiled per-sample primitives shared by navlib's modules and their numba kernels.

Each is the one implementation of its formula: the public, validated functions
(:func:`navlib.earth.gravity`, :func:`navlib.earth.radii`, :func:`navlib.kalman.predict`,
:func:`navlib.kalman.update`, :func:`navlib.strapdown.nav_step`, :func:`navlib.robust.stuck_mask`) and the
compiled filters (strapdown, Kalman filters, pedestrian, attitude and planar filters) and the Gauss-Krüger
series call these. The small-matrix primitives (:func:`fma`, :func:`mat3_vec`) reproduce the operation order
of the BLAS that numpy calls, so that a fixed-size step written with them returns the bits of the generic one
without its library calls.
Arguments are plain floats or float arrays in SI units, unvalidated: validate at the public boundary. A
compiled kernel calls the primitive (e.g. :func:`kalman_update`), never the public validated wrapper.
The per-sample quaternion helpers (:func:`quat_mult_t`, :func:`rotvec_to_quat_t`, :func:`quat_to_dcm_t`, ...)
are the compiled twins of :mod:`navlib.attitude`'s vectorised functions; this module imports no other
navlib module.

Reference counts: numba counts a reference to each array a compiled function receives, unpacks from a tuple or
record, or slices, unless it can prove the count is released on every path (a function that may raise, e.g.
divide, or that calls one that is not inlined, keeps them). Each count is an atomic operation, dearer than a
small product. Per-sample code therefore reads a record's arrays once, before its loop, and calls per-sample
steps with arrays, never a tuple or record to unpack. (numba's private option to compile without its runtime would
remove the counts altogether; navlib uses only numba's public options.)
"""

from __future__ import annotations

import gc
import math
import os
import time
from fractions import Fraction

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.core import event
from numba.extending import intrinsic, overload


class CompileLog(event.Listener):
    """When an outermost numba compilation ends: run the cyclic garbage collector and append a line
    ``<seconds> <module.function> <CPU seconds>`` (the compiled function, its callees' compilation included;
    the process's CPU time, which unlike the wall time does not grow on a busy machine) to ``path``.

    Registered only when ``NAVLIB_COMPILE_LOG`` names that file (``tools/reproduce.py`` sets it for its
    notebook kernels): importing navlib installs nothing process-wide otherwise. A compilation leaves tens
    of thousands of objects in reference cycles (typing and LLVM IR objects, llvmlite modules holding
    native LLVM memory) that only the collector frees, and numba's caches then make its full passes rare,
    which raised a cold notebook run's peak memory. Cache loads are not compilations. The log lets
    ``tools/reproduce.py`` plan a warm run from a cold run's times and list the kernels by compile time.
    """

    def __init__(self, path: str):
        self.path, self.depth, self.start, self.start_cpu, self.name = path, 0, 0.0, 0.0, ""

    def on_start(self, ev):
        if self.depth == 0:
            self.start, self.start_cpu = time.perf_counter(), time.process_time()
            func = getattr(ev.data.get("dispatcher"), "py_func", None)
            self.name = f"{getattr(func, '__module__', '?')}.{getattr(func, '__qualname__', '?')}".replace(" ", "_")
        self.depth += 1

    def on_end(self, ev):
        self.depth -= 1
        if self.depth == 0:
            gc.collect()
            with open(self.path, "a") as fh:
                fh.write(f"{time.perf_counter() - self.start:.3f} {self.name} {time.process_time() - self.start_cpu:.3f}\n")


if os.environ.get("NAVLIB_COMPILE_LOG"):  # opt-in only
    event.register("numba:compile", CompileLog(os.environ["NAVLIB_COMPILE_LOG"]))


def fma(a: float, b: float, c: float) -> float:
    """``a * b + c`` rounded once (IEEE 754 fused multiply-add) for floats.

    Compiled kernels get one machine instruction (LLVM's ``llvm.fma``); the small-matrix kernels use it
    to add products in the order, and with the rounding, of the BLAS that numpy and numba call (OpenBLAS's
    x86-64 kernels fuse them). Uncompiled (``NUMBA_DISABLE_JIT=1``) it is ``math.fma`` (Python >= 3.13),
    else exact rational arithmetic rounded once.
    """
    if hasattr(math, "fma"):
        try:
            return math.fma(a, b, c)
        except (ValueError, OverflowError):  # Python 3.13 raises where IEEE gives nan / inf
            return a * b + c
    if not (math.isfinite(a) and math.isfinite(b) and math.isfinite(c)):
        return a * b + c
    exact = Fraction(a) * Fraction(b) + Fraction(c)
    if not exact:
        return a * b + c  # an exact zero: the product is exact, and IEEE's sign of zero follows
    try:
        return float(exact)
    except OverflowError:
        return math.copysign(math.inf, exact)


@intrinsic
def _llvm_fma(typingctx, a, b, c):
    if not all(isinstance(x, types.Float) for x in (a, b, c)):
        return None

    def codegen(context, builder, signature, args):
        d = ir.DoubleType()
        fn = builder.module.declare_intrinsic("llvm.fma", [d], ir.FunctionType(d, [d, d, d]))
        return builder.call(fn, [context.cast(builder, v, t, types.float64) for v, t in zip(args, signature.args, strict=True)])

    return types.float64(a, b, c), codegen


@overload(fma)
def _fma_compiled(a, b, c):
    return lambda a, b, c: _llvm_fma(a, b, c)  # type: ignore[call-arg]  # compiled: numba passes the typing context


@njit(cache=True)
def mat3_vec(C, v):
    """``C @ v`` of a 3 x 3 matrix (array, or tuple of rows) and a 3-vector, as a tuple; allocates nothing.

    Rounded as numba's ``C @ v`` (OpenBLAS's dgemv for 3 x 3) rounds it, so that either gives the same bits:
    per row the second product, fused with the first, fused with the third, added to a zeroed output.
    """
    return (
        0.0 + fma(C[0][2], v[2], fma(C[0][0], v[0], C[0][1] * v[1])),
        0.0 + fma(C[1][2], v[2], fma(C[1][0], v[0], C[1][1] * v[1])),
        0.0 + fma(C[2][2], v[2], fma(C[2][0], v[0], C[2][1] * v[1])),
    )


@njit(cache=True)
def normal_gravity(lat, h, a, f, e2, m, gamma_e, k):
    """Normal gravity (m/s^2): Somigliana's closed form with the second-order height series."""
    s2 = np.sin(lat) ** 2
    g0 = gamma_e * (1 + k * s2) / np.sqrt(1 - e2 * s2)
    return g0 * (1 - 2 / a * (1 + f + m - 2 * f * s2) * h + 3 * h * h / (a * a))


@njit(cache=True)
def radii_mn(lat, a, e2):
    """Meridian and prime-vertical radii of curvature ``(R_M, R_N)`` (m)."""
    w = 1 - e2 * np.sin(lat) ** 2
    R_N = a / np.sqrt(w)
    return R_N * (1 - e2) / w, R_N


@njit(cache=True)
def wrap_pi(a):
    """A scalar angle wrapped to (-pi, pi] (rad): :func:`navlib.attitude.wrap_pi`, compiled, same bits."""
    w = _mod_2pi(a + np.pi) - np.pi
    return np.pi if w == -np.pi else w


@njit(cache=True)
def wrap_2pi(a):
    """A scalar angle wrapped to [0, 2 pi) (rad): :func:`navlib.attitude.wrap_2pi`, compiled, same bits."""
    w = _mod_2pi(a)
    return 0.0 if w >= 2 * np.pi else w


@njit(cache=True, inline="always")
def _mod_2pi(x):
    """``np.mod(x, 2 pi)``. Inside [0, 2 pi) that is ``x`` itself (fmod is exact; + 0.0 turns -0 into +0
    as np.mod does), which skips the fmod call for almost every angle a kernel wraps."""
    if 0.0 <= x < 2 * np.pi:
        return x + 0.0
    return np.mod(x, 2 * np.pi)


@njit(cache=True, inline="always")
def dcm_heading(c12, c22):
    """Heading (rad, (-pi, pi]) of ``C_bn`` from its elements ``C[0, 1]`` and ``C[1, 1]`` (hpr convention)."""
    return np.arctan2(c12, c22)


@njit(cache=True, inline="always")
def level(ax, ay, az):
    """Pitch and roll (rad) from one specific-force sample: :func:`navlib.alignment.level`, compiled."""
    return np.arctan2(ay, np.sqrt(ax * ax + az * az)), np.arctan2(-ax, az)


@njit(cache=True, inline="always")
def euler_to_quat(h, p, r):
    """q_b^n of heading, pitch, roll (rad): :func:`navlib.attitude.euler_to_quat`, compiled (no sign fix-up)."""
    ch, sh, cp, sp, cr, sr = np.cos(h / 2), np.sin(h / 2), np.cos(p / 2), np.sin(p / 2), np.cos(r / 2), np.sin(r / 2)
    return (ch * cp * cr + sh * sp * sr, ch * sp * cr + sh * cp * sr, ch * cp * sr - sh * sp * cr, -sh * cp * cr + ch * sp * sr)


@njit(cache=True)
def tilt_heading(mx, my, mz, pitch, roll):
    """Tilt-compensated magnetic heading in [0, 2 pi) (rad) of a right-front-up magnetometer reading.

    The field is levelled with ``pitch`` and ``roll`` (hpr convention of :mod:`navlib`); the heading is
    ``atan2(-m_h,x, m_h,y)``, clockwise from magnetic north. Works on floats and arrays alike.
    """
    sp, cp, sr, cr = np.sin(pitch), np.cos(pitch), np.sin(roll), np.cos(roll)
    mhx = mx * cr + mz * sr
    mhy = my * cp + mx * sp * sr - mz * sp * cr
    a = np.mod(np.arctan2(-mhx, mhy), 2 * np.pi)
    return a * (a < 2 * np.pi)  # [0, 2 pi): a rounded-up 2 pi is north


MAD_TO_SIGMA = 1.4826
"""Gaussian standard deviations per median absolute deviation (1 / Phi^-1(3/4))."""


@njit(cache=True)
def robust_sigma(mad, step):
    """Robust sigma of a MAD, floored for a quantised reading: ``max(1.4826 max(MAD, q / 2), 1e-12)``.

    ``step`` is the quantisation step q (:func:`quant_step`; 0 or far below the MAD for continuous
    readings, where this is the plain 1.4826 MAD). A quantised reading resolves the MAD only to a step: a
    MAD that reads 0 (more than half of the samples on the median's code, noise sigma below ~0.74 q)
    means a true MAD anywhere below q / 2, and 1.4826 q / 2 is the largest Gaussian sigma that agrees
    with it. Without the floor every sample off the median code is an outlier. The one floor of navlib's
    MAD outlier tests (:mod:`navlib.alignment` static windows, :mod:`navlib.papers.rotation_bias` dwells);
    scalars or arrays (broadcast).
    """
    return np.maximum(MAD_TO_SIGMA * np.maximum(mad, step / 2), 1e-12)


@njit(cache=True)
def quant_step(x):
    """Quantisation step of the readings ``x`` (1-D): the smallest non-zero difference between two finite
    values, 0 when there are no two distinct ones."""
    v = np.sort(x[np.isfinite(x)])
    q = np.inf
    for j in range(1, v.shape[0]):
        d = v[j] - v[j - 1]
        if 0.0 < d < q:
            q = d
    return q if q < np.inf else 0.0


@njit(cache=True)
def quant_steps(x):
    """:func:`quant_step` of each row of ``x`` (M, n)."""
    out = np.empty(x.shape[0])
    for i in range(x.shape[0]):
        out[i] = quant_step(x[i])
    return out


@njit(cache=True)
def kalman_predict(x, P, F, Q):
    """Linear prediction ``x = F x``, ``P = F P F^T + Q`` (symmetrised); :func:`navlib.kalman.predict` unvalidated."""
    Pn = F @ P @ np.ascontiguousarray(F.T) + Q
    return F @ x, (Pn + Pn.T) / 2


@njit(cache=True)
def kalman_update(x, P, z, h, H, R, angle_mask, gate=np.inf):
    """Joseph-form update skipping NaN components; :func:`navlib.kalman.update` unvalidated.

    Returns ``(x, P, y, nis, status)`` with status 1 (accepted), 0 (no data) or -1 (rejected by ``gate``).
    """
    m = z.shape[0]
    finite = np.isfinite(z)
    n_used = int(finite.sum())
    if n_used == 0:
        return x.copy(), P.copy(), np.full(m, np.nan), np.nan, 0
    y = z - h
    for j in range(m):
        if angle_mask[j] and finite[j]:
            y[j] = wrap_pi(y[j])
    if n_used == m:  # common case: no dropout, no copies
        Hs, Rs, ys = H, R, y
    else:
        idx = np.nonzero(finite)[0]
        Hs = np.ascontiguousarray(H[idx, :])
        Rs = np.ascontiguousarray(R[idx][:, idx])
        ys = y[idx]
    PHt = P @ np.ascontiguousarray(Hs.T)
    S = Hs @ PHt + Rs
    S_inv = np.linalg.inv((S + S.T) / 2)
    nis = ys @ S_inv @ ys
    if nis > gate:
        return x.copy(), P.copy(), y, nis, -1
    K = PHt @ S_inv
    IKH = np.eye(x.shape[0]) - K @ Hs
    Pn = IKH @ P @ np.ascontiguousarray(IKH.T) + K @ Rs @ np.ascontiguousarray(K.T)
    return x + K @ ys, (Pn + Pn.T) / 2, y, nis, 1


@njit(cache=True)
def spd_solve_into(S, B):
    """``B = S^-1 B`` in place for a symmetric positive definite ``S`` (m, m) and ``B`` (m, k), by Cholesky.

    ``S``'s lower triangle becomes the factor L (``S = L L^T``; only the lower triangle is read), with the
    reciprocals of its diagonal on the diagonal. Returns False, ``B`` unsolved, when S is not positive definite
    (to rounding). Allocates nothing.
    """
    m = S.shape[0]
    for j in range(m):
        d = S[j, j]
        for k in range(j):
            d -= S[j, k] * S[j, k]
        if not d > 0.0:
            return False
        inv = 1.0 / np.sqrt(d)
        S[j, j] = inv
        for i in range(j + 1, m):
            t = S[i, j]
            for k in range(j):
                t -= S[i, k] * S[j, k]
            S[i, j] = t * inv
    n = B.shape[1]
    for i in range(m):  # L W = B, all columns at once (independent chains, along B's rows)
        for k in range(i):
            s = S[i, k]
            for c in range(n):
                B[i, c] -= s * B[k, c]
        for c in range(n):
            B[i, c] *= S[i, i]
    for i in range(m - 1, -1, -1):  # L^T U = W
        for k in range(i + 1, m):
            s = S[k, i]
            for c in range(n):
                B[i, c] -= s * B[k, c]
        for c in range(n):
            B[i, c] *= S[i, i]
    return True


@njit(cache=True)
def scalar_update(P, dx, y, h, cols, r):
    """Joseph-form update of a closed-loop error-state filter (state 0 before it) by one scalar measurement, in
    place; compiled, unvalidated.

    ``P`` (n, n) symmetric, ``y`` the innovation, ``h`` (n,) the measurement row, zero outside the columns
    ``cols``, ``r`` its variance. Writes ``dx = k y`` (n,) and ``P = (I - k h) P (I - k h)^T + k r k^T``
    (symmetric, exactly): :func:`kalman_update`'s algebra for one component, ``x = 0`` and ``h x = 0``, equal
    to it to rounding (the sums skip h's zeros; one triangle is computed).
    """
    n = P.shape[0]
    ph, k, g, L = np.empty(n), np.empty(n), np.empty(n), np.empty((n, n))
    for i in range(n):  # P h^T
        t = 0.0
        for c in cols:
            t += P[i, c] * h[c]
        ph[i] = t
    s = r
    for c in cols:
        s += h[c] * ph[c]
    for i in range(n):
        k[i] = ph[i] / s
        dx[i] = k[i] * y
    for i in range(n):  # L = (I - k h) P = P - k (P h^T)^T
        for j in range(n):
            L[i, j] = P[i, j] - k[i] * ph[j]
    for i in range(n):  # g = L h^T
        t = 0.0
        for c in cols:
            t += L[i, c] * h[c]
        g[i] = t
    for i in range(n):  # P = L - g k^T + k r k^T, one triangle
        w = r * k[i] - g[i]
        for j in range(i, n):
            P[i, j] = P[j, i] = L[i, j] + w * k[j]


# --------------------------------------------------------------------------
# Per-sample quaternion helpers (scalar first, Hamilton product, the conventions of navlib.attitude)
# --------------------------------------------------------------------------
# Per-sample twins of navlib.attitude's vectorised functions for compiled kernels, tested against them.


@njit(cache=True, inline="always")
def quat_mult_t(a0, a1, a2, a3, b0, b1, b2, b3):
    """Hamilton product on scalars, returned as a tuple (allocation-free kernel helper)."""
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


@njit(cache=True, inline="always")
def rotvec_to_quat_t(rx, ry, rz):
    """Quaternion of a rotation vector, as a tuple (allocation-free kernel helper).

    Below 0.05 rad (every gyro increment at 100 Hz below 5 rad/s) the Taylor
    series of cos(a/2) and sin(a/2)/a to a^8 is exact in double precision and
    avoids three transcendental calls per sample.
    """
    a2 = rx * rx + ry * ry + rz * rz
    if a2 < 2.5e-3:
        c = 1 - a2 / 8 + a2 * a2 / 384 - a2 * a2 * a2 / 46080 + a2**4 / 10321920
        k = 0.5 - a2 / 48 + a2 * a2 / 3840 - a2 * a2 * a2 / 645120 + a2**4 / 185794560
    else:
        a = np.sqrt(a2)
        c = np.cos(a / 2)
        k = np.sin(a / 2) / a
    return c, k * rx, k * ry, k * rz


@njit(cache=True)
def quat_mult_1(p, q):
    """Hamilton product of two quaternions, shape (4,) (compiled helper)."""
    return np.array(quat_mult_t(p[0], p[1], p[2], p[3], q[0], q[1], q[2], q[3]))


@njit(cache=True)
def rotvec_to_quat_1(rv):
    """Quaternion of one rotation vector (compiled helper)."""
    return np.array(rotvec_to_quat_t(rv[0], rv[1], rv[2]))


@njit(cache=True)
def quat_normalize_1(q):
    """Unit quaternion (compiled helper)."""
    return q / np.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])


@njit(cache=True)
def quat_to_dcm_t(q0, q1, q2, q3):
    """C_b^n of one unit quaternion as a tuple of rows (allocation-free kernel helper)."""
    return (
        (q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)),
        (2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1)),
        (2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3),
    )


@njit(cache=True)
def quat_to_dcm_into(C, q):
    """C_b^n of one unit quaternion ``q`` (4,) written into ``C`` (3, 3) (allocation-free kernel helper)."""
    r0, r1, r2 = quat_to_dcm_t(q[0], q[1], q[2], q[3])
    C[0, 0], C[0, 1], C[0, 2] = r0
    C[1, 0], C[1, 1], C[1, 2] = r1
    C[2, 0], C[2, 1], C[2, 2] = r2


@njit(cache=True)
def quat_to_dcm_1(q):
    """C_b^n of one unit quaternion (compiled helper)."""
    C = np.empty((3, 3))
    quat_to_dcm_into(C, q)
    return C


@njit(cache=True)
def nav_step(lla, vel, q, w, f, dt, earth_consts, hold_height=False):
    """One ENU strapdown step updating ``lla``, ``vel``, ``q`` in place; :func:`navlib.strapdown.nav_step` unvalidated.

    Written on scalars and tuples, it allocates nothing; each operation is the one the former array form did
    (``0.0 + x`` included, the zero component of w_ie), so the results are bit for bit those of that form.
    """
    a, flat, e2, m, gamma_e, k_som, omega = (
        earth_consts[0],
        earth_consts[1],
        earth_consts[2],
        earth_consts[3],
        earth_consts[4],
        earth_consts[5],
        earth_consts[6],
    )
    lat, h = lla[0], lla[2]
    sl, cl = np.sin(lat), np.cos(lat)
    R_M, R_N = radii_mn(lat, a, e2)
    w_ie1, w_ie2 = omega * cl, omega * sl  # w_ie = (0, w_ie1, w_ie2)
    w_en0, w_en1, w_en2 = -vel[1] / (R_M + h), vel[0] / (R_N + h), vel[0] * sl / cl / (R_N + h)
    w_in0, w_in1, w_in2 = 0.0 + w_en0, w_ie1 + w_en1, w_ie2 + w_en2
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    half = dt / 2
    n0, n1, n2, n3 = rotvec_to_quat_t(-w_in0 * half, -w_in1 * half, -w_in2 * half)
    b0, b1, b2, b3 = rotvec_to_quat_t(w[0] * half, w[1] * half, w[2] * half)
    m0, m1, m2, m3 = quat_mult_t(n0, n1, n2, n3, q0, q1, q2, q3)
    m0, m1, m2, m3 = quat_mult_t(m0, m1, m2, m3, b0, b1, b2, b3)  # mid-interval attitude
    f_n = mat3_vec(quat_to_dcm_t(m0, m1, m2, m3), f)
    g = normal_gravity(lat, h, a, flat, e2, m, gamma_e, k_som)
    u0, u1, u2 = 0.0 + w_en0, 2 * w_ie1 + w_en1, 2 * w_ie2 + w_en2  # 2 w_ie + w_en
    v0, v1, v2 = vel[0], vel[1], vel[2]
    vn0 = v0 + (f_n[0] - (u1 * v2 - u2 * v1)) * dt  # v + (f_n - u x v) dt
    vn1 = v1 + (f_n[1] - (u2 * v0 - u0 * v2)) * dt
    vn2 = v2 + (f_n[2] - (u0 * v1 - u1 * v0)) * dt
    vn2 -= g * dt
    if hold_height:
        vn2 = 0.0
    n0, n1, n2, n3 = rotvec_to_quat_t(-w_in0 * dt, -w_in1 * dt, -w_in2 * dt)
    b0, b1, b2, b3 = rotvec_to_quat_t(w[0] * dt, w[1] * dt, w[2] * dt)
    m0, m1, m2, m3 = quat_mult_t(n0, n1, n2, n3, q0, q1, q2, q3)
    m0, m1, m2, m3 = quat_mult_t(m0, m1, m2, m3, b0, b1, b2, b3)
    s = np.sqrt(m0 * m0 + m1 * m1 + m2 * m2 + m3 * m3)
    q[0], q[1], q[2], q[3] = m0 / s, m1 / s, m2 / s, m3 / s
    lla[0] = lat + (v1 + vn1) / 2 / (R_M + h) * dt
    lla[1] += (v0 + vn0) / 2 / ((R_N + h) * cl) * dt
    lla[2] = h + (v2 + vn2) / 2 * dt
    vel[0], vel[1], vel[2] = vn0, vn1, vn2


@njit(cache=True, nogil=True)
def stuck_runs(t0, t1, x, run, rail, out):
    """Compiled :func:`navlib.robust.stuck_mask` of series t0 to t1 - 1 of ``x`` (T, N, k), per component: set
    ``out`` (T, N, k).

    A maximal run of ``run`` or more exactly equal values of one component marks all its samples.
    NaN, and values with ``|x| >= rail`` (saturated, not stuck), are never part of a run.
    """
    n = x.shape[1]
    for t in range(t0, t1):
        for c in range(x.shape[2]):
            start = 0
            for i in range(1, n + 1):
                v = x[t, i - 1, c]
                if i < n and x[t, i, c] == v and abs(v) < rail:
                    continue  # the run goes on
                if i - start >= run:
                    out[t, start:i, c] = True
                start = i


@njit(cache=True, nogil=True)
def count_flags(t0, t1, flags, counts):
    """``counts[:, t] = flags[:, t].sum(-1)`` for series t0 to t1 - 1 of the flags (K, T, N) (numpy counts a batch
    serially, holding the GIL)."""
    for key in range(flags.shape[0]):
        for t in range(t0, t1):
            c = 0
            for k in range(flags.shape[2]):
                c += flags[key, t, k]
            counts[key, t] = c
