"""What a humanoid team believes: every robot localizes itself, sees through its head camera,
shares its sightings over the team radio, fuses them in Hough space and tracks the ball with a
particle filter (papers 000 and 001).

Per humanoid ("brain"), per step:

1. **Odometry** from its walk engine is kept with its time stamps.
2. **Head-camera frames** (:class:`~soccer_env.headcam.HeadCameraSensor`) arrive late. For a
   frame captured at ``t_c`` the localization is moved by the odometry up to ``t_c`` and
   weighted by the frame's landmarks (``localization="kld"``: paper 001's KLD-sampling
   particle filter, :class:`~estimators.KLDLocalizer`, with ambiguous landmark kinds: a robot
   sees an "L" corner, not which one; ``"odometry"``: dead reckoning from the known start;
   ``"truth"``: the true pose, an oracle for ablations). The ball detection nearest the
   present belief becomes a sighting line: from the estimated position at ``t_c`` along the
   estimated heading plus the detection's bearing, with the ground projection's range.
3. **Radio** (:class:`~soccer_env.radio.TeamRadio`): each frame's pose estimate and sighting
   are broadcast; a fallen robot is silent; received messages update the team-mates' poses
   and their latest sighting lines.
4. **Fusion** at each own frame: the robot's own line and the team-mates' lines captured
   within 1.5 frame periods plus the radio's latency and jitter of it (the latest per
   team-mate), each moved by the tracked ball velocity times its age,
   are fused by :func:`~estimators.fuse_sightings` (``fusion="equal" | "inverse" |
   "inverse_square"``: paper 000's Hough-space least squares with the weighting named; with
   ``"own"`` only the robot's own sighting is used).
5. **Tracking**: the fused point feeds paper 000's particle filter
   (:class:`~estimators.ParticleBallTracker`, ``ball_tracker="mfbpf" | "fbpf" |
   "bootstrap"``, 100 particles) stamped with the capture time, so its prediction to the
   present compensates the camera latency; with ``"none"`` the belief is the latest fused
   point with the velocity of the last two (at least 0.1 s apart).
6. **Opponents** are the robot's own sightings of robots of the other team's colour, each
   associated with the nearest opponent track within 1 m (no identity is seen); tracks start
   at the kick-off positions, which the rules fix.

Raw observations (``obs_mode="raw"``) run the same pipeline with the filters off: odometry
dead reckoning, the robot's own sightings only, no tracker.

The head is aimed by :class:`HeadController` unless the policy controls it.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from estimators import KLDConfig, KLDLocalizer, ParticleBallTracker, fuse_sightings
from soccer_env.headcam import (
    HeadCameraSensor,
    HeadCameraSpec,
    HeadFrame,
    HeadState,
    field_landmarks,
    head_camera,
)
from soccer_env.presets import BallSpec, FieldSpec, HumanoidRobotSpec, RobotSpec
from soccer_env.radio import Message, RadioSpec, TeamRadio
from soccer_env.state import WorldState

__all__ = ["HumanoidTeamPerception", "HeadController", "LOCALIZATIONS",
           "FUSIONS", "BALL_TRACKERS", "HEAD_MODES", "head_state", "aim_heads",
           "landmark_sightings"]

#: Self-localization choices.
LOCALIZATIONS = {
    "kld": "paper 001's KLD-sampling particle filter on odometry and landmark sightings",
    "odometry": "dead reckoning from the known start pose (no landmarks)",
    "truth": "the true pose (oracle, for ablations)",
}
#: Ball fusion choices: the robot's own sighting only, or paper 000's Hough-space fusion of
#: the team's sightings with the weighting named.
FUSIONS = {
    "own": "the robot's own sighting only",
    "equal": "Hough-space fusion of the team's sightings, equal weights",
    "inverse": "Hough-space fusion, weights 1/L (paper 000's weighted fusion)",
    "inverse_square": "Hough-space fusion, weights 1/L^2",
}
#: Ball trackers fed by the fused sightings.
BALL_TRACKERS = {
    "none": "no tracking: the latest fused point, velocity from the last two",
    "bootstrap": "bootstrap particle filter, 100 particles",
    "fbpf": "fission bootstrap particle filter (FBPF), 100 particles",
    "mfbpf": "paper 000's modified FBPF, 100 particles",
}
#: Who aims a humanoid's head: the :class:`HeadController` (``"auto"``: at the believed ball,
#: scanning when it is lost or the localization needs landmarks), a fixed scan, or the
#: policy's action entries 4 and 5.
HEAD_MODES = ("auto", "scan", "action")

#: Fused sightings older than this many frame periods are not fused with a new one.
_FUSION_WINDOW_FRAMES = 1.5
#: Measurement standard deviation floor of the ball tracker [m].
_MIN_SIGMA = 0.02
#: A robot detection is associated with an opponent track within this distance [m].
_TRACK_GATE = 1.0
#: The fastest ball [m/s]: the tracked velocity that moves old sighting lines is capped at it.
_MAX_BALL_SPEED = 10.0
#: Raw and untracked velocities are differences of points at least this far apart [s].
_MIN_DIFF_GAP = 0.1


def head_state(world: Any) -> HeadState:
    """The :class:`~soccer_env.headcam.HeadState` of every robot of ``world`` from its walk
    engine (zeros and not blind for SSL robots)."""
    n = world.n_robots
    pan, tilt, sp, st = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    blind = np.zeros(n, dtype=bool)
    walk = world.walk
    if walk is not None:
        idx = walk.indices
        pan[idx], tilt[idx] = walk.pan, walk.tilt
        sp[idx], st[idx] = walk.sway_pan, walk.sway_tilt
        blind[idx] = walk.fallen
    return HeadState(pan, tilt, sp, st, blind)


def landmark_sightings(frame: HeadFrame) -> tuple[list[str], np.ndarray, np.ndarray]:
    """The landmarks of ``frame`` that have a ground point: their kinds, ranges [m] and
    bearings [rad] in the robot frame (what the localization weighs)."""
    kinds, ranges, bearings = [], [], []
    for kind, _u, _v, x, y, bearing in frame.landmarks:
        r = math.hypot(x, y)
        if math.isfinite(r):
            kinds.append(kind)
            ranges.append(r)
            bearings.append(bearing)
    return kinds, np.array(ranges), np.array(bearings)


def look_at(spec: HumanoidRobotSpec, camera_height: float, pose: Sequence[float],
            x: float, y: float) -> tuple[float, float]:
    """Pan and tilt [rad] that centre the ground point ``(x, y)`` in the image of a robot at
    ``pose`` ``(x, y, theta)``: pan its bearing, tilt ``atan(h / d)``, both within the head's
    limits."""
    dx, dy = x - pose[0], y - pose[1]
    c, s = math.cos(pose[2]), math.sin(pose[2])
    pan = math.atan2(c * dy - s * dx, c * dx + s * dy)
    tilt = math.atan2(camera_height, max(math.hypot(dx, dy), 0.05))
    return (max(-spec.head_pan_limit, min(spec.head_pan_limit, pan)),
            max(spec.head_tilt_min, min(spec.head_tilt_max, tilt)))


def aim_heads(world: Any) -> None:
    """Turn every humanoid's head to the ball at the start of an episode (set-up, like placing
    the robots: play was going on before the episode and the robots were watching the ball;
    whether they see it is still up to their cameras)."""
    walk = world.walk
    if walk is None:
        return
    bx, by = world.ball_array()[0:2].tolist()
    robots = world.robot_array()
    for j, i in enumerate(walk.indices):
        spec = walk.specs[j]
        walk.pan[j], walk.tilt[j] = look_at(spec, head_camera(spec.camera).height,
                                            robots[i, 0:3].tolist(), bx, by)


def _compose(a: tuple[float, float, float], b: tuple[float, float, float]
             ) -> tuple[float, float, float]:
    """Body-frame displacement ``a`` followed by ``b`` (``b`` in the frame ``a`` ends in)."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])


class HeadController:
    """Aims a humanoid's head (pan and tilt targets [rad]).

    ``mode="scan"``: pan sweeps ``+-scan_pan`` sinusoidally with period ``scan_period`` [s]
    at a tilt that sees from about 0.4 m to 4 m. ``mode="auto"``: looks at the believed ball
    (centred in the image: pan its bearing, tilt ``atan(h / d)``) while the robot's own
    sighting of it is under ``ball_lost_after`` seconds old, or a team-mate's is; otherwise
    scans; and, when no landmark has been seen for ``landmark_period`` seconds and the ball
    is not coming at the robot, scans for ``glance`` seconds to find some (a ball starting to
    come at it ends the glance).
    """

    def __init__(self, spec: HumanoidRobotSpec, camera_height: float, mode: str = "auto",
                 scan_pan: float = math.radians(90.0), scan_period: float = 4.0,
                 ball_lost_after: float = 1.0, landmark_period: float = 3.0,
                 glance: float = 1.5) -> None:
        if mode not in ("auto", "scan"):
            raise ValueError(f"head mode must be 'auto' or 'scan', got {mode!r}")
        self.spec, self.h, self.mode = spec, camera_height, mode
        self.scan_pan = min(scan_pan, spec.head_pan_limit)
        self.scan_period = scan_period
        self.scan_tilt = min(max(math.radians(30.0), spec.head_tilt_min), spec.head_tilt_max)
        self.ball_lost_after = ball_lost_after
        self.landmark_period = landmark_period
        self.glance = glance
        self._glance_until = -math.inf

    def reset(self) -> None:
        self._glance_until = -math.inf

    def scan(self, now: float) -> tuple[float, float]:
        """The scan pattern at time ``now``."""
        return (self.scan_pan * math.sin(2.0 * math.pi * now / self.scan_period),
                self.scan_tilt)

    def targets(self, now: float, pose: np.ndarray, ball: np.ndarray | None,
                ball_age: float, landmark_age: float) -> tuple[float, float]:
        """Pan and tilt targets at ``now`` for a robot believing itself at ``pose`` (x, y,
        theta) and the ball at ``ball`` (x, y, vx, vy, or None), last seen ``ball_age``
        seconds ago, a landmark ``landmark_age`` seconds ago."""
        if self.mode == "scan" or ball is None:
            return self.scan(now)
        dx, dy = ball[0] - pose[0], ball[1] - pose[1]
        dist = math.hypot(dx, dy)
        coming = dist > 1e-6 and -(dx * ball[2] + dy * ball[3]) / dist > 0.3
        if coming:
            self._glance_until = -math.inf  # a ball coming at the robot ends a glance
        elif now < self._glance_until:
            return self.scan(now)
        elif landmark_age > self.landmark_period:
            self._glance_until = now + self.glance
            return self.scan(now)
        if ball_age > self.ball_lost_after:
            return self.scan(now)
        return look_at(self.spec, self.h, pose, ball[0], ball[1])


@dataclass
class _Line:
    """A sighting line: from ``origin`` at ``angle`` [rad], range [m] (NaN: bearing only),
    captured at ``stamp`` [s]."""

    stamp: float
    origin: tuple[float, float]
    angle: float
    range: float


class _Brain:
    """One humanoid's estimation stack (see the module docstring)."""

    def __init__(self, index: int, name: str, team: int, perception: HumanoidTeamPerception,
                 rng: np.random.Generator) -> None:
        self.i, self.name, self.team = index, name, team
        self.p = perception
        self.rng = rng
        cfg = perception.config
        self.kind = cfg.localization
        self.fusion = cfg.fusion
        if perception.pixels:
            from soccer_env.pixel_vision import BallImageTracker

            self.finder: Any = BallImageTracker(perception.camera, perception.ball_spec)
        else:
            self.finder = None
        self.tracker = (None if cfg.ball_tracker == "none" else ParticleBallTracker(
            rng, filter=cfg.ball_tracker, n_particles=100, accel_sigma=1.0,
            deceleration=perception.ball_spec.rolling_deceleration,
            lost_after=2.0, max_speed=_MAX_BALL_SPEED, reinit_after=2))

    def reset(self, state: WorldState) -> None:
        p = self.p
        start = state.robots[self.i, 0:3].copy()  # placed at a known pose
        self.pose = start.copy()
        self.loc = (KLDLocalizer(p.bounds, self.rng, p.kld_config, pose=start,
                                 pose_sigma=(0.05, 0.05, 0.05))
                    if self.kind == "kld" else None)
        self._loc_estimate = start
        self.odo: deque[tuple[float, tuple[float, float, float]]] = deque()
        self.gait_velocity = (0.0, 0.0, 0.0)
        self.own_line: _Line | None = None
        self.mate_lines: dict[str, _Line] = {}
        self.mate_poses: dict[int, tuple[float, np.ndarray, np.ndarray]] = {}
        for j in p.team_members[self.team]:
            if j != self.i:
                self.mate_poses[j] = (state.time, state.robots[j, 0:3].copy(), np.zeros(3))
        self.opponents = {j: [state.time, state.robots[j, 0:2].copy(), np.zeros(2)]
                          for j in range(p.n_robots) if p.teams[j] != self.team}
        if self.tracker is not None:
            self.tracker.reset()
        if self.finder is not None:
            self.finder.reset()
        self.points: deque[tuple[float, float, float]] = deque(maxlen=8)
        self.ball_seen = -math.inf  # capture time of the last own sighting
        self.ball_heard = -math.inf  # capture time of the last team sighting
        self.landmark_seen = state.time
        self.last_frame = state.time
        self.down = False  # fallen at the last update

    # ------------------------------------------------------------------------------------

    def odometry(self, t: float, d: tuple[float, float, float], truth: np.ndarray) -> None:
        """The walk engine's displacement over the step ending at ``t``."""
        if self.kind == "truth":
            self.pose = truth.copy()
            return
        if d == (0.0, 0.0, 0.0):
            return
        self.odo.append((t, d))
        if self.kind == "odometry":
            self.pose = self._moved(self.pose, d)
            self.odo.clear()

    @staticmethod
    def _moved(pose: np.ndarray, d: tuple[float, float, float]) -> np.ndarray:
        th = pose[2] + 0.5 * d[2]
        c, s = math.cos(th), math.sin(th)
        return np.array([pose[0] + c * d[0] - s * d[1], pose[1] + s * d[0] + c * d[1],
                         math.remainder(pose[2] + d[2], 2.0 * math.pi)])

    def _odometry_until(self, t: float) -> tuple[float, float, float]:
        """Compose and drop the odometry of the steps that ended by ``t``."""
        total = (0.0, 0.0, 0.0)
        while self.odo and self.odo[0][0] <= t + 1e-9:
            total = _compose(total, self.odo.popleft()[1])
        return total

    def _predict(self, d: tuple[float, float, float]) -> None:
        if d == (0.0, 0.0, 0.0) or self.loc is None:
            return
        # KLDLocalizer rotates the displacement by the mid-step heading; ``d`` is in the
        # start frame, so express it in the frame turned by half its rotation.
        c, s = math.cos(0.5 * d[2]), math.sin(0.5 * d[2])
        self.loc.predict((c * d[0] + s * d[1], -s * d[0] + c * d[1], d[2]))
        self._loc_estimate = self.loc.estimate()

    def stood_up(self, heading_sigma: float) -> None:
        """The robot got up, turned by an angle its odometry does not report (Gaussian,
        ``heading_sigma`` [rad]): spread the localization's headings by as much."""
        if self.loc is None or heading_sigma <= 0.0:
            return
        p = self.loc.particles
        turn = self.rng.normal(0.0, heading_sigma, len(p))
        p[:, 2] = np.remainder(p[:, 2] + turn + math.pi, 2.0 * math.pi) - math.pi
        self._loc_estimate = self.loc.estimate()

    def estimate_pose(self) -> np.ndarray:
        """The present pose estimate (localization plus the odometry not yet applied)."""
        if self.loc is None:
            return self.pose
        pose = self._loc_estimate
        for _, d in self.odo:
            pose = self._moved(pose, d)
        return pose

    # ------------------------------------------------------------------------------------

    def frame(self, f: HeadFrame) -> Message:
        """Process one of the robot's frames; return its broadcast."""
        p = self.p
        self.last_frame = f.t_delivered
        if self.loc is not None:
            self._predict(self._odometry_until(f.t_capture))
            kinds, ranges, bearings = landmark_sightings(f)
            if kinds:
                self.loc.update_kinds(kinds, ranges, bearings, p.landmark_table)
                self.landmark_seen = f.t_capture
            pose = self._loc_estimate = self.loc.estimate()
        else:
            pose = self.pose
            if any(math.isfinite(d[3]) for d in f.landmarks):
                self.landmark_seen = f.t_capture
        c, s = math.cos(pose[2]), math.sin(pose[2])
        # The ball: of several detections, the one nearest the present belief.
        line = None
        balls = f.balls
        if self.finder is not None and f.image is not None:  # find it in the image
            balls = self.finder.detect(f.image, float(pose[2]) + f.pan, f.tilt, f.pan)
        if balls:
            if len(balls) > 1:
                guess = self.ball_point(f.t_capture)
                if guess is not None:
                    gx, gy = guess[0] - pose[0], guess[1] - pose[1]
                    gb = math.atan2(-s * gx + c * gy, c * gx + s * gy)
                    balls = sorted(balls, key=lambda b: abs(math.remainder(b[4] - gb,
                                                                           2 * math.pi)))
            _u, _v, x, y, bearing = balls[0]
            line = _Line(f.t_capture, (float(pose[0]), float(pose[1])),
                         float(pose[2] + bearing), math.hypot(x, y))
            self.own_line = line
            self.ball_seen = f.t_capture
        for team, _u, _v, x, y, _b in f.robots:
            if team != self.team and math.isfinite(x):
                self._opponent(f.t_capture, pose[0] + c * x - s * y, pose[1] + s * x + c * y)
        self._fuse(f.t_capture)
        sighting = None if line is None else (*line.origin, line.angle, line.range)
        return Message(self.name, f.t_capture, (float(pose[0]), float(pose[1]),
                                                float(pose[2])), sighting)

    def message(self, m: Message, now: float) -> None:
        """A team-mate's broadcast arrived."""
        j = self.p.index_of[m.sender]
        prev = self.mate_poses.get(j)
        pose = np.array(m.pose)
        vel = np.zeros(3)
        if prev is not None and m.stamp - prev[0] >= _MIN_DIFF_GAP:
            vel = (pose - prev[1]) / (m.stamp - prev[0])
            vel[2] = math.remainder(pose[2] - prev[1][2], 2 * math.pi) / (m.stamp - prev[0])
        if prev is None or m.stamp >= prev[0]:
            self.mate_poses[j] = (m.stamp, pose, vel if prev is None or
                                  m.stamp - prev[0] >= _MIN_DIFF_GAP else prev[2])
        if m.sighting is not None and self.fusion != "own":
            x0, y0, angle, rng_ = m.sighting
            self.mate_lines[m.sender] = _Line(m.stamp, (x0, y0), angle, rng_)
            self.ball_heard = max(self.ball_heard, m.stamp)
            if now - self.last_frame > self.p.frame_gap:
                # No frames of its own (fallen, or its camera is late): the team's sightings
                # alone keep the belief going.
                self._fuse(m.stamp)

    def _opponent(self, t: float, x: float, y: float) -> None:
        best, dist = None, _TRACK_GATE
        for j, (_t, pos, _v) in self.opponents.items():
            d = math.hypot(pos[0] - x, pos[1] - y)
            if d < dist:
                best, dist = j, d
        if best is None:  # the stalest track takes it
            if not self.opponents:
                return
            best = min(self.opponents, key=lambda j: self.opponents[j][0])
        t0, pos, vel = self.opponents[best]
        new = np.array([x, y])
        if t - t0 >= _MIN_DIFF_GAP and dist < _TRACK_GATE:
            vel = (new - pos) / (t - t0)
        self.opponents[best] = [t, new, vel]

    # ------------------------------------------------------------------------------------

    def _fuse(self, t: float) -> None:
        """Fuse the lines available at the frame captured at ``t`` and feed the tracker."""
        window = self.p.fusion_window
        lines = []
        if self.own_line is not None and self.own_line.stamp == t:
            lines.append(self.own_line)
        if self.fusion != "own":
            lines += [ln for ln in self.mate_lines.values() if abs(ln.stamp - t) <= window]
        if not lines:
            return
        velocity = None
        if self.tracker is not None:
            est = self.tracker.estimate(t)
            if est is not None:
                velocity = est[2:4]
                speed = math.hypot(*velocity)
                if speed > _MAX_BALL_SPEED:  # never move lines by an impossible motion
                    velocity = velocity * (_MAX_BALL_SPEED / speed)
        weighting = "inverse" if self.fusion == "own" else self.fusion
        ranges = np.array([ln.range for ln in lines])
        known = ranges[np.isfinite(ranges)]
        p = self.p
        rel = max(0.05, p.range_per_metre * (float(known.max()) if len(known) else 1.0))
        try:
            fused = fuse_sightings(
                np.array([ln.origin for ln in lines]), np.array([ln.angle for ln in lines]),
                ranges, np.array([ln.stamp for ln in lines]), now=t, velocity=velocity,
                weighting=weighting, bearing_sigma=p.bearing_sigma, range_sigma_rel=rel)
        except ValueError:  # bearings only, no crossing: no position
            return
        point = fused.point
        x0, x1, y0, y1 = p.bounds
        if not (np.all(np.isfinite(point)) and x0 <= point[0] <= x1 and y0 <= point[1] <= y1):
            return  # no ball can be there (outside the walls)
        if self.tracker is not None:
            self.tracker.update(t, point, fused.cov + _MIN_SIGMA**2 * np.eye(2))
        self.points.append((t, float(point[0]), float(point[1])))

    def ball_point(self, t: float) -> np.ndarray | None:
        """The believed ball ``(x, y, vx, vy)`` at ``t`` (None if never seen); a prediction
        that would leave the walled area stops at the wall."""
        if self.tracker is not None:
            est = self.tracker.estimate(t)
            if est is None:
                return None
            x0, x1, y0, y1 = self.p.bounds
            if not (x0 <= est[0] <= x1 and y0 <= est[1] <= y1):
                est = np.array([min(x1, max(x0, est[0])), min(y1, max(y0, est[1])), 0.0, 0.0])
            return est
        if not self.points:
            return None
        t1, x1, y1 = self.points[-1]
        for t0, x0, y0 in reversed(self.points):
            if t1 - t0 >= _MIN_DIFF_GAP:
                return np.array([x1, y1, (x1 - x0) / (t1 - t0), (y1 - y0) / (t1 - t0)])
        return np.array([x1, y1, 0.0, 0.0])

    def belief(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """``ball`` (6,) and ``robots`` (N, 6) as this robot believes them at ``t``."""
        p = self.p
        ball = np.zeros(6)
        b = self.ball_point(t)
        if b is not None:
            ball[0:2], ball[3:5] = b[0:2], b[2:4]
        robots = np.zeros((p.n_robots, 6))
        pose = self.estimate_pose()
        gx, gy, gw = self.gait_velocity
        c, s = math.cos(pose[2]), math.sin(pose[2])
        robots[self.i] = (*pose, c * gx - s * gy, s * gx + c * gy, gw)
        for j, (_t, mpose, mvel) in self.mate_poses.items():
            robots[j, 0:3], robots[j, 3:6] = mpose, mvel
        for j, (_t, pos, vel) in self.opponents.items():
            robots[j, 0:2], robots[j, 3:5] = pos, vel
        return ball, robots


class HumanoidTeamPerception:
    """The estimation stacks of the humanoids ``observers`` of a world (of one or both
    teams; each team has its own radio).

    Args:
        config: the :class:`~soccer_env.perception.PerceptionConfig` (its ``camera``,
            ``radio``, ``localization``, ``fusion`` and ``ball_tracker``).
        field, ball: the world's field and ball.
        specs: every robot's model (radii; the observers' camera height and head limits).
        teams: every robot's team.
        names: every robot's name.
        observers: indices of the humanoids whose beliefs are modelled.
        camera: the head camera of the observers.
        radio: the team radio's link.
        head_mode: ``"auto"``, ``"scan"`` or ``"action"`` (see :data:`HEAD_MODES`).
    """

    def __init__(self, config: Any, field: FieldSpec, ball: BallSpec,
                 specs: Sequence[RobotSpec], teams: Sequence[int], names: Sequence[str],
                 observers: Sequence[int], camera: HeadCameraSpec, radio: RadioSpec,
                 head_mode: str = "auto") -> None:
        self.config = config
        self.field, self.ball_spec = field, ball
        self.specs = list(specs)
        self.teams = [int(t) for t in teams]
        self.names = list(names)
        self.index_of = {n: i for i, n in enumerate(self.names)}
        self.n_robots = len(self.teams)
        self.observers = list(observers)
        self.team_members = {t: [i for i in self.observers if self.teams[i] == t]
                             for t in (0, 1)}
        self.camera, self.radio_spec = camera, radio
        self.pixels = getattr(config, "detector", "geometric") == "pixels"
        if self.pixels:  # rendered images; the robots find the ball in them
            from soccer_env.pixel_vision import PixelHeadCamera

            self.sensor = PixelHeadCamera(camera, field, ball, self.specs, self.teams,
                                          self.observers)
        else:
            self.sensor = HeadCameraSensor(camera, field, ball, [s.radius for s in self.specs],
                                           self.teams, self.observers)
        positions, kinds = field_landmarks(field, camera.distinct_goals)
        table: dict[str, list] = {}
        for pos, kind in zip(positions, kinds):
            table.setdefault(kind, []).append(pos)
        self.landmark_table = {k: np.array(v) for k, v in table.items()}
        wx, wy = field.half_length + field.boundary, field.half_width + field.boundary
        self.bounds = (-wx, wx, -wy, wy)
        # Landmark noise as the camera makes it: a pixel or a tilt error e moves a ground
        # point at distance d by about d^2 e / h along the line of sight; bearings by the
        # pixel noise and the yaw sway. The sway's errors repeat from frame to frame (the
        # gait is periodic), so recovery waits for a deeper and longer drop of the likelihood
        # than the textbook rule.
        f_px = camera.camera.focal_px
        hum = [s for s in self.specs if s.kind == "humanoid"]
        sway_t = max((s.sway_tilt for s in hum), default=0.0)
        sway_p = max((s.sway_pan for s in hum), default=0.0)
        ang = math.hypot(sway_t, camera.pixel_sigma / f_px)
        self.kld_config = KLDConfig(
            min_particles=50, max_particles=2000,
            range_sigma=0.05, range_sigma_rel=0.05,
            range_sigma_quad=max(0.01, ang / camera.height),
            bearing_sigma=max(math.radians(1.0), math.hypot(sway_p, camera.pixel_sigma / f_px)),
            alpha_fast=0.1, recovery_ratio=0.2)
        self.fusion_window = ((_FUSION_WINDOW_FRAMES / camera.frame_rate
                               if camera.frame_rate else 0.05)
                              + radio.latency + radio.jitter)
        # The sightings' error model for the fusion: bearings off by the pixel noise and the
        # yaw sway; ranges (ground projections) off by about d^2 e / h for an angular error
        # e of the tilt (pixel noise and pitch sway), i.e. relatively by d e / h.
        self.bearing_sigma = max(math.radians(0.5), math.hypot(sway_p,
                                                               camera.pixel_sigma / f_px))
        self.range_per_metre = max(1e-3, ang / camera.height)
        #: Without an own frame for this long [s], team-mates' sightings are fused as they
        #: arrive.
        self.frame_gap = 1.5 / camera.frame_rate if camera.frame_rate else 0.05
        if head_mode not in HEAD_MODES:
            raise ValueError(f"head must be one of {list(HEAD_MODES)}, got {head_mode!r}")
        self.head_mode = head_mode
        self.heads = {i: HeadController(self.specs[i], camera.height,
                                        "scan" if head_mode == "scan" else "auto")
                      for i in self.observers}
        self._brains: dict[int, _Brain] = {}
        self._radios: dict[int, TeamRadio] = {}
        self._walk_index: dict[int, dict[int, int]] = {}

    # ------------------------------------------------------------------------------------

    def reset(self, state: WorldState, heads: HeadState, rng: np.random.Generator) -> None:
        """Start an episode at ``state`` (the robots' poses at the start are known)."""
        self._rngs = rng.spawn(len(self.observers) + 2)
        self._brains = {i: _Brain(i, self.names[i], self.teams[i], self, r)
                        for i, r in zip(self.observers, self._rngs)}
        self._radios = {}
        for t, members in self.team_members.items():
            if members:
                radio = TeamRadio(self.radio_spec, self._rngs[-1 - t])
                for i in members:
                    radio.join(self.names[i])
                self._radios[t] = radio
        for b in self._brains.values():
            b.reset(state)
        for h in self.heads.values():
            h.reset()
        self.time = state.time
        self._consume(self.sensor.reset(state, heads, self._rngs[-1]), state, None)

    def update(self, state: WorldState, heads: HeadState, walk: Any) -> None:
        """Advance to ``state``: odometry, frames, radio, fusion and tracking."""
        self.time = state.time
        self._consume(self.sensor.step(state, heads), state, walk)

    def _consume(self, frames: list[HeadFrame], state: WorldState, walk: Any) -> None:
        """The estimation of one step (the sensor simulation done): odometry, the frames,
        the radio."""
        now = state.time
        if walk is not None:
            pos = self._walk_index.get(id(walk))
            if pos is None:  # robot index -> position in the walk engine, once per world
                pos = self._walk_index[id(walk)] = {i: j for j, i in enumerate(walk.indices)}
            for i, b in self._brains.items():
                j = pos[i]
                b.odometry(now, walk.odometry[j], state.robots[i, 0:3])
                b.gait_velocity = tuple(walk.gait[j])
                radio = self._radios[b.team]
                radio.set_silent(b.name, walk.fallen[j])
                if b.down and not walk.fallen[j]:
                    b.stood_up(walk.specs[j].fall_heading_sigma)
                b.down = walk.fallen[j]
        for f in frames:
            b = self._brains[f.robot]
            msg = b.frame(f)
            self._radios[b.team].broadcast(msg, f.t_delivered)
        for t, radio in self._radios.items():
            for i in self.team_members[t]:
                b = self._brains[i]
                for m in radio.receive(b.name, now):
                    b.message(m, now)

    # ------------------------------------------------------------------------------------

    def belief(self, i: int, t: float) -> tuple[np.ndarray, np.ndarray]:
        """Robot ``i``'s belief at ``t``: ``ball`` (6,) and ``robots`` (N, 6)."""
        return self._brains[i].belief(t)

    def head_targets(self, i: int, now: float) -> tuple[float, float]:
        """Where robot ``i``'s head controller aims now (pan, tilt) [rad]."""
        b = self._brains[i]
        ball = b.ball_point(now)
        age = now - max(b.ball_seen, b.ball_heard)
        return self.heads[i].targets(now, b.estimate_pose(), ball, age,
                                     now - b.landmark_seen)

    def localization(self, i: int) -> KLDLocalizer | None:
        """Robot ``i``'s localization filter (None unless ``localization="kld"``)."""
        return self._brains[i].loc

    def tracker(self, i: int) -> ParticleBallTracker | None:
        """Robot ``i``'s ball tracker (None with ``ball_tracker="none"``)."""
        return self._brains[i].tracker
