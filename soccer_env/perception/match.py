"""The perception of both teams of a world (:class:`MatchPerception`): each team its own
pipeline, and a belief per robot.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from soccer_env.perception.base import PerceptionConfig
from soccer_env.perception.humanoid import HumanoidTeamPerception
from soccer_env.perception.options import ROBOT_PREDICTIONS
from soccer_env.perception.overhead import (
    FilteredPerception,
    TruthPerception,
    VisionPerception,
    make_perception,
)
from soccer_env.perception.randomization import check_ranges, draw
from soccer_env.presets import BallSpec, FieldSpec, HeadCameraSpec, RobotSpec, head_camera
from soccer_env.state import Attention, Belief, BeliefSpread, BodyState, WorldState

__all__ = ["MatchPerception"]


class MatchPerception:
    """The perception of both teams of a world: each team's own pipeline, and a belief per
    robot (the match's, and the humanoid keeper's with its team-mates).

    SSL teams share the overhead vision: two SSL teams with the same configuration and
    observation mode share one pipeline (SSL-Vision serves both; their beliefs coincide); with
    different ones each team runs its own pipeline on the same camera frames when both use the
    same geometric vision preset without randomisation (what each team does with SSL-Vision's
    frames is its own), else on its own sensor. A humanoid team runs a
    :class:`~soccer_env.perception.humanoid.HumanoidTeamPerception` over its humanoids, each
    with its own belief. In truth mode every agent of that team believes the truth.

    Args:
        obs_mode: the observation mode, one for both teams or ``(blue's, yellow's)`` (or
            ``{"blue": ..., "yellow": ...}``).
        configs: the two teams' :class:`PerceptionConfig` (blue, yellow).
        field, ball: the world's field and ball.
        robots: every robot's model, in world order (blue first).
        teams: every robot's team (0 blue, 1 yellow).
        names: every robot's name.
        control_dt: the world's control step [s] (the actuation latency is applied in whole
            steps).
        features: the observations' beliefs carry their
            :class:`~soccer_env.state.BeliefQuality` (the environments' belief features).

    Reads the world's :class:`~soccer_env.state.WorldState` and, with humanoids,
    :class:`~soccer_env.state.BodyState` snapshots; never the world itself.
    """

    def __init__(self, obs_mode: str, configs: tuple[PerceptionConfig, PerceptionConfig],
                 field: FieldSpec, ball: BallSpec, robots: Sequence[RobotSpec],
                 teams: Sequence[int], names: Sequence[str], control_dt: float,
                 features: bool = False) -> None:
        if isinstance(obs_mode, str):
            modes = (obs_mode, obs_mode)
        elif isinstance(obs_mode, Mapping):
            modes = (obs_mode["blue"], obs_mode["yellow"])
        else:
            modes = tuple(obs_mode)
        #: Each team's observation mode (blue, yellow).
        self.obs_modes: tuple[str, str] = (str(modes[0]), str(modes[1]))
        #: The observation mode of both teams, or ``"blue/yellow"`` modes when they differ.
        self.obs_mode = modes[0] if modes[0] == modes[1] else f"{modes[0]}/{modes[1]}"
        self.features = bool(features)
        # In truth mode every robot believes the truth: the latest state is every belief.
        self._truth = modes[0] == modes[1] == "truth"
        self._state: WorldState | None = None
        specs = list(robots)
        teams = [int(t) for t in teams]
        n = len(specs)
        members = [[i for i in range(n) if teams[i] == t] for t in (0, 1)]
        kinds = [specs[m[0]].kind if m else None for m in members]
        #: Every team's actuation latency in whole control steps and command loss
        #: probability (0 for humanoids); with randomised figures, this episode's.
        self.delays = [0, 0]
        self.losses = [0.0, 0.0]
        #: Whether a team's pipeline predicts its own robots from its commands (the
        #: environment then hands them to :meth:`command` every step).
        self.driven = False
        #: The head camera of every humanoid (robot index -> spec).
        self.cameras: dict[int, HeadCameraSpec] = {}
        # (robots, pipeline, whether it is a humanoid team's: it reads the bodies and keeps a
        # belief per robot)
        self._groups: list[tuple[list[int], Any, bool]] = []
        # robot -> its team's HumanoidTeamPerception (see _index_humanoids)
        self._humanoid: dict[int, Any] = {}
        #: Groups whose sensor figures are drawn every episode: group index -> (the
        #: preset's spec, the randomisation, what builds the group's pipeline from a drawn
        #: spec).
        self._randomized: dict[int, tuple[Any, Any, Any]] = {}
        self._add_ssl_teams(configs, modes, field, ball, specs, teams, members, kinds,
                            control_dt)
        self._add_humanoid_teams(configs, modes, field, ball, specs, teams, names, members,
                                 kinds)
        self._index_humanoids()
        self._beliefs: dict[int, Any] = {}
        self._current: dict[int, Any] = {}

    def _add_ssl_teams(self, configs: tuple[PerceptionConfig, PerceptionConfig],
                       modes: tuple[str, str], field: FieldSpec, ball: BallSpec,
                       specs: list[RobotSpec], teams: list[int], members: list[list[int]],
                       kinds: list[str | None], control_dt: float) -> None:
        """The SSL teams' groups: one pipeline shared by both teams, or one each (on shared
        camera frames where they can be; :meth:`_share_frames`)."""
        n, features = len(specs), self.features
        ssl_teams = [t for t in (0, 1) if kinds[t] == "ssl"]
        if not ssl_teams:
            return
        # Teams that predict their own robots from their commands believe different things:
        # each runs its own filters (on shared frames).
        shared = (len(ssl_teams) == 2 and configs[0] == configs[1]
                  and modes[0] == modes[1]
                  and not ROBOT_PREDICTIONS[configs[0].robot_prediction])
        for t in ([ssl_teams[0]] if shared else ssl_teams):
            cfg = configs[t]
            mode = modes[t]
            group = members[0] + members[1] if shared else members[t]
            tts = ssl_teams if shared else [t]

            def build(spec, cfg=cfg, t=t, tts=tts, mode=mode):
                # The commands' latency in whole control steps and their loss follow the
                # (drawn) spec; the filters predict to when the commands take effect.
                delay = round(spec.actuation_latency / control_dt)
                for tt in tts:
                    self.delays[tt], self.losses[tt] = delay, spec.command_loss
                pipe = make_perception(mode, dataclasses.replace(cfg, vision=spec),
                                       field, specs[members[t][0]], ball, n,
                                       delay * control_dt, teams, specs, features)
                if isinstance(pipe, FilteredPerception) and ROBOT_PREDICTIONS[
                        cfg.robot_prediction]:
                    pipe.drive_own(members[t], specs[members[t][0]], control_dt)
                    self.driven = True
                return pipe

            if cfg.randomize and mode != "truth":
                check_ranges(cfg.vision, cfg.randomize, "ssl")
                self._randomized[len(self._groups)] = (cfg.vision, cfg.randomize, build)
            self._groups.append((group, build(cfg.vision), False))
        self._share_frames()

    def _add_humanoid_teams(self, configs: tuple[PerceptionConfig, PerceptionConfig],
                            modes: tuple[str, str], field: FieldSpec, ball: BallSpec,
                            specs: list[RobotSpec], teams: list[int], names: Sequence[str],
                            members: list[list[int]], kinds: list[str | None]) -> None:
        """The humanoid teams' groups: the truth, or a
        :class:`~soccer_env.perception.humanoid.HumanoidTeamPerception` per team (with the
        filters off in raw mode)."""
        for t in (0, 1):
            if kinds[t] != "humanoid":
                continue
            cfg = configs[t]
            spec = specs[members[t][0]]
            camera = cfg.camera if cfg.camera is not None else head_camera(spec.camera)
            self.cameras.update(dict.fromkeys(members[t], camera))
            if modes[t] == "truth":
                self._groups.append((members[t], TruthPerception(cfg), False))
                continue
            if modes[t] == "raw":
                cfg = dataclasses.replace(cfg, localization="odometry", fusion="own",
                                          ball_tracker="none")

            def build_team(cam, cfg=cfg, t=t):
                return HumanoidTeamPerception(cfg, field, ball, specs, teams, names,
                                              members[t], cam, cfg.radio)

            if cfg.randomize:
                check_ranges(camera, cfg.randomize, "humanoid")
                self._randomized[len(self._groups)] = (camera, cfg.randomize, build_team)
            self._groups.append((members[t], build_team(camera), True))

    def _share_frames(self) -> None:
        """Two SSL teams' own pipelines on the same camera frames: the second takes the
        first's frames when both read the same geometric vision (one preset, no
        randomisation)."""
        vision = [(g, pipe) for g, (_, pipe, _) in enumerate(self._groups)
                  if isinstance(pipe, VisionPerception)]
        if len(vision) != 2 or self._randomized:
            return
        (_, a), (_, b) = vision
        if (a.detector is None and b.detector is None
                and a.vision_spec == b.vision_spec):
            b.frames_from = a

    @property
    def reads_bodies(self) -> bool:
        """Whether :meth:`reset` and :meth:`update` need the robots'
        :class:`~soccer_env.state.BodyState` (a humanoid team's pipeline reads it)."""
        return bool(self._humanoid)

    @property
    def groups(self) -> list[list[int]]:
        """Robots that share one belief (a list per belief source; a humanoid team's robots
        each have their own)."""
        out = []
        for robots, _, humanoid in self._groups:
            if humanoid:
                out += [[i] for i in robots]
            else:
                out.append(list(robots))
        return out

    @property
    def ball_modes(self) -> tuple[str, ...]:
        """The motion modes of the ball filter of every team (an interacting multiple model
        filter's, whose probabilities the beliefs' quality then carries: the belief features
        ``ball.p_<mode>``); empty when a team's filter has none or the teams' differ."""
        modes = {tuple(getattr(pipe, "ball_modes", ())) for pipe in self.pipelines}
        return modes.pop() if len(modes) == 1 else ()

    @property
    def pipelines(self) -> list[Any]:
        """The teams' pipelines (overhead vision, truth, or a humanoid team's)."""
        return [pipe for _, pipe, _ in self._groups]

    def humanoid_team(self, i: int) -> Any:
        """The :class:`~soccer_env.perception.humanoid.HumanoidTeamPerception` of humanoid
        ``i`` (perceived and raw modes)."""
        return self._humanoid[i]

    def command(self, now: float, commands: np.ndarray) -> None:
        """Every robot's physical commands ``(N, 6)`` sent at ``now`` [s], for the pipelines
        that predict their team's robots from them (each takes its own rows, effective one
        actuation latency later)."""
        for _, pipe, _ in self._groups:
            history = getattr(pipe, "history", None)
            if history is not None:
                pipe.command(now + pipe.ahead, commands[history.robots])

    def reset(self, state: WorldState, rng: np.random.Generator, body: BodyState | None = None
              ) -> tuple[Any, Any]:
        """Start an episode at ``state`` (``body``: the robots' bodies, needed with
        humanoids); returns robot 0's beliefs (for its observation, now)."""
        if self._truth:
            self._state = state
            return state, state
        if self._randomized:
            # The sensor figures of the episode, from a stream of their own taken first.
            self._draw(np.random.default_rng(rng.integers(2**63)))
        # One pipeline draws from the episode's sensor stream itself, several from streams
        # spawned from it.
        rngs = [rng] if len(self._groups) == 1 else rng.spawn(len(self._groups))
        for (robots, pipe, humanoid), r in zip(self._groups, rngs):
            if humanoid:
                pipe.reset(state, body, r)
            else:
                seen, now = pipe.reset(state, r)
                for i in robots:
                    self._beliefs[i], self._current[i] = seen, now
        self._collect(state.time)
        return self._beliefs[0], self._current[0]

    def _draw(self, rng: np.random.Generator) -> None:
        """Draw the randomised groups' sensor figures and rebuild their pipelines."""
        for g, (spec, ranges, build) in sorted(self._randomized.items()):
            robots, _, humanoid = self._groups[g]
            kind = "humanoid" if humanoid else "ssl"
            self._groups[g] = (robots, build(draw(spec, ranges, rng, kind)), humanoid)
        self._index_humanoids()

    def _index_humanoids(self) -> None:
        """Map every humanoid of a modelled team to its team's pipeline (from the groups)."""
        self._humanoid = {i: pipe for robots, pipe, humanoid in self._groups if humanoid
                          for i in robots}

    def update(self, state: WorldState, body: BodyState | None = None) -> tuple[Any, Any]:
        """Advance to ``state`` (``body``: the robots' bodies, needed with humanoids);
        returns robot 0's beliefs (for its observation, now)."""
        if self._truth:
            self._state = state
            return state, state
        beliefs, current = self._beliefs, self._current
        for robots, pipe, humanoid in self._groups:
            if humanoid:
                pipe.update(state, body)
            else:
                seen, now = pipe.update(state)
                for i in robots:
                    beliefs[i], current[i] = seen, now
        if self._humanoid:
            self._collect(state.time)
        return beliefs[0], current[0]

    def _collect(self, t: float) -> None:
        features = self.features
        for i, team in self._humanoid.items():
            ball, robots = team.belief(i, t)
            b = Belief(t, ball, robots, team.brain(i).quality(t, t) if features else None)
            self._beliefs[i] = self._current[i] = b

    def belief(self, i: int) -> Any:
        """Robot ``i``'s belief for its observation (a WorldState in truth mode)."""
        return self._state if self._truth else self._beliefs[i]

    def current(self, i: int) -> Any:
        """Robot ``i``'s belief at the present time."""
        return self._state if self._truth else self._current[i]

    def spread(self, i: int, t: float) -> BeliefSpread | None:
        """How robot ``i``'s belief at ``t`` [s] is spread, for drawing: its team's filters'
        covariances and particles, read without changing them (see
        :class:`~soccer_env.state.BeliefSpread`); None in truth mode and before the first
        reset."""
        if self._truth:
            return None
        if i in self._humanoid:
            return self._humanoid[i].spread(i, t)
        for robots, pipe, _ in self._groups:
            if i in robots:
                reader = getattr(pipe, "spread", None)
                return None if reader is None or i not in self._current else reader(t)
        return None

    def attention(self, i: int, now: float) -> Attention:
        """What humanoid ``i``'s head controller needs of its belief at ``now`` (in truth
        mode: the true pose and ball, just seen)."""
        if i in self._humanoid:
            return self._humanoid[i].attention(i, now)
        s = self.belief(i)
        b = s.ball
        return Attention(s.robots[i, 0:3], np.array([b[0], b[1], b[3], b[4]]), 0.0, 0.0)
