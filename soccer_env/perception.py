"""Perception: what a team believes about the world, fed to the observation builder.

Three observation modes share one observation layout:

* ``"truth"``: the oracle, the true state itself;
* ``"raw"``: the latest delayed detections of the overhead vision, unfiltered (positions as
  last seen; velocities as the difference of the last two sightings);
* ``"perceived"``: the estimation stack's belief: the ball tracker chosen by
  ``ball_filter`` (paper 002's EKF by default) and batched robot pose filters, fed with the
  vision's frames by capture time and predicted to the present plus the actuation latency,
  so that the policy acts on where things will be when its command takes effect.

``perception=`` chooses the vision preset (:data:`soccer_env.vision.VISION`), which also sets
the actuation latency and command loss that apply in every mode, and the ball filter. Its
default is ``"ideal"`` for ``obs_mode="truth"`` and ``"realistic"`` otherwise.

Humanoid robots see through their head cameras instead (:mod:`soccer_env.humanoid_perception`):
``perception=`` then names a head-camera preset (:data:`soccer_env.headcam.HEAD_CAMERAS`,
default the robot preset's camera) or gives ``camera``, ``radio``, ``localization``, ``fusion``
and ``ball_tracker``; their commands reach the walk engine on board, without latency or loss.

Every pipeline returns two beliefs per step: the one the observation is built from (predicted
ahead by the actuation latency) and the one at the present time, reported in
``info["estimate"]`` with the keys of ``info["truth"]`` so that errors can be measured.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple, Protocol

import numpy as np

from estimators import MIN_SIGMA_XY, BallFilterConfig, BallTracker, LeastSquaresBall, RobotTracker
from soccer_env.headcam import HEAD_CAMERAS, HeadCameraSpec, head_camera
from soccer_env.humanoid_perception import BALL_TRACKERS, FUSIONS, LOCALIZATIONS
from soccer_env.presets import BallSpec, FieldSpec, SSLRobotSpec
from soccer_env.radio import RADIO_PRESETS, RadioSpec
from soccer_env.state import WorldState
from soccer_env.vision import VISION, DetectionFrame, OverheadVision, VisionSpec, vision

__all__ = ["Belief", "Perception", "PerceptionConfig", "TruthPerception", "RawPerception",
           "FilteredPerception", "MatchPerception", "OBS_MODES", "BALL_FILTERS",
           "make_perception", "ball_filter_config"]

#: Observation modes.
OBS_MODES = ("truth", "raw", "perceived")
#: Where detections come from: the sensor models, or image trackers on rendered frames.
DETECTORS = {
    "geometric": "the sensor model's noisy detections",
    "pixels": "rendered camera images tracked by paper 003's mean-shift particle filters "
              "(overhead) and paper 004's Kalman-started mean shift (head cameras)",
}

#: Ball filter configurations of ``obs_mode="perceived"``.
BALL_FILTERS = {
    "kf": "constant-velocity Kalman filter fed arrival times (no latency compensation), "
          "no gating",
    "kf-comp": "the same with latency compensation",
    "ekf": "paper 002's friction EKF (analytic Jacobian), latency compensation, eq. 19 "
           "collision-aware noise, gating and reset on kicks (default)",
    "ekf-improved": "paper 002's improved EKF (Runge-Kutta propagation, F = M), otherwise "
                    "as 'ekf'",
    "ekf-2phase": "'ekf' with the two-phase sliding/rolling model after detected kicks",
    "ls": "paper 002's least-squares predictor (line fit to the last 6 detections)",
}


class Belief(NamedTuple):
    """A belief laid out like :class:`~soccer_env.state.WorldState`'s arrays: ``ball`` (6,)
    ``x, y, z, vx, vy, vz`` and ``robots`` (N, 6) ``x, y, theta, vx, vy, omega``, at
    ``time``."""

    time: float
    ball: np.ndarray
    robots: np.ndarray


class Perception(Protocol):
    """One perception pipeline (shared by both teams of a match)."""

    vision_spec: VisionSpec

    def reset(self, state: WorldState, rng: np.random.Generator) -> tuple[Any, Any]:
        """Start an episode at ``state``; return ``(belief for the observation, belief now)``."""
        ...

    def update(self, state: WorldState) -> tuple[Any, Any]:
        """Advance to ``state``; return ``(belief for the observation, belief now)``."""
        ...


@dataclass(frozen=True)
class PerceptionConfig:
    """What a team perceives with.

    SSL robots (overhead vision):

    Attributes:
        vision: a :class:`~soccer_env.vision.VisionSpec` (or preset name).
        ball_filter: one of :data:`BALL_FILTERS` (used by ``obs_mode="perceived"``).
        detector: ``"geometric"`` (the sensor model's detections) or ``"pixels"`` (rendered
            images tracked by paper 003's mean-shift particle filters,
            :mod:`soccer_env.pixel_vision`; needs the ``pixels`` extra).

    Humanoids (head cameras, :mod:`soccer_env.humanoid_perception`):

    Attributes:
        camera: a :class:`~soccer_env.headcam.HeadCameraSpec`, a preset name, or None for the
            robot preset's camera.
        radio: the team radio, a :class:`~soccer_env.radio.RadioSpec` or preset name.
        localization: one of :data:`~soccer_env.humanoid_perception.LOCALIZATIONS`.
        fusion: one of :data:`~soccer_env.humanoid_perception.FUSIONS`.
        ball_tracker: one of :data:`~soccer_env.humanoid_perception.BALL_TRACKERS`.
    """

    vision: VisionSpec
    ball_filter: str = "ekf"
    detector: str = "geometric"
    camera: HeadCameraSpec | str | None = None
    radio: RadioSpec | str = "zigbee"
    localization: str = "kld"
    fusion: str = "inverse"
    ball_tracker: str = "mfbpf"

    def __post_init__(self) -> None:
        if isinstance(self.vision, str):
            object.__setattr__(self, "vision", vision(self.vision))
        elif not isinstance(self.vision, VisionSpec):
            raise TypeError(f"perception vision must be a preset name or a VisionSpec, got "
                            f"{type(self.vision).__name__}")
        if self.ball_filter not in BALL_FILTERS:
            raise ValueError(f"ball_filter must be one of {list(BALL_FILTERS)}, got "
                             f"{self.ball_filter!r}")
        if self.detector not in DETECTORS:
            raise ValueError(f"detector must be one of {list(DETECTORS)}, got "
                             f"{self.detector!r}")
        if isinstance(self.camera, str):
            object.__setattr__(self, "camera", head_camera(self.camera))
        elif self.camera is not None and not isinstance(self.camera, HeadCameraSpec):
            raise TypeError(f"perception camera must be a head-camera preset name, a "
                            f"HeadCameraSpec or None, got {type(self.camera).__name__}")
        if isinstance(self.radio, str):
            if self.radio not in RADIO_PRESETS:
                raise ValueError(f"radio must be one of {sorted(RADIO_PRESETS)} or a "
                                 f"RadioSpec, got {self.radio!r}")
            object.__setattr__(self, "radio", RADIO_PRESETS[self.radio])
        elif not isinstance(self.radio, RadioSpec):
            raise TypeError(f"perception radio must be a preset name or a RadioSpec, got "
                            f"{type(self.radio).__name__}")
        for name, allowed in (("localization", LOCALIZATIONS), ("fusion", FUSIONS),
                              ("ball_tracker", BALL_TRACKERS)):
            if getattr(self, name) not in allowed:
                raise ValueError(f"{name} must be one of {list(allowed)}, got "
                                 f"{getattr(self, name)!r}")

    @classmethod
    def create(cls, value: Any, obs_mode: str, kind: str = "ssl") -> PerceptionConfig:
        """From ``perception=``: None (``"ideal"`` vision for truth, else ``"realistic"``),
        a vision preset name or :class:`VisionSpec` (for humanoids, ``kind="humanoid"``: a
        head-camera preset name or :class:`~soccer_env.headcam.HeadCameraSpec`), a mapping of
        this class's fields, or an instance."""
        default_vision = "ideal" if obs_mode == "truth" else "realistic"
        if value is None:
            return cls(vision(default_vision))
        if isinstance(value, cls):
            return value
        if kind == "humanoid" and isinstance(value, (str, HeadCameraSpec)):
            if isinstance(value, str) and value not in HEAD_CAMERAS:
                raise ValueError(f"unknown head-camera preset {value!r} for humanoid "
                                 f"perception; known: {sorted(HEAD_CAMERAS)}")
            return cls(vision(default_vision), camera=value)
        if isinstance(value, (str, VisionSpec)):
            if isinstance(value, str) and value not in VISION:
                raise ValueError(f"unknown vision preset {value!r}; known: {sorted(VISION)}")
            return cls(vision(value))
        if isinstance(value, Mapping):
            allowed = {f.name for f in dataclasses.fields(cls)}
            unknown = sorted(set(value) - allowed)
            if unknown:
                raise ValueError(f"unknown perception key(s) {unknown}; allowed: "
                                 f"{sorted(allowed)}")
            return cls(**{"vision": default_vision if kind == "humanoid" else "realistic",
                          **value})
        raise TypeError(f"perception must be a preset name, a VisionSpec or HeadCameraSpec, a "
                        f"mapping or a PerceptionConfig, got {type(value).__name__}")


def ball_filter_config(name: str, ball: BallSpec, spec: VisionSpec
                       ) -> tuple[BallFilterConfig | None, bool]:
    """The :class:`~estimators.BallFilterConfig` of ball filter ``name`` for this ball and
    sensor (None for ``"ls"``), and whether it is fed capture times (latency compensation).

    The filters assume the sensor's noise (at least 1 mm) and the ball's rolling
    deceleration; the other parameters are paper 002's.
    """
    sigma = max(spec.ball_sigma, MIN_SIGMA_XY)
    if name == "ls":
        return None, True
    if name in ("kf", "kf-comp"):
        cfg = BallFilterConfig(deceleration=0.0, sigma_xy=sigma, collision_noise=False,
                               gate=None, reset_after=None)
        return cfg, name == "kf-comp"
    two_phase = (ball.sliding_deceleration, ball.k_switch) if name == "ekf-2phase" else None
    propagation = "rk" if name == "ekf-improved" else "jacobian"
    return BallFilterConfig(deceleration=ball.rolling_deceleration, propagation=propagation,
                            sigma_xy=sigma, two_phase=two_phase), True


class TruthPerception:
    """The oracle of ``obs_mode="truth"``: the belief is the true state itself."""

    def __init__(self, config: PerceptionConfig) -> None:
        self.vision_spec = config.vision

    def reset(self, state: WorldState, rng: np.random.Generator):
        return state, state

    def update(self, state: WorldState):
        return state, state


class _VisionPerception:
    """Shared part of the pipelines fed by the overhead vision."""

    def __init__(self, config: PerceptionConfig, field: FieldSpec, robot: SSLRobotSpec,
                 ball: BallSpec, n_robots: int, teams: Sequence[int] | None = None,
                 robots: Sequence[Any] | None = None) -> None:
        self.config = config
        self.vision_spec = config.vision
        if config.detector == "pixels":
            from soccer_env.pixel_vision import PixelVision

            self.sensor = PixelVision(config.vision, field, robots or [robot] * n_robots, ball,
                                      teams if teams is not None else [0] * n_robots)
        else:
            self.sensor = OverheadVision(config.vision, field, robot, ball, n_robots)
        self.n_robots = n_robots

    def reset(self, state: WorldState, rng: np.random.Generator):
        self._clear()
        self._consume(self.sensor.reset(state, rng), state.time)
        return self._beliefs(state.time)

    def update(self, state: WorldState):
        self._consume(self.sensor.step(state), state.time)
        return self._beliefs(state.time)

    def _clear(self) -> None:
        raise NotImplementedError

    def _consume(self, frames: list[DetectionFrame], now: float) -> None:
        raise NotImplementedError

    def _beliefs(self, now: float):
        raise NotImplementedError


class RawPerception(_VisionPerception):
    """``obs_mode="raw"``: the latest delayed detections, no filtering.

    The ball is its most recent detection (of several in a frame, the one nearest the previous
    raw ball); a robot is its most recent detection. Velocities are the differences of the last
    two sightings at least half a frame period apart (overlapping cameras see an object a
    fraction of a millisecond apart; differencing those would turn centimetres of noise into
    metres per second). Objects never seen read as zeros.
    """

    def _clear(self) -> None:
        rate = self.vision_spec.frame_rate
        self._min_gap = 0.0 if rate is None else 0.5 / rate
        n = self.n_robots
        self._ball = [None, None]  # last two (t, x, y)
        self._robots = [[None, None] for _ in range(n)]

    def _consume(self, frames: list[DetectionFrame], now: float) -> None:
        for f in sorted(frames, key=lambda f: f.t_capture):
            t = f.t_capture
            if f.balls:
                last = self._ball[1]
                balls = f.balls
                if last is not None and len(balls) > 1:
                    bx, by = min(balls, key=lambda b: math.hypot(b[0] - last[1], b[1] - last[2]))
                else:
                    bx, by = balls[0]
                _push(self._ball, (t, bx, by), self._min_gap)
            for i, pose in zip(f.robot_ids, f.robots):
                _push(self._robots[i], (t, *pose), self._min_gap)

    def _beliefs(self, now: float):
        ball = np.zeros(6)
        ball[0:2], ball[3:5] = _last_and_rate(self._ball, 2)
        robots = np.zeros((self.n_robots, 6))
        for i, hist in enumerate(self._robots):
            pose, rate = _last_and_rate(hist, 3)
            robots[i, 0:3], robots[i, 3:6] = pose, rate
        belief = Belief(now, ball, robots)
        return belief, belief


def _push(hist: list, item: tuple, min_gap: float) -> None:
    """Keep the last two sightings, newest last, captured at least ``min_gap`` [s] apart."""
    last = hist[1]
    if last is not None and (item[0] <= last[0] or item[0] < last[0] + min_gap):
        if item[0] >= last[0]:
            hist[1] = item  # the same moment seen by another camera: keep the later report
        return
    hist[0], hist[1] = hist[1], item


def _last_and_rate(hist: list, dims: int) -> tuple[list, list]:
    prev, last = hist
    if last is None:
        return [0.0] * dims, [0.0] * dims
    if prev is None:
        return list(last[1:]), [0.0] * dims
    dt = last[0] - prev[0]
    rate = [(a - b) / dt for a, b in zip(last[1:], prev[1:])]
    if dims == 3:
        rate[2] = math.remainder(last[3] - prev[3], 2.0 * math.pi) / dt
    return list(last[1:]), rate


class FilteredPerception(_VisionPerception):
    """``obs_mode="perceived"``: batched robot pose filters and a ball tracker.

    Frames are processed in capture-time order: the robots first (their detections in the same
    frame give the ball filter's eq. 19 its nearest-robot distance), then the ball. The belief
    for the observation is predicted to ``now + actuation_latency``.
    """

    def __init__(self, config: PerceptionConfig, field: FieldSpec, robot: SSLRobotSpec,
                 ball: BallSpec, n_robots: int, teams: Sequence[int] | None = None,
                 robots: Sequence[Any] | None = None) -> None:
        super().__init__(config, field, robot, ball, n_robots, teams, robots)
        spec = config.vision
        # The filters weigh detections with the sensor's own measurement models.
        self.robot_tracker = RobotTracker(n_robots, measurement=self.sensor.robot_model)
        cfg, self._capture_times = ball_filter_config(config.ball_filter, ball, spec)
        self.ball_tracker = (LeastSquaresBall() if cfg is None
                             else BallTracker(cfg, self.sensor.ball_model))
        self.ahead = spec.actuation_latency

    def _clear(self) -> None:
        self.robot_tracker.reset()
        self.ball_tracker.reset()

    def _consume(self, frames: list[DetectionFrame], now: float) -> None:
        if not frames:
            return
        robots, ball = self.robot_tracker, self.ball_tracker
        for f in sorted(frames, key=lambda f: f.t_capture):
            t = f.t_capture
            for i, pose in zip(f.robot_ids, f.robots):
                robots.update_one(i, t, pose)
            if f.balls:
                # Without latency compensation a pipeline stamps frames when they arrive.
                stamp = t if self._capture_times else f.t_delivered
                ball.add(stamp, f.balls, f.robots)

    def _beliefs(self, now: float):
        current = self._belief(now)
        return (self._belief(now + self.ahead) if self.ahead else current), current

    def _belief(self, t: float) -> Belief:
        est = self.ball_tracker.estimate(t)
        ball = np.zeros(6) if est is None else np.array((est[0], est[1], 0.0, est[2], est[3],
                                                         0.0))
        return Belief(t, ball, self.robot_tracker.estimate_array(t))


def make_perception(obs_mode: str, config: PerceptionConfig, field: FieldSpec,
                    robot: SSLRobotSpec, ball: BallSpec, n_robots: int,
                    actuation_delay: float | None = None, teams: Sequence[int] | None = None,
                    robots: Sequence[Any] | None = None) -> Perception:
    """The overhead-vision pipeline of ``obs_mode`` for SSL robots (humanoids:
    :class:`MatchPerception`); unknown modes raise ``ValueError``.

    ``actuation_delay`` [s] is how far ahead the perceived belief is predicted (default: the
    vision preset's actuation latency; environments pass the latency as they apply it, in
    whole control steps). ``teams`` and ``robots`` (every robot's team and spec) are what the
    ``pixels`` detector draws.
    """
    if obs_mode == "truth":
        return TruthPerception(config)
    if obs_mode == "raw":
        return RawPerception(config, field, robot, ball, n_robots, teams, robots)
    if obs_mode == "perceived":
        p = FilteredPerception(config, field, robot, ball, n_robots, teams, robots)
        if actuation_delay is not None:
            p.ahead = float(actuation_delay)
        return p
    raise ValueError(f"obs_mode must be one of {list(OBS_MODES)}, got {obs_mode!r}")


class MatchPerception:
    """The perception of both teams of a world: each team's own pipeline, and a belief per
    robot (the match's, and the humanoid keeper's with its team-mates).

    SSL teams share the overhead vision: two SSL teams with the same configuration share one
    pipeline (SSL-Vision serves both; their beliefs coincide). A humanoid team runs a
    :class:`~soccer_env.humanoid_perception.HumanoidTeamPerception` over its humanoids, each
    with its own belief. In truth mode every agent believes the truth.

    Args:
        obs_mode: the observation mode.
        configs: the two teams' :class:`PerceptionConfig` (blue, yellow).
        field, ball: the world's field and ball.
        world: the :class:`~soccer_env.physics.World`.
        head: who aims humanoid agents' heads (see
            :data:`~soccer_env.humanoid_perception.HEAD_MODES`).
    """

    def __init__(self, obs_mode: str, configs: tuple[PerceptionConfig, PerceptionConfig],
                 field: FieldSpec, ball: BallSpec, world: Any, head: str = "auto") -> None:
        from soccer_env.humanoid_perception import HeadController, HumanoidTeamPerception

        self.obs_mode, self.world = obs_mode, world
        n = world.n_robots
        teams = world.teams.tolist()
        members = [[i for i in range(n) if teams[i] == t] for t in (0, 1)]
        kinds = [world.robot_specs[m[0]].kind if m else None for m in members]
        self.delays = [0, 0]
        self._groups: list[tuple[list[int], Any]] = []  # (robots, pipeline)
        self._humanoid: dict[int, Any] = {}  # robot -> its team's HumanoidTeamPerception
        self._heads: dict[int, Any] = {}
        ssl_teams = [t for t in (0, 1) if kinds[t] == "ssl"]
        if ssl_teams:
            shared = len(ssl_teams) == 2 and configs[0] == configs[1]
            for t in ([ssl_teams[0]] if shared else ssl_teams):
                spec = configs[t].vision
                delay = round(spec.actuation_latency / world.control_dt)
                robots = members[0] + members[1] if shared else members[t]
                pipe = make_perception(obs_mode, configs[t], field,
                                       world.robot_specs[members[t][0]], ball, n,
                                       delay * world.control_dt, teams, world.robot_specs)
                for tt in (ssl_teams if shared else [t]):
                    self.delays[tt] = delay
                self._groups.append((robots, pipe))
        for t in (0, 1):
            if kinds[t] != "humanoid":
                continue
            cfg = configs[t]
            spec = world.robot_specs[members[t][0]]
            camera = cfg.camera if cfg.camera is not None else head_camera(spec.camera)
            if obs_mode == "truth":
                self._groups.append((members[t], TruthPerception(cfg)))
                for i in members[t]:
                    self._heads[i] = HeadController(world.robot_specs[i], camera.height,
                                                    "scan" if head == "scan" else "auto")
                continue
            if obs_mode == "raw":
                cfg = dataclasses.replace(cfg, localization="odometry", fusion="own",
                                          ball_tracker="none")
            team = HumanoidTeamPerception(cfg, field, ball, world.robot_specs, teams,
                                          world.names, members[t], camera, cfg.radio, head)
            for i in members[t]:
                self._humanoid[i] = team
            self._groups.append((members[t], team))
        self._beliefs: dict[int, Any] = {}
        self._current: dict[int, Any] = {}

    @property
    def groups(self) -> list[list[int]]:
        """Robots that share one belief (a list per belief source; a humanoid team's robots
        each have their own)."""
        out = []
        for robots, pipe in self._groups:
            if isinstance(pipe, (TruthPerception, FilteredPerception, RawPerception)):
                out.append(list(robots))
            else:
                out += [[i] for i in robots]
        return out

    @property
    def pipelines(self) -> list[Any]:
        """The teams' pipelines (overhead vision, truth, or a humanoid team's)."""
        return [pipe for _, pipe in self._groups]

    def humanoid_team(self, i: int) -> Any:
        """The :class:`~soccer_env.humanoid_perception.HumanoidTeamPerception` of humanoid
        ``i`` (perceived and raw modes)."""
        return self._humanoid[i]

    def reset(self, state: WorldState, rng: np.random.Generator) -> tuple[Any, Any]:
        """Start an episode at ``state``; returns robot 0's beliefs (for its observation,
        now)."""
        from soccer_env.humanoid_perception import head_state

        # One pipeline draws from the episode's sensor stream itself, several from streams
        # spawned from it.
        rngs = [rng] if len(self._groups) == 1 else rng.spawn(len(self._groups))
        for (robots, pipe), r in zip(self._groups, rngs):
            if hasattr(pipe, "head_targets"):
                pipe.reset(state, head_state(self.world), r)
            else:
                seen, now = pipe.reset(state, r)
                for i in robots:
                    self._beliefs[i], self._current[i] = seen, now
        self._collect(state.time)
        return self._beliefs[0], self._current[0]

    def update(self, state: WorldState) -> tuple[Any, Any]:
        """Advance to ``state``; returns robot 0's beliefs (for its observation, now)."""
        from soccer_env.humanoid_perception import head_state

        heads = None
        for robots, pipe in self._groups:
            if hasattr(pipe, "head_targets"):
                heads = heads if heads is not None else head_state(self.world)
                pipe.update(state, heads, self.world.walk)
            else:
                seen, now = pipe.update(state)
                for i in robots:
                    self._beliefs[i], self._current[i] = seen, now
        self._collect(state.time)
        return self._beliefs[0], self._current[0]

    def _collect(self, t: float) -> None:
        for i, team in self._humanoid.items():
            ball, robots = team.belief(i, t)
            b = Belief(t, ball, robots)
            self._beliefs[i] = self._current[i] = b

    def belief(self, i: int) -> Any:
        """Robot ``i``'s belief for its observation (a WorldState in truth mode)."""
        return self._beliefs[i]

    def current(self, i: int) -> Any:
        """Robot ``i``'s belief at the present time."""
        return self._current[i]

    def head_targets(self, i: int, now: float) -> tuple[float, float]:
        """Pan and tilt targets [rad] of humanoid ``i``'s head controller."""
        if i in self._humanoid:
            return self._humanoid[i].head_targets(i, now)
        s = self._beliefs[i]
        b = s.ball
        return self._heads[i].targets(now, s.robots[i, 0:3],
                                      np.array([b[0], b[1], b[3], b[4]]), 0.0, 0.0)
