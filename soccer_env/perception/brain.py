"""One humanoid's estimation stack (:class:`Brain`): odometry, its head-camera frames, the
team-mates' radio messages, Hough fusion and ball tracking, as described in
:mod:`soccer_env.perception.humanoid`.

A brain reads nothing of the team's pipeline that owns it but a :class:`BrainContext`: the
figures of the team, its sensors and its noise models, fixed for an episode, which
:class:`~soccer_env.perception.humanoid.HumanoidTeamPerception` hands to each of its brains.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from estimators import (
    INVERSE_VARIANCE,
    KLDConfig,
    LandmarkTable,
    SightingNoise,
    fuse_lines,
    weighting_power,
)
from estimators.fusion.hough import MIN_CROSSING_ANGLE
from soccer_env.perception.base import ball_status, sigmas
from soccer_env.perception.options import BALL_TRACKERS, FUSIONS, LOCALIZATIONS
from soccer_env.perception.sighting import (
    SightingLine,
    landmark_sightings,
    sighting_sigmas,
    sway_scale,
)
from soccer_env.presets import BallSpec, RobotSpec
from soccer_env.presets.sensors import HeadCameraSpec
from soccer_env.sensors.headcam import HeadFrame
from soccer_env.sensors.radio import Message
from soccer_env.state import BeliefQuality, BeliefSpread, WorldState

__all__ = ["Brain", "BrainContext"]
#: Measurement standard deviation floor of the ball tracker [m].
_MIN_SIGMA = 0.02

#: The least relative range error of a sighting (the fusion's floor of ``rel``).
_MIN_RANGE_SIGMA_REL = 0.05

#: The least relative range error of a sighting line the line tracker assumes: a standing
#: robot's ``kidsize-2012`` ball ranges are off by 0.6 % (0.8 m), 1.3 % (2.5 m) and 1.9 %
#: (3.8 m) standard deviation, the pixel noise alone (``tests/soccer_env/sensors/
#: test_headcam.py``, the standing robot's range test); 2 % covers them; walking adds the
#: sway's share (:func:`~soccer_env.perception.sighting.sighting_sigmas`).
_LINE_RANGE_SIGMA_REL = 0.02


#: A robot detection is associated with an opponent track within this distance [m].
_TRACK_GATE = 1.0


#: The fastest ball [m/s]: the tracked velocity that moves old sighting lines is capped at it.
_MAX_BALL_SPEED = 10.0


#: Raw and untracked velocities are differences of points at least this far apart [s].
_MIN_DIFF_GAP = 0.1


def _compose(a: tuple[float, float, float], b: tuple[float, float, float]
             ) -> tuple[float, float, float]:
    """Body-frame displacement ``a`` followed by ``b`` (``b`` in the frame ``a`` ends in)."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])


@dataclass(frozen=True)
class BrainContext:
    """What a :class:`Brain` reads of its team's perception: the options, the world's robots
    and the team's sensor and noise figures, fixed for an episode (built by
    :meth:`~soccer_env.perception.humanoid.HumanoidTeamPerception.reset`).

    Attributes:
        localization, fusion, ball_tracker: the options of the
            :class:`~soccer_env.perception.base.PerceptionConfig`.
        specs: every robot's model (a brain reads its own odometry noise figures).
        teams: every robot's team (0 blue, 1 yellow).
        index_of: robot index by name (the radio's senders).
        team_members: per team, the humanoids whose beliefs are modelled.
        ball_spec: the ball (its rolling deceleration, for the tracker).
        camera: the robots' head camera (for the ball finder).
        ball_finder: builds a robot's ball finder for its frame images
            (``ball_finder(camera, ball)``), or None: the frames carry ball detections.
        bounds: the walled area ``(x_min, x_max, y_min, y_max)`` [m].
        landmark_table: the field's landmarks by kind, for the localization.
        kld_config: the localization filter's configuration.
        pose_sigmas: the observers' pose errors the inverse-variance fusion weighs lines by,
            ``(position per axis [m], heading [rad])``.
        fusion_window: team-mates' sightings captured within this time of a frame [s] are
            fused with it.
        frame_gap: without an own frame for this long [s], team-mates' sightings are fused as
            they arrive.
        bearing_sigma: the sightings' bearing error [rad].
        range_per_metre: the sightings' relative range error per metre of range [1/m].
        coast_age: the oldest the latest fused sighting is while the ball is seen in every
            frame [s].
    """

    localization: str
    fusion: str
    ball_tracker: str
    specs: Sequence[RobotSpec]
    teams: Sequence[int]
    index_of: Mapping[str, int]
    team_members: Mapping[int, Sequence[int]]
    ball_spec: BallSpec
    camera: HeadCameraSpec
    ball_finder: Callable[..., Any] | None
    bounds: tuple[float, float, float, float]
    landmark_table: LandmarkTable
    kld_config: KLDConfig
    pose_sigmas: tuple[float, float]
    fusion_window: float
    frame_gap: float
    bearing_sigma: float
    range_per_metre: float
    coast_age: float

    @property
    def n_robots(self) -> int:
        """The number of robots of the world."""
        return len(self.teams)


class Brain:
    """One humanoid's estimation stack (see the module docstring).

    Args:
        index, name, team: the robot's index, name and team.
        context: what it reads of its team's perception.
        rng: its generator (localization, tracker, the turns of getting up).
    """

    def __init__(self, index: int, name: str, team: int, context: BrainContext,
                 rng: np.random.Generator) -> None:
        self.i, self.name, self.team = index, name, team
        self.context = context
        self.rng = rng
        self.kind = context.localization
        self.fusion = context.fusion
        weighting = FUSIONS[context.fusion]
        #: The fusion's weighting power (``K = 1 / L^power``; the inverse-variance weighting
        #: starts from ``1 / L``) and, for the inverse-variance weighting, the observers'
        #: pose errors ``(position [m], heading [rad])`` (else None).
        self.power = weighting_power(weighting)
        self.pose_sigmas = (context.pose_sigmas if weighting == INVERSE_VARIANCE
                            else None)
        finder = context.ball_finder
        self.finder: Any = None if finder is None else finder(context.camera,
                                                               context.ball_spec)
        tracker = BALL_TRACKERS[context.ball_tracker]
        noise = SightingNoise(context.bearing_sigma, context.range_per_metre,
                              _LINE_RANGE_SIGMA_REL, *context.pose_sigmas, _MIN_SIGMA)
        self.tracker = (None if tracker is None else tracker(
            rng, context.ball_spec, _MAX_BALL_SPEED, noise,
            tuple(context.team_members[team]) or (index,)))
        #: Whether the tracker takes the sighting lines one by one (else fused points).
        self.takes_lines = bool(getattr(self.tracker, "takes_lines", False))
        self._localizer = LOCALIZATIONS[self.kind]

    def reset(self, state: WorldState) -> None:
        p = self.context
        start = state.robots[self.i, 0:3].copy()  # placed at a known pose
        self.pose = start.copy()
        self.loc = (None if self._localizer is None
                    else self._localizer(p.bounds, self.rng, p.kld_config, start))
        self.loc_estimate = start
        self.odo: deque[tuple[float, tuple[float, float, float]]] = deque()
        self.gait_velocity = (0.0, 0.0, 0.0)
        self.own_line: SightingLine | None = None
        self.mate_lines: dict[str, SightingLine] = {}
        self.mate_poses: dict[int, tuple[float, np.ndarray, np.ndarray]] = {}
        # The other robots' rows of the belief (pose and velocity of the team-mates, position
        # and velocity of the opponents), kept as they change.
        self._others = np.zeros((p.n_robots, 6))
        for j in p.team_members[self.team]:
            if j != self.i:
                self.mate_poses[j] = (state.time, state.robots[j, 0:3].copy(), np.zeros(3))
                self._others[j, 0:3] = state.robots[j, 0:3]
        self.opponents = {j: [state.time, state.robots[j, 0:2].copy(), np.zeros(2)]
                          for j in range(p.n_robots) if p.teams[j] != self.team}
        for j in self.opponents:
            self._others[j, 0:2] = state.robots[j, 0:2]
        # Without a tracker, the ball point of the latest fused points (in a 1-tuple, None
        # until asked for after a fusion); the present pose estimate (None until asked for
        # after odometry or the localization moved it).
        self._ball_memo: tuple[np.ndarray | None] | None = None
        self._pose_memo: np.ndarray | None = None
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
        # The latest fusion: its capture time, how many robots' lines it used, its
        # covariance.
        self.fused_at = -math.inf
        self.fused_lines = 0
        self.fused_cov: np.ndarray | None = None
        # Dead reckoning's variance: position per axis [m^2], heading [rad^2].
        self.odo_var = [0.0, 0.0]

    # ------------------------------------------------------------------------------------

    def odometry(self, t: float, d: tuple[float, float, float], truth: np.ndarray) -> None:
        """The walk engine's displacement over the step ending at ``t``."""
        if self.kind == "truth":
            self.pose = truth.copy()
            self._pose_memo = None
            return
        if d == (0.0, 0.0, 0.0):
            return
        self._pose_memo = None
        self.odo.append((t, d))
        if self.kind == "odometry":
            self.pose = self._moved(self.pose, d)
            self.odo.clear()
            self._dead_reckoning_variance(d)

    def _dead_reckoning_variance(self, d: tuple[float, float, float]) -> None:
        """Grow the dead reckoning's variance by the step ``d`` with the walk engine's
        odometry noise figures (which a team calibrates): per axis ``(s_t |d_xy|)^2 / 2`` of
        relative translation error, ``(slip d_theta)^2 / 2`` of sideways slip and
        ``var_theta |d_xy|^2 / 2`` from the heading already wrong; heading
        ``(s_r d_theta)^2``. Errors drawn per gait step are treated as drawn per control step
        (the same variance per metre walked)."""
        spec = self.context.specs[self.i]
        dist2 = d[0] * d[0] + d[1] * d[1]
        var_xy, var_th = self.odo_var
        var_xy += 0.5 * (spec.odometry_trans_sigma**2 * dist2
                         + (spec.odometry_turn_slip * d[2]) ** 2 + var_th * dist2)
        var_th += (spec.odometry_rot_sigma * d[2]) ** 2
        self.odo_var = [var_xy, var_th]

    @staticmethod
    def _moved(pose: np.ndarray, d: tuple[float, float, float]) -> np.ndarray:
        th = pose[2] + 0.5 * d[2]
        c, s = math.cos(th), math.sin(th)
        return np.array([pose[0] + c * d[0] - s * d[1], pose[1] + s * d[0] + c * d[1],
                         math.remainder(pose[2] + d[2], 2.0 * math.pi)])

    def odometry_until(self, t: float) -> tuple[float, float, float]:
        """Compose and drop the odometry of the steps that ended by ``t``."""
        total = (0.0, 0.0, 0.0)
        self._pose_memo = None
        while self.odo and self.odo[0][0] <= t + 1e-9:
            total = _compose(total, self.odo.popleft()[1])
        return total

    def move_localization(self, d: tuple[float, float, float]) -> None:
        """Move the localization filter by the odometry ``d`` (``dx, dy, dtheta``, body frame
        at its start); its estimate is kept in :attr:`loc_estimate`."""
        if d == (0.0, 0.0, 0.0) or self.loc is None:
            return
        # KLDLocalizer rotates the displacement by the mid-step heading; ``d`` is in the
        # start frame, so express it in the frame turned by half its rotation.
        c, s = math.cos(0.5 * d[2]), math.sin(0.5 * d[2])
        self.loc.predict((c * d[0] + s * d[1], -s * d[0] + c * d[1], d[2]))
        self.loc_estimate = self.loc.estimate()
        self._pose_memo = None

    def stood_up(self, heading_sigma: float) -> None:
        """The robot got up, turned by an angle its odometry does not report (Gaussian,
        ``heading_sigma`` [rad]): spread the localization's headings by as much."""
        if self.loc is None or heading_sigma <= 0.0:
            return
        p = self.loc.particles
        turn = self.rng.normal(0.0, heading_sigma, len(p))
        p[:, 2] = np.remainder(p[:, 2] + turn + math.pi, 2.0 * math.pi) - math.pi
        self.loc_estimate = self.loc.estimate()
        self._pose_memo = None

    def estimate_pose(self) -> np.ndarray:
        """The present pose estimate (localization plus the odometry not yet applied)."""
        if self.loc is None:
            return self.pose
        if not self.odo:
            return self.loc_estimate
        if self._pose_memo is None:
            # _moved step by step, in plain floats (the same roundings as on the array).
            x, y, theta = self.loc_estimate.tolist()
            for _, d in self.odo:
                th = theta + 0.5 * d[2]
                c, s = math.cos(th), math.sin(th)
                x, y, theta = (x + c * d[0] - s * d[1], y + s * d[0] + c * d[1],
                               math.remainder(theta + d[2], 2.0 * math.pi))
            self._pose_memo = np.array([x, y, theta])
        return self._pose_memo.copy()

    # ------------------------------------------------------------------------------------

    def frame(self, f: HeadFrame) -> Message:
        """Process one of the robot's frames; return its broadcast."""
        p = self.context
        self.last_frame = f.t_delivered
        if self.loc is not None:
            self.move_localization(self.odometry_until(f.t_capture))
            kinds, ranges, bearings = landmark_sightings(f)
            if kinds:
                self.loc.update_sightings(kinds, ranges, bearings, p.landmark_table)
                self.landmark_seen = f.t_capture
            pose = self.loc_estimate = self.loc.estimate()
            self._pose_memo = None
        else:
            pose = self.pose
            if any(math.isfinite(d[3]) for d in f.landmarks):
                self.landmark_seen = f.t_capture
        px, py, pth = pose.tolist()  # plain floats: the same roundings as the array's
        c, s = math.cos(pth), math.sin(pth)
        # The ball: of several detections, the one nearest the present belief.
        line = None
        balls = f.balls
        if self.finder is not None and f.image is not None:  # find it in the image
            balls = self.finder.detect(f.image, pth + f.pan, f.tilt, f.pan)
        if balls:
            if len(balls) > 1:
                guess = self.ball_point(f.t_capture)
                if guess is not None:
                    gx, gy = guess[0] - px, guess[1] - py
                    gb = math.atan2(-s * gx + c * gy, c * gx + s * gy)
                    balls = sorted(balls, key=lambda b: abs(math.remainder(b[4] - gb,
                                                                           2 * math.pi)))
            _u, _v, x, y, bearing = balls[0]
            # (Its sway only matters to a tracker that weighs each line.)
            line = SightingLine(f.t_capture, (px, py), float(pth + bearing), math.hypot(x, y),
                                sway_scale(p.specs[self.i], self.gait_velocity)
                                if self.takes_lines else 1.0)
            self.own_line = line
            self.ball_seen = f.t_capture
        for team, _u, _v, x, y, _b in f.robots:
            if team != self.team and math.isfinite(x):
                self._opponent(f.t_capture, px + c * x - s * y, py + s * x + c * y)
        if self.takes_lines:
            if line is not None:
                self._feed(line, self.i)
        else:
            self._fuse(f.t_capture)
        sighting = None if line is None else (*line.origin, line.angle, line.range)
        return Message(self.name, f.t_capture, (px, py, pth), sighting,
                       1.0 if line is None else line.sway)

    def message(self, m: Message, now: float) -> None:
        """A team-mate's broadcast arrived."""
        j = self.context.index_of[m.sender]
        prev = self.mate_poses.get(j)
        if prev is None or m.stamp >= prev[0]:
            pose = np.array(m.pose)
            if prev is None:
                vel = np.zeros(3)
            elif m.stamp - prev[0] >= _MIN_DIFF_GAP:
                # The finite difference, the heading's wrapped (in plain floats).
                span = m.stamp - prev[0]
                (x, y, theta), (x0, y0, theta0) = m.pose, prev[1].tolist()
                vel = np.array([(x - x0) / span, (y - y0) / span,
                                math.remainder(theta - theta0, 2 * math.pi) / span])
            else:
                vel = prev[2]
            self.mate_poses[j] = (m.stamp, pose, vel)
            row = self._others[j]
            row[0:3] = pose
            row[3:6] = vel
        if m.sighting is not None and self.fusion != "own":
            x0, y0, angle, rng_ = m.sighting
            line = self.mate_lines[m.sender] = SightingLine(m.stamp, (x0, y0), angle, rng_, m.sway)
            self.ball_heard = max(self.ball_heard, m.stamp)
            if self.takes_lines:
                self._feed(line, j)
            elif now - self.last_frame > self.context.frame_gap:
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
        row = self._others[best]
        row[0:2] = new
        row[3:5] = vel

    # ------------------------------------------------------------------------------------

    def _feed(self, line: SightingLine, observer: int) -> None:
        """Give a line-taking tracker one sighting line of robot ``observer`` (this robot's
        own, or a team-mate's); a line from the camera's foot (range 0) has no direction to
        weigh and is left out."""
        r = line.range
        if r <= 0.0:
            return
        spec = self.context.specs[observer]
        sb, k = sighting_sigmas(self.context.camera, line.sway * spec.sway_pan,
                                line.sway * spec.sway_tilt)
        self.tracker.line(line.stamp, line.origin[0], line.origin[1], line.angle, r,
                          observer == self.i, observer, sb, k)
        self.fused_at, self.fused_lines = max(self.fused_at, line.stamp), 1

    def _fuse(self, t: float) -> None:
        """Fuse the lines available at the frame captured at ``t`` and feed the tracker."""
        window = self.context.fusion_window
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
                _, _, vx, vy = est.tolist()
                speed = math.hypot(vx, vy)
                if speed > _MAX_BALL_SPEED:  # never move lines by an impossible motion
                    k = _MAX_BALL_SPEED / speed
                    vx, vy = vx * k, vy * k
                velocity = (vx, vy)
        ranges = [ln.range for ln in lines]
        known = [r for r in ranges if math.isfinite(r)]
        if min(known, default=1.0) <= 0.0:
            return  # a sighting at the camera's foot: no line to weigh
        p = self.context
        rel = max(_MIN_RANGE_SIGMA_REL, p.range_per_metre * (max(known) if known else 1.0))
        try:
            fused = fuse_lines(
                [list(ln.origin) for ln in lines], [ln.angle for ln in lines], ranges,
                self.power, p.bearing_sigma, rel, MIN_CROSSING_ANGLE,
                [ln.stamp for ln in lines], t, velocity, pose_sigmas=self.pose_sigmas)
        except ValueError:  # bearings only, no crossing: no position
            return
        point = fused.point
        px, py = point.tolist()
        # (fuse_lines builds an exactly symmetric covariance, as the tracker takes it.) The
        # floor's variance on the diagonal, + 0.0 off it (as adding the matrix did: -0.0
        # becomes 0.0).
        (c00, c01), (c10, c11) = fused.cov.tolist()
        floor = _MIN_SIGMA**2
        cov = np.array([[c00 + floor, c01 + 0.0], [c10 + 0.0, c11 + floor]])
        x0, x1, y0, y1 = p.bounds
        if not (math.isfinite(px) and math.isfinite(py) and math.isfinite(c00 + floor)
                and math.isfinite(c01) and math.isfinite(c10) and math.isfinite(c11 + floor)
                and x0 <= px <= x1 and y0 <= py <= y1):
            return  # no ball can be there (outside the walls), or a degenerate fusion
        self._ball_memo = None
        if self.tracker is not None:
            self.tracker.update_fused(t, point, cov)
        self.points.append((t, px, py))
        self.fused_at, self.fused_lines, self.fused_cov = t, len(lines), cov

    def ball_point(self, t: float) -> np.ndarray | None:
        """The believed ball ``(x, y, vx, vy)`` at ``t`` (None if never seen); a prediction
        that would leave the walled area stops at the wall. A new array each call (the
        tracker keeps its estimate at the latest time asked for; without a tracker the
        latest fused points' is kept until the next fusion)."""
        if self.tracker is not None:
            est = self.tracker.estimate(t)
            if est is None:
                return None
            x0, x1, y0, y1 = self.context.bounds
            if not (x0 <= est[0] <= x1 and y0 <= est[1] <= y1):
                est = np.array([min(x1, max(x0, est[0])), min(y1, max(y0, est[1])), 0.0, 0.0])
            return est
        if self._ball_memo is None:
            self._ball_memo = (self._fused_point(),)
        b = self._ball_memo[0]
        return None if b is None else b.copy()

    def _fused_point(self) -> np.ndarray | None:
        """The latest fused point with the velocity of the latest two at least
        ``_MIN_DIFF_GAP`` apart (zero without such a pair); None before the first."""
        if not self.points:
            return None
        t1, x1, y1 = self.points[-1]
        for t0, x0, y0 in reversed(self.points):
            if t1 - t0 >= _MIN_DIFF_GAP:
                return np.array([x1, y1, (x1 - x0) / (t1 - t0), (y1 - y0) / (t1 - t0)])
        return np.array([x1, y1, 0.0, 0.0])

    def quality(self, t: float, now: float) -> BeliefQuality:
        """How sure the belief at ``t`` is (ages at ``now``): the tracker's covariance and
        track state (with ``ball_tracker="none"``: the latest fusion's covariance and, for
        the velocity of two fused points ``gap`` apart, ``sqrt(2) sigma / gap``), the own
        pose's spread (the localization's particles, dead reckoning's grown variance, 0 for
        the oracle); other robots' spreads are not modelled (``inf``)."""
        p = self.context
        tracker = self.tracker
        if tracker is not None:
            sigma, sigma_v = sigmas(tracker.covariance(t))
            last, since = tracker.last_fused, tracker.since_start
            lost_after = tracker.lost_after if tracker.lost_after is not None else math.inf
        else:
            last, since, lost_after = self.fused_at, len(self.points), 2.0
            sigma = sigma_v = math.inf
            if self.fused_cov is not None:
                sigma = math.sqrt(0.5 * float(np.trace(self.fused_cov)))
                t1 = self.points[-1][0]
                gaps = [t1 - t0 for t0, _, _ in self.points if t1 - t0 >= _MIN_DIFF_GAP]
                if gaps:
                    sigma_v = math.sqrt(2.0) * sigma / min(gaps)
        fused_age = now - last
        status = ball_status(fused_age, p.coast_age, since, lost_after)
        spread = np.full((p.n_robots, 2), math.inf)
        if self.loc is not None:
            spread[self.i] = self.loc.pose_sigma()
        elif self.kind == "truth":
            spread[self.i] = 0.0
        else:
            spread[self.i] = (math.sqrt(self.odo_var[0]), math.sqrt(self.odo_var[1]))
        line = self.own_line
        measured = (None if line is None or not math.isfinite(line.range) else np.array(
            [line.origin[0] + line.range * math.cos(line.angle),
             line.origin[1] + line.range * math.sin(line.angle)]))
        return BeliefQuality(sigma, sigma_v, now - self.ball_seen, status, spread, fused_age,
                             self.fused_lines if status < 3 else 0, measured)

    def spread(self, t: float) -> BeliefSpread:
        """How this robot's belief at ``t`` [s] is spread, for drawing (reads, never changes,
        its filters):

        * ball: the tracker's covariance of ``(x, y)`` predicted to ``t`` (with
          ``ball_tracker="none"``, the latest fusion's), None before the first;
        * its own position: the localization particles' weighted covariance (full ``2 x 2``);
          for dead reckoning ``var I`` with its grown per-axis variance (a circle); zero for
          the oracle; the other robots' spreads are not modelled (NaN);
        * the tracker's particles, moved by the mean's predicted displacement from the
          filter's time to ``t``, and the localization's particles (at its latest frame).
        """
        p = self.context
        tracker = self.tracker
        ball = particles = None
        if tracker is not None:
            cov = tracker.covariance(t)
            if cov is not None:
                ball = np.array(cov[0:2, 0:2], dtype=np.float64)
                particles = tracker.particles[:, 0:2]
                now, then = tracker.estimate(t), tracker.estimate(tracker.time)
                particles += (now - then)[0:2]
        elif self.fused_cov is not None:
            ball = self.fused_cov.copy()
        robots = np.full((p.n_robots, 2, 2), np.nan)
        poses = None
        if self.loc is not None:
            w, xy = self.loc.weights, self.loc.particles[:, 0:2]
            d = xy - w @ xy
            robots[self.i] = (d * w[:, None]).T @ d
            poses = self.loc.particles.copy()
        elif self.kind == "truth":
            robots[self.i] = 0.0
        else:
            robots[self.i] = self.odo_var[0] * np.eye(2)
        return BeliefSpread(ball, robots, particles, poses, self.i)

    def belief(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """``ball`` (6,) and ``robots`` (N, 6) as this robot believes them at ``t``."""
        b = self.ball_point(t)
        if b is None:
            ball = np.zeros(6)
        else:
            bx, by, bvx, bvy = b.tolist()
            ball = np.array([bx, by, 0.0, bvx, bvy, 0.0])
        robots = self._others.copy()
        x, y, theta = self.estimate_pose().tolist()
        gx, gy, gw = self.gait_velocity
        c, s = math.cos(theta), math.sin(theta)
        robots[self.i] = (x, y, theta, c * gx - s * gy, s * gx + c * gy, gw)
        return ball, robots

