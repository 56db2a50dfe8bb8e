"""One seeded episode of Yu, Wei and Zhang (2010)'s reproduction: the scripted scene (a
humanoid sweeping its heading around the ball, walking towards it in ``follow``, the ball
rolled now and then) and both trackers at every window scale on the same head-camera frames
(see :mod:`soccer_lab.papers.following`)."""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from estimators import KalmanMeanShift, PlainMeanShift, apparent_height, depth_from_size

__all__ = ["ROBOTS", "VARIANTS", "TRACKERS", "STEPS_PER_FRAME", "MIN_FILL", "SETTLE_S",
           "ROLL_MAX_SPEED", "view", "size_distance", "labels", "run_episode", "Scene",
           "Tracking"]

#: Robot preset -> (field preset, head-camera preset).
ROBOTS = {"humanoid-2012": ("humanoid-2012", "kidsize-2012"),
          "humanoid": ("humanoid-kid", "kidsize")}
VARIANTS = ("turn", "follow")
TRACKERS = ("kalman", "kalman-paper", "plain")
STEPS_PER_FRAME = 4
#: Lost below this mean weight in a window of the target's size (the estimators' default);
#: a window ``x`` times larger is lost below ``MIN_FILL / x^2``.
MIN_FILL = 0.2
SETTLE_S = 0.5
ROLL_MAX_SPEED = 0.5


def _wrap(a: float) -> float:
    return math.remainder(a, 2.0 * math.pi)


def view(robot: np.ndarray, ball: np.ndarray, pan: float, tilt: float, height: float,
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


def size_distance(bp: np.ndarray, pos: np.ndarray, window: tuple[int, int], diameter: float,
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


def labels(scales: tuple[float, ...]) -> list[str]:
    """Tracker labels: ``"kalman x1"``, ``"kalman-paper x1"``, ``"plain x1"``, ... per window
    scale."""
    return [f"{tr} x{sc:g}" for sc in scales for tr in TRACKERS]


def run_episode(args: tuple) -> dict[str, Any]:
    """One seeded episode ``(robot, variant, index, seed, duration, size, appearance,
    scales)``: per-frame truth and every tracker's output (module level, for a process
    pool)."""

    robot_name, variant, index, seed, duration, size, appearance, scales = args
    scene = Scene(robot_name, variant, index, seed, size, appearance)
    scene.settle()
    tracking = Tracking(scene, scales, int(round(duration / scene.frame_dt)) + 1)
    rot_odo, adv = 0.0, {}
    for k in range(tracking.n_frames):
        state = scene.world.snapshot()
        heads = scene.world.head_state()
        img = tracking.record(k, state, heads, rot_odo)
        tracking.track(k, img, rot_odo, adv)
        # On to the next frame, with the robot's odometry over the period.
        rot_odo, adv = scene.frame_period(tracking.bearings())
        tracking.adv_odo = adv[tracking.labels[0]]
    return tracking.result()


class Scene:
    """The scripted world of one episode (see :mod:`soccer_lab.papers.following`): the
    robot placed facing the ball, its heading swept back and forth around the ball's bearing
    (and, in ``follow``, walking towards it), the ball rolled now and then in odd episodes;
    the head camera's renderer. Every random draw of the script comes from one generator, in
    the order the episode makes them."""

    def __init__(self, robot_name: str, variant: str, index: int, seed: int,
                 size: tuple[int, int], appearance: str) -> None:
        from soccer_env import presets
        from soccer_env.presets.sensors import head_camera
        from soccer_env.sensors.images.head import HeadFrameRenderer
        from soccer_env.sim.world import World

        field_name, camera_name = ROBOTS[robot_name]
        self.field = field = presets.field(field_name)
        self.ball_spec = ball_spec = presets.ball(field.ball)
        self.spec = spec = presets.robot(robot_name)
        cam_spec = head_camera(camera_name)
        self.frame_dt = 1.0 / float(cam_spec.frame_rate)
        self.world = World(field, ball_spec, spec, 1, 0, self.frame_dt / STEPS_PER_FRAME)
        self.renderer = HeadFrameRenderer(cam_spec, field, spec, ball_spec, [0], appearance,
                                          size)
        self.cam = self.renderer.camera
        self.drop = self.cam.height - ball_spec.radius
        self.variant, self.index = variant, index
        vi_ = VARIANTS.index(variant)
        self.rng = np.random.default_rng([seed, vi_, index])
        world_rng = np.random.default_rng([seed, vi_, index, 1])
        self.image_rng = np.random.default_rng([seed, vi_, index, 2])
        self.rolling = index % 2 == 1
        # Head tilt: the middle of the depression angles of balls at 1 m and 3 m.
        tilt = 0.5 * (math.atan2(self.drop, 1.0) + math.atan2(self.drop, 3.0))
        self.tilt = min(spec.head_tilt_max, max(spec.head_tilt_min, tilt))
        self._place(world_rng)
        self.wmax, self.alpha = spec.max_turn_speed, spec.max_angular_acceleration
        self.vmax = spec.max_forward_speed
        self.sweep = {"dir": 1.0 if self.rng.random() < 0.5 else -1.0, "rate": 0.0,
                      "amp": 0.0}
        self._new_sweep()
        self.roll = {"wait_until": 0.0, "moving": False}
        self.lim_x = min(field.half_length + field.boundary - 0.4, field.half_length + 0.3)
        self.lim_y = field.half_width + field.boundary - 0.4

    def _place(self, world_rng: np.random.Generator) -> None:
        """The robot inside the walls, facing +x, the ball ahead of it (``follow``: 2.2-2.8
        m, ``turn``: 1-3 m)."""
        rng = self.rng
        if self.variant == "follow":
            rx, ry = -2.4 + rng.uniform(-0.2, 0.2), rng.uniform(-0.6, 0.6)
            d0 = rng.uniform(2.2, 2.8)
        else:
            rx, ry = -1.8 + rng.uniform(-0.3, 0.3), rng.uniform(-0.6, 0.6)
            d0 = rng.uniform(1.0, 3.0)
        b0 = rng.uniform(-0.4, 0.4)
        bx, by = rx + d0 * math.cos(b0), ry + d0 * math.sin(b0)
        heading = b0 + rng.uniform(-0.2, 0.2)
        self.world.reset(np.array([[rx, ry, heading]]), (bx, by), world_rng)

    def _new_sweep(self) -> None:
        self.sweep["rate"] = self.wmax * self.rng.uniform(0.15, 1.0)
        self.sweep["amp"] = self.rng.uniform(0.15, 0.3)

    def command(self, moving: bool) -> np.ndarray:
        """The robot's command: the sweep's turn (reversed, with a new rate and amplitude,
        once the heading is past the ball's bearing by the amplitude less the braking
        overshoot), in ``follow`` walking towards the ball; standing when not ``moving``."""
        world, sweep = self.world, self.sweep
        rb = world.robot_array()[0]
        ball = world.ball_array()
        dx, dy = ball[0] - rb[0], ball[1] - rb[1]
        e = _wrap(rb[2] - math.atan2(dy, dx))
        rate = sweep["rate"]
        brake = rate * rate / (2.0 * self.alpha)
        if sweep["dir"] * e > sweep["amp"] - brake:
            sweep["dir"] = -sweep["dir"]
            self._new_sweep()
        omega = sweep["dir"] * sweep["rate"] if moving else 0.0
        vx = 0.0
        if moving and self.variant == "follow":
            vx = min(self.vmax, max(0.0, 0.4 * (math.hypot(dx, dy) - 1.0)))
        return np.array([[vx, 0.0, omega, 0.0, 0.0, self.tilt]])

    def nudge_ball(self) -> None:
        """In a rolling episode, once the ball has stopped and its wait is over, roll it
        towards a point near the robot's line of sight."""
        if not self.rolling:
            return
        world, roll, rng = self.world, self.roll, self.rng
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
        lo, hi = (1.5, 2.5) if self.variant == "follow" else (1.2, 2.8)
        d = rng.uniform(lo, hi)
        tx = min(self.lim_x, max(-self.lim_x, rb[0] + d * math.cos(bearing)))
        ty = min(self.lim_y, max(-self.lim_y, rb[1] + d * math.sin(bearing)))
        gx, gy = tx - ball[0], ty - ball[1]
        dist = math.hypot(gx, gy)
        if dist < 0.05:
            return
        v0 = min(ROLL_MAX_SPEED, math.sqrt(2.0 * self.ball_spec.rolling_deceleration * dist))
        world.set_ball(ball[0], ball[1], v0 * gx / dist, v0 * gy / dist)
        roll["moving"] = True

    def settle(self) -> None:
        """Stand while the head goes to its tilt; draw the first roll's wait."""
        world = self.world
        for _ in range(int(round(SETTLE_S / world.control_dt))):
            world.step(self.command(False))
        self.roll["wait_until"] = world.time + self.rng.uniform(0.0, 1.0)

    def frame_period(self, bearings: dict[str, float]) -> tuple[float, dict[str, float]]:
        """The control steps of one frame period; the robot's odometry over them: the
        rotation, and per Kalman tracker the displacement along the bearing of its position
        (the paper's linear angle model)."""
        rot_odo = 0.0
        adv = dict.fromkeys(bearings, 0.0)
        for _ in range(STEPS_PER_FRAME):
            self.nudge_ball()
            self.world.step(self.command(True))
            ox, oy, oth = self.world.walk.odometry[0]
            rot_odo += oth
            for lab, b in bearings.items():
                adv[lab] += ox * math.cos(b) + oy * math.sin(b)
        return rot_odo, adv


class Tracking:
    """The frames of one episode: the truth per frame (``rec``), the hue back-projection and
    every tracker's output (``out``), started on the first frame."""

    def __init__(self, scene: Scene, scales: tuple[float, ...], n_frames: int) -> None:
        self.scene, self.scales, self.n_frames = scene, scales, n_frames
        self.rec = {k: np.full(n_frames, np.nan) for k in (
            "t", "u", "v", "u_still", "v_still", "radius", "distance", "turn_rate", "jump",
            "jump_still", "rotation_odo", "rotation_true", "advance_odo")}
        self.rec["in_view"] = np.zeros(n_frames, bool)
        self.labels = labels(scales)
        self.out = {lab: {"x": np.full(n_frames, np.nan), "y": np.full(n_frames, np.nan),
                          "lost": np.zeros(n_frames, bool), "ms": np.full(n_frames, np.nan),
                          "size_distance": np.full(n_frames, np.nan)} for lab in self.labels}
        self.bp_ms = np.full(n_frames, np.nan)
        self.trackers: dict[str, Any] = {}
        self.window = (1, 1)
        self.diameter = 2.0 * scene.ball_spec.radius
        self.prev_heading = float(scene.world.robot_array()[0, 2])
        self.adv_odo = 0.0
        self.hist: np.ndarray | None = None

    def record(self, k: int, state: Any, heads: Any, rot_odo: float) -> np.ndarray:
        """Frame ``k``'s truth: the ball's pixel with and without the gait's sway, its
        apparent radius, distance and whether it is in view, the body's turn and the
        odometry since the last frame; and the rendered image."""
        scene, rec = self.scene, self.rec
        cam, r_ball = scene.cam, scene.ball_spec.radius
        focal, centre = cam.focal_px, cam.centre
        robot = state.robots[0]
        pan, tl = float(heads.pan[0]), float(heads.tilt[0])
        u, v, depth = view(robot, state.ball, pan + float(heads.sway_pan[0]),
                           tl + float(heads.sway_tilt[0]), cam.height, r_ball, focal, centre)
        us, vs, _ = view(robot, state.ball, pan, tl, cam.height, r_ball, focal, centre)
        rec["t"][k] = k * scene.frame_dt
        rec["u"][k], rec["v"][k] = u - 0.5, v - 0.5  # mean-shift pixel coordinates
        rec["u_still"][k], rec["v_still"][k] = us - 0.5, vs - 0.5  # without the sway
        rec["radius"][k] = focal * r_ball / depth if depth > 0 else math.nan
        rec["distance"][k] = math.hypot(state.ball[0] - robot[0], state.ball[1] - robot[1])
        rec["in_view"][k] = (depth > 0 and 0.0 <= u <= scene.renderer.width
                             and 0.0 <= v <= scene.renderer.height)
        heading = float(robot[2])
        if k > 0:
            dth = _wrap(heading - self.prev_heading)
            rec["rotation_true"][k] = dth
            rec["turn_rate"][k] = abs(dth) / scene.frame_dt
            rec["rotation_odo"][k] = rot_odo
            rec["advance_odo"][k] = self.adv_odo
            rec["jump"][k] = math.hypot(rec["u"][k] - rec["u"][k - 1],
                                        rec["v"][k] - rec["v"][k - 1])
            rec["jump_still"][k] = math.hypot(rec["u_still"][k] - rec["u_still"][k - 1],
                                              rec["v_still"][k] - rec["v_still"][k - 1])
        self.prev_heading = heading
        return scene.renderer.render(state, heads, 0, scene.image_rng)

    def track(self, k: int, img: np.ndarray, rot_odo: float, adv: dict[str, float]) -> None:
        """Back-project frame ``k`` (timed) with the first frame's hue histogram; start the
        trackers on the first frame, update them on the others (each timed alone)."""
        from estimators.image.colour import back_project

        if k == 0:
            self.hist = self._target_model(img)
        t0 = time.perf_counter()
        bp = back_project(img, self.hist)
        self.bp_ms[k] = 1e3 * (time.perf_counter() - t0)
        if k == 0:
            self._start(bp)
            return
        cam, out = self.scene.cam, self.out
        for lab in self.labels:
            tracker = self.trackers[lab]
            t0 = time.perf_counter()
            if lab.startswith("kalman"):
                pos = tracker.update(bp, rotation=rot_odo, advance=adv[lab])[:2]
            else:
                pos = tracker.update(bp)
            out[lab]["ms"][k] = 1e3 * (time.perf_counter() - t0)
            out[lab]["x"][k], out[lab]["y"][k] = pos
            out[lab]["lost"][k] = tracker.lost
            if not tracker.lost:
                out[lab]["size_distance"][k] = size_distance(
                    bp, pos, self.window, self.diameter, cam.focal_px, cam.centre,
                    self.scene.drop)

    def _target_model(self, img: np.ndarray) -> np.ndarray:
        """The hue histogram of the ball's inner disc in the first frame."""
        from estimators.image.colour import hue_histogram

        rec = self.rec
        if not rec["in_view"][0]:  # pragma: no cover - the placement keeps it in view
            raise RuntimeError("the ball is not in view in the first frame")
        r_px = rec["radius"][0]
        ui, vi = int(round(rec["u"][0])), int(round(rec["v"][0]))
        half = int(math.ceil(r_px)) + 2
        y0, x0 = max(vi - half, 0), max(ui - half, 0)
        patch = np.ascontiguousarray(img[y0:vi + half + 1, x0:ui + half + 1])
        yy, xx = np.mgrid[y0:y0 + patch.shape[0], x0:x0 + patch.shape[1]]
        inner = max(1.0, 0.8 * r_px)
        mask = ((xx - rec["u"][0]) ** 2 + (yy - rec["v"][0]) ** 2) <= inner * inner
        return hue_histogram(patch, bins=16, mask=mask.astype(np.uint8) * 255)

    def _start(self, bp: np.ndarray) -> None:
        """Every tracker at the ball's true pixel of the first frame, its window the ball's
        apparent diameter there; the first size-based distance."""
        scene, rec = self.scene, self.rec
        cam = scene.cam
        w = 2 * int(round(rec["radius"][0])) + 1
        self.window = (w, w)
        start = (rec["u"][0], rec["v"][0])
        d_start = size_distance(bp, np.array(start), self.window, self.diameter, cam.focal_px,
                                cam.centre, scene.drop)
        if not math.isfinite(d_start):  # pragma: no cover - the ball is in view
            d_start = rec["distance"][0]
        for sc in self.scales:
            # Lost below the same weight whatever the window: 0.2 of the target's size.
            fill = MIN_FILL / (sc * sc)
            self.trackers[f"kalman x{sc:g}"] = KalmanMeanShift(
                start, self.window, image_size=(scene.renderer.width, scene.renderer.height),
                fov=(cam.hfov, cam.vfov), camera_height=scene.drop, distance=d_start,
                target_height_m=self.diameter, window_scale=sc, min_fill=fill)
            self.trackers[f"kalman-paper x{sc:g}"] = KalmanMeanShift(
                start, self.window, image_size=(scene.renderer.width, scene.renderer.height),
                fov=(cam.hfov, cam.vfov), camera_height=scene.drop, distance=d_start,
                target_height_m=self.diameter, window_scale=sc, min_fill=fill, order="paper")
            self.trackers[f"plain x{sc:g}"] = PlainMeanShift(start, self.window,
                                                             window_scale=sc, min_fill=fill)
        for lab in self.labels:
            self.out[lab]["x"][0], self.out[lab]["y"][0] = start
            self.out[lab]["size_distance"][0] = d_start

    def bearings(self) -> dict[str, float]:
        """The bearing of each Kalman tracker's position (its advance is measured along
        it)."""
        W, hfov = self.scene.renderer.width, self.scene.cam.hfov
        return {lab: (0.5 * W - (self.trackers[lab].state[0] + 0.5)) * hfov / W
                for lab in self.labels if lab.startswith("kalman")}

    def result(self) -> dict[str, Any]:
        """The episode's truth and trackers' outputs per frame."""
        scene = self.scene
        return {"variant": scene.variant, "index": scene.index, "rolling": scene.rolling,
                "rec": self.rec, "out": self.out, "labels": self.labels, "bp_ms": self.bp_ms,
                "window": self.window, "tilt": scene.tilt, "max_turn": scene.wmax,
                "frame_dt": scene.frame_dt}
