"""The compiled line fusion (estimators.fusion.line_kernels, behind fuse_lines) against the
plain-float fusion it replaced, to the bit, over seeded random sightings: crossing lines,
bearing-only and ranged ones, nearly parallel ones, time shifts and the inverse-variance
refit."""

import math

import numpy as np
import pytest

from estimators import fuse_lines
from estimators.fusion.line_kernels import MIN_CONDITION


def reference_fuse(P: list[list[float]], angles: list[float], R: list[float], power: float,
                   bearing_sigma: float, range_sigma_rel: float, min_angle: float,
                   stamps: list[float] | None = None, now: float = 0.0,
                   velocity: tuple[float, float] | None = None, *,
                   pose_sigmas: tuple[float, float] | None = None) -> tuple:
    """fuse_lines as plain Python floats computed it before the kernels (its helpers
    below): ``(point, n_lines, fused, sigma, cov)``."""
    # Plain floats: a handful of lines, where numpy's per-call overhead would cost several
    # times the arithmetic (this runs at every camera frame of every robot).
    if stamps is not None and velocity is not None:
        vx, vy = velocity  # each line moved with the target since its stamp
        P = [[x + (now - t) * vx, y + (now - t) * vy] for (x, y), t in zip(P, stamps)]
    n = len(P)
    ux = [math.cos(a) for a in angles]
    uy = [math.sin(a) for a in angles]
    has = [math.isfinite(v) for v in R]
    if n >= 2:
        far = 2.0 * max((v for v, h in zip(R, has) if h), default=0.5)
        k = [(v if h else far) ** -power for v, h in zip(R, has)]
        # Line normals n = (cos theta, sin theta) = (-sin psi, cos psi), rho = p . n.
        nx, ny = [-v for v in uy], ux
        rho = [x * a + y * b for (x, y), a, b in zip(P, nx, ny)]
        crossing = _solve_lines(nx, ny, rho, k)
        if crossing is not None:
            _, M0 = _solve_lines(nx, ny, rho, [1.0] * n, normal_only=True)
            a11, a12, a22 = M0
            if (a11 * a22 - a12 * a12) / (a11 + a22) ** 2 > 0.25 * math.sin(min_angle) ** 2:
                if pose_sigmas is not None:
                    return _crossing_inverse_variance(crossing, P, nx, ny, rho, k,
                                                      bearing_sigma, pose_sigmas)
                return _crossing(crossing, P, nx, ny, rho, k, bearing_sigma)
    if any(has):
        return _ranged_mean(P, R, ux, uy, has, power, bearing_sigma, range_sigma_rel)
    if n >= 2 and crossing is not None:
        if pose_sigmas is not None:
            return _crossing_inverse_variance(crossing, P, nx, ny, rho, k, bearing_sigma,
                                              pose_sigmas)
        return _crossing(crossing, P, nx, ny, rho, k, bearing_sigma)
    raise ValueError("no position: need two crossing lines or a sighting with a range, got "
                     f"{n} bearing-only sighting(s)" + (" (parallel)" if n > 1 else ""))


def _ranged_mean(P: list[list[float]], R: list[float], ux: list[float], uy: list[float],
                 has: list[bool], power: float, bearing_sigma: float, range_sigma_rel: float
                 ) -> tuple:
    n = len(P)
    idx = [i for i in range(n) if has[i]]
    kq = [R[i] ** -power for i in idx]
    total = sum(kq)
    wq = [v / total for v in kq]
    qx = [P[i][0] + R[i] * ux[i] for i in idx]
    qy = [P[i][1] + R[i] * uy[i] for i in idx]
    px_ = sum(w * x for w, x in zip(wq, qx))
    py_ = sum(w * y for w, y in zip(wq, qy))
    b2, rel2 = bearing_sigma**2, range_sigma_rel**2
    # cov_i = r^2 (b^2 I + (rel^2 - b^2) u u^T); cov = sum w^2 cov_i.
    c00 = c01 = c11 = 0.0
    covs = []
    for w, i in zip(wq, idx):
        r2, a, b = R[i] ** 2, ux[i], uy[i]
        d = rel2 - b2
        ci = (r2 * (b2 + d * a * a), r2 * d * a * b, r2 * (b2 + d * b * b))
        covs.append(ci)
        c00 += w * w * ci[0]
        c01 += w * w * ci[1]
        c11 += w * w * ci[2]
    m = len(idx)
    if m >= 2:
        chi2 = 0.0
        for (s00, s01, s11), x, y in zip(covs, qx, qy):
            ex, ey = x - px_, y - py_
            chi2 += (s11 * ex * ex - 2.0 * s01 * ex * ey + s00 * ey * ey) / (
                s00 * s11 - s01 * s01)
        f = max(1.0, chi2 / (2.0 * (m - 1)))
        c00, c01, c11 = c00 * f, c01 * f, c11 * f
    cov = np.array([[c00, c01], [c01, c11]])
    return (np.array([px_, py_]), m, False, math.sqrt(0.5 * (c00 + c11)), cov)


def _solve_lines(nx: list[float], ny: list[float], rho: list[float], k: list[float],
                 normal_only: bool = False):
    a11 = a12 = a22 = b1 = b2 = 0.0
    for a, b, q, w in zip(nx, ny, rho, k):
        wa, wb = w * a, w * b
        a11 += wa * a
        a12 += wa * b
        a22 += wb * b
        b1 += wa * q
        b2 += wb * q
    if normal_only:
        return None, (a11, a12, a22)
    det = a11 * a22 - a12 * a12
    trace = a11 + a22
    if trace <= 0.0 or det <= MIN_CONDITION * trace * trace:
        return None
    return ((a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det), (a11, a12, a22)


#: The smallest offset variance [m^2] :func:`_crossing_inverse_variance` divides by (a line
#: whose origin is at the fused point, with no position error, would have none).
_MIN_OFFSET_VARIANCE = 1e-12


def _crossing_inverse_variance(crossing: tuple, P: list, nx: list[float], ny: list[float],
                               rho: list[float], k: list[float], bearing_sigma: float,
                               pose_sigmas: tuple[float, float]) -> tuple:
    position_sigma, heading_sigma = pose_sigmas
    a = bearing_sigma * bearing_sigma + heading_sigma * heading_sigma
    c = position_sigma * position_sigma

    def variances(point: tuple[float, float]) -> list[float]:
        X, Y = point  # plain floats, as line_offset_variance's formula
        return [max(((X - x) ** 2 + (Y - y) ** 2) * a + c, _MIN_OFFSET_VARIANCE)
                for x, y in P]

    var = variances(crossing[0])
    kv = [1.0 / v for v in var]
    again = _solve_lines(nx, ny, rho, kv)
    if again is None:
        return _crossing(crossing, P, nx, ny, rho, k, bearing_sigma,
                         [math.sqrt(v) for v in var])
    return _crossing(again, P, nx, ny, rho, kv, bearing_sigma,
                     [math.sqrt(v) for v in variances(again[0])])


def _crossing(crossing: tuple, P: list, nx: list[float], ny: list[float], rho: list[float],
              k: list[float], bearing_sigma: float, sigmas: list[float] | None = None
              ) -> tuple:
    (X, Y), (a11, a12, a22) = crossing
    det = a11 * a22 - a12 * a12
    i00, i01, i11 = a22 / det, -a12 / det, a11 / det  # M^-1
    s00 = s01 = s11 = 0.0
    # The lines' lateral standard deviations at the fused point.
    sig = [bearing_sigma * math.hypot(X - x, Y - y) for x, y in P] if sigmas is None \
        else sigmas
    for a, b, w, sd in zip(nx, ny, k, sig):
        g = (w * sd) ** 2
        s00 += g * a * a
        s01 += g * a * b
        s11 += g * b * b
    # cov = Minv S Minv (all symmetric 2 x 2).
    t00, t01 = i00 * s00 + i01 * s01, i00 * s01 + i01 * s11
    t10, t11 = i01 * s00 + i11 * s01, i01 * s01 + i11 * s11
    c00 = t00 * i00 + t01 * i01
    c01 = 0.5 * ((t00 * i01 + t01 * i11) + (t10 * i00 + t11 * i01))
    c11 = t10 * i01 + t11 * i11
    n = len(rho)
    if n >= 3:
        chi2 = sum(((q - a * X - b * Y) / max(sd, 1e-12)) ** 2
                   for q, a, b, sd in zip(rho, nx, ny, sig))
        f = max(1.0, chi2 / (n - 2))
        c00, c01, c11 = c00 * f, c01 * f, c11 * f
    cov = np.array([[c00, c01], [c01, c11]])
    return (np.array([X, Y]), n, True, math.sqrt(0.5 * (c00 + c11)), cov)


def _outcome(f, *args, **kwargs):
    try:
        r = f(*args, **kwargs)
    except ValueError as err:
        return ("error", str(err))
    point, n_lines, fused, sigma, cov = r
    return (list(np.asarray(point).tolist()), n_lines, fused, sigma,
            np.asarray(cov).tolist())


@pytest.mark.parametrize("seed", range(4))
def test_fuse_lines_equals_the_plain_float_fusion(seed):
    rng = np.random.default_rng(seed)
    for trial in range(400):
        n = int(rng.integers(0, 7))
        P = rng.uniform(-5, 5, (n, 2)).tolist()
        ball = rng.uniform(-4, 4, 2)
        angles = [math.atan2(ball[1] - y, ball[0] - x) + float(rng.normal(0, 0.05))
                  for x, y in P]
        if trial % 4 == 3 and n >= 2:  # nearly parallel lines
            angles = [angles[0] + float(rng.normal(0, 1e-3)) for _ in angles]
        R = [math.hypot(ball[0] - x, ball[1] - y) * float(rng.uniform(0.8, 1.2))
             for x, y in P]
        R = [r if rng.random() < 0.5 else math.nan for r in R]
        power = int(rng.integers(0, 3))
        sigmas = (float(rng.uniform(0.01, 0.1)), float(rng.uniform(0.05, 0.3)),
                  math.radians(5.0) if rng.random() < 0.8 else float(rng.uniform(0.01, 1.5)))
        pose = None if rng.random() < 0.5 else (float(rng.uniform(0, 0.3)),
                                                float(rng.uniform(0, 0.1)))
        shift = ()
        if rng.random() < 0.5:
            shift = (rng.uniform(0, 0.1, n).tolist(), 0.1,
                     (float(rng.normal()), float(rng.normal())))
        got = _outcome(fuse_lines, P, angles, R, power, *sigmas, *shift, pose_sigmas=pose)
        want = _outcome(reference_fuse, P, angles, R, power, *sigmas, *shift,
                        pose_sigmas=pose)
        assert got == want
