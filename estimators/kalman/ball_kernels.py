"""The friction EKF of :class:`~estimators.BallTracker` as compiled kernels over rows of tracks.

One frame of one track is :func:`ball_frame`: predict with the friction model
(:func:`~estimators.models.motion.friction_step`, eq. 19's collision-aware velocity noise by
:func:`collision_sigma`, the optional two-phase deceleration), take the detection nearest the
prediction (Mahalanobis, the first of equals) and fuse it with the Kalman blocks of
:mod:`estimators.kalman.blocks` when the gate admits it; a gated-out detection near the
prediction that the ball could have reached is a maneuver, any other is offered to the track
initiator's candidates, and a track restarts from the first and the latest of ``reset_after``
candidates that agree. :func:`ball_frames` runs it over the tracks of many environments, so
:class:`~estimators.BallTracker` (a batch of one, with its replay of late frames) and
:class:`~estimators.BallTrackerBatch` run the same code. :func:`ball_estimate` and
:func:`ball_predicted` predict a track to a later time.

**A track** is one float64 row (:data:`TRACK_WIDTH` plus three columns per candidate): the
time of its latest frame ``t`` [s] (``-inf`` before the first) in column 0, the state
``(x, y, vx, vy)`` [m, m/s] in 1-4, the covariance blocks ``P11, P12, P22`` row-major in 5-16
(:data:`~estimators.kalman.blocks.Blocks`), the two-phase switch speed [m/s] in 17, the
capture time of the latest fused detection [s] in 18, the detections fused since the latest
(re)start in 19 (0 before the first: no track), the number of candidates in 20, and from 21
the candidates ``(t, x, y)`` [s, m], oldest first. The counters ``fused, rejected, resets,
maneuvers`` are an int64 row of four (:data:`FUSED` ...).

**Parameters** are one float64 array built by :func:`ball_parameters` from a
:class:`~estimators.BallFilterConfig` (the squares of its figures computed there, in Python, as
the config's own arithmetic rounds them). The arithmetic is the plain-float arithmetic of the
Python tracker in the same order (``math.hypot`` by :func:`~estimators.exact.hypot_exact`, the
finite-difference variance's ``span ** 2`` by the C library's ``pow`` as Python's float power
calls it), so results are bit for bit those of the tracker written in Python floats.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..compiled import kernel
from ..exact import hypot_exact
from ..models.motion import PAPER_CYCLE, friction_step
from .blocks import Blocks, State, innovation, predict_covariance, update

__all__ = ["TRACK_WIDTH", "FUSED", "REJECTED", "RESETS", "MANEUVERS", "ball_parameters",
           "track_width", "as_points", "collision_sigma", "ball_frame", "ball_frames",
           "ball_estimate", "ball_estimates", "ball_predicted"]

#: Columns of a track row before its candidates (see the module docstring).
TRACK_WIDTH = 21
_T, _X, _P, _VS, _FA, _SS, _NC, _CAND = 0, 1, 5, 17, 18, 19, 20, 21

#: Columns of the counters row: detections fused, gated out, track restarts, maneuvers.
FUSED, REJECTED, RESETS, MANEUVERS = 0, 1, 2, 3

# Entries of the parameter array (ball_parameters).
(_R, _VAR0, _SIGMA_R, _COLLISION, _GAIN, _LIMIT, _MANEUVER, _M_RADIUS, _SIGMA_XY, _M_VAR,
 _TWO_PHASE, _A_SLIDE, _K_SWITCH, _KICK_SPEED, _DECEL, _RK, _INITIATOR, _COUNT, _PRIOR_VAR,
 _SXY2, _SR2, _GATE_KICK, _MAX_SPEED, _TWO, _SIZE) = range(25)


def ball_parameters(config: Any, r: float, gate_kick: float, initiator: Any) -> np.ndarray:
    """The parameter array of the kernels for a :class:`~estimators.BallFilterConfig`
    ``config``, the measurement noise variance ``r`` [m^2] per axis, the
    :class:`~estimators.tracking.Gate`'s ``kick_speed`` ``gate_kick`` [m/s] and the
    :class:`~estimators.tracking.TrackInitiator` ``initiator`` (None: no restarts)."""
    c = config
    p = np.zeros(_SIZE)
    p[_R], p[_VAR0], p[_SIGMA_R] = r, c.tau**2, c.sigma_r
    p[_COLLISION] = float(c.collision_noise)
    p[_GAIN] = c.gain_k * (c.robot_radius + c.ball_radius)
    p[_LIMIT] = math.inf if c.gate is None else c.gate
    p[_MANEUVER] = float(c.maneuver_radius is not None)
    p[_M_RADIUS] = 0.0 if c.maneuver_radius is None else c.maneuver_radius
    p[_SIGMA_XY], p[_M_VAR] = c.sigma_xy, c.maneuver_speed**2
    if c.two_phase is not None:
        p[_TWO_PHASE], p[_A_SLIDE], p[_K_SWITCH] = 1.0, c.two_phase[0], c.two_phase[1]
    p[_KICK_SPEED], p[_DECEL] = c.kick_speed, c.deceleration
    p[_RK] = float(c.propagation == "rk")
    if initiator is not None:
        p[_INITIATOR], p[_COUNT], p[_PRIOR_VAR] = 1.0, initiator.count, initiator.prior_var
        p[_MAX_SPEED] = initiator.max_speed
    p[_SXY2], p[_SR2] = c.sigma_xy**2, c.sigma_r**2
    p[_GATE_KICK], p[_TWO] = gate_kick, 2.0
    return p


def as_points(rows) -> np.ndarray:
    """Points or poses ``rows`` (an array or a sequence of rows whose first two entries are a
    position, k may be 0) as a new C-contiguous float64 array ``(k, 2+)``: what the kernels
    of :mod:`~estimators.kalman.ball_kernels` take."""
    if len(rows) == 0:
        return np.zeros((0, 2))
    try:
        a = np.array(rows, dtype=np.float64)
    except ValueError:  # rows of different lengths
        a = np.array([(r[0], r[1]) for r in rows], dtype=np.float64)
    return a if a.ndim == 2 else a.reshape(len(rows), -1)


def track_width(config: Any) -> int:
    """Columns of a track row for ``config`` (room for ``reset_after`` candidates)."""
    return TRACK_WIDTH + 3 * (config.reset_after or 0)


@kernel
def collision_sigma(px: float, py: float, obstacles: np.ndarray, seen: np.ndarray,
                    p: np.ndarray) -> float:
    """Eq. 19 of Zhao et al. (2012): the velocity noise ``sigma_v`` [m/s per paper cycle] of a
    ball at ``(px, py)`` [m], ``max(k (R + r) / max(d, 1 um) sigma_R, sigma_R)`` with ``d``
    the distance to the nearest robot of ``obstacles`` ``(j, 2+)`` [m] of which ``seen``
    ``(j+,)`` are real; ``sigma_R`` without one or with ``collision_noise`` off."""
    sigma_r = p[_SIGMA_R]
    if p[_COLLISION] == 0.0:
        return sigma_r
    d = math.inf
    near = False
    for j in range(obstacles.shape[0]):
        if seen[j]:
            dj = hypot_exact(obstacles[j, 0] - px, obstacles[j, 1] - py)
            if not near or dj < d:
                d, near = dj, True
    if not near:
        return sigma_r
    v = p[_GAIN] / (1e-6 if 1e-6 > d else d) * sigma_r
    return sigma_r if sigma_r > v else v


@kernel
def _blocks(row: np.ndarray) -> Blocks:
    """The covariance blocks of a track row."""
    return ((row[5], row[6], row[7], row[8]), (row[9], row[10], row[11], row[12]),
            (row[13], row[14], row[15], row[16]))


@kernel
def _write(row: np.ndarray, t: float, x: State, P: Blocks, fused_at: float, since: float
           ) -> None:
    """Write the time, state, covariance, fusion time and count of a track row."""
    row[_T] = t
    for i in range(4):
        row[_X + i] = x[i]
    for b in range(3):
        for i in range(4):
            row[_P + 4 * b + i] = P[b][i]
    row[_FA], row[_SS] = fused_at, since


@kernel
def _step(row: np.ndarray, dt: float, p: np.ndarray):
    """The friction model's ``(x', A, B)`` over ``dt`` [s] from the track ``row``: the
    sliding deceleration while a two-phase ball is faster than its switch speed."""
    vx, vy = row[3], row[4]
    a = p[_DECEL]
    if p[_TWO_PHASE] != 0.0 and hypot_exact(vx, vy) > row[_VS]:
        a = p[_A_SLIDE]
    return friction_step(row[1], row[2], vx, vy, dt, a, p[_RK] != 0.0)


@kernel
def _start(row: np.ndarray, t: float, zx: float, zy: float, p: np.ndarray) -> None:
    """Start the track at the detection ``(zx, zy)`` [m] captured at ``t`` [s]: at rest,
    every component of variance ``tau^2``."""
    v = p[_VAR0]
    _write(row, t, (zx, zy, 0.0, 0.0), ((v, 0.0, 0.0, v), (0.0, 0.0, 0.0, 0.0),
                                        (v, 0.0, 0.0, v)), t, 1.0)
    row[_VS], row[_NC] = 0.0, 0.0


@kernel
def _maneuver(row: np.ndarray, counts: np.ndarray, t: float, x: State, P0: Blocks,
              moved: bool, A, B, q: float, zx: float, zy: float, p: np.ndarray) -> None:
    """The ball changed its motion where it is: redo the prediction from the track's previous
    covariance ``P0`` (by ``A``, ``B``, ``q`` when ``moved``; not when the frame is another
    view of the same instant) with a velocity change of ``maneuver_speed`` at the previous
    frame, so that the uncertainty reaches the position through the motion, then fuse the
    detection ``(zx, zy)`` into the predicted state ``x``."""
    r, m = p[_R], p[_M_VAR]
    counts[MANEUVERS] += 1
    n = P0[2]
    P = (P0[0], P0[1], (n[0] + m, n[1], n[2], n[3] + m))
    if moved:
        P = predict_covariance(P, A, B, q)
    y, Si, _ = innovation(x, P, (zx, zy), r)
    xn, Pn = update(x, P, y, Si, r)
    speed = hypot_exact(xn[2], xn[3])
    if p[_TWO_PHASE] != 0.0 and speed > p[_KICK_SPEED]:
        row[_VS] = p[_K_SWITCH] * speed
    _write(row, t, xn, Pn, t, row[_SS] + 1.0)
    row[_NC] = 0.0


@kernel
def _restart(row: np.ndarray, counts: np.ndarray, t: float, n: int, p: np.ndarray) -> None:
    """Restart the track from the first and the latest of its ``n`` candidates: at the latest
    with their finite-difference velocity combined with the initiator's prior (a velocity
    variance of ``2 sigma^2 / span^2`` per axis, unbounded for views a moment apart)."""
    c1 = _CAND + 3 * (n - 1)
    t0, z0x, z0y = row[_CAND], row[_CAND + 1], row[_CAND + 2]
    t1, z1x, z1y = row[c1], row[c1 + 1], row[c1 + 2]
    span = t1 - t0
    s0_2 = p[_PRIOR_VAR]
    if span > 1e-9:
        var_fd = 2.0 * p[_SXY2] / span ** p[_TWO]  # the C library's pow, as Python's
        g = s0_2 / (s0_2 + var_fd)
        vx, vy = g * (z1x - z0x) / span, g * (z1y - z0y) / span
        var_v = g * var_fd + p[_SR2]
    else:
        vx = vy = 0.0
        var_v = s0_2 + p[_SR2]
    var_p = p[_SXY2]
    speed = hypot_exact(vx, vy)
    row[_VS] = (p[_K_SWITCH] * speed if p[_TWO_PHASE] != 0.0 and speed > p[_KICK_SPEED]
                else 0.0)
    counts[RESETS] += 1
    _write(row, t, (z1x, z1y, vx, vy), ((var_p, 0.0, 0.0, var_p), (0.0, 0.0, 0.0, 0.0),
                                        (var_v, 0.0, 0.0, var_v)), t, 1.0)
    row[_NC] = 0.0


@kernel
def _outlier(row: np.ndarray, counts: np.ndarray, t: float, zx: float, zy: float,
             p: np.ndarray) -> None:
    """Offer a gated-out detection ``(zx, zy)`` at ``t`` to the candidates (the row holds the
    predicted track already): it agrees with the latest if a ball at most ``max_speed`` fast
    connects them, else the older ones are dropped; a view of the same instant adds nothing;
    restart once ``reset_after`` agree (:class:`~estimators.tracking.TrackInitiator`)."""
    counts[REJECTED] += 1
    if p[_INITIATOR] == 0.0:
        return
    n = int(row[_NC])
    append = True
    if n > 0:
        c = _CAND + 3 * (n - 1)
        t0 = row[c]
        dt = t - t0
        if not (hypot_exact(zx - row[c + 1], zy - row[c + 2])
                <= p[_MAX_SPEED] * (0.0 if 0.0 > dt else dt) + 5.0 * p[_SIGMA_XY]):
            n = 0
        elif t <= t0:
            append = False
    if append:
        c = _CAND + 3 * n
        row[c], row[c + 1], row[c + 2] = t, zx, zy
        n += 1
    row[_NC] = n
    if n >= int(p[_COUNT]):
        _restart(row, counts, t, n, p)


@kernel
def ball_frame(before: np.ndarray, after: np.ndarray, counts: np.ndarray, t: float,
               z: np.ndarray, has: np.ndarray, obstacles: np.ndarray, seen: np.ndarray,
               p: np.ndarray) -> tuple[float, float, int]:
    """The track ``after`` (a row, may be ``before`` itself) of the track ``before`` after one
    frame captured at ``t`` [s], no earlier than the track's time, with ball detections ``z``
    ``(k, 2)`` [m] of which ``has`` ``(k+,)`` are real and the robots ``obstacles``
    ``(j, 2+)`` [m] of which ``seen`` ``(j+,)`` are real (module docstring; flags beyond the
    rows are not read); ``counts`` (int64, four) is updated. Returns the new track's
    ``(t, fused_at, since_start)``."""
    for i in range(before.shape[0]):
        after[i] = before[i]
    first = -1
    for j in range(z.shape[0]):
        if has[j]:
            first = j
            break
    if after[_SS] == 0.0:  # no track yet: the first detection starts one
        if first >= 0:
            _start(after, t, z[first, 0], z[first, 1], p)
        return after[_T], after[_FA], int(after[_SS])
    x = (after[1], after[2], after[3], after[4])
    P0 = _blocks(after)
    P = P0
    dt = t - after[_T]
    moved = dt > 0.0
    A = B = (0.0, 0.0, 0.0, 0.0)
    q = 0.0
    if moved:
        sigma_v = collision_sigma(x[0], x[1], obstacles, seen, p)
        x, A, B = _step(after, dt, p)
        q = sigma_v * sigma_v * dt / PAPER_CYCLE
        P = predict_covariance(P0, A, B, q)
    after[_T] = t
    if first < 0:  # no detection: the prediction is the track
        _write(after, t, x, P, after[_FA], after[_SS])
        return after[_T], after[_FA], int(after[_SS])
    # The detection nearest the prediction (Mahalanobis, the first of equals).
    r = p[_R]
    s0, s1, s3 = P[0][0] + r, P[0][1], P[0][3] + r
    det = s0 * s3 - s1 * s1
    i0, i1, i3 = s3 / det, -s1 / det, s0 / det
    best, d2 = first, math.inf
    for j in range(first, z.shape[0]):
        if has[j]:
            y0, y1 = z[j, 0] - x[0], z[j, 1] - x[1]
            d = y0 * (i0 * y0 + i1 * y1) + y1 * (i1 * y0 + i3 * y1)
            if d < d2:
                best, d2 = j, d
    zx, zy = z[best, 0], z[best, 1]
    y = (zx - x[0], zy - x[1])
    if d2 <= p[_LIMIT]:
        counts[FUSED] += 1
        xn, Pn = update(x, P, y, (i0, i1, i1, i3), r)
        _write(after, t, xn, Pn, t, after[_SS] + 1.0)
        after[_NC] = 0.0
    else:
        # A maneuver must be near the prediction and reachable: a velocity change of at most
        # the gate's kick speed over the time since the last frame, plus noise.
        jump = hypot_exact(y[0], y[1])
        if (p[_MANEUVER] != 0.0 and jump <= p[_M_RADIUS]
                and jump <= p[_GATE_KICK] * (0.0 if 0.0 > dt else dt) + 3.0 * p[_SIGMA_XY]):
            _maneuver(after, counts, t, x, P0, moved, A, B, q, zx, zy, p)
        else:
            _write(after, t, x, P, after[_FA], after[_SS])
            _outlier(after, counts, t, zx, zy, p)
    return after[_T], after[_FA], int(after[_SS])


@kernel
def ball_frames(tracks: np.ndarray, counts: np.ndarray, rows: np.ndarray, t: np.ndarray,
                z: np.ndarray, has: np.ndarray, obstacles: np.ndarray, seen: np.ndarray,
                p: np.ndarray) -> None:
    """:func:`ball_frame` of the tracks ``rows`` ``(d,)`` (distinct) of ``tracks`` ``(m, w)``
    and ``counts`` ``(m, 4)``, in place: frames at ``t`` ``(d,)``, detections ``z``
    ``(d, k, 2)`` with ``has`` ``(d, k)``, robots ``obstacles`` ``(d, j, 2+)`` with ``seen``
    ``(d, j)``."""
    for i in range(rows.shape[0]):
        k = rows[i]
        ball_frame(tracks[k], tracks[k], counts[k], t[i], z[i], has[i], obstacles[i], seen[i],
                   p)


@kernel
def ball_estimate(row: np.ndarray, t: float, out: np.ndarray, p: np.ndarray) -> None:
    """The state ``(x, y, vx, vy)`` of the started track ``row`` predicted to ``t`` [s] into
    ``out`` ``(4,)`` (the track's own state for ``t`` at or before its time)."""
    dt = t - row[_T]
    if dt <= 0.0:
        for i in range(4):
            out[i] = row[_X + i]
        return
    x = _step(row, dt, p)[0]
    for i in range(4):
        out[i] = x[i]


@kernel
def ball_estimates(tracks: np.ndarray, t: np.ndarray, out: np.ndarray, p: np.ndarray) -> None:
    """:func:`ball_estimate` of every track of ``tracks`` ``(m, w)`` to its time ``t``
    ``(m,)`` into ``out`` ``(m, 4)`` (zeros for tracks not started)."""
    for k in range(tracks.shape[0]):
        if tracks[k, _SS] > 0.0:
            ball_estimate(tracks[k], t[k], out[k], p)
        else:
            for i in range(4):
                out[k, i] = 0.0


@kernel
def ball_predicted(row: np.ndarray, t: float, x_out: np.ndarray, P_out: np.ndarray,
                   p: np.ndarray) -> None:
    """``(x, P)`` of the started track ``row`` predicted to ``t`` [s] into ``x_out`` ``(4,)``
    and the full covariance ``P_out`` ``(4, 4)``, with the velocity noise ``sigma_R`` (no
    robots)."""
    P = _blocks(row)
    dt = t - row[_T]
    if dt <= 0.0:
        for i in range(4):
            x_out[i] = row[_X + i]
    else:
        x, A, B = _step(row, dt, p)
        sr = p[_SIGMA_R]
        P = predict_covariance(P, A, B, sr * sr * dt / PAPER_CYCLE)
        for i in range(4):
            x_out[i] = x[i]
    P11, P12, P22 = P
    for i in range(2):
        for j in range(2):
            P_out[i, j] = P11[2 * i + j]
            P_out[i, 2 + j] = P12[2 * i + j]
            P_out[2 + i, j] = P12[2 * j + i]
            P_out[2 + i, 2 + j] = P22[2 * i + j]
