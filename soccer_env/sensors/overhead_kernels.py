"""Compiled kernels of the overhead vision: the capture of every frame due in a step, the rule
that :class:`~soccer_env.sensors.overhead.OverheadVision` (one field) and
:class:`~soccer_env.sensors.overhead_batch.OverheadVisionBatch` (many) both call.

Rows are frames: a (field, camera, capture time) triple with the field's truth at the start
and the end of its step (a *state*, shared by the frames of one field's step). The maths (SI
units, angles in radians; the model is in :mod:`soccer_env.sensors.overhead`):

* **Interpolation** to the capture time ``t`` of a step from ``t0`` to ``t0 + span``: weight
  ``w = (t - t0) / span`` (1 for ``span <= 0``); ``x = x0 + w (x1 - x0)`` for positions, and
  ``theta = theta0 + w turn`` on the short arc, ``turn = remainder(theta1 - theta0, 2 pi)``
  (``math.remainder``, :func:`~estimators.exact.wrap_angle`) when the step captures few
  poses (frames times robots at most :data:`FEW_POSES`), else ``mod(theta1 - theta0 + pi, 2
  pi) - pi`` (numpy's floored remainder, :func:`~estimators.exact.floor_remainder`): the two
  differ only for a turn of exactly pi, and the choice is the one the sensor has always made
  (its Python version wrapped small steps, its numpy version large ones).
* **Robots**: a robot inside the camera's view ``x_min <= x <= x_max``, ``y_min <= y <=
  y_max`` is detected if its uniform is below ``robot_detection``, at ``(x + s n0, y + s n1,
  remainder(theta + s_theta n2, 2 pi))`` (``n`` its standard normals, ``s``, ``s_theta`` the
  pose noise [m, rad]). A spurious ball appears at its dribbler if its second uniform is
  below ``p_dribbler``: at ``(x + d cos theta + sigma n0', y + d sin theta + sigma n1')``, ``d``
  its dribbler's distance plus the ball's radius (robots without a dribbler have none), all
  such balls of a frame with the frame's same two normals ``n0', n1'``.
* **The ball**, at ``(bx, by)`` with its centre ``zc = r + z`` above the carpet, is seen where
  the camera's ray through it meets the plane of a resting ball: ``s = c + (b - c) (h - r) /
  (h - zc)`` for a camera at ``(cx, cy, h)``; it is detected if ``s`` is in view, its uniform
  is below ``ball_detection`` and the robots hide less than ``occlusion_threshold`` of it
  (:func:`hidden_fraction`; a threshold above 1 disables occlusion), at ``s + sigma n``.
* **Spurious ball anywhere** in view with probability ``p_random``: ``(x_min + (x_max -
  x_min) u, y_min + (y_max - y_min) u')``, no noise.
* **Delivery** at ``t + latency + latency_jitter u``.

Why kernels: a single field's step captures a handful of frames of a dozen robots, where
Python's per-object loop (and numpy's per-call overhead) cost more than the arithmetic; a
batch's capture was some forty numpy calls with the rare events (occlusion, dribbler balls)
frame by frame in Python. One compiled pass serves both, so the rule is written once.

Bit for bit: the kernels evaluate the expressions of the Python and numpy versions in the
same order (elementwise float64 arithmetic, no fastmath; ``math.cos``, ``math.sin`` are the C
library's, as Python's). One difference is proven harmless: the Python occlusion test squared
with ``** 2`` (the C library's ``pow``, which differs from ``x * x`` in the last bit for about
one argument in a thousand), the kernel multiplies; those squares enter only the two
rejection bounds (a robot too far to matter, a capsule out of reach), whose margins (0.01 m,
and the ring points lying 0.1 ball radii inside the disc) make the outcome the same either
way.

The random numbers stay with the callers' generators, drawn in blocks as before
(:class:`~soccer_env.sensors.draws.BlockDraws` for one field,
:class:`~soccer_env.sensors.draws.BatchDraws` for many), and come in as arrays: a frame
takes a fixed count of them (``3 (N + 2)`` normals, ``2 N + 5`` uniforms) whether it uses them
or not, so nothing is drawn conditionally.
"""

from __future__ import annotations

import math

import numpy as np

from estimators.compiled import kernel
from estimators.exact import floor_remainder, wrap_angle

__all__ = ["FEW_POSES", "PARAMS", "RING", "capture_frames",
           "frame_columns", "hidden_fraction", "interpolate_poses"]

#: Points on the ball's disc (centre and two rings), in radii, for the hidden fraction:
#: ``(19, 2)``.
RING = np.array([(0.0, 0.0)]
                + [(0.5 * math.cos(2 * math.pi * i / 6), 0.5 * math.sin(2 * math.pi * i / 6))
                   for i in range(6)]
                + [(0.9 * math.cos(2 * math.pi * i / 12), 0.9 * math.sin(2 * math.pi * i / 12))
                   for i in range(12)])
RING.setflags(write=False)

#: A step that captures at most this many poses (frames times robots) wraps headings with
#: ``math.remainder``, a larger one with numpy's floored remainder (the two versions' picks).
FEW_POSES = 16

#: The entries of :func:`capture_frames`' ``params``, in order.
PARAMS = ("ball_radius", "robot_detection", "ball_detection", "p_dribbler", "p_random",
          "robot_sigma", "robot_sigma_theta", "ball_sigma", "occlusion_threshold", "latency",
          "latency_jitter")

_TWO_PI = 2.0 * math.pi


@kernel
def interpolate_poses(w: float, prev: np.ndarray, cur: np.ndarray, short: bool,
                      X: np.ndarray, Y: np.ndarray, TH: np.ndarray) -> None:
    """The poses ``(N, >=3)`` ``prev`` and ``cur`` (``x, y, theta`` [m, rad]) interpolated to
    weight ``w`` into ``X, Y, TH`` ``(N,)``: ``x0 + w (x1 - x0)``, the heading on the short arc
    (``math.remainder`` if ``short``, else numpy's ``remainder(d + pi, 2 pi) - pi``; module
    docstring)."""
    for i in range(prev.shape[0]):
        d = cur[i, 2] - prev[i, 2]
        turn = wrap_angle(d) if short else floor_remainder(d + math.pi, _TWO_PI) - math.pi
        X[i] = prev[i, 0] + w * (cur[i, 0] - prev[i, 0])
        Y[i] = prev[i, 1] + w * (cur[i, 1] - prev[i, 1])
        TH[i] = prev[i, 2] + w * turn


@kernel
def hidden_fraction(bx: float, by: float, zc: float, X: np.ndarray, Y: np.ndarray,
                    camera: np.ndarray, r: float, heights: np.ndarray, radii: np.ndarray
                    ) -> float:
    """Fraction of the ball's disc (radius ``r`` [m], centre ``bx, by`` as seen, centre
    height ``zc`` [m]) that the camera ``(cx, cy, h, ...)`` cannot see past the robots at ``X,
    Y`` [m] of heights ``heights`` and footprint radii ``radii`` [m]: the share of the
    :data:`RING` points covered.

    A robot of radius ``R`` and height ``H`` hides, in the horizontal plane through the
    ball's centre, the region swept by its cross-section from its own position ``p`` to the
    projection of its top, ``t = c + (p - c) k`` with ``k = (h - zc) / (h - H)``, whose radius
    grows to ``R k``: a capsule of the larger radius (3 % at most larger than the true shape
    of an SSL robot under a 4 m camera). A ball above a robot (``zc >= H``) cannot be hidden by
    it. Robots farther than ``R k + r + 10 (k - 1) + 0.01`` from the ball (their capsule
    reaches ``R k + (k - 1) |p - c|``, with ``|p - c|`` under 10 m on any field) and those
    whose capsule stays ``R k + r`` away from its centre are skipped; ring point ``q`` is
    covered if its distance to the capsule's axis, at ``s = clip((q - p).(t - p) / |t -
    p|^2, 0, 1)`` (0 for ``|t - p|^2 <= 1e-12``), is at most ``R k``."""
    cx, cy, h = camera[0], camera[1], camera[2]
    covered = np.zeros(RING.shape[0], dtype=np.bool_)
    count = 0
    for i in range(X.shape[0]):
        H, R = heights[i], radii[i]
        if zc >= H:
            continue
        k = (h - zc) / (h - H)
        radius = R * k
        reach = radius + r
        near = radius + r + 10.0 * (k - 1.0) + 0.01
        x, y = X[i], Y[i]
        if (x - bx) * (x - bx) + (y - by) * (y - by) > near * near:
            continue
        tx, ty = cx + (x - cx) * k, cy + (y - cy) * k
        sx, sy = tx - x, ty - y
        seg2 = sx * sx + sy * sy
        s = ((bx - x) * sx + (by - y) * sy) / seg2 if seg2 > 1e-12 else 0.0
        s = 0.0 if s < 0.0 else (1.0 if s > 1.0 else s)
        dx, dy = bx - x - s * sx, by - y - s * sy
        if dx * dx + dy * dy > reach * reach:
            continue
        for j in range(RING.shape[0]):
            if covered[j]:
                continue
            px, py = bx + r * RING[j, 0] - x, by + r * RING[j, 1] - y
            s = (px * sx + py * sy) / seg2 if seg2 > 1e-12 else 0.0
            s = 0.0 if s < 0.0 else (1.0 if s > 1.0 else s)
            qx, qy = px - s * sx, py - s * sy
            if qx * qx + qy * qy <= radius * radius:
                covered[j] = True
                count += 1
    return count / RING.shape[0]


@kernel
def frame_columns(n: int) -> tuple[int, int, int, int, int]:
    """Where :func:`capture_frames` writes a frame of ``n`` robots in its row: the first
    columns of the ball flags, the balls, the robot flags, the poses, and the row's width
    (column 0 holds the delivery time)."""
    balls = 1 + (n + 2)
    robot_flags = balls + 2 * (n + 2)
    poses = robot_flags + n
    return 1, balls, robot_flags, poses, poses + 3 * n


@kernel
def _robots(row: np.ndarray, normals: np.ndarray, uniforms: np.ndarray, X: np.ndarray,
            Y: np.ndarray, TH: np.ndarray, camera: np.ndarray, fronts: np.ndarray,
            params: np.ndarray) -> None:
    """A frame's robot detections and dribbler balls (module docstring) from the robots at
    ``X, Y, TH`` [m, rad] in the view of ``camera``, written into its ``row`` of
    :func:`capture_frames` (``normals``, ``uniforms``: the frame's numbers; ``fronts``: each
    robot's dribbler distance plus the ball's radius [m], NaN for none)."""
    n = X.shape[0]
    _, balls, robot_flags, poses, _ = frame_columns(n)
    x0, x1, y0, y1 = camera[3], camera[4], camera[5], camera[6]
    p_robot, p_dribbler = params[1], params[3]
    s, st, sigma = params[5], params[6], params[7]
    for i in range(n):
        x, y, th = X[i], Y[i], TH[i]
        if not (x0 <= x <= x1 and y0 <= y <= y1):
            continue
        if uniforms[i] < p_robot:
            row[robot_flags + i] = 1.0
            row[poses + 3 * i] = x + s * normals[3 * i]
            row[poses + 3 * i + 1] = y + s * normals[3 * i + 1]
            row[poses + 3 * i + 2] = wrap_angle(th + st * normals[3 * i + 2])
        d = fronts[i]
        if uniforms[n + i] < p_dribbler and not math.isnan(d):
            row[2 + i] = 1.0
            row[balls + 2 + 2 * i] = x + d * math.cos(th) + sigma * normals[3 * n]
            row[balls + 3 + 2 * i] = y + d * math.sin(th) + sigma * normals[3 * n + 1]


@kernel
def _ball(row: np.ndarray, normals: np.ndarray, uniforms: np.ndarray, w: float,
          b0: np.ndarray, b1: np.ndarray, X: np.ndarray, Y: np.ndarray, camera: np.ndarray,
          bodies: np.ndarray, params: np.ndarray) -> None:
    """A frame's true ball (interpolated to weight ``w`` between ``b0`` and ``b1``, ``x, y,
    z`` [m]) and its spurious ball anywhere in view (module docstring), written into its
    ``row`` of :func:`capture_frames`; ``X, Y`` [m] are the robots that may hide it."""
    n = X.shape[0]
    _, balls, _, _, _ = frame_columns(n)
    r, p_ball, p_random, sigma, threshold = params[0], params[2], params[4], params[7], params[8]
    cx, cy, h, x0, x1, y0, y1 = (camera[0], camera[1], camera[2], camera[3], camera[4],
                                 camera[5], camera[6])
    # Where this camera's ray through the ball meets the resting-ball plane.
    bx = b0[0] + w * (b1[0] - b0[0])
    by = b0[1] + w * (b1[1] - b0[1])
    zc = r + b0[2] + w * (b1[2] - b0[2])
    k = (h - r) / (h - zc)
    sx, sy = cx + (bx - cx) * k, cy + (by - cy) * k
    if (x0 <= sx <= x1 and y0 <= sy <= y1 and uniforms[2 * n] < p_ball
            and (threshold > 1.0
                 or hidden_fraction(sx, sy, zc, X, Y, camera, r, bodies[:, 1], bodies[:, 2])
                 < threshold)):
        row[1] = 1.0
        row[balls] = sx + sigma * normals[3 * n + 3]
        row[balls + 1] = sy + sigma * normals[3 * n + 4]
    if uniforms[2 * n + 1] < p_random:  # a spurious ball anywhere in view
        row[2 + n] = 1.0
        row[balls + 2 * (n + 1)] = x0 + (x1 - x0) * uniforms[2 * n + 2]
        row[balls + 2 * (n + 1) + 1] = y0 + (y1 - y0) * uniforms[2 * n + 3]


@kernel
def capture_frames(rows: np.ndarray, cams: np.ndarray, times: np.ndarray, clock: np.ndarray,
                   ball0: np.ndarray, ball1: np.ndarray, robots0: np.ndarray,
                   robots1: np.ndarray, normals: np.ndarray, uniforms: np.ndarray,
                   cameras: np.ndarray, bodies: np.ndarray, params: np.ndarray, out: np.ndarray
                   ) -> None:
    """The ``F`` frames of cameras ``cams`` captured at ``times`` [s], frame ``f`` of state
    ``rows[f]`` (module docstring). Frames of a state are its step's captures: their number
    chooses the heading wrap (:data:`FEW_POSES`).

    Args:
        rows: ``(F,)`` each frame's state. cams: ``(F,)`` camera indices; times: ``(F,)``.
        clock: ``(S, 2)`` each state's step start ``t0`` and length ``span`` [s].
        ball0, ball1: ``(S, >=3)`` the ball ``x, y, z`` [m] (z of its lowest point) at the
            step's start and end; robots0, robots1: ``(S, N, >=3)`` the poses.
        normals: ``(F 3 (N + 2),)`` standard normals, frame by frame: three per robot, then
            two for the dribbler balls, one unused, two for the ball. uniforms: ``(F (2 N +
            5),)``, frame by frame: robot detection (N), dribbler ball (N), ball detection,
            spurious ball, its x and y, latency jitter.
        cameras: ``(C, 7)`` rows ``(x, y, height, x_min, x_max, y_min, y_max)`` [m].
        bodies: ``(N, 3)`` each robot's dribbler distance plus the ball's radius (NaN: no
            dribbler), height and footprint radius [m].
        params: the numbers named by :data:`PARAMS` (probabilities, metres, radians,
            seconds).
        out: ``(>= F, 7 N + 7)``, written: row ``f`` is frame ``f``, its columns
            (:func:`frame_columns`) the delivery time [s], the ball flags (1.0: a detection;
            ``N + 2`` slots as :class:`~soccer_env.sensors.overhead_batch.FrameBatch`'s: the
            ball, the dribbler balls of robots ``0 .. N-1``, the spurious ball), the balls
            ``x, y`` [m] by slot, the robot flags (``N``) and the poses ``x, y, theta`` [m,
            rad] by robot; empty slots hold zeros. (Filled rather than returned: an array
            returned to Python costs about a microsecond, a sizable share of a single
            field's capture.)
    """
    F, n = rows.shape[0], robots0.shape[1]
    latency, jitter = params[9], params[10]
    for f in range(F):  # loops, not slices: a slice assignment costs seconds to compile
        for k in range(out.shape[1]):
            out[f, k] = 0.0
    counts = np.zeros(clock.shape[0], dtype=np.int64)
    for f in range(F):
        counts[rows[f]] += 1
    X, Y, TH = np.empty(n), np.empty(n), np.empty(n)
    nn, nu = 3 * (n + 2), 2 * n + 5
    for f in range(F):
        g, cam, t = rows[f], cameras[cams[f]], times[f]
        t0, span = clock[g, 0], clock[g, 1]
        w = (t - t0) / span if span > 0 else 1.0
        interpolate_poses(w, robots0[g], robots1[g], counts[g] * n <= FEW_POSES, X, Y, TH)
        nf, uf = normals[f * nn:(f + 1) * nn], uniforms[f * nu:(f + 1) * nu]
        _robots(out[f], nf, uf, X, Y, TH, cam, bodies[:, 0], params)
        _ball(out[f], nf, uf, w, ball0[g], ball1[g], X, Y, cam, bodies, params)
        out[f, 0] = t + (latency + jitter * uf[2 * n + 4])
