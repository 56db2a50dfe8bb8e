"""What a humanoid team believes: every robot localizes itself, sees through its head camera,
shares its sightings over the team radio, fuses them in Hough space and tracks the ball with a
particle filter (Xu et al. 2012 and Guo and Li (2013)).

Per humanoid ("brain"), per step:

1. **Odometry** from its walk engine is kept with its time stamps.
2. **Head-camera frames** (:class:`~soccer_env.sensors.headcam.HeadCameraSensor`) arrive late. For a
   frame captured at ``t_c`` the localization is moved by the odometry up to ``t_c`` and
   weighted by the frame's landmarks (``localization="kld-triangulate"``, the default: paper
   001's KLD-sampling particle filter, :class:`~estimators.KLDLocalizer`, with ambiguous
   landmark kinds: a robot sees an "L" corner, not which one, its recovery drawing half of the
   new particles around poses triangulated from the last frames' landmarks, Xu et al. (2012);
   ``"kld"``: the same with a uniform recovery; ``"odometry"``: dead reckoning from the known
   start;
   ``"truth"``: the true pose, an oracle for ablations). The ball detection nearest the
   present belief becomes a sighting line: from the estimated position at ``t_c`` along the
   estimated heading plus the detection's bearing, with the ground projection's range.
3. **Radio** (:class:`~soccer_env.sensors.radio.TeamRadio`): each frame's pose estimate and sighting
   are broadcast; a fallen robot is silent; received messages update the team-mates' poses
   and their latest sighting lines.
4. **Fusion** at each own frame: the robot's own line and the team-mates' lines captured
   within 1.5 frame periods plus the radio's latency and jitter of it (the latest per
   team-mate), each moved by the tracked ball velocity times its age,
   are fused by :func:`~estimators.fuse_sightings` (``fusion="equal" | "inverse" |
   "inverse_square"``: Xu et al.'s (2012) Hough-space least squares with the weighting named; with
   ``"own"`` only the robot's own sighting is used).
5. **Tracking**: the fused point feeds Xu et al.'s (2012) particle filter
   (:class:`~estimators.ParticleBallTracker`, ``ball_tracker="mfbpf" | "fbpf" |
   "bootstrap"``, 100 particles) stamped with the capture time, so its prediction to the
   present compensates the camera latency; with ``"none"`` the belief is the latest fused
   point with the velocity of the last two (at least 0.1 s apart). With ``"kick"``
   (:class:`~estimators.LineBallTracker`) there is no fusion step: the robot's own line and
   each team-mate's as it arrives (with the sender's sway, which the message carries) go to
   a Kalman filter that keeps every observer's localization error in its state, processes
   lines in capture order and opens a kick hypothesis as soon as a line leaves where the
   resting ball should be seen (the team's lines are used unless ``fusion="own"``).
6. **Opponents** are the robot's own sightings of robots of the other team's colour, each
   associated with the nearest opponent track within 1 m (no identity is seen); tracks start
   at the kick-off positions, which the rules fix.

Raw observations (``obs_mode="raw"``) run the same pipeline with the filters off: odometry
dead reckoning, the robot's own sightings only, no tracker.

The head is aimed by :class:`HeadController` unless the policy controls it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from estimators import KLDConfig, KLDLocalizer, LandmarkTable, ParticleBallTracker
from soccer_env.perception.base import expected_age
from soccer_env.perception.brain import Brain, BrainContext
from soccer_env.perception.options import DETECTORS
from soccer_env.perception.sighting import sighting_sigmas
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.presets.sensors import HeadCameraSpec, RadioSpec
from soccer_env.sensors.headcam import HeadFrame, field_landmarks
from soccer_env.sensors.radio import TeamRadio
from soccer_env.state import Attention, BeliefSpread, BodyState, WorldState

__all__ = ["HumanoidTeamPerception"]

#: The localization's pose errors the inverse-variance fusion assumes (see
#: :attr:`HumanoidTeamPerception.pose_sigmas`): position per axis [m], heading [rad].
_POSE_SIGMAS = (0.05, math.radians(2.5))

#: Fused sightings older than this many frame periods are not fused with a new one.
_FUSION_WINDOW_FRAMES = 1.5


class HumanoidTeamPerception:
    """The estimation stacks of the humanoids ``observers`` of a world (of one or both
    teams; each team has its own radio).

    Args:
        config: the :class:`~soccer_env.perception.base.PerceptionConfig` (its ``camera``,
            ``radio``, ``localization``, ``fusion`` and ``ball_tracker``).
        field, ball: the world's field and ball.
        specs: every robot's model (radii; the observers' camera height and head limits).
        teams: every robot's team.
        names: every robot's name.
        observers: indices of the humanoids whose beliefs are modelled.
        camera: the head camera of the observers.
        radio: the team radio's link.

    Reads, per step, the world's :class:`~soccer_env.state.WorldState` (what the cameras see;
    the oracle localization's pose) and :class:`~soccer_env.state.BodyState` (head angles,
    odometry, gait, falls); writes nothing but its own state.
    """

    def __init__(self, config: Any, field: FieldSpec, ball: BallSpec,
                 specs: Sequence[RobotSpec], teams: Sequence[int], names: Sequence[str],
                 observers: Sequence[int], camera: HeadCameraSpec, radio: RadioSpec) -> None:
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
        detector = DETECTORS[getattr(config, "detector", "geometric")]
        self.sensor = detector.head(camera, field, ball, self.specs, self.teams, self.observers)
        #: Builds a robot's ball finder for its frame images (None: the frames carry ball
        #: detections).
        self.ball_finder = detector.ball_finder
        positions, kinds = field_landmarks(field, camera.distinct_goals)
        table: dict[str, list] = {}
        for pos, kind in zip(positions, kinds):
            table.setdefault(kind, []).append(pos)
        self.landmark_table = LandmarkTable(table)
        wx, wy = field.half_length + field.boundary, field.half_width + field.boundary
        self.bounds = (-wx, wx, -wy, wy)
        # Landmark noise as the camera makes it: a pixel or a tilt error e moves a ground
        # point at distance d by about d^2 e / h along the line of sight; bearings by the
        # pixel noise and the yaw sway. The sway's errors repeat from frame to frame (the
        # gait is periodic), so recovery waits for a deeper and longer drop of the likelihood
        # than the textbook rule.
        hum = [s for s in self.specs if s.kind == "humanoid"]
        sway_t = max((s.sway_tilt for s in hum), default=0.0)
        sway_p = max((s.sway_pan for s in hum), default=0.0)
        # The sightings' error model for the fusion, for the worst sway of the team's robots
        # (:func:`~soccer_env.perception.sighting.sighting_sigmas`); the landmarks' is the same
        # with larger floors.
        self.bearing_sigma, self.range_per_metre = sighting_sigmas(camera, sway_p, sway_t)
        self.kld_config = KLDConfig(
            min_particles=50, max_particles=2000,
            range_sigma=0.05, range_sigma_rel=0.05,
            range_sigma_quad=max(0.01, self.range_per_metre),
            bearing_sigma=max(math.radians(1.0), self.bearing_sigma),
            alpha_fast=0.1, recovery_ratio=0.2)
        self.fusion_window = ((_FUSION_WINDOW_FRAMES / camera.frame_rate
                               if camera.frame_rate else 0.05)
                              + radio.latency + radio.jitter)
        #: The observers' pose errors the inverse-variance fusion weighs lines by
        #: ``(position per axis [m], heading [rad])``: none for the oracle; else the
        #: localization's error while tracking, as ``soccer-env paper team`` and ``paper
        #: localization`` measure it (median position error about 0.05 m, a per-axis sigma of
        #: 0.05 / 1.18 for a Rayleigh-distributed error, rounded up to 0.05 m; median heading
        #: error 1-2 degrees, a sigma of about 2.5 degrees).
        self.pose_sigmas = ((0.0, 0.0) if getattr(config, "localization", "") == "truth"
                            else _POSE_SIGMAS)
        #: Without an own frame for this long [s], team-mates' sightings are fused as they
        #: arrive.
        self.frame_gap = 1.5 / camera.frame_rate if camera.frame_rate else 0.05
        #: The oldest the latest fused sighting is while the ball is seen in every frame [s]
        #: (beyond it the belief features call the track coasting): the camera's, plus the
        #: radio's latency and jitter when team-mates' sightings are fused.
        self.coast_age = expected_age(camera.frame_rate, camera.latency,
                                      camera.latency_jitter) + (
            0.0 if getattr(config, "fusion", "own") == "own" else radio.latency + radio.jitter)
        self._brains: dict[int, Brain] = {}
        self._radios: dict[int, TeamRadio] = {}

    # ------------------------------------------------------------------------------------

    def context(self) -> BrainContext:
        """What each robot's :class:`~soccer_env.perception.brain.Brain` reads of this
        pipeline (its present figures)."""
        cfg = self.config
        return BrainContext(
            localization=cfg.localization, fusion=cfg.fusion, ball_tracker=cfg.ball_tracker,
            specs=tuple(self.specs), teams=tuple(self.teams), index_of=dict(self.index_of),
            team_members={t: tuple(m) for t, m in self.team_members.items()},
            ball_spec=self.ball_spec, camera=self.camera, ball_finder=self.ball_finder,
            bounds=self.bounds, landmark_table=self.landmark_table, kld_config=self.kld_config,
            pose_sigmas=self.pose_sigmas, fusion_window=self.fusion_window,
            frame_gap=self.frame_gap, bearing_sigma=self.bearing_sigma,
            range_per_metre=self.range_per_metre, coast_age=self.coast_age)

    def reset(self, state: WorldState, body: BodyState, rng: np.random.Generator) -> None:
        """Start an episode at ``state`` (the robots' poses at the start are known; ``body``
        gives their heads)."""
        self._rngs = rng.spawn(len(self.observers) + 2)
        context = self.context()
        self._brains = {i: Brain(i, self.names[i], self.teams[i], context, r)
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
        self.time = state.time
        self.consume(self.sensor.reset(state, body.heads, self._rngs[-1]), state, None)

    def update(self, state: WorldState, body: BodyState) -> None:
        """Advance to ``state``: odometry, frames, radio, fusion and tracking."""
        self.time = state.time
        self.consume(self.sensor.step(state, body.heads), state, body)

    def consume(self, frames: list[HeadFrame], state: WorldState, body: BodyState | None
                 ) -> None:
        """The estimation of one step (the sensor simulation done): odometry (none at the
        start, ``body=None``), the frames, the radio."""
        now = state.time
        if body is not None:
            for i, b in self._brains.items():
                b.odometry(now, body.odometry[i], state.robots[i, 0:3])
                b.gait_velocity = body.gait[i]
                fallen = body.fallen[i]
                self._radios[b.team].set_silent(b.name, fallen)
                if b.down and not fallen:
                    b.stood_up(self.specs[i].fall_heading_sigma)
                b.down = fallen
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

    def spread(self, i: int, t: float) -> BeliefSpread | None:
        """How robot ``i``'s belief at ``t`` [s] is spread, for drawing (read-only; see
        :meth:`~soccer_env.perception.brain.Brain.spread`); None before the first reset."""
        brain = self._brains.get(i)
        return None if brain is None else brain.spread(t)

    def attention(self, i: int, now: float) -> Attention:
        """What robot ``i``'s head controller needs of its belief at ``now``."""
        b = self._brains[i]
        return Attention(b.estimate_pose(), b.ball_point(now),
                         now - max(b.ball_seen, b.ball_heard), now - b.landmark_seen)

    def brain(self, i: int) -> Brain:
        """Robot ``i``'s estimation stack (its localization, tracker, the team-mates' poses
        and sightings it has heard)."""
        return self._brains[i]

    def localization(self, i: int) -> KLDLocalizer | None:
        """Robot ``i``'s localization filter (None unless ``localization`` is ``"kld"`` or
        ``"kld-triangulate"``)."""
        return self._brains[i].loc

    def tracker(self, i: int) -> ParticleBallTracker | None:
        """Robot ``i``'s ball tracker (None with ``ball_tracker="none"``)."""
        return self._brains[i].tracker
