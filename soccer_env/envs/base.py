"""The task seam: the fixed part of every environment, and the hooks a task fills in.

Data flows one way through a step (the README's "Layout" section has the layers)::

    actions -> robot models -> head control -> command channels -> World.step
            -> task events (a shot is fired, the referee restarts play)
            -> WorldState -> perception (sensors, estimators) -> beliefs -> observations
            -> outcome, reward terms, info

:class:`SoccerCore` owns that loop: the world and its robots' action models, the perception of
both teams (:class:`~soccer_env.perception.match.MatchPerception`), the command channels with
each team's actuation latency and command loss, the humanoids' head control, and rendering
(:class:`~soccer_env.render.RenderingMixin`). :class:`~soccer_env.envs.task.SingleAgentTask`
is its Gymnasium side (robot 0 learns; ``reset`` and ``step`` are fixed); the PettingZoo match
(:class:`~soccer_env.envs.match.SoccerParallelEnv`) is the other. A task's constructor takes its
own arguments and the common settings (:class:`~soccer_env.envs.settings.EnvSettings`, declared
once), and builds the core once with :meth:`SoccerCore._build`.

Every hook, in one place. The required ones are abstract methods: a task class without one of
them cannot be instantiated (``TypeError`` naming it).

The core's (:class:`SoccerCore`, both kinds of task):

=============================  ========  =====================================================
hook                           required  what it gives
=============================  ========  =====================================================
``_place(rng)``                yes       the robots' poses and the ball's position at the
                                         start of an episode
``_streams(rng)``                        the random streams of the world and of the sensors
                                         (default: seeded from the episode's generator, the
                                         world's first)
``_begin(rng)``                          the task's own state at the start (counters, a shot)
``_after_physics()``                     what happens between the physics and the snapshot
                                         (a shot is fired, the referee restarts play); returns
                                         the step's event (default None)
=============================  ========  =====================================================

A Gymnasium task's (:class:`~soccer_env.envs.task.SingleAgentTask`):

=============================  ========  =====================================================
hook                           required  what it gives
=============================  ========  =====================================================
``_outcome(state, event)``     yes       the episode's outcome (None while it goes on)
``_success(outcome)``          yes       whether an outcome is a success (``is_success``)
``_reward_terms(state,``       yes       the step's named reward terms (the reward is their
``action, outcome)``                     sum)
``_observe(belief)``                     the learner's observation (default: row 0 of
                                         :attr:`~SoccerCore.builder`'s)
``_others(actions)``                     the other robots' actions (default: standing still)
``_task_info(info)``                     the task's own entries of the full info
``_flat_task_info(info)``                its own flat entries
                                         (:attr:`~soccer_env.envs.task.SingleAgentTask.FLAT_TASK_KEYS`)
``_zero_terms()``                        the reward terms of the first observation (default:
                                         ``"outcome"`` and every shaping term)
=============================  ========  =====================================================

Rendering's (:class:`~soccer_env.render.RenderingMixin`), every one optional:

=============================  ========  =====================================================
hook                           required  what it gives
=============================  ========  =====================================================
``_hud()``                               the info bar's lines of text (time, shot, score)
``_banner()``                            the outcome banner on frames after the episode's end
                                         (a Gymnasium task's: from
                                         :attr:`~soccer_env.envs.task.SingleAgentTask.OUTCOME_TEXT`)
``_team_labels()``                       the legend's words for the two teams
``_title_card()``                        the title card's lines (the core's: from
                                         :attr:`~SoccerCore.TASK_ID`, the seed, the robots
                                         and the perception)
``_belief_owner()``                      whose belief the frames draw (the core's: robot 0's)
=============================  ========  =====================================================

The attributes the seam reads are declared (annotated) on the classes: those that
:meth:`SoccerCore._build` sets from the settings, and those a task's constructor sets
(:attr:`~SoccerCore.builder`; :attr:`~SoccerCore.shaping`, which
:meth:`~soccer_env.envs.task.SingleAgentTask._build_learner` parses from the class's
:attr:`~SoccerCore.SHAPING`), beside the class constants a task overrides
(:attr:`~SoccerCore.TASK_ID`, :attr:`~SoccerCore.SHAPING`,
:attr:`~soccer_env.envs.task.SingleAgentTask.FLAT_TASK_KEYS`,
:attr:`~soccer_env.envs.task.SingleAgentTask.OUTCOME_TEXT`). ``soccer_env/envs/shootout.py``
is a complete task in one file.
"""

from __future__ import annotations

import abc
from collections.abc import Mapping, Sequence
from typing import Any, ClassVar

import numpy as np

from soccer_env.envs.flat_info import INFO_MODES
from soccer_env.envs.settings import EnvSettings
from soccer_env.observations import ObservationBuilder
from soccer_env.perception.base import OBS_MODES, PerceptionConfig
from soccer_env.perception.match import MatchPerception
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.render import RENDER_MODES, RenderingMixin, check_view
from soccer_env.render.title import TeamCard, belief_owner, perception_text, title_card
from soccer_env.sim.commands import (
    OUT_OF_RANGE_MODES,
    CommandChannel,
    HumanoidRobot,
    SSLRobot,
    robot_model,
)
from soccer_env.sim.heads import HEAD_MODES, HeadControl, aim_heads
from soccer_env.sim.world import World
from soccer_env.state import Belief, WorldState, state_dict
from soccer_env.validation import check_choice, check_integer

__all__ = ["SoccerCore", "RENDER_WIDTHS"]

#: The frame widths a renderer draws, pixels (a 4K frame at most: a frame is width x 2/3
#: width x 3 bytes).
RENDER_WIDTHS = (64, 3840)


class SoccerCore(RenderingMixin, abc.ABC):
    """The world, perception, command channels, head control and rendering of an
    environment, and the fixed parts of its reset and step (the module docstring lists the
    hooks).

    Attributes set by :meth:`_build`: ``settings`` (as given), ``field``, ``ball_spec``,
    ``team_specs`` (blue's and yellow's robot model), ``robot_spec`` (the first robot's),
    ``world``, ``obs_mode`` (a string, or ``{"blue": ..., "yellow": ...}`` when the teams'
    modes differ), ``perceptions`` (both teams'
    :class:`~soccer_env.perception.base.PerceptionConfig`), ``perception`` (blue's),
    ``render_mode``, ``out_of_range_actions``, ``head``, ``info_mode`` (``"full"``: nested
    dicts; ``"flat"``: numbers under fixed keys, see :mod:`soccer_env.envs.flat_info`),
    ``belief_features``. Set by the task's constructor: ``shaping`` and ``builder``.
    """

    metadata: dict[str, Any] = {"render_modes": list(RENDER_MODES), "render_fps": 60}
    #: The registered id of the task (the title card and the window's caption name it).
    TASK_ID: ClassVar[str] = "soccer_env"
    #: The task's shaping terms, name -> description (``shaping={name: scale}`` turns them
    #: on; all off by default).
    SHAPING: ClassVar[Mapping[str, str]] = {}

    # Set by _build.
    settings: EnvSettings
    field: FieldSpec
    ball_spec: BallSpec
    team_specs: tuple[RobotSpec, RobotSpec]
    robot_spec: RobotSpec
    world: World
    obs_mode: str | dict[str, str]
    perceptions: tuple[PerceptionConfig, PerceptionConfig]
    perception: PerceptionConfig
    render_mode: str | None
    out_of_range_actions: str
    head: str
    info_mode: str
    belief_features: bool
    # Set by the task's constructor.
    #: The scales of the task's shaping terms (:attr:`SHAPING`; 0: off).
    shaping: dict[str, float]
    #: The observation builder of the task's learners (its ``names`` name the entries).
    builder: ObservationBuilder

    # ------------------------------------------------------------------------------------
    # Construction
    # ------------------------------------------------------------------------------------

    def _build(self, settings: EnvSettings, *, team_specs: tuple[RobotSpec, RobotSpec],
               n_blue: int, n_yellow: int, field: FieldSpec, ball: BallSpec,
               obs_mode: str | Mapping[str, str],
               perceptions: tuple[PerceptionConfig, PerceptionConfig],
               policy_heads: Sequence[int]) -> None:
        """Build the world and everything around it from the ``settings`` and what the task
        made of them: the teams (``team_specs``, ``n_blue``, ``n_yellow``), the ``field``
        and ``ball`` presets, each team's observation mode (``obs_mode``: one, or
        ``{"blue": ..., "yellow": ...}``) and ``perceptions``.

        ``policy_heads``: the humanoids whose head the policy aims with its action entries 4
        and 5 (with ``head="action"``); every other humanoid's head is aimed by the head
        control. The settings' choices are checked here (``ValueError`` naming the setting).
        """
        s = settings
        for mode in ([obs_mode] if isinstance(obs_mode, str) else obs_mode.values()):
            check_choice("obs_mode", mode, OBS_MODES)
        check_choice("info_mode", s.info_mode, INFO_MODES)
        check_choice("render_mode", s.render_mode, [None, *RENDER_MODES])
        check_choice("out_of_range_actions", s.out_of_range_actions, OUT_OF_RANGE_MODES)
        check_choice("head", s.head, HEAD_MODES)
        if s.head != "auto" and "humanoid" not in (team_specs[0].kind, team_specs[1].kind):
            raise ValueError(f"head aims humanoids' head cameras; these robots are SSL robots, "
                             f"which have none (head must be 'auto'), got {s.head!r}")
        check_integer("render_width", s.render_width, *RENDER_WIDTHS, " pixels")
        self._render_view = check_view(s.render_view)
        self.settings = s
        self.team_specs = team_specs
        self.field, self.ball_spec = field, ball
        self.obs_mode = obs_mode
        self.render_mode = s.render_mode
        self.out_of_range_actions = s.out_of_range_actions
        self.head = s.head
        self.info_mode = s.info_mode
        self._flat = s.info_mode == "flat"
        if not isinstance(s.belief_features, (bool, np.bool_)):
            raise TypeError(f"belief_features must be True or False, got {s.belief_features!r}")
        self.belief_features = bool(s.belief_features)
        self.world = World(field, ball, [team_specs[0]] * n_blue + [team_specs[1]] * n_yellow,
                           n_blue, n_yellow, s.control_dt, s.physics_dt)
        w = self.world
        self._learner = w.names[:1]  # robot 0, named as validate_actions names it
        #: The first robot's model (every robot's when the teams play the same robot).
        self.robot_spec = w.robot_spec
        self.metadata = {**self.metadata, "render_fps": round(1.0 / w.control_dt)}
        self._models: list[SSLRobot | HumanoidRobot] = [robot_model(spec)
                                                         for spec in team_specs]
        self.perceptions = perceptions
        #: Blue's perception configuration (the match's, when both teams share one).
        self.perception = perceptions[0]
        self._perception = MatchPerception(obs_mode, perceptions, field, ball, w.robot_specs,
                                           w.teams.tolist(), w.names, w.control_dt,
                                           self.belief_features)
        self._build_channels(n_blue, n_yellow)
        free = set(policy_heads) if s.head == "action" else set()
        auto = [i for i in w.humanoid_indices if i not in free]
        self._heads = (HeadControl(w.robot_specs, auto,
                                   [self._perception.cameras[i].height for i in auto], s.head)
                       if auto else None)
        self._render_width = int(s.render_width)
        #: Robot 0's beliefs: for its observation, and at the present time (shown and
        #: reported in ``info["estimate"]``).
        self._seen: Any = None
        self._shown_belief: Any = None

    def _build_channels(self, n_blue: int, n_yellow: int) -> None:
        """The command channels: commands reach each team's robots with its actuation latency,
        in whole control steps, and its command loss (none for humanoids, whose walk engine
        is on board)."""
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

    @abc.abstractmethod
    def _place(self, rng: np.random.Generator) -> tuple[np.ndarray, tuple[float, float]]:
        """The robots' poses ``(N, 3)`` and the ball's position at the start of an episode,
        drawn from the episode's generator ``rng``."""

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
        if self._perception.driven:  # a team predicts its robots from what it sends
            self._perception.command(w.time, commands)
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

    # ------------------------------------------------------------------------------------
    # What rendering draws: the scene, and the facts of the title card
    # ------------------------------------------------------------------------------------

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

    def _title_card(self) -> list[str]:
        """The title card (:func:`~soccer_env.render.title.title_card`): the task and seed,
        and every team with robots, its robot preset and its perception."""
        w, p = self.world, self._perception
        cards = []
        for t, n in ((0, w.n_blue), (1, w.n_yellow)):
            if n:
                spec = self.team_specs[t]
                cams = [c.name for i, c in p.cameras.items() if int(w.teams[i]) == t]
                words = perception_text(p.obs_modes[t], self.perceptions[t],
                                        spec.kind == "humanoid", cams[0] if cams else None)
                cards.append(TeamCard(t, n, spec.name, words))
        return title_card(self.TASK_ID, self._seed_text(), cards)

    def _belief_owner(self) -> str:
        """Whose belief the frames draw: robot 0's (a humanoid's own, else its team's)."""
        return belief_owner(self.world.names[0], self.world.robot_specs[0].kind == "humanoid")

    def _caption(self) -> str:
        return self.TASK_ID
