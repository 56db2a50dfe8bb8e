"""The Kalman-started mean shift of paper 004 (Yu, Wei, Zhang 2010) with ego-motion
compensation, on a turning humanoid's head-camera images.

``soccer-env paper following``: one ``humanoid-2012`` robot (the robot of paper 000 (Xu, Xie,
Wang, Ni 2012): 0.6 rad/s top turn rate, 3 rad/s^2, 0.2 m/s forward;
:mod:`soccer_env.sim.walk`'s walk engine with its gait sway and odometry errors in
:class:`~soccer_env.sim.world.World`) on the ``humanoid-2012`` field (6 m x 4 m, orange ball of
33 mm radius) watches the ball through its ``kidsize-2012`` head camera (0.56 m, 51 degrees,
25 Hz). ``robot="humanoid"`` runs the current KidSize robot instead
(1 rad/s, ``humanoid-kid`` field, size-1 ball of 76 mm radius, ``kidsize`` camera at 30 Hz).
Frames are rendered at the camera's frame rate with
:class:`~soccer_env.sensors.images.head.HeadFrameRenderer` at ``size`` (320 x 240 by default,
for speed; the renderer keeps the camera's horizontal field of view, so the image jump of the
ball in ball radii does not depend on the size) with the ``"realistic"`` appearance (gain,
brightness ramp and pixel noise), from the TRUE head orientation, gait sway included. The world
steps four control steps per frame (100 Hz at 25 Hz), so frames are exactly one period apart.

Scene, per seeded episode: the head is fixed at pan 0 and at the tilt that puts the middle of
the depression angles of balls at 1 m and 3 m on the optical axis (about 19 degrees), set during
0.5 s of standing before the first frame. The robot sweeps its heading back and forth around the
line to the ball: each sweep turns at a rate drawn from [0.15, 1] times the top turn rate until
the heading is ``A`` (drawn from [0.15, 0.3] rad) past the ball's bearing, less the braking
overshoot, then reverses (so the turn rate changes all the time and the ball stays in view). Two
variants, each with ``episodes`` episodes of ``duration`` seconds:

* ``turn``: turning in place, the ball 1-3 m away;
* ``follow`` (paper 004's person following): the robot also walks forward towards the ball
  (``vx = 0.4 (d - 1 m)``, clipped to its top speed; the gait's speed ellipsoid then slows the
  turning), starting 2.2-2.8 m away.

Even episodes leave the ball lying still; odd episodes roll it slowly: whenever it has stopped
(plus a wait of 0.3-1.5 s) it is given a speed of at most 0.5 m/s towards a point 1.2-2.8 m
(``follow``: 1.5-2.5 m) from the robot within 0.35 rad of its bearing. The scene's script reads
the truth; the trackers see only the images and the robot's odometry.

Trackers, on the same frames (the hue back-projection, :func:`~estimators.colour.back_project`,
of a 16-bin hue histogram of the first frame's ball: the pixels within 0.8 of its apparent
radius of its true centre, as an operator marking the target would give), all started at the
ball's true pixel of the first frame. The target window is the ball's apparent diameter there
(``2 round(r) + 1`` px); each tracker runs at each of ``window_scales`` times it: 1 (the target
size: the bandwidth of paper 004's argument) and 2 (the paper's back-projection region ``R``,
twice the target). A tracker reports lost when the mean weight in its converged window is below
``0.2 / scale^2`` (the estimators' default 0.2 for a target-sized window, scaled so that the
same amount of target must be in any window: a round ball fills only ``pi / 16`` of a window
twice its size, below 0.2). Otherwise the estimators' defaults (flat kernel, 10 iterations;
Kalman noise 2 px/frame^2 and 2 px):

* ``kalman``: :class:`estimators.meanshift.KalmanMeanShift` (paper 004) fed with the robot's
  own motion between frames: the rotation is the walk engine's odometry ``dtheta`` summed
  over the frame's control steps, the advance the odometry's displacement projected on the
  bearing of the tracked position (the paper's ``s`` towards the target). Odometry, not the
  truth: that is what the robot knows (it has the walk engine's 15 % rotation error per step
  and does not see the sway). The camera height above the ball's centre and the ball's
  diameter (``target_height_m``: depth from the apparent size each frame, the first frame's
  size-based depth to start) are given. When lost it only predicts (its velocity kept).
* ``plain``: :class:`estimators.meanshift.PlainMeanShift`, mean shift from the last position;
  when lost it stays where it was.

Neither searches the whole image after a loss (paper 004 has no such step).

Measured per tracker on the frames after the first in which the ball's centre is in the image
(frames with the ball out of view are counted apart): the share of frames in which it reports
lost; the share "off target", its position farther from the true pixel than the ball's apparent
radius (the lost-track rate the aim is judged on); the loss hazard, the share of frames off
target among those whose previous frame was on target (how often a held track is lost, apart
from how long it then stays lost); the pixel error (median over all these frames, RMSE over
those on target); losses and recoveries (on -> off and off -> on target); time per update (the
tracker only; the back-projection, shared, is timed apart); and the depth from the ball's known
size: the ball's apparent height in a region twice the target window around the tracker's
position (:func:`~estimators.meanshift.apparent_height`), ``D = f 2 r / height``
(:func:`~estimators.meanshift.depth_from_size`), turned into a ground distance with the pixel's
ray (``sqrt(R^2 - (h - r)^2)``, ``R`` the range along the ray) and compared with the true ground
distance (median relative and median signed error, frames on target and not reported lost). The
same rates by turn-rate bin (the true body turn rate over the frame period: slow below a third
of the top rate, medium, fast above two thirds: 0.2 and 0.4 rad/s for the 2012 robot), with the
ball's mean image jump between frames in its apparent radii, with and without the gait's sway
(the pixel the ball would have had with the servo angles alone), and by that jump (a window of
scale ``x`` has a half-width of about ``x`` radii), the quantity paper 004's argument is about.

The paper's claim and the issue's aim ("the Kalman-started tracker losing the ball at most half
as often as plain mean shift under fast turns") are printed beside ours, the aim judged per
window scale on the off-target share in the fast bin, both variants pooled (met if the Kalman
tracker's share is at most half the plain one's), with the readings by the lost reports and by
the loss hazard beside it.
"""

from __future__ import annotations

import math
import os
import time
from pathlib import Path
from typing import Any

import numpy as np

from estimators import (
    KalmanMeanShift,
    PlainMeanShift,
    apparent_height,
    depth_from_size,
)
from soccer_env.render.plots import pyplot, save_figure
from soccer_lab.papers._io import map_jobs, write_report

__all__ = ["run", "PAPER", "AIM", "ROBOTS", "VARIANTS", "TRACKERS", "TURN_BINS",
           "JUMP_BINS"]

#: Robot preset -> (field preset, head-camera preset).
ROBOTS = {"humanoid-2012": ("humanoid-2012", "kidsize-2012"),
          "humanoid": ("humanoid-kid", "kidsize")}
VARIANTS = ("turn", "follow")
TRACKERS = ("kalman", "plain")
#: Turn-rate bins as fractions of the robot's top turn rate.
TURN_BINS = (("slow", 0.0, 1.0 / 3.0), ("medium", 1.0 / 3.0, 2.0 / 3.0),
             ("fast", 2.0 / 3.0, math.inf))
#: Bins of the ball's image jump between frames, in its apparent radii (a window of scale x
#: has a half-width, the mean-shift bandwidth, of about x radii).
JUMP_BINS = (("< 1", 0.0, 1.0), ("1-2", 1.0, 2.0), ("2-4", 2.0, 4.0),
             (">= 4", 4.0, math.inf))
PAPER = {
    "claim": "mean shift assumes the target moves less than the kernel bandwidth between "
             "frames, which fails when the robot itself moves (the target jumps in the image "
             "plane); a Kalman filter on the image-plane state with the robot's rotation and "
             "advance as control input predicts where to start mean shift, and keeps the track",
    "results": "outdoor person following: robust, good tracking and real time (no figures "
               "in the part of the paper we have)",
}
AIM = ("the Kalman-started tracker losing the ball at most half as often as plain mean shift "
       "under fast turns")
STEPS_PER_FRAME = 4
#: Lost below this mean weight in a window of the target's size (the estimators' default);
#: a window ``x`` times larger is lost below ``MIN_FILL / x^2``.
MIN_FILL = 0.2
SETTLE_S = 0.5
ROLL_MAX_SPEED = 0.5


# ------------------------------------------------------------------------------------------
# One episode
# ------------------------------------------------------------------------------------------

def _wrap(a: float) -> float:
    return math.remainder(a, 2.0 * math.pi)


def _view(robot: np.ndarray, ball: np.ndarray, pan: float, tilt: float, height: float,
          radius: float, focal: float, centre: tuple[float, float]
          ) -> tuple[float, float, float]:
    """The ball centre's continuous pixel ``(u, v)`` and its depth along the optical axis
    [m] for the camera at ``height`` over ``robot`` looking at ``pan``, ``tilt`` (the
    renderer's geometry); depth <= 0 when behind."""
    x, y, th = robot[0:3].tolist()
    psi = th + pan
    c, s, cb, sb = math.cos(psi), math.sin(psi), math.cos(tilt), math.sin(tilt)
    dx, dy, dz = ball[0] - x, ball[1] - y, ball[2] + radius - height
    q = c * dx + s * dy
    xc = s * dx - c * dy
    yc = cb * q - sb * dz
    zc = sb * q + cb * dz
    if yc <= 1e-6:
        return math.nan, math.nan, yc
    return centre[0] + focal * xc / yc, centre[1] - focal * zc / yc, yc


def _size_distance(bp: np.ndarray, pos: np.ndarray, window: tuple[int, int], diameter: float,
                   focal: float, centre: tuple[float, float], drop: float) -> float:
    """Ground distance [m] from the ball's apparent height around ``pos`` (mean-shift
    coordinates), NaN when nothing is seen: the depth ``f 2 r / height``, then the range
    along the pixel's ray and the ground distance below a camera ``drop`` above the ball's
    centre."""
    w, h = window
    region = (int(round(pos[0] - w)), int(round(pos[1] - h)), 2 * w, 2 * h)
    size = apparent_height(bp, region)
    if size <= 0.0:
        return math.nan
    depth = depth_from_size(diameter, size, focal)
    du, dv = (pos[0] + 0.5 - centre[0]) / focal, (pos[1] + 0.5 - centre[1]) / focal
    rng = depth * math.sqrt(1.0 + du * du + dv * dv)
    return math.sqrt(max(rng * rng - drop * drop, 0.0))


def _labels(scales: tuple[float, ...]) -> list[str]:
    """Tracker labels: ``"kalman x1"``, ``"plain x1"``, ... per window scale."""
    return [f"{tr} x{sc:g}" for sc in scales for tr in TRACKERS]


def _episode(args: tuple) -> dict[str, Any]:
    """One seeded episode of ``variant``; per-frame truth and every tracker's output."""
    from estimators.colour import back_project, hue_histogram
    from soccer_env import presets
    from soccer_env.presets.sensors import head_camera
    from soccer_env.sensors.images.head import HeadFrameRenderer
    from soccer_env.sim.heads import head_state
    from soccer_env.sim.world import World

    robot_name, variant, index, seed, duration, size, appearance, scales = args
    field_name, camera_name = ROBOTS[robot_name]
    field = presets.field(field_name)
    ball_spec = presets.ball(field.ball)
    spec = presets.robot(robot_name)
    cam_spec = head_camera(camera_name)
    frame_dt = 1.0 / float(cam_spec.frame_rate)
    world = World(field, ball_spec, spec, 1, 0, frame_dt / STEPS_PER_FRAME)
    renderer = HeadFrameRenderer(cam_spec, field, spec, ball_spec, [0], appearance, size)
    cam = renderer.camera
    focal, centre = cam.focal_px, cam.centre
    W, H = renderer.width, renderer.height
    r_ball = ball_spec.radius
    drop = cam.height - r_ball
    vi_ = VARIANTS.index(variant)
    rng = np.random.default_rng([seed, vi_, index])
    world_rng = np.random.default_rng([seed, vi_, index, 1])
    image_rng = np.random.default_rng([seed, vi_, index, 2])
    rolling = index % 2 == 1

    # Head tilt: the middle of the depression angles of balls at 1 m and 3 m.
    tilt = 0.5 * (math.atan2(drop, 1.0) + math.atan2(drop, 3.0))
    tilt = min(spec.head_tilt_max, max(spec.head_tilt_min, tilt))
    # Placement (inside the walls, facing +x).
    if variant == "follow":
        rx, ry = -2.4 + rng.uniform(-0.2, 0.2), rng.uniform(-0.6, 0.6)
        d0 = rng.uniform(2.2, 2.8)
    else:
        rx, ry = -1.8 + rng.uniform(-0.3, 0.3), rng.uniform(-0.6, 0.6)
        d0 = rng.uniform(1.0, 3.0)
    b0 = rng.uniform(-0.4, 0.4)
    bx, by = rx + d0 * math.cos(b0), ry + d0 * math.sin(b0)
    heading = b0 + rng.uniform(-0.2, 0.2)
    world.reset(np.array([[rx, ry, heading]]), (bx, by), world_rng)

    wmax, alpha = spec.max_turn_speed, spec.max_angular_acceleration
    vmax = spec.max_forward_speed
    sweep = {"dir": 1.0 if rng.random() < 0.5 else -1.0, "rate": 0.0, "amp": 0.0}

    def new_sweep() -> None:
        sweep["rate"] = wmax * rng.uniform(0.15, 1.0)
        sweep["amp"] = rng.uniform(0.15, 0.3)

    new_sweep()
    roll = {"wait_until": 0.0, "moving": False}
    lim_x = min(field.half_length + field.boundary - 0.4, field.half_length + 0.3)
    lim_y = field.half_width + field.boundary - 0.4

    def command(moving: bool) -> np.ndarray:
        rb = world.robot_array()[0]
        ball = world.ball_array()
        dx, dy = ball[0] - rb[0], ball[1] - rb[1]
        e = _wrap(rb[2] - math.atan2(dy, dx))
        rate = sweep["rate"]
        brake = rate * rate / (2.0 * alpha)
        if sweep["dir"] * e > sweep["amp"] - brake:
            sweep["dir"] = -sweep["dir"]
            new_sweep()
        omega = sweep["dir"] * sweep["rate"] if moving else 0.0
        vx = 0.0
        if moving and variant == "follow":
            vx = min(vmax, max(0.0, 0.4 * (math.hypot(dx, dy) - 1.0)))
        return np.array([[vx, 0.0, omega, 0.0, 0.0, tilt]])

    def nudge_ball() -> None:
        if not rolling:
            return
        ball = world.ball_array()
        t = world.time
        if roll["moving"]:
            if math.hypot(ball[3], ball[4]) > 0.02:
                return
            roll["moving"] = False
            roll["wait_until"] = t + rng.uniform(0.3, 1.5)
        if t < roll["wait_until"]:
            return
        rb = world.robot_array()[0]
        bearing = math.atan2(ball[1] - rb[1], ball[0] - rb[0]) + rng.uniform(-0.35, 0.35)
        lo, hi = (1.5, 2.5) if variant == "follow" else (1.2, 2.8)
        d = rng.uniform(lo, hi)
        tx = min(lim_x, max(-lim_x, rb[0] + d * math.cos(bearing)))
        ty = min(lim_y, max(-lim_y, rb[1] + d * math.sin(bearing)))
        gx, gy = tx - ball[0], ty - ball[1]
        dist = math.hypot(gx, gy)
        if dist < 0.05:
            return
        v0 = min(ROLL_MAX_SPEED, math.sqrt(2.0 * ball_spec.rolling_deceleration * dist))
        world.set_ball(ball[0], ball[1], v0 * gx / dist, v0 * gy / dist)
        roll["moving"] = True

    # Settle: stand, head to its tilt.
    for _ in range(int(round(SETTLE_S / world.control_dt))):
        world.step(command(False))
    roll["wait_until"] = world.time + rng.uniform(0.0, 1.0)

    n_frames = int(round(duration / frame_dt)) + 1
    rec = {k: np.full(n_frames, np.nan) for k in (
        "t", "u", "v", "u_still", "v_still", "radius", "distance", "turn_rate", "jump",
        "jump_still", "rotation_odo", "rotation_true", "advance_odo")}
    rec["in_view"] = np.zeros(n_frames, bool)
    labels = _labels(scales)
    out = {lab: {"x": np.full(n_frames, np.nan), "y": np.full(n_frames, np.nan),
                 "lost": np.zeros(n_frames, bool), "ms": np.full(n_frames, np.nan),
                 "size_distance": np.full(n_frames, np.nan)} for lab in labels}
    bp_ms = np.full(n_frames, np.nan)
    trackers: dict[str, Any] = {}
    window = (1, 1)
    diameter = 2.0 * r_ball
    prev_heading = float(world.robot_array()[0, 2])
    rot_odo = adv_odo = 0.0
    adv: dict[str, float] = {}
    hist = None
    for k in range(n_frames):
        state = world.snapshot()
        heads = head_state(world)
        robot = state.robots[0]
        pan, tl = float(heads.pan[0]), float(heads.tilt[0])
        u, v, depth = _view(robot, state.ball, pan + float(heads.sway_pan[0]),
                            tl + float(heads.sway_tilt[0]), cam.height, r_ball, focal, centre)
        us, vs, _ = _view(robot, state.ball, pan, tl, cam.height, r_ball, focal, centre)
        rec["t"][k] = k * frame_dt
        rec["u"][k], rec["v"][k] = u - 0.5, v - 0.5  # mean-shift pixel coordinates
        rec["u_still"][k], rec["v_still"][k] = us - 0.5, vs - 0.5  # without the sway
        rec["radius"][k] = focal * r_ball / depth if depth > 0 else math.nan
        rec["distance"][k] = math.hypot(state.ball[0] - robot[0], state.ball[1] - robot[1])
        rec["in_view"][k] = depth > 0 and 0.0 <= u <= W and 0.0 <= v <= H
        heading = float(robot[2])
        if k > 0:
            dth = _wrap(heading - prev_heading)
            rec["rotation_true"][k] = dth
            rec["turn_rate"][k] = abs(dth) / frame_dt
            rec["rotation_odo"][k] = rot_odo
            rec["advance_odo"][k] = adv_odo
            rec["jump"][k] = math.hypot(rec["u"][k] - rec["u"][k - 1],
                                        rec["v"][k] - rec["v"][k - 1])
            rec["jump_still"][k] = math.hypot(rec["u_still"][k] - rec["u_still"][k - 1],
                                              rec["v_still"][k] - rec["v_still"][k - 1])
        prev_heading = heading
        img = renderer.render(state, heads, 0, image_rng)
        if k == 0:
            if not rec["in_view"][0]:  # pragma: no cover - the placement keeps it in view
                raise RuntimeError("the ball is not in view in the first frame")
            # Target model: the hue of the ball's inner disc in the first frame.
            r_px = rec["radius"][0]
            ui, vi = int(round(rec["u"][0])), int(round(rec["v"][0]))
            half = int(math.ceil(r_px)) + 2
            y0, x0 = max(vi - half, 0), max(ui - half, 0)
            patch = np.ascontiguousarray(img[y0:vi + half + 1, x0:ui + half + 1])
            yy, xx = np.mgrid[y0:y0 + patch.shape[0], x0:x0 + patch.shape[1]]
            inner = max(1.0, 0.8 * r_px)
            mask = ((xx - rec["u"][0]) ** 2 + (yy - rec["v"][0]) ** 2) <= inner * inner
            hist = hue_histogram(patch, bins=16, mask=mask.astype(np.uint8) * 255)
        t0 = time.perf_counter()
        bp = back_project(img, hist)
        bp_ms[k] = 1e3 * (time.perf_counter() - t0)
        if k == 0:
            w = 2 * int(round(rec["radius"][0])) + 1
            window = (w, w)
            start = (rec["u"][0], rec["v"][0])
            d_start = _size_distance(bp, np.array(start), window, diameter, focal, centre,
                                     drop)
            if not math.isfinite(d_start):  # pragma: no cover - the ball is in view
                d_start = rec["distance"][0]
            for sc in scales:
                # Lost below the same weight whatever the window: 0.2 of the target's size.
                fill = MIN_FILL / (sc * sc)
                trackers[f"kalman x{sc:g}"] = KalmanMeanShift(
                    start, window, image_size=(W, H), fov=(cam.hfov, cam.vfov),
                    camera_height=drop, distance=d_start, target_height_m=diameter,
                    window_scale=sc, min_fill=fill)
                trackers[f"plain x{sc:g}"] = PlainMeanShift(start, window, window_scale=sc,
                                                            min_fill=fill)
            for lab in labels:
                out[lab]["x"][0], out[lab]["y"][0] = start
                out[lab]["size_distance"][0] = d_start
        else:
            for lab in labels:
                tracker = trackers[lab]
                t0 = time.perf_counter()
                if lab.startswith("kalman"):
                    pos = tracker.update(bp, rotation=rot_odo, advance=adv[lab])[:2]
                else:
                    pos = tracker.update(bp)
                out[lab]["ms"][k] = 1e3 * (time.perf_counter() - t0)
                out[lab]["x"][k], out[lab]["y"][k] = pos
                out[lab]["lost"][k] = tracker.lost
                if not tracker.lost:
                    out[lab]["size_distance"][k] = _size_distance(
                        bp, pos, window, diameter, focal, centre, drop)
        # On to the next frame; the robot's odometry over the period: the rotation, and the
        # displacement along the bearing of the Kalman tracker's position (the paper's
        # linear angle model), each Kalman tracker its own.
        bearings = {lab: (0.5 * W - (trackers[lab].state[0] + 0.5)) * cam.hfov / W
                    for lab in labels if lab.startswith("kalman")}
        rot_odo = 0.0
        adv = dict.fromkeys(bearings, 0.0)
        for _ in range(STEPS_PER_FRAME):
            nudge_ball()
            world.step(command(True))
            ox, oy, oth = world.walk.odometry[0]
            rot_odo += oth
            for lab, b in bearings.items():
                adv[lab] += ox * math.cos(b) + oy * math.sin(b)
        adv_odo = adv[labels[0]]
    return {"variant": variant, "index": index, "rolling": rolling, "rec": rec, "out": out,
            "labels": labels, "bp_ms": bp_ms, "window": window, "tilt": tilt,
            "max_turn": wmax, "frame_dt": frame_dt}
# ------------------------------------------------------------------------------------------
# Figures
# ------------------------------------------------------------------------------------------

def _scored(ep: dict[str, Any]) -> np.ndarray:
    """Frames that count: after the first, the ball's centre in the image."""
    m = ep["rec"]["in_view"].copy()
    m[0] = False
    return m


def _errors(ep: dict[str, Any], lab: str) -> tuple[np.ndarray, np.ndarray]:
    """Pixel error per frame and whether it is off target (beyond the ball's radius)."""
    rec, o = ep["rec"], ep["out"][lab]
    err = np.hypot(o["x"] - rec["u"], o["y"] - rec["v"])
    return err, err > rec["radius"]


def _transitions(off: np.ndarray, mask: np.ndarray) -> tuple[int, int]:
    """Losses (on -> off) and recoveries (off -> on) between consecutive scored frames; the
    first frame (the start) counts as on target."""
    state = np.where(mask, off.astype(float), np.nan)
    state[0] = 0.0
    d = np.diff(state[~np.isnan(state)])
    return int(np.sum(d > 0)), int(np.sum(d < 0))


def _was_on(off: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Frames whose previous frame was scored and on target (the start counts as on)."""
    prev = np.zeros(len(off), bool)
    prev[1:] = mask[:-1] & ~off[:-1]
    prev[1] = True
    return prev & mask


def _rate(x: np.ndarray) -> float:
    return float(np.mean(x)) if len(x) else math.nan


def _summarise(eps: list[dict[str, Any]]) -> dict[str, Any]:
    """Per tracker: rates, errors, transitions, timing and depth over ``eps`` pooled."""
    res: dict[str, Any] = {"trackers": {}}
    frames = sum(int(_scored(e).sum()) for e in eps)
    total = sum(len(e["rec"]["t"]) - 1 for e in eps)
    for lab in eps[0]["labels"]:
        err, off, lost, ms, rel, signed, hazard = [], [], [], [], [], [], []
        losses = recoveries = 0
        for e in eps:
            m = _scored(e)
            er, of = _errors(e, lab)
            hazard.append(of[_was_on(of, m)])
            err.append(er[m])
            off.append(of[m])
            lost.append(e["out"][lab]["lost"][m])
            ms.append(e["out"][lab]["ms"][1:])
            lo, rc = _transitions(of, m)
            losses += lo
            recoveries += rc
            on = m & ~of & np.isfinite(e["out"][lab]["size_distance"])
            truth = e["rec"]["distance"][on]
            est = e["out"][lab]["size_distance"][on]
            rel.append(np.abs(est - truth) / truth)
            signed.append((est - truth) / truth)
        err_a, off_a = np.concatenate(err), np.concatenate(off)
        rel_a, signed_a = np.concatenate(rel), np.concatenate(signed)
        on_err = err_a[~off_a]
        res["trackers"][lab] = {
            "frames": int(len(err_a)),
            "lost_rate": _rate(np.concatenate(lost)),
            "off_target_rate": _rate(off_a),
            "loss_hazard": _rate(np.concatenate(hazard)),
            "median_error_px": float(np.median(err_a)) if len(err_a) else math.nan,
            "rmse_on_target_px": (float(np.sqrt(np.mean(on_err ** 2))) if len(on_err)
                                  else math.nan),
            "losses": losses, "recoveries": recoveries,
            "ms_per_frame": float(np.nanmean(np.concatenate(ms))),
            "depth_frames": int(len(rel_a)),
            "depth_median_rel": float(np.median(rel_a)) if len(rel_a) else math.nan,
            "depth_median_signed": float(np.median(signed_a)) if len(signed_a) else math.nan,
        }
    res["frames"] = frames
    res["out_of_view_rate"] = 1.0 - frames / total if total else math.nan
    res["bp_ms_per_frame"] = float(np.nanmean(np.concatenate([e["bp_ms"] for e in eps])))
    return res


def _binned(eps: list[dict[str, Any]], key: str) -> list[dict[str, Any]]:
    """Rates per bin of the turn rate (``key="turn"``, fractions of the top turn rate) or of
    the ball's image jump in its apparent radii (``"jump"``), pooled over ``eps``."""
    bins = TURN_BINS if key == "turn" else JUMP_BINS
    labels = eps[0]["labels"]
    rows = []
    for name, lo, hi in bins:
        parts: dict[str, list[np.ndarray]] = {"jump": [], "still": [], "rate": []}
        acc = {lab: {"off": [], "lost": [], "hazard": []} for lab in labels}
        for e in eps:
            rec = e["rec"]
            x = (rec["turn_rate"] / e["max_turn"] if key == "turn"
                 else rec["jump"] / rec["radius"])
            sel = _scored(e) & (x >= lo) & (x < hi)
            parts["jump"].append(rec["jump"][sel] / rec["radius"][sel])
            parts["still"].append(rec["jump_still"][sel] / rec["radius"][sel])
            parts["rate"].append(rec["turn_rate"][sel])
            for lab in labels:
                of = _errors(e, lab)[1]
                acc[lab]["off"].append(of[sel])
                acc[lab]["lost"].append(e["out"][lab]["lost"][sel])
                acc[lab]["hazard"].append(of[sel & _was_on(of, _scored(e))])
        jump, still, rate = (np.concatenate(parts[k]) for k in ("jump", "still", "rate"))
        row: dict[str, Any] = {"bin": name, "frames": int(len(jump)),
                               "mean_turn_rate": _rate(rate),
                               "mean_jump_radii": _rate(jump),
                               "mean_jump_radii_without_sway": _rate(still)}
        for lab in labels:
            row[f"{lab} off_target_rate"] = _rate(np.concatenate(acc[lab]["off"]))
            row[f"{lab} lost_rate"] = _rate(np.concatenate(acc[lab]["lost"]))
            row[f"{lab} loss_hazard"] = _rate(np.concatenate(acc[lab]["hazard"]))
        rows.append(row)
    return rows


def _verdict(kalman: float, plain: float) -> str:
    if not (math.isfinite(kalman) and math.isfinite(plain)):
        return "not testable (no frames)"
    if plain == 0.0 and kalman == 0.0:
        return "not testable (neither tracker lost the ball)"
    return "met" if kalman <= 0.5 * plain else "not met"


def _pct(x: float) -> str:
    return "n/a" if not math.isfinite(x) else f"{100 * x:.1f} %"


def _num(x: float, fmt: str = ".2f") -> str:
    return "n/a" if not math.isfinite(x) else format(x, fmt)


# ------------------------------------------------------------------------------------------
# Entry point
# ------------------------------------------------------------------------------------------

def _check_count(name: str, v: object, lo: int, hi: int) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not lo <= v <= hi:
        raise ValueError(f"{name} must be an integer in [{lo}, {hi}], got {v!r}")
    return int(v)


def run(out: str | Path = "paper_output", episodes: int = 10, duration: float = 20.0,
        seed: int = 0, workers: int | None = None, *, robot: str = "humanoid-2012",
        size: tuple[int, int] = (320, 240), appearance: str = "realistic",
        window_scales: tuple[float, ...] = (1.0, 2.0)) -> dict[str, Any]:
    """Run ``episodes`` seeded episodes of ``duration`` seconds per variant (``turn``,
    ``follow``) with both trackers at each of ``window_scales`` (mean-shift window over the
    ball's apparent diameter: 1, the bandwidth of paper 004's argument, and 2, its
    back-projection region R) on the same frames (module docstring); write
    ``paper_following.md``, ``.csv``, ``.json`` and ``.png`` into ``out``. ``workers``
    processes share the episodes (default: all cores; 1 runs them here; the figures other
    than the timings do not depend on it)."""
    from soccer_env.presets.images import HEAD_FRAMES

    episodes = _check_count("episodes", episodes, 1, 1000)
    if not (isinstance(duration, (int, float)) and not isinstance(duration, bool)
            and math.isfinite(duration) and 0.2 <= duration <= 600.0):
        raise ValueError(f"duration must be in [0.2, 600] s, got {duration!r}")
    seed = _check_count("seed", seed, 0, 2**31 - 1)
    if workers is not None:
        workers = _check_count("workers", workers, 1, 1024)
    if not isinstance(robot, str) or robot not in ROBOTS:
        raise ValueError(f"robot must be one of {list(ROBOTS)}, got {robot!r}")
    try:
        w, h = size
    except (TypeError, ValueError):
        raise ValueError(f"size must be (width, height) in pixels, got {size!r}") from None
    w = _check_count("size[0] (width)", w, 64, 4096)
    h = _check_count("size[1] (height)", h, 48, 4096)
    if not isinstance(appearance, str) or appearance not in HEAD_FRAMES:
        raise ValueError(f"appearance must be one of {list(HEAD_FRAMES)}, got {appearance!r}")
    try:
        scales = tuple(float(x) for x in window_scales)
    except (TypeError, ValueError):
        raise ValueError(f"window_scales must be numbers, got {window_scales!r}") from None
    if not scales or len(set(scales)) != len(scales) or not all(
            math.isfinite(x) and 0.5 <= x <= 4.0 for x in scales):
        raise ValueError(f"window_scales must be distinct numbers in [0.5, 4], got "
                         f"{window_scales!r}")
    t0 = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    jobs = [(robot, variant, k, seed, float(duration), (w, h), appearance, scales)
            for variant in VARIANTS for k in range(episodes)]
    n_workers = min(workers or os.cpu_count() or 1, len(jobs))
    eps = map_jobs(_episode, jobs, n_workers)
    labels = eps[0]["labels"]
    by_variant = {v: [e for e in eps if e["variant"] == v] for v in VARIANTS}
    summary = {v: _summarise(by_variant[v]) for v in VARIANTS}
    summary["all"] = _summarise(eps)
    turn_bins = {v: _binned(by_variant[v], "turn") for v in VARIANTS}
    turn_bins["all"] = _binned(eps, "turn")
    jump_bins = _binned(eps, "jump")
    fast = turn_bins["all"][-1]
    verdicts = {}
    for sc in scales:
        k_lab, p_lab = f"kalman x{sc:g}", f"plain x{sc:g}"
        verdicts[f"x{sc:g}"] = {
            "kalman_off_target": fast[f"{k_lab} off_target_rate"],
            "plain_off_target": fast[f"{p_lab} off_target_rate"],
            "kalman_lost": fast[f"{k_lab} lost_rate"],
            "plain_lost": fast[f"{p_lab} lost_rate"],
            "off_target": _verdict(fast[f"{k_lab} off_target_rate"],
                                   fast[f"{p_lab} off_target_rate"]),
            "kalman_hazard": fast[f"{k_lab} loss_hazard"],
            "plain_hazard": fast[f"{p_lab} loss_hazard"],
            "lost": _verdict(fast[f"{k_lab} lost_rate"], fast[f"{p_lab} lost_rate"]),
            "hazard": _verdict(fast[f"{k_lab} loss_hazard"], fast[f"{p_lab} loss_hazard"])}

    from soccer_env import presets
    from soccer_env.presets.sensors import head_camera

    field_name, camera_name = ROBOTS[robot]
    spec = presets.robot(robot)
    cam = head_camera(camera_name)
    ball = presets.ball(presets.field(field_name).ball)
    wmax = spec.max_turn_speed
    e0 = eps[0]
    windows = [e["window"][0] for e in eps]
    lines = [
        f"Paper 004 on a turning humanoid: robot `{robot}` (top turn rate {wmax:g} rad/s, "
        f"gait sway {math.degrees(spec.sway_pan):g} degrees yaw / "
        f"{math.degrees(spec.sway_tilt):g} degrees pitch at {spec.step_frequency:g} steps/s) on "
        f"field `{field_name}` (ball radius {1000 * ball.radius:.0f} mm), head camera "
        f"`{camera_name}` ({cam.frame_rate:g} Hz, {math.degrees(cam.hfov):.0f} degrees) "
        f"rendered at {w} x {h} (`{appearance}`), head at pan 0 and tilt "
        f"{math.degrees(e0['tilt']):.1f} degrees. {episodes} seeded episode(s) of "
        f"{duration:g} s per variant (seed {seed}; odd episodes roll the ball): `turn` "
        "sweeps the heading in place, `follow` also walks towards the ball. All trackers on "
        "the same hue back-projections, started at the ball's true pixel; window: the ball's "
        f"apparent diameter at the start ({min(windows)}-{max(windows)} px) times x "
        f"({', '.join(f'{sc:g}' for sc in scales)}). The Kalman tracker gets the walk "
        "engine's odometry (rotation, advance) between frames, not the truth.", "",
        "| variant | tracker | frames | reports lost | off target | loss hazard | median "
        "error [px] | RMSE on target [px] | losses | recoveries | ms per frame | size-based "
        "distance: median rel. error (signed) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    rows: list[dict[str, Any]] = []
    for v in (*VARIANTS, "all"):
        for lab in labels:
            r = summary[v]["trackers"][lab]
            lines.append(
                f"| {v} | {lab} | {r['frames']} | {_pct(r['lost_rate'])} | "
                f"{_pct(r['off_target_rate'])} | {_pct(r['loss_hazard'])} | "
                f"{_num(r['median_error_px'], '.1f')} | "
                f"{_num(r['rmse_on_target_px'], '.1f')} | {r['losses']} | {r['recoveries']} | "
                f"{_num(r['ms_per_frame'], '.3f')} | {_pct(r['depth_median_rel'])} "
                f"({_pct(r['depth_median_signed'])}) |")
            rows.append({"table": "summary", "variant": v, "tracker": lab, **r})
    oov = summary["all"]["out_of_view_rate"]
    lines += ["", "Off target: farther from the ball's true pixel than its apparent radius. "
              "Loss hazard: the share of frames off target among those whose previous frame "
              "was on target (how often a held track is lost, whatever happens after). "
              f"Ball out of view (not scored): {_pct(oov)} of frames. Hue back-projection "
              f"(shared): {summary['all']['bp_ms_per_frame']:.3f} ms per frame.", "",
              "By turn rate (true body turn rate over the frame period; bins at 1/3 and 2/3 of "
              f"{wmax:g} rad/s): the ball's mean image jump between frames in its apparent "
              "radii (without the gait's sway), and per tracker the share of frames off "
              "target / the loss hazard:", "",
              "| variant | turn rate [rad/s] | frames | mean rate | jump [radii] | "
              + " | ".join(labels) + " |", "|---" * (5 + len(labels)) + "|"]
    for v in (*VARIANTS, "all"):
        for b, (name, lo, hi) in zip(turn_bins[v], TURN_BINS):
            span = (f"{name} {lo * wmax:.2f}-{hi * wmax:.2f}" if math.isfinite(hi)
                    else f"{name} >= {lo * wmax:.2f}")
            lines.append(
                f"| {v} | {span} | {b['frames']} | {_num(b['mean_turn_rate'])} | "
                f"{_num(b['mean_jump_radii'], '.1f')} "
                f"({_num(b['mean_jump_radii_without_sway'], '.1f')}) | "
                + " | ".join(f"{_pct(b[f'{lab} off_target_rate'])} / "
                             f"{_pct(b[f'{lab} loss_hazard'])}" for lab in labels) + " |")
            rows.append({"table": "turn_rate", "variant": v, **b})
    lines += ["", "By the ball's true image jump between frames in its apparent radii (a "
              "window of scale x has a half-width of about x radii, the bandwidth), both "
              "variants, share of frames off target / loss hazard:", "",
              "| jump [radii] | frames | mean turn rate [rad/s] | " + " | ".join(labels) + " |",
              "|---" * (3 + len(labels)) + "|"]
    for b in jump_bins:
        lines.append(f"| {b['bin']} | {b['frames']} | {_num(b['mean_turn_rate'])} | "
                     + " | ".join(f"{_pct(b[f'{lab} off_target_rate'])} / "
                                  f"{_pct(b[f'{lab} loss_hazard'])}" for lab in labels)
                     + " |")
        rows.append({"table": "jump", "variant": "all", **b})
    lines += ["", f"Paper 004's claim: {PAPER['claim']}. Its results: {PAPER['results']}.", "",
              f"Aim: {AIM}. Fast turns (>= {TURN_BINS[-1][1] * wmax:.2f} rad/s, "
              f"{fast['frames']} frames, both variants), Kalman against plain, judged on the "
              "share of frames off target (the lost-track rate):"]
    for key, vd in verdicts.items():
        lines.append(f"- window {key}: {_pct(vd['kalman_off_target'])} against "
                     f"{_pct(vd['plain_off_target'])}: **{vd['off_target']}**; by the "
                     f"trackers' own lost reports {_pct(vd['kalman_lost'])} against "
                     f"{_pct(vd['plain_lost'])}: {vd['lost']}; by the loss hazard "
                     f"{_pct(vd['kalman_hazard'])} against {_pct(vd['plain_hazard'])}: "
                     f"{vd['hazard']}.")
    text = "\n".join(lines)

    # The figure's episode: the first of paper 004's setting (following).
    ep_plot = by_variant["follow"][0]
    series: dict[str, Any] = {"t": ep_plot["rec"]["t"].tolist(),
                              "turn_rate": (ep_plot["rec"]["rotation_true"]
                                            / ep_plot["frame_dt"]).tolist(),
                              "radius": ep_plot["rec"]["radius"].tolist()}
    for lab in labels:
        series[f"{lab} error_px"] = _errors(ep_plot, lab)[0].tolist()
    data = {"robot": robot, "field": field_name, "camera": camera_name, "size": [w, h],
            "appearance": appearance, "episodes": episodes, "duration": duration,
            "seed": seed, "window_scales": list(scales), "summary": summary,
            "turn_bins": turn_bins, "jump_bins": jump_bins, "aim": AIM, "verdicts": verdicts,
            "paper": PAPER,
            "episode_list": [{"variant": e["variant"], "index": e["index"],
                              "rolling": e["rolling"], "window_px": e["window"][0]}
                             for e in eps],
            "plotted_episode": {"variant": ep_plot["variant"], "index": ep_plot["index"],
                                **series}}
    files = write_report(out, "paper_following", text, rows, data)

    plt = pyplot()
    from matplotlib.colors import ListedColormap

    fig, (ax, rx, bx) = plt.subplots(1, 3, figsize=(17, 4.6),
                                     gridspec_kw={"width_ratios": [1.2, 1.0, 0.9]})
    colours = [f"C{j}" for j in range(len(labels))]
    t = ep_plot["rec"]["t"]
    for lab, c in zip(labels, colours):
        ax.plot(t, np.maximum(_errors(ep_plot, lab)[0], 0.05),
                "-" if lab.startswith("kalman") else "--", color=c, lw=1, label=lab)
    ax.plot(t, ep_plot["rec"]["radius"], ":", color="grey",
            label="ball radius (off target above)")
    ax.set(xlabel="time [s]", ylabel="pixel error [px] (log)", yscale="log",
           title=f"episode `{ep_plot['variant']}` #{ep_plot['index']} (the first "
                 f"`{ep_plot['variant']}`): pixel error")
    ax2 = ax.twinx()
    ax2.plot(t, series["turn_rate"], color="black", alpha=0.3, lw=1, label="turn rate")
    ax2.set_ylabel("turn rate [rad/s]")
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=7, loc="upper left")
    # Every episode, every tracker: the frames off target.
    n = min(len(e["rec"]["t"]) for e in eps)
    raster = np.zeros((len(eps) * len(labels), n))
    for i, e in enumerate(eps):
        for j, lab in enumerate(labels):
            raster[i * len(labels) + j] = np.where(_errors(e, lab)[1][:n], j + 1, 0)
    rx.imshow(raster, aspect="auto", interpolation="nearest",
              cmap=ListedColormap(["white", *colours]), vmin=0, vmax=len(labels),
              extent=(0.0, n * ep_plot["frame_dt"], len(raster), 0))
    rx.set_yticks([(i + 0.5) * len(labels) for i in range(len(eps))],
                  [f"{e['variant']} #{e['index']}" for e in eps], fontsize=6)
    rx.set(xlabel="time [s]", title="frames off target, every episode (rows: "
           + ", ".join(labels) + ")")
    rx.title.set_fontsize(8)
    xs = np.arange(len(TURN_BINS))
    width = 0.8 / len(labels)
    for j, lab in enumerate(labels):
        vals = [b[f"{lab} off_target_rate"] for b in turn_bins["all"]]
        bx.bar(xs + (j - 0.5 * (len(labels) - 1)) * width, np.nan_to_num(vals), width,
               color=colours[j], label=lab)
    bx.set_xticks(xs, [f"{nm}\n{lo * wmax:.2f}-{hi * wmax:.2f} rad/s" if math.isfinite(hi)
                       else f"{nm}\n>= {lo * wmax:.2f} rad/s" for nm, lo, hi in TURN_BINS])
    bx.set(ylabel="share of frames off target", ylim=(0, 1),
           title="lost-track rate by turn rate (both variants)")
    bx.legend(fontsize=8)
    files.append(save_figure(fig, out / "paper_following.png"))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "summary": summary, "turn_bins": turn_bins, "jump_bins": jump_bins,
            "verdicts": verdicts}
