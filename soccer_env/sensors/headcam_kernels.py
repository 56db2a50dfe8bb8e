"""Compiled kernels of the head camera (:class:`~soccer_env.sensors.headcam.HeadCameraSensor`):
the visibility test, the occlusion test and the back-projection of every (frame, object) pair
of the frames captured in one step.

The maths (SI units, angles in radians; the module docstring of
:mod:`soccer_env.sensors.headcam` has the full model). Observer ``i`` at ``(x_i, y_i,
theta_i)`` with a camera ``h`` above its centre, head pan ``alpha`` and tilt ``beta`` and the
gait's sway ``(sway_pan, sway_tilt)``: the TRUE orientation is ``psi = theta_i + alpha +
sway_pan``, ``beta_t = beta + sway_tilt``. An object at offset ``(dx, dy, dz)`` from the camera
foot (the ball's centre at ``z = ball z + radius``; landmarks and the other robots' foot points
``c_j - R_j (c_j - c_i) / |c_j - c_i|`` on the ground) has

    fwd = cos(psi) dx + sin(psi) dy,   depth = cos(beta_t) fwd - sin(beta_t) dz,
    du = (sin(psi) dx - cos(psi) dy) f / depth,   dv = (sin(beta_t) fwd + cos(beta_t) dz) f / depth

(pixel offsets from the principal point ``(u0, v0)``, ``dv`` upwards, ``f`` the focal length
[px]). It is a candidate if ``depth > 1e-9`` m, ``|du| <= u0``, ``|dv| <= v0``, ``dx^2 + dy^2
<= range^2`` of its kind and its detection uniform is below its kind's probability; it is
hidden if the ground segment from the observer's centre to it meets another robot's disc ``|q
- t s| < R`` (``q`` that robot's offset, ``s = (dx, dy)``, ``t = clip(q.s / s.s, 0, 1)``).
The pixel ``u = u0 + du + sigma n_u``, ``v = v0 - dv + sigma n_v`` (``n`` standard normals,
``sigma`` the pixel noise [px]) is projected back with the BELIEVED angles ``(alpha, beta)``
(:func:`back_project`).

Why kernels: a step captures one to a few frames of some 30 object slots each; the array
version cost about twenty numpy calls on arrays of a few rows, then a Python loop over the
candidates, so numpy's per-call overhead, not the arithmetic, set the cost. The kernels do the
same arithmetic in one compiled pass. They evaluate the same expressions in the same order as
the array code did (elementwise float64 arithmetic, no fastmath; ``math.cos``, ``sin``,
``sqrt``, ``atan2``, the C library's), so the frames are bit for bit those of the array code
wherever numpy's float64 ``cos`` and ``sin`` equal the C library's (checked on an x86-64 CPU
with AVX2; on AVX-512 CPUs numpy dispatches to other implementations, known to differ in the
last bit for some angles). The random draws stay with the caller's
``numpy.random.Generator`` and come in as arrays.
"""

from __future__ import annotations

import math

import numpy as np

from estimators.compiled import kernel

__all__ = ["back_project", "head_detections"]


@kernel
def back_project(u: float, v: float, head: tuple[float, float, float, float],
                 lens: tuple[float, float, float], height: float, plane: float
                 ) -> tuple[float, float, float]:
    """Ground point ``(x, y)`` [m, robot frame: x forward, y left, origin under the camera] of
    pixel ``(u, v)`` [px] on the plane ``z = plane`` [m], and the bearing [rad] of its ray.

    ``head`` is the believed ``(cos pan, sin pan, cos tilt, sin tilt)``, ``lens`` the focal
    length and principal point ``(f, u0, v0)`` [px], ``height`` the camera's [m]. The camera
    ray ``(a, 1, e) = ((u - u0) / f, 1, (v0 - v) / f)`` turned back by ``Rz(pan)^T
    Rx(tilt)^T`` (as :meth:`~estimators.HeadCamera.ground_point`) is ``(ray_x, ray_y, rz)``;
    it meets the plane at ``t = (plane - height) / rz`` if ``t > 0`` (and ``|rz| > 1e-12``),
    else the point is ``(nan, nan)``. The bearing ``atan2(ray_y, ray_x)`` is always defined.
    """
    ca, sa, ct, st = head
    f, u0, v0 = lens
    a = (u - u0) / f
    e = (v0 - v) / f
    fw = ct + st * e  # horizontal component along the panned axis
    rz = ct * e - st  # vertical component
    ray_x = ca * fw + sa * a  # robot frame: x forward
    ray_y = sa * fw - ca * a  # y to the left
    drop = plane - height
    bearing = math.atan2(ray_y, ray_x)
    if rz * drop > 0.0 and abs(rz) > 1e-12:
        t = drop / rz
        return t * ray_x, t * ray_y, bearing
    return math.nan, math.nan, bearing


@kernel
def _hidden(sx: float, sy: float, ox: np.ndarray, oy: np.ndarray, r2: np.ndarray, me: int,
            target: int) -> bool:
    """Whether the ground segment from the observer ``me`` to the object at offset ``(sx,
    sy)`` [m] meets the disc of a robot other than ``me`` and ``target`` (the object's own
    robot, or -1 and below for none): robot ``j`` at offset ``(ox[j], oy[j])`` [m] with squared
    radius ``r2[j]`` [m^2] hides it if the segment's point closest to its centre, at ``t =
    clip(q.s / s.s, 0, 1)`` (``s.s`` at least 1e-24), is within its radius."""
    seg2 = sx * sx + sy * sy
    if seg2 < 1e-24:
        seg2 = 1e-24
    for j in range(ox.shape[0]):
        if j == me or j == target:
            continue
        qx, qy = ox[j], oy[j]
        t = (sx * qx + sy * qy) / seg2
        t = 0.0 if t < 0.0 else (1.0 if t > 1.0 else t)
        ex, ey = qx - t * sx, qy - t * sy
        if ex * ex + ey * ey < r2[j]:
            return True
    return False


@kernel
def _offset(slot: int, ball: np.ndarray, landmarks: np.ndarray, radii: np.ndarray,
            ox: np.ndarray, oy: np.ndarray, rx: float, ry: float) -> tuple[float, float]:
    """Ground offset ``(dx, dy)`` [m] of object ``slot`` (see :func:`head_detections`) from
    the observer's centre ``(rx, ry)``: the ball, a landmark, or robot ``j``'s foot point
    nearest the observer, ``o_j (1 - R_j / max(|o_j|, 1e-9))`` for its centre's offset
    ``o_j = (ox[j], oy[j])``."""
    m = landmarks.shape[0]
    if slot == 0:
        return ball[0] - rx, ball[1] - ry
    if slot <= m:
        return landmarks[slot - 1, 0] - rx, landmarks[slot - 1, 1] - ry
    j = slot - 1 - m
    dist = math.sqrt(ox[j] * ox[j] + oy[j] * oy[j])
    if dist < 1e-9:  # as numpy.maximum: NaN stays NaN
        dist = 1e-9
    keep = 1.0 - radii[j] / dist
    return ox[j] * keep, oy[j] * keep


@kernel
def head_detections(robots: np.ndarray, ball: np.ndarray, obs: np.ndarray, pan: np.ndarray,
                    tilt: np.ndarray, sway_pan: np.ndarray, sway_tilt: np.ndarray,
                    landmarks: np.ndarray, radii: np.ndarray, r2: np.ndarray,
                    range2: np.ndarray, p_detect: np.ndarray, U: np.ndarray, Z: np.ndarray,
                    camera: tuple[float, float, float, float, float, float], occlusion: bool
                    ) -> tuple[np.ndarray, np.ndarray]:
    """The detections of the frames of observers ``obs`` (``(F,)`` robot indices) on one
    world state (module docstring): visibility, occlusion, pixel noise, back-projection.

    Args:
        robots: ``(N, >=3)`` poses ``x, y, theta`` [m, m, rad].
        ball: ``(>=3,)`` its ``x, y, z`` [m].
        obs: ``(F,)`` the observers' robot indices.
        pan: ``(N,)`` every robot's head pan [rad].
        tilt: ``(N,)`` every robot's head tilt [rad].
        sway_pan: ``(N,)`` the gait's sway of the pan [rad].
        sway_tilt: ``(N,)`` the gait's sway of the tilt [rad].
        landmarks: ``(M, 2)`` positions [m].
        radii: ``(N,)`` robot radii [m].
        r2: ``(N,)`` their squares [m^2].
        range2: ``(P,)`` squared range [m^2] of each object slot, ``P = 1 + M + N``: 0 the
            ball, ``1..M`` the landmarks, ``M + 1 + j`` robot ``j``'s foot point.
        p_detect: ``(P,)`` the detection probability of each object slot.
        U: ``(F, >=P)`` detection uniforms.
        Z: ``(F, 2, P)`` pixel-noise normals (u, v).
        camera: ``(height [m], f [px], u0 [px], v0 [px], ball radius [m], pixel sigma
            [px])``.
        occlusion: whether robots hide what is behind them.

    Returns:
        Every detection, frame by frame and slot by slot: ``(D, 2)`` int64 rows ``(frame,
        slot)`` (``frame`` a position in ``obs``) and ``(D, 5)`` float64 rows ``(u, v, x, y,
        bearing)``: the pixel [px], the ground point [m, robot frame] and the bearing [rad].
        (Two arrays rather than seven: each array returned to Python costs a microsecond.)
    """
    h, f, u0, v0, r_ball, sigma = camera
    lens = (f, u0, v0)
    n, m, nf = robots.shape[0], landmarks.shape[0], obs.shape[0]
    p = 1 + m + n
    where = np.empty((nf * p, 2), np.int64)
    out = np.empty((nf * p, 5))
    ox, oy = np.empty(n), np.empty(n)
    count = 0
    for k in range(nf):
        i = obs[k]
        rx, ry = robots[i, 0], robots[i, 1]
        psi = robots[i, 2] + pan[i] + sway_pan[i]
        beta = tilt[i] + sway_tilt[i]
        c, s, cb, sb = math.cos(psi), math.sin(psi), math.cos(beta), math.sin(beta)
        head = (math.cos(pan[i]), math.sin(pan[i]), math.cos(tilt[i]), math.sin(tilt[i]))
        for j in range(n):
            ox[j], oy[j] = robots[j, 0] - rx, robots[j, 1] - ry
        for slot in range(p):
            if slot == 1 + m + i or not U[k, slot] < p_detect[slot]:
                continue  # oneself, or a missed detection
            dx, dy = _offset(slot, ball, landmarks, radii, ox, oy, rx, ry)
            dz = (ball[2] + r_ball) - h if slot == 0 else 0.0 - h
            if not dx * dx + dy * dy <= range2[slot]:
                continue
            fwd = c * dx + s * dy
            depth = cb * fwd - sb * dz
            if not depth > 1e-9:
                continue
            scale = f / depth
            du = (s * dx - c * dy) * scale
            dv = (sb * fwd + cb * dz) * scale  # upwards
            if not (abs(du) <= u0 and abs(dv) <= v0):
                continue
            if occlusion and _hidden(dx, dy, ox, oy, r2, i, slot - 1 - m):
                continue
            u = u0 + du + sigma * Z[k, 0, slot]
            v = v0 - dv + sigma * Z[k, 1, slot]
            x, y, b = back_project(u, v, head, lens, h, r_ball if slot == 0 else 0.0)
            where[count, 0], where[count, 1] = k, slot
            out[count, 0], out[count, 1], out[count, 2] = u, v, x
            out[count, 3], out[count, 4] = y, b
            count += 1
    return where[:count], out[:count]
