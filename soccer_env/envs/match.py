"""The PettingZoo match: two teams of SSL or humanoid robots (or one of each) on one field.

:class:`SoccerParallelEnv` is the PettingZoo API on the core (:mod:`soccer_env.envs.base`);
what the game flow asks of the world is :class:`~soccer_env.envs.game_flow.GameFlow`'s, the
game block of the observations :class:`~soccer_env.envs.game_rows.GameRows`', and the match's
flat infos :func:`~soccer_env.envs.flat_info.flat_match`'s.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import gymnasium
import numpy as np
from pettingzoo import ParallelEnv

from soccer_env import presets
from soccer_env.envs.base import SoccerCore
from soccer_env.envs.flat_info import (
    FLAT_GAME_KEYS,
    MATCH_KEYS,
    NO_EVENT,
    as_float64,
    flat_common,
    flat_keys,
    flat_match,
)
from soccer_env.envs.game_flow import GameFlow
from soccer_env.envs.game_rows import GAME_FLOW_NAMES, GAME_NAMES, GameRows, game_bounds
from soccer_env.envs.registration import MATCH_ID
from soccer_env.envs.settings import EnvSettings, per_team, settings_keywords
from soccer_env.envs.task_rules import match_terms
from soccer_env.perception.base import OBS_MODES, PerceptionConfig
from soccer_env.presets import RobotSpec
from soccer_env.presets.rules import HumanoidRuleSpec, RuleSpec
from soccer_env.render import RENDER_MODES, Banner
from soccer_env.sim.commands import validate_actions
from soccer_env.sim.game import GameController, GameOptions, game_config
from soccer_env.sim.humanoid_game import HumanoidGameController
from soccer_env.sim.referee import classify_exit, place_free_kick, place_kickoff
from soccer_env.sim.world import MAX_TEAM_SIZE
from soccer_env.validation import (
    check_choice,
    check_int,
    check_options,
    check_range,
    check_seed,
    parse_scales,
    real_array,
)

__all__ = ["SoccerParallelEnv", "parallel_env", "MATCH_SHAPING", "GAME_NAMES",
           "GAME_FLOW_NAMES", "FLAT_GAME_KEYS"]

#: Shaping terms of the match (all off unless given a scale). Rates are per second and
#: multiplied by the control step.
MATCH_SHAPING = {
    "ball_progress": "ball velocity towards the opponent goal [m/s] per second, shared by the "
                     "team (zero-sum between the teams)",
    "ball_distance": "-distance from the agent to the ball [m] per second",
}


class SoccerParallelEnv(SoccerCore, ParallelEnv):
    """A match between a blue and a yellow team (PettingZoo ``ParallelEnv``) of SSL robots,
    humanoids, or one team of each.

    ## Agents
    ``blue_0 .. blue_{n-1}`` and ``yellow_0 .. yellow_{m-1}``; blue attacks ``+x``. With two
    or more robots, robot 0 of each team starts in the keeper slot. All agents act at once and
    the physics steps once per parallel step.

    ## Actions
    ``Box(-1, 1, (6,), float32)`` per agent, as in :class:`~soccer_env.sim.commands.SSLRobot` or,
    for humanoids, :class:`~soccer_env.sim.commands.HumanoidRobot` (whose head entries 4 and 5 are
    used only with ``head="action"``).

    ## Observations
    ``Box(float32)`` per agent, laid out as in :mod:`soccer_env.observations` (own pose and
    velocity, ball, team-mates, opponents, goal posts), followed by the game state
    :data:`GAME_NAMES`: match time left as a fraction of ``match_duration``, goals for,
    goals against, and +1 / -1 while a restart awarded to the agent's own team / the opponents
    waits for its first touch (0 otherwise); with the game flow (``game=...``) also the
    referee state :data:`GAME_FLOW_NAMES` (the command as a situation, ours or theirs, the
    designated position, the stage and its time left, cards, fouls, robots allowed, and
    whether the agent's robot is on the field), and ``game.time_left`` counts playing time.
    Yellow's observations are in its own team frame, so one policy can play both sides.

    ## Rewards
    Zero-sum on goals: +1 to every agent of the scoring team, -1 to every agent of the other.
    Shaping terms :data:`MATCH_SHAPING` are off unless ``shaping={name: scale}`` turns them on;
    ``info[agent]["reward_terms"]`` logs each.

    ## Rules and episode end
    By default (``game=None``) the simple referee of :mod:`soccer_env.sim.referee`: goals,
    outs, free kicks and kick-offs, robots moved instantly. All agents are terminated when the
    match clock reaches ``match_duration`` (the clock is part of the observation, so its end is
    a terminal state of the game); all are truncated after ``max_cycles`` parallel steps if
    that is set.

    With ``game=...`` the match plays the game flow of the rule book on the truth: for SSL
    teams the RoboCup SSL rules, 2025 edition (:class:`~soccer_env.sim.game.GameController`:
    stop, ball placement by the teams' robots, kick-offs, free kicks, penalty kicks, fouls,
    yellow and red cards, half time), for humanoid teams the RoboCup Humanoid League laws,
    2025 (:class:`~soccer_env.sim.humanoid_game.HumanoidGameController`: kick-off, drop ball,
    throw-in, goal and corner kicks, removal penalties). The robots play the restarts
    themselves (the teams' software reads the game block); the simulation only lines the
    teams up for kick-offs and penalty kicks, places the ball where the referee would, and
    takes robots sent off to the run-off area beyond the touch line at ``y < 0`` (their
    actions are ignored until they return). ``match_duration`` is then playing time (the
    clock stops while the ball is out of play in SSL matches), and the episode terminates when
    the controller ends the match. ``game``: True (the robot kind's rules), a rule preset's
    name (:data:`~soccer_env.presets.rules.RULES`: ``"ssl-2025-div-b"``,
    ``"ssl-2025-div-a"``, ``"humanoid-2025-kid"``) or spec, or a mapping with ``rules`` and,
    for SSL rules, the options of :class:`~soccer_env.sim.game.GameOptions` (``placement``,
    ``fouls``, ``cards``, ``half_time``, ``free_kicks``). Batched matches and mixed matches do
    not play it.

    ## Info
    Every agent's info holds ``truth`` (the same dict for all agents: ball and every robot in
    field coordinates), ``estimate`` (the present-time belief of the agent's team, or for a
    humanoid its own, same keys), ``reward_terms``, ``score`` ``{"blue": int, "yellow":
    int}`` and ``event`` (``""`` when nothing ended the ball's play, ``"goal"``,
    ``"touch"``, ``"goal_line"``, ``"over_bar"`` or, with the game flow, ``"invalid_goal"``);
    with the game flow, ``game`` (the referee state: ``command``, ``command_team``,
    ``situation``, ``situation_team`` (``""`` for no team), ``next_command`` (``(command,
    team)``, ``()`` for none), ``designated`` (``(x, y)``, ``()`` for none), ``in_play``,
    ``stage``, ``stage_time_left``,
    ``playing_time_left``, the step's ``events`` as the SSL game controller names them, and
    per team ``goals``, ``fouls``, ``yellow_cards`` (time left of each [s]), ``red_cards``,
    ``placement_failures``, ``can_place``, ``robots_allowed``, ``off_field``);
    with humanoids in the match, ``robot_state`` (every humanoid's walk engine state, see
    :meth:`~soccer_env.sim.world.World.humanoid_state`). With ``info_mode="flat"``: numbers
    only under fixed keys (:attr:`flat_info_keys`), the agent's own robot's truth and belief,
    ``event`` as a code, ``score_blue`` and ``score_yellow`` (:mod:`soccer_env.envs.flat_info`).

    ## Perception
    Each team perceives with its own pipeline (``perception`` for both, or
    ``{"blue": ..., "yellow": ...}``, and likewise ``obs_mode``: one team may see the truth or
    raw detections while the other filters them): SSL teams through the overhead vision (two
    SSL teams on the same vision preset read the same camera frames, as SSL-Vision serves both
    teams, each filtering them its own way), humanoid teams
    each robot through its head camera, its localization and the team radio
    (:mod:`soccer_env.perception.humanoid`), so a humanoid agent's observation and
    ``info["estimate"]`` are its own belief.

    ## Arguments
    ``blue``, ``yellow`` (team sizes, 0..11, at least one robot in all); ``robot`` (a preset
    name or spec for both teams, or ``{"blue": ..., "yellow": ...}``), ``field`` (default:
    Division B for SSL, the humanoid preset's field otherwise), ``ball``, ``obs_mode``,
    ``perception``, ``render_mode``, ``control_dt``, ``physics_dt``,
    ``out_of_range_actions`` as in :class:`~soccer_env.envs.goalkeeper.GoalkeeperEnv`;
    ``match_duration`` [s]; ``max_cycles``; ``shaping``; ``formation_jitter`` (metres of
    uniform jitter of the kick-off formation); ``render_width``; ``render_view`` ("field" or
    "follow", as in :class:`~soccer_env.envs.goalkeeper.GoalkeeperEnv`); ``head`` (humanoid
    agents: "auto", "scan" or "action"); ``belief_features`` (every agent's observation ends with
    how sure its belief is: 11 entries, 13 with humanoids in the match, 3 more when every team's
    ball filter is ``"imm"``; see
    :mod:`soccer_env.observations`); ``info_mode`` ("full", the default, or "flat");
    ``game`` (see Rules).
    """

    #: ``name`` is the registered id (``pettingzoo.make``'s and ``soccer_env.PETTINGZOO``'s).
    metadata = {"name": MATCH_ID, "render_modes": list(RENDER_MODES),
                "render_fps": 60, "is_parallelizable": True}
    TASK_ID = metadata["name"]
    SHAPING = MATCH_SHAPING

    #: The match's length [s] (playing time with the game flow).
    match_duration: float
    #: Parallel steps after which every agent is truncated (None: no limit).
    max_cycles: int | None
    #: Metres of uniform jitter of the kick-off formation.
    formation_jitter: float
    #: The game flow's rule preset and options (None: the simple referee).
    game_rules: RuleSpec | HumanoidRuleSpec | None
    game_options: GameOptions | None
    #: The first robot's action mapping.
    robot_model: Any
    #: The bounds of :meth:`state`.
    state_space: gymnasium.spaces.Box
    #: Goals of blue and yellow in the running match.
    score: list[int]
    #: The team whose restart waits for its first touch (-1: none).
    restart_team: int
    #: Parallel steps of the running match.
    cycles: int

    @settings_keywords
    def __init__(self, *, blue: int = 6, yellow: int = 6, match_duration: float = 300.0,
                 max_cycles: int | None = None, formation_jitter: float = 0.1,
                 game: Any = None, **settings: Any) -> None:
        s = EnvSettings.from_keywords("parallel_env", settings, SoccerParallelEnv.__init__)
        blue = check_int("blue", blue, 0, MAX_TEAM_SIZE)
        yellow = check_int("yellow", yellow, 0, MAX_TEAM_SIZE)
        if blue + yellow < 1:
            raise ValueError(f"a match needs at least one robot: blue + yellow must be >= 1, "
                             f"got {blue} + {yellow}")
        modes = per_team("obs_mode", s.obs_mode)
        for team, mode in zip(("blue", "yellow"), modes):
            # before it picks the default perception
            check_choice("obs_mode" if modes[0] == modes[1] else f"obs_mode of {team}", mode,
                         OBS_MODES)
        self.match_duration = check_range("match_duration", match_duration, 1e-3, 1e6)
        if max_cycles is not None:
            max_cycles = check_int("max_cycles (a positive integer or None)", max_cycles, 1,
                                   10**12)
        self.max_cycles = max_cycles
        self.formation_jitter = check_range("formation_jitter", formation_jitter, 0.0, 1.0)
        team_specs = tuple(presets.robot(r) for r in per_team("robot", s.robot))
        _, fld, bl = s.presets(team_specs[0] if blue else team_specs[1])
        self.shaping = parse_scales("shaping", s.shaping, self.SHAPING)
        perceptions = tuple(PerceptionConfig.create(p, m, spec.kind) for p, m, spec in
                            zip(per_team("perception", s.perception), modes, team_specs))
        both = modes[0] if modes[0] == modes[1] else {"blue": modes[0], "yellow": modes[1]}
        self._build(s, team_specs=team_specs, n_blue=blue, n_yellow=yellow, field=fld,
                    ball=bl, obs_mode=both, perceptions=perceptions,
                    policy_heads=range(blue + yellow))
        self._build_game(game, team_specs, blue, yellow)
        self._build_agents(blue)

    def _build_game(self, game: Any, team_specs: tuple[RobotSpec, RobotSpec], blue: int,
                    yellow: int) -> None:
        """The game flow of the ``game`` argument (None: the simple referee). It needs both
        teams of one robot kind (SSL rules or humanoid laws)."""
        kinds = {spec.kind for spec, n in zip(team_specs, (blue, yellow)) if n}
        cfg = game_config(game, "ssl-2025-div-b" if kinds == {"ssl"} else "humanoid-2025-kid")
        if cfg is not None and kinds != {cfg[0].kind}:
            raise ValueError(f"game rules {cfg[0].name!r} are for matches of {cfg[0].kind} "
                             f"robots; this match plays {sorted(kinds)} (the game flow needs "
                             "both teams of one robot kind)")
        self.game_rules, self.game_options = cfg if cfg is not None else (None, None)
        self._flow = (None if cfg is None else
                      GameFlow(self.world, cfg[0], cfg[1], self.match_duration,
                               self.formation_jitter))

    def _build_agents(self, blue: int) -> None:
        """The agents, their spaces and observation builders, and the match's state."""
        w = self.world
        self.robot_model = self._models[0] if blue else self._models[1]
        self.possible_agents = list(w.names)
        self.agents: list[str] = []
        game_low, game_high, game_names = game_bounds(self.field, self.game_rules is not None,
                                                      w.n_robots - 1)
        self.builder = self._observation_builder(range(w.n_robots), game_low, game_high,
                                                 game_names)
        self._teams = w.teams.tolist()
        #: Every possible agent's spaces (PettingZoo's ``observation_spaces`` and
        #: ``action_spaces``; ``observation_space(agent)`` reads them).
        self.observation_spaces = {a: self.builder.space() for a in self.possible_agents}
        self.action_spaces = {a: self._models[t].action_space()
                              for a, t in zip(self.possible_agents, self._teams)}
        # One observation builder per group of robots that share a belief.
        self._builders = [(g, self._observation_builder(g, game_low, game_high, game_names))
                          for g in self._perception.groups]
        self._rows = GameRows(self._teams, w.n_blue, self.match_duration)
        self.state_space = _state_space(self.field, w.n_robots)
        self.score = [0, 0]
        self.restart_team = -1
        self.cycles = 0
        self._rng: np.random.Generator | None = None

    @property
    def game(self) -> GameController | HumanoidGameController | None:
        """The episode's game controller (None without the game flow, or before the first
        reset)."""
        return None if self._flow is None else self._flow.game

    @property
    def off_field(self) -> list[int]:
        """The robots off the field (by cards or removal penalties), in the order they
        left."""
        return [] if self._flow is None else self._flow.off_field

    # ------------------------------------------------------------------------------------
    # Task hooks
    # ------------------------------------------------------------------------------------

    def _place(self, rng: np.random.Generator) -> tuple[np.ndarray, tuple[float, float]]:
        self._kickoff = int(rng.integers(2))
        return place_kickoff(self.world, self._kickoff, rng, self.formation_jitter), (0.0, 0.0)

    def _begin(self, rng: np.random.Generator) -> None:
        self.agents = list(self.possible_agents)
        self.score = [0, 0]
        self.restart_team = self._kickoff
        self.cycles = 0
        if self._flow is not None:
            self._flow.start(self._kickoff, rng)
            self.restart_team = self._flow.game.restart_team

    def _after_physics(self) -> tuple[str | None, int]:
        """The referee: the step's event (None, ``"goal"``, ``"touch"``, ``"goal_line"``,
        ``"over_bar"``, with the game flow also ``"invalid_goal"``) and the scoring team (-1
        if none)."""
        self.cycles += 1
        if self._flow is not None:
            return self._referee_game()
        w = self.world
        if any(w.touched):
            self.restart_team = -1
        event, scorer = None, -1
        if w.ball_exit is not None:
            kind = classify_exit(w.ball_exit, self.field, self.ball_spec)
            event = kind.kind
            if kind.kind == "goal":
                scorer = kind.scorer
                self.score[scorer] += 1
                self.restart_team = 1 - scorer
                w.place_all(place_kickoff(w, 1 - scorer, self._rng, self.formation_jitter))
            else:
                self.restart_team = place_free_kick(w, w.ball_exit, kind)
            w.clear_exit()
        return event, scorer

    def _referee_game(self) -> tuple[str | None, int]:
        """One step of the game flow (:meth:`~soccer_env.envs.game_flow.GameFlow.step`): the
        step's event and the scoring team (-1 if none)."""
        d = self._flow.step(self._rng)
        self.restart_team = self._flow.game.restart_team
        if d.scorer >= 0:
            self.score[d.scorer] += 1
        event = d.exit_kind
        if event == "goal" and d.scorer < 0:
            event = "invalid_goal"
        return event, d.scorer

    # ------------------------------------------------------------------------------------
    # PettingZoo API
    # ------------------------------------------------------------------------------------

    def observation_space(self, agent: str) -> gymnasium.spaces.Box:
        return self.observation_spaces[agent]

    def action_space(self, agent: str) -> gymnasium.spaces.Box:
        return self.action_spaces[agent]

    def reset(self, seed: int | None = None, options: dict | None = None):
        check_seed(seed)
        # PettingZoo's API test resets with options no environment knows: others are
        # ignored, but they must be a dict.
        check_options(options, (), type(self).__name__, strict=False)
        if seed is not None or self._rng is None:
            self._rng = np.random.default_rng(seed)
        state = self._start(self._rng)
        self._note_reset(seed)
        self._end_reason = None
        obs = self._observe()
        zero = dict.fromkeys(("goal", *MATCH_SHAPING), 0.0)
        infos = self._infos(state, {a: zero for a in self.agents}, None)
        if self.render_mode == "human":
            self.render()
        return obs, infos

    def step(self, actions: Mapping[str, Any]):
        if not self.agents:
            raise RuntimeError("the match is over (no live agents); call reset()")
        act = self._gather(actions)
        off_field = self.off_field
        if off_field:  # robots off the field stand still
            act[off_field] = 0.0
        w = self.world
        ball_x_before = float(w.ball_array()[0]) if self.shaping["ball_progress"] else 0.0
        state, (event, scorer) = self._advance(act)
        rewards, terms = self._rewards(state, event, scorer, ball_x_before)
        obs = self._observe()
        if self._flow is not None:
            decision = self._flow.decision
            done = decision is not None and decision.over
        else:
            done = w.time >= self.match_duration - 1e-9
        trunc = self.max_cycles is not None and self.cycles >= self.max_cycles
        infos = self._infos(state, terms, event)
        terminations = dict.fromkeys(self.agents, bool(done))
        truncations = dict.fromkeys(self.agents, bool(trunc and not done))
        if done or trunc:
            self.agents = []
            self._end_reason = "full time" if done else "time limit"
        if self.render_mode == "human":
            self.render()
        return obs, rewards, terminations, truncations, infos

    def state(self) -> np.ndarray:
        """Global true state for centralised critics: ball ``x, y, z, vx, vy, vz`` then each
        robot's ``x, y, theta, vx, vy, omega`` (field frame), float32."""
        s = self.world.snapshot()
        return np.concatenate([s.ball, s.robots.ravel()]).astype(np.float32)

    def _hud(self) -> list[str]:
        lines = [f"blue {self.score[0]} : {self.score[1]} yellow",
                 f"t = {self.world.time:6.2f} s"]
        g = self.game
        if g is not None:
            team = "" if g.command_team < 0 else (" blue" if g.command_team == 0 else " yellow")
            lines.append(f"{g.command}{team}, {g.stage}")
        return lines

    #: Why the latest match ended (``"full time"``, ``"time limit"``), None while it runs.
    _end_reason: str | None = None

    def _banner(self) -> Banner | None:
        """The final score once the match is over: full time (the clock or the game
        controller ended it) or the ``max_cycles`` time limit."""
        if self._end_reason is None:
            return None
        head = "FULL TIME" if self._end_reason == "full time" else "TIME LIMIT"
        return Banner(head, f"blue {self.score[0]} : {self.score[1]} yellow")

    # ------------------------------------------------------------------------------------
    # Actions
    # ------------------------------------------------------------------------------------

    def check_action(self, agent: str, action: Any) -> np.ndarray:
        """``action`` of the live agent ``agent`` as the step will take it (a float array of
        shape ``(6,)``, clipped under ``out_of_range_actions="clip"``); ``ValueError`` naming
        the agent for an unknown or finished agent, a wrong shape, a non-finite value or
        (``"raise"``) a value outside [-1, 1]. The AEC environment checks each agent's action
        with it when the agent acts."""
        if agent not in self.agents:
            raise ValueError(f"action for unknown or finished agent {agent!r}; live agents: "
                             f"{self.agents}")
        try:
            act = np.asarray(action, dtype=np.float64)
        except (TypeError, ValueError):
            act = None
        if act is None or act.shape != (6,):
            raise ValueError(f"action for agent {agent!r} must have shape (6,) "
                             f"({self._action_names(agent)}), got {np.shape(action)}")
        return validate_actions(act[None], [agent], self.out_of_range_actions)[0]

    def _action_names(self, agent: str) -> str:
        """The names of the action entries of ``agent``'s robot model, in words."""
        model = self._models[self._teams[self.possible_agents.index(agent)]]
        return ", ".join(model.action_names)

    def _gather(self, actions: Mapping[str, Any]) -> np.ndarray:
        """Stack the live agents' actions into ``(N, 6)``; validate before touching the world."""
        if not isinstance(actions, Mapping):
            raise TypeError(f"actions must be a dict {{agent: action}}, got "
                            f"{type(actions).__name__}")
        agents = self.agents
        if len(actions) != len(agents) or not all(a in actions for a in agents):
            unknown = sorted(set(actions) - set(agents), key=repr)
            if unknown:
                raise ValueError(f"actions for unknown or finished agent(s) {unknown}; live "
                                 f"agents: {agents}")
            missing = [a for a in agents if a not in actions]
            raise ValueError(f"missing actions for agent(s) {missing}; every live agent must "
                             "act")
        try:
            act = real_array("actions", [actions[a] for a in agents])
        except (TypeError, ValueError):  # ragged or not real numbers: find the culprit below
            act = None
        if act is None or act.shape != (len(agents), 6):
            for a in agents:
                try:
                    shape: Any = np.shape(actions[a])
                except ValueError:  # a ragged sequence has no shape
                    shape = "a ragged sequence"
                if shape != (6,):
                    raise ValueError(f"action for agent {a!r} must have shape (6,) "
                                     f"({self._action_names(a)}), got {shape}")
            raise ValueError("actions must be arrays of 6 real numbers")
        return validate_actions(act, agents, self.out_of_range_actions)

    # ------------------------------------------------------------------------------------
    # Observations, rewards, infos
    # ------------------------------------------------------------------------------------

    def _observe(self) -> dict[str, np.ndarray]:
        g = self.game
        if g is None:
            game = self._rows.simple(self.world.time, self.score, self.restart_team)
        else:
            game = self._rows.flow(g, self.score, self.restart_team, self._flow.off_field)
        if len(self._builders) == 1:
            rows = self.builder.build(self._perception.belief(0), game)
            return dict(zip(self.possible_agents, rows))
        out = {}
        for group, builder in self._builders:
            rows = builder.build(self._perception.belief(group[0]), game[group])
            for i, row in zip(group, rows):
                out[self.possible_agents[i]] = row
        return {a: out[a] for a in self.possible_agents}

    def _rewards(self, state, event: str | None, scorer: int, ball_x_before: float):
        """Per-agent rewards and their named terms (see :data:`MATCH_SHAPING`)."""
        decision = None if self._flow is None else self._flow.decision
        moved = decision is not None and (decision.line_up is not None
                                          or decision.place_ball is not None)
        sc = self.shaping
        goal, progress, distance = match_terms(
            (float(state.ball[0]), float(state.ball[1])), state.robots, state.teams,
            scorer, float(state.ball[0]) - ball_x_before, event is None and not moved,
            (float(sc["ball_progress"]), float(sc["ball_distance"])),
            self.world.control_dt).T.tolist()
        rewards, terms = {}, {}
        for a, g, p, d in zip(self.possible_agents, goal, progress, distance):
            rewards[a] = g + p + d
            terms[a] = {"goal": g, "ball_progress": p, "ball_distance": d}
        return rewards, terms

    @property
    def flat_info_keys(self) -> tuple[str, ...]:
        """The keys of every agent's flat info (``info_mode="flat"``), in order: the same for
        every agent at every reset and step."""
        extra = MATCH_KEYS
        if self.game_rules is not None:
            extra += FLAT_GAME_KEYS
        return flat_keys(("goal", *MATCH_SHAPING), extra)

    def _infos(self, state, terms: dict, event: str | None) -> dict[str, dict]:
        """Every live agent's info: the truth, its team's or its own present belief."""
        if self._flat:
            return self._flat_infos(state, terms, event)
        truth = state.truth_dict()
        robot_state = self.world.humanoid_state() if self.world.walk is not None else None
        game = self._flow.info(self.score) if self.game is not None else None
        estimates: dict[int, dict] = {}
        infos = {}
        for a in self.agents:
            i = self.world.names.index(a)
            belief = self._perception.current(i)
            key = id(belief)
            if key not in estimates:
                estimates[key] = self._estimate(state, belief, truth)
            infos[a] = {"truth": truth, "estimate": estimates[key], "reward_terms": terms[a],
                        "score": {"blue": self.score[0], "yellow": self.score[1]},
                        "event": NO_EVENT if event is None else event}
            if robot_state is not None:
                infos[a]["robot_state"] = robot_state
            if game is not None:
                infos[a]["game"] = game
        return infos

    def _flat_infos(self, state, terms: dict, event: str | None) -> dict[str, dict]:
        """Every live agent's flat info (:mod:`soccer_env.envs.flat_info`)."""
        game = flat_match(event, self.score, self.game)
        names = self.world.names
        infos = {}
        for a in self.agents:
            i = names.index(a)
            info = flat_common(state, self._perception.current(i), i, self._fallen(i), terms[a])
            info.update(game)
            infos[a] = as_float64(info)
        return infos


#: Bounds of :meth:`SoccerParallelEnv.state` beyond the walls' and the robots' own limits:
#: a metre past the walls for contact penetration, the ball's height up to 10 m (a chip at
#: the kick cap rises under 2 m), speeds up to 100 m/s and turn rates up to 1,000 rad/s (an
#: order of magnitude above the robots' and the kicker's caps).
STATE_MARGIN, STATE_MAX_HEIGHT, STATE_MAX_SPEED, STATE_MAX_TURN = 1.0, 10.0, 100.0, 1000.0


def _state_space(field: Any, n_robots: int) -> gymnasium.spaces.Box:
    """The finite ``Box`` of the global state: ball ``x, y, z, vx, vy, vz``, then per robot
    ``x, y, theta, vx, vy, omega`` [m, rad, m/s, rad/s]."""
    x = field.half_length + field.boundary + STATE_MARGIN
    y = field.half_width + field.boundary + STATE_MARGIN
    v, w = STATE_MAX_SPEED, STATE_MAX_TURN
    ball_low, ball_high = [-x, -y, 0.0, -v, -v, -v], [x, y, STATE_MAX_HEIGHT, v, v, v]
    robot_low, robot_high = [-x, -y, -math.pi, -v, -v, -w], [x, y, math.pi, v, v, w]
    return gymnasium.spaces.Box(np.array(ball_low + robot_low * n_robots, np.float32),
                                np.array(ball_high + robot_high * n_robots, np.float32),
                                dtype=np.float32)


def parallel_env(**kwargs: Any) -> SoccerParallelEnv:
    """The match as a PettingZoo ``ParallelEnv`` (see :class:`SoccerParallelEnv`)."""
    return SoccerParallelEnv(**kwargs)
