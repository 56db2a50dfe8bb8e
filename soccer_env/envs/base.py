"""The fixed part of every environment, and the hooks a task fills in.

Data flows one way through a step (the README's "Layout" section has the layers)::

    actions -> robot models -> head control -> command channels -> World.step
            -> task events (a shot is fired, the referee restarts play)
            -> WorldState -> perception (sensors, estimators) -> beliefs -> observations
            -> outcome, reward terms, info

:class:`SoccerCore` owns that loop: the world and its robots' action models, the perception of
both teams (:class:`~soccer_env.perception.match.MatchPerception`), the command channels with
each team's actuation latency and command loss, the humanoids' head control, and rendering. A
task builds it once (:meth:`SoccerCore._build`) and implements the hooks:

* :meth:`~SoccerCore._place` (required): where the robots and the ball start an episode;
* :meth:`~SoccerCore._streams`: the random streams of the world and of the sensors (default:
  seeded from the episode's generator, the world's first);
* :meth:`~SoccerCore._begin`: the task's own state at the start (counters, a shot to fire);
* :meth:`~SoccerCore._after_physics`: what happens between the physics and the snapshot (a
  shot is fired, the referee restarts play); returns the step's event;
* the outcome, reward terms and info of the task, in the Gymnasium or PettingZoo wrapper's
  terms (:class:`SingleAgentTask` for Gymnasium tasks, the match for PettingZoo).

:class:`SingleAgentTask` is the Gymnasium side: robot 0 is the learner, every other robot acts
through :meth:`SingleAgentTask._others` (standing team-mates, a scripted keeper), and
``reset``/``step`` are fixed; a task adds :meth:`~SingleAgentTask._observe`,
:meth:`~SingleAgentTask._outcome`, :meth:`~SingleAgentTask._reward_terms` and
:meth:`~SingleAgentTask._task_info`. ``soccer_env/envs/shootout.py`` is a complete task in one
file.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import gymnasium as gym
import numpy as np

from soccer_env import presets
from soccer_env.envs.flat_info import (
    INFO_MODES,
    OUTCOME_CODES,
    as_float64,
    flat_common,
    flat_keys,
)
from soccer_env.envs.registration import GYMNASIUM
from soccer_env.observations import ObservationBuilder
from soccer_env.perception.base import OBS_MODES, PerceptionConfig
from soccer_env.perception.match import MatchPerception
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.render import RENDER_MODES, Banner, RenderingMixin, check_view
from soccer_env.sim.commands import (
    OUT_OF_RANGE_MODES,
    CommandChannel,
    HumanoidRobot,
    SSLRobot,
    robot_model,
    validate_actions,
)
from soccer_env.sim.heads import HEAD_MODES, HeadControl, aim_heads
from soccer_env.sim.world import World
from soccer_env.state import Belief, WorldState, state_dict
from soccer_env.validation import check_choice, check_integer, check_seed

__all__ = ["SoccerCore", "SingleAgentTask", "resolve_world", "action_cost", "RENDER_WIDTHS"]

#: The frame widths a renderer draws, pixels (a 4K frame at most: a frame is width x 2/3
#: width x 3 bytes).
RENDER_WIDTHS = (64, 3840)


class SoccerCore(RenderingMixin):
    """The world, perception, command channels, head control and rendering of an
    environment, and the fixed parts of its reset and step (see the module docstring).

    Attributes set by :meth:`_build`: ``field``, ``ball_spec``, ``team_specs`` (blue's and
    yellow's robot model), ``robot_spec`` (the first robot's), ``world``, ``obs_mode`` (a
    string, or ``{"blue": ..., "yellow": ...}`` when the teams' modes differ),
    ``perceptions`` (both teams' :class:`~soccer_env.perception.base.PerceptionConfig`),
    ``perception`` (blue's), ``render_mode``, ``out_of_range_actions``, ``head``,
    ``info_mode`` (``"full"``: nested dicts; ``"flat"``: numbers under fixed keys, see
    :mod:`soccer_env.envs.flat_info`).
    """

    metadata: dict[str, Any] = {"render_modes": list(RENDER_MODES), "render_fps": 60}

    # ------------------------------------------------------------------------------------
    # Construction
    # ------------------------------------------------------------------------------------

    def _build(self, *, team_specs: tuple[RobotSpec, RobotSpec], n_blue: int, n_yellow: int,
               field: FieldSpec, ball: BallSpec, obs_mode: str | Mapping[str, str],
               perceptions: tuple[PerceptionConfig, PerceptionConfig], control_dt: float,
               physics_dt: float, out_of_range_actions: str, render_mode: str | None,
               render_width: int, head: str, policy_heads: Sequence[int],
               belief_features: bool = False, info_mode: str = "full",
               render_view: str = "field") -> None:
        """Build the world and everything around it.

        ``policy_heads``: the humanoids whose head the policy aims with its action entries 4
        and 5 (with ``head="action"``); every other humanoid's head is aimed by the head
        control. ``belief_features``: the observations end with the belief features (see
        :mod:`soccer_env.observations`; builders made by :meth:`_observation_builder`).
        ``info_mode``: ``"full"`` or ``"flat"`` (:mod:`soccer_env.envs.flat_info`).
        ``render_view``: ``"field"`` or ``"follow"`` (:data:`~soccer_env.render.RENDER_VIEWS`).
        """
        for mode in ([obs_mode] if isinstance(obs_mode, str) else obs_mode.values()):
            check_choice("obs_mode", mode, OBS_MODES)
        check_choice("info_mode", info_mode, INFO_MODES)
        check_choice("render_mode", render_mode, [None, *RENDER_MODES])
        check_choice("out_of_range_actions", out_of_range_actions, OUT_OF_RANGE_MODES)
        check_choice("head", head, HEAD_MODES)
        check_integer("render_width", render_width, *RENDER_WIDTHS, " pixels")
        self._render_view = check_view(render_view)
        self.team_specs = team_specs
        self.field, self.ball_spec = field, ball
        self.obs_mode = obs_mode
        self.render_mode = render_mode
        self.out_of_range_actions = out_of_range_actions
        self.head = head
        self.info_mode = info_mode
        self._flat = info_mode == "flat"
        if not isinstance(belief_features, (bool, np.bool_)):
            raise TypeError(f"belief_features must be True or False, got {belief_features!r}")
        self.belief_features = bool(belief_features)
        self.world = World(field, ball, [team_specs[0]] * n_blue + [team_specs[1]] * n_yellow,
                           n_blue, n_yellow, control_dt, physics_dt)
        w = self.world
        self._learner = w.names[:1]  # robot 0, named as validate_actions names it
        #: The first robot's model (every robot's when the teams play the same robot).
        self.robot_spec = w.robot_spec
        self.metadata = {**self.metadata, "render_fps": round(1.0 / w.control_dt)}
        self._models: list[SSLRobot | HumanoidRobot] = [robot_model(s) for s in team_specs]
        self.perceptions = perceptions
        #: Blue's perception configuration (the match's, when both teams share one).
        self.perception = perceptions[0]
        self._perception = MatchPerception(obs_mode, perceptions, field, ball, w.robot_specs,
                                           w.teams.tolist(), w.names, w.control_dt,
                                           self.belief_features)
        # Commands reach each team's robots with its actuation latency, in whole control
        # steps, and its command loss (none for humanoids, whose walk engine is on board).
        self._slices = [slice(0, n_blue), slice(n_blue, n_blue + n_yellow)]
        self._channels = [CommandChannel(n, d, loss) for n, d, loss in
                          zip((n_blue, n_yellow), self._perception.delays,
                              self._perception.losses)]
        # The teams with robots, as (action model, their rows, command channel): with one,
        # a step maps and sends the whole command array at once.
        self._teams_in_play = [(m, sl, ch) for m, sl, ch, n in
                               zip(self._models, self._slices, self._channels,
                                   (n_blue, n_yellow)) if n]
        self._one_team = self._teams_in_play[0] if len(self._teams_in_play) == 1 else None
        #: Whether the perception reads the robots' bodies (humanoid teams' pipelines do).
        self._reads_bodies = self._perception.reads_bodies
        free = set(policy_heads) if head == "action" else set()
        auto = [i for i in w.humanoid_indices if i not in free]
        self._heads = (HeadControl(w.robot_specs, auto,
                                   [self._perception.cameras[i].height for i in auto], head)
                       if auto else None)
        self._render_width = int(render_width)
        #: Robot 0's beliefs: for its observation, and at the present time (shown and
        #: reported in ``info["estimate"]``).
        self._seen: Any = None
        self._shown_belief: Any = None

    def _observation_builder(self, agents: Sequence[int], game_low: Sequence[float] = (),
                             game_high: Sequence[float] = (), game_names: Sequence[str] = (),
                             teams: Sequence[int] | None = None) -> ObservationBuilder:
        """An :class:`~soccer_env.observations.ObservationBuilder` for the robots ``agents``
        of this world (``teams``: the robots it lays out, default all), with the belief
        features when the environment has them."""
        w = self.world
        return ObservationBuilder(self.field, w.teams if teams is None else teams, agents,
                                  game_low, game_high, game_names,
                                  belief_features=self.belief_features,
                                  humanoid=bool(w.humanoid_indices),
                                  team_size=max(w.n_blue, w.n_yellow),
                                  ball_modes=(self._perception.ball_modes
                                              if self.belief_features else ()))

    # ------------------------------------------------------------------------------------
    # Hooks
    # ------------------------------------------------------------------------------------

    def _place(self, rng: np.random.Generator) -> tuple[np.ndarray, tuple[float, float]]:
        """The robots' poses ``(N, 3)`` and the ball's position at the start of an episode,
        drawn from the episode's generator ``rng``."""
        raise NotImplementedError

    def _streams(self, rng: np.random.Generator
                 ) -> tuple[np.random.Generator, np.random.Generator]:
        """The generators of the world's random events (humanoids' falls, kicks, odometry)
        and of the sensors and radio, seeded from ``rng`` after :meth:`_place`: their own
        streams, so that the episode's placements do not depend on the perception
        configuration."""
        world_rng = np.random.default_rng(rng.integers(2**63))
        return world_rng, np.random.default_rng(rng.integers(2**63))

    def _begin(self, rng: np.random.Generator) -> None:
        """The task's own state at the start of an episode (after the world is placed)."""

    def _after_physics(self) -> Any:
        """Events between the physics step and the snapshot; returns the step's event (None
        by default)."""
        return None

    # ------------------------------------------------------------------------------------
    # The fixed parts of reset and step
    # ------------------------------------------------------------------------------------

    def _start(self, rng: np.random.Generator) -> WorldState:
        """Start an episode from ``rng``: place, seed the streams, reset the world, turn the
        heads to the ball, the task's start, the channels and the perception."""
        poses, ball = self._place(rng)
        world_rng, sensor_rng = self._streams(rng)
        w = self.world
        w.reset(poses, ball, world_rng)
        aim_heads(w)
        if self._heads is not None:
            self._heads.reset()
        self._begin(rng)
        state = w.snapshot()
        self._seen, self._shown_belief = self._perception.reset(
            state, sensor_rng, w.body_state() if self._reads_bodies else None)
        # After the perception's reset: randomised sensors draw the episode's command latency
        # and loss there.
        p = self._perception
        for channel, delay, loss in zip(self._channels, p.delays, p.losses):
            channel.reset(sensor_rng, delay, loss)
        return state

    def _advance(self, actions: np.ndarray) -> tuple[WorldState, Any]:
        """One step with every robot's validated ``actions`` ``(N, 6)``: commands, heads,
        channels, physics, the task's events, perception. Returns the new state and the
        step's event."""
        w = self.world
        teams, one = self._teams_in_play, self._one_team
        if one is not None:
            commands = one[0].commands(actions)
        else:
            commands = np.concatenate([m.commands(actions[sl]) for m, sl, _ in teams])
        if self._heads is not None:
            self._heads.apply(commands, w.time, self._perception.attention)
        if one is not None:
            w.step(one[2].send(commands))
        else:
            w.step(np.concatenate([ch.send(commands[sl]) for _, sl, ch in teams]))
        event = self._after_physics()
        state = w.snapshot()
        # Robot 0's beliefs, for its observation and at the present time.
        self._seen, self._shown_belief = self._perception.update(
            state, w.body_state() if self._reads_bodies else None)
        return state, event

    # ------------------------------------------------------------------------------------
    # Reading
    # ------------------------------------------------------------------------------------

    @property
    def pipelines(self) -> list[Any]:
        """The teams' perception pipelines, to inspect their sensors, filters and trackers:
        an SSL team's (:mod:`soccer_env.perception.overhead`; two SSL teams with the same
        configuration share one), a humanoid team's
        (:class:`~soccer_env.perception.humanoid.HumanoidTeamPerception`), or the truth."""
        return self._perception.pipelines

    def _estimate(self, state: WorldState, belief: Any, truth: dict[str, Any]
                  ) -> dict[str, Any]:
        """``info["estimate"]`` of ``belief`` (the truth's dict itself in truth mode)."""
        if belief is state:
            return truth
        return state_dict(belief.time, belief.ball, belief.robots, state.names)

    def _fallen(self, robot: int) -> bool:
        """Whether robot ``robot`` is a humanoid that lies or gets up."""
        walk = self.world.walk
        if walk is None or robot not in walk.indices:
            return False
        return bool(walk.fallen[walk.indices.index(robot)])

    def _scene(self) -> tuple[WorldState, Belief | None, dict[int, tuple]]:
        """What :meth:`render` draws: the truth, the shown belief (None when it is the truth)
        and every humanoid's camera view (see :meth:`~soccer_env.render.Renderer.draw`)."""
        w = self.world
        state = w.snapshot()
        belief = self._shown_belief
        heads: dict[int, tuple] = {}
        if w.walk is not None:
            body = w.body_state()
            for i in w.humanoid_indices:
                lying = body.lying[i]
                heads[i] = (body.heads.pan[i] + body.heads.sway_pan[i],
                            self._perception.cameras[i].hfov, 1.0,
                            None if lying is None else (lying, w.robot_specs[i].lying_length))
        if belief is None or belief is state or not isinstance(belief, Belief):
            return state, None, heads
        # The filters' covariances and particles, read for drawing only.
        return state, belief._replace(spread=self._perception.spread(0, belief.time)), heads

    # ------------------------------------------------------------------------------------
    # What the renderer writes beside the field
    # ------------------------------------------------------------------------------------

    #: The id the title card names (the registered id of the task).
    TASK_ID = "soccer_env"
    #: The seed of the latest seeded reset, and the episodes begun since it (0: this one).
    _render_seed: int | None = None
    _render_episode = 0

    def _note_reset(self, seed: int | None) -> None:
        """Remember the episode's seed for the title card (a reset without a seed continues
        the generator of the latest seeded one)."""
        if seed is not None:
            self._render_seed, self._render_episode = int(seed), 0
        else:
            self._render_episode += 1

    def _seed_text(self) -> str:
        if self._render_seed is None:
            return "unseeded"
        if self._render_episode == 0:
            return f"seed {self._render_seed}"
        return f"seed {self._render_seed} + {self._render_episode} episodes"

    def _perception_text(self, team: int) -> str:
        """Team ``team``'s observations and perception in words (the title card's)."""
        modes = self._perception.obs_modes
        mode, cfg = modes[team], self.perceptions[team]
        if mode == "truth":
            return "truth (no sensors)"
        if self.team_specs[team].kind == "humanoid":
            cams = [c for i, c in self._perception.cameras.items()
                    if int(self.world.teams[i]) == team]
            camera = f"camera {cams[0].name}" if cams else "head cameras"
            if mode == "raw":
                return f"raw: {camera}, dead reckoning, own sightings"
            text = (f"perceived: {camera}, {cfg.localization} localization, {cfg.fusion} "
                    f"fusion, {cfg.ball_tracker} tracker")
        else:
            text = f"{mode}: vision {cfg.vision.name}"
            if mode == "perceived":
                text += f", ball filter {cfg.ball_filter}"
            if cfg.detector != "geometric":
                text += f", {cfg.detector} detector"
        return text + (", randomised" if cfg.randomize else "")

    def _teams_present(self) -> list[int]:
        w = self.world
        return [t for t, n in ((0, w.n_blue), (1, w.n_yellow)) if n]

    def _title_card(self) -> list[str]:
        """The title card: the task and seed, the robots, the observations and perception."""
        w = self.world
        teams = self._teams_present()
        robots = []
        for t in teams:
            n = (w.n_blue, w.n_yellow)[t]
            robots.append(f"{('blue', 'yellow')[t]}: {n} {self.team_specs[t].name} "
                          f"robot{'s' if n > 1 else ''}")
        lines = [f"{self.TASK_ID}    {self._seed_text()}", ",  ".join(robots)]
        texts = [self._perception_text(t) for t in teams]
        if len(set(texts)) == 1:
            lines.append(f"obs {texts[0]}")
        else:
            lines += [f"{('blue', 'yellow')[t]} obs {text}" for t, text in zip(teams, texts)]
        return lines

    def _belief_owner(self) -> str:
        """Whose belief the frames draw: robot 0's (a humanoid's own, else its team's)."""
        name = self.world.names[0]
        if self.world.robot_specs[0].kind == "humanoid":
            return name.replace("_", " ")
        return f"{name.split('_')[0]} team"

    def _caption(self) -> str:
        return self.TASK_ID


class SingleAgentTask(SoccerCore, gym.Env):
    """A Gymnasium task on :class:`SoccerCore`: robot 0 (blue) is the learner.

    ``reset`` and ``step`` are fixed. A task implements :meth:`_place`, :meth:`_observe`,
    :meth:`_outcome`, :meth:`_reward_terms`, :meth:`_task_info` and, when it has other
    robots, :meth:`_others`; optionally :meth:`_streams`, :meth:`_begin` and
    :meth:`_after_physics` (see :class:`SoccerCore`).

    The episode ends (terminated) when :meth:`_outcome` names an outcome; ``info["outcome"]``
    names it and ``info["is_success"]`` says whether it is a success (:meth:`_success`).
    Truncation is left to the registration's ``max_episode_steps``.

    With ``info_mode="flat"`` the info is :func:`~soccer_env.envs.flat_info.flat_common`'s
    entries for robot 0, then ``outcome`` and ``is_success`` as numbers and the task's own
    numbers (:attr:`FLAT_TASK_KEYS`, filled by :meth:`_flat_task_info`).
    """

    #: The task's own flat info keys, after ``outcome`` and ``is_success``.
    FLAT_TASK_KEYS: tuple[str, ...] = ()

    def _observe(self, belief: Any) -> np.ndarray:
        """The learner's observation from its ``belief`` (default: the task's
        ``builder``, an :class:`~soccer_env.observations.ObservationBuilder` for robot 0)."""
        return self.builder.build(belief)[0]

    def _others(self, actions: np.ndarray) -> None:
        """Fill the rows of the other robots in ``actions`` ``(N, 6)`` (row 0 is the
        learner's; the others are zeros: standing still)."""

    def _outcome(self, state: WorldState, event: Any) -> str | None:
        """The episode's outcome at ``state`` (None while it goes on)."""
        raise NotImplementedError

    def _success(self, outcome: str) -> bool:
        """Whether ``outcome`` is a success (``info["is_success"]``)."""
        raise NotImplementedError

    def _reward_terms(self, state: WorldState, action: np.ndarray, outcome: str | None
                      ) -> dict[str, float]:
        """The step's named reward terms (the reward is their sum)."""
        raise NotImplementedError

    def _task_info(self, info: dict[str, Any]) -> None:
        """Add the task's own entries to ``info`` (in place)."""

    def _flat_task_info(self, info: dict[str, float]) -> None:
        """Add the task's own flat entries, :attr:`FLAT_TASK_KEYS`, to ``info`` (in place;
        floats)."""

    @property
    def flat_info_keys(self) -> tuple[str, ...]:
        """The keys of this environment's flat infos (``info_mode="flat"``), in order: the
        same at every reset and step."""
        return flat_keys(self._zero_terms(), ("outcome", "is_success", *self.FLAT_TASK_KEYS))

    def _zero_terms(self) -> dict[str, float]:
        """The reward terms of the first observation, all zero (default: ``"outcome"`` and
        every term of the task's ``shaping`` scales)."""
        return dict.fromkeys(("outcome", *self.shaping), 0.0)

    # ------------------------------------------------------------------------------------

    #: Whether an episode runs (set by :meth:`reset`, cleared when it terminates).
    _running = False
    #: How the last episode ended (its outcome), None while one runs or before the first.
    _ended: str | None = None

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        check_seed(seed)
        super().reset(seed=seed)
        state = self._start(self.np_random)
        self._running, self._ended = True, None
        self._note_reset(seed)
        obs = self._observe(self._seen)
        info = self._info(state, self._zero_terms(), None)
        if self.render_mode == "human":
            self.render()
        return obs, info

    def step(self, action):
        if not self._running:
            if self._ended is not None:
                raise RuntimeError(f"the episode has ended ({self._ended!r}): call reset() "
                                   "before stepping again")
            raise RuntimeError("call reset() before step()")
        try:
            act = np.asarray(action, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError(f"action must be 6 numbers, got {action!r}") from None
        if act.shape != (6,):
            names = ", ".join(self._models[0].action_names)
            raise ValueError(f"action must have shape (6,) ({names}), got {act.shape}")
        act = validate_actions(act[None], self._learner, self.out_of_range_actions)
        n = self.world.n_robots
        if n > 1:
            full = np.zeros((n, 6))
            full[0] = act[0]
            self._others(full)
        else:
            full = act
        state, event = self._advance(full)
        outcome = self._outcome(state, event)
        terms = self._reward_terms(state, act[0], outcome)
        reward = float(sum(terms.values()))
        obs = self._observe(self._seen)
        info = self._info(state, terms, outcome)
        if outcome is not None:  # terminated: a further step would act on a finished shot
            self._running, self._ended = False, outcome
        if self.render_mode == "human":
            self.render()
        return obs, reward, outcome is not None, False, info

    # ------------------------------------------------------------------------------------
    # The outcome banner

    #: The banner's words for each outcome: ``{outcome: (headline, detail)}``.
    OUTCOME_TEXT: dict[str, tuple[str, str]] = {}

    def _time_limit(self) -> int | None:
        """The registered ``max_episode_steps`` of the task this environment was made as
        (``gymnasium.make`` by its id), or None. The banner assumes the registered limit: a
        ``max_episode_steps`` given to ``gymnasium.make`` is the wrapper's, which the
        environment does not see."""
        spec = getattr(self, "spec", None)
        task = GYMNASIUM.get(spec.id) if spec is not None else None
        return None if task is None else task.max_episode_steps

    def _banner(self) -> Banner | None:
        """The outcome banner on frames after the episode's end: the outcome
        (:attr:`OUTCOME_TEXT`; green for a success, red otherwise), or the time limit once the
        registered ``max_episode_steps`` are played."""
        if self._ended is not None:
            head, detail = self.OUTCOME_TEXT.get(self._ended, (self._ended.upper(), ""))
            return Banner(head, detail, "good" if self._success(self._ended) else "bad")
        limit = self._time_limit()
        w = self.world
        if self._running and limit is not None and round(w.time / w.control_dt) >= limit:
            return Banner("TIME LIMIT", f"{w.time:.1f} s played, no outcome")
        return None

    def _info(self, state: WorldState, terms: dict[str, float], outcome: str | None
              ) -> dict[str, Any]:
        if self._flat:
            flat = flat_common(state, self._shown_belief, 0, self._fallen(0), terms)
            flat["outcome"] = float(OUTCOME_CODES[outcome])
            flat["is_success"] = 1.0 if outcome is not None and self._success(outcome) else 0.0
            self._flat_task_info(flat)
            return as_float64(flat)
        truth = state.truth_dict()
        info = {"truth": truth,
                "estimate": self._estimate(state, self._shown_belief, truth),
                "reward_terms": terms, "outcome": outcome}
        self._task_info(info)
        if self.world.walk is not None:
            info["robot_state"] = self.world.humanoid_state()
        if outcome is not None:
            info["is_success"] = self._success(outcome)
        return info


def action_cost(action: np.ndarray, scale: float, dt: float) -> float:
    """The ``action_cost`` shaping term of a step of ``dt`` seconds: ``-scale (vx^2 + vy^2 +
    omega^2) / 3`` of the normalised ``action`` per second."""
    return -scale * float(action[0:3] @ action[0:3]) / 3.0 * dt


def resolve_world(robot: Any, field: Any, ball: Any) -> tuple[RobotSpec, FieldSpec, BallSpec]:
    """The robot, field and ball presets of an environment's arguments: the field defaults to
    the robot preset's, the ball to the field's."""
    spec = presets.robot(robot)
    fld = presets.field(field if field is not None else presets.default_field(spec))
    return spec, fld, presets.ball(ball if ball is not None else fld.ball)
