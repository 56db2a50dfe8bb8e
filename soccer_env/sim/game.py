"""The SSL game flow: the referee commands, stages, fouls and cards of the RoboCup Small Size
League rules, 2025 edition (https://robocup-ssl.github.io/ssl-rules/2025/sslrules.html; the
numbers in :data:`soccer_env.presets.RULES`, section numbers below are the rule book's).

:class:`GameController` plays the SSL game controller and its automatic referees on the truth:
each control step it reads a :class:`Frame` (the ball, the robots and which robots touched the
ball during the step) and returns a :class:`Decision`: the game events of the step (named as
the SSL game controller names them), whether a goal counts, and what the simulation must do
for the referee (place the ball, line the teams up, take a robot off the field or bring it
back). It never touches the physics itself, so each rule is tested on constructed frames.

Commands (what a team's software receives, :data:`COMMANDS`): ``stop``, ``ball_placement``
(by a team), ``prepare_kickoff``, ``prepare_penalty``, ``normal_start``, ``direct_free`` (for
a team) and ``force_start``. Halt is not used: the simulation has no emergencies.

The flow (5):

* **Kick-off** (5.3.2) at the start of each half and after a goal: the ball on the centre
  spot, both teams lined up in their halves by the simulation (the referee places the ball;
  the formation is the one :func:`~soccer_env.sim.referee.place_kickoff` builds, in which the
  robots' own software would have driven them), then ``normal_start``. The ball is in play
  once it has moved :attr:`~RuleSpec.ball_in_play_distance` or after
  :attr:`~RuleSpec.kickoff_time`.
* **Stop** (5.1.1) after the ball leaves the field, a foul that stops the game, or a goal:
  every robot must keep :attr:`~RuleSpec.stop_distance` from the ball and move slower than
  :attr:`~RuleSpec.stop_speed`.
* **Ball placement** (5.2) by the team that will bring the ball into play, when the ball is
  not already close to the designated position: it succeeds when the ball rests within
  :attr:`~RuleSpec.placement_tolerance` of it, no robot within
  :attr:`~RuleSpec.placement_clearance`, no earlier than :attr:`~RuleSpec.placement_min_time`
  and within :attr:`~RuleSpec.placement_time`. A failure gives the free kick to the other
  team, which must place in turn; if it fails too, the referee places the ball and the
  original command follows. A team that failed :attr:`~RuleSpec.max_placement_failures` times
  (net of successes) may not place for the rest of the half. With ``placement="referee"`` (or
  for a team that may not place) the referee places the ball at once.
* **Free kick** (5.3.3) for throw-ins, goal kicks, corner kicks (6), fouls and failed
  placements: all free kicks are direct, as in the 2025 rules; with ``free_kicks="2019"`` the
  2019 edition's indirect free kick is played after throw-ins, double touches, aimless kicks
  and failed placements: a goal counts only if the ball touched a robot of the attacking team
  after it entered play (the 2019 rules, 5.3.4). The ball is in play once it has moved
  :attr:`~RuleSpec.ball_in_play_distance` or after :attr:`~RuleSpec.free_kick_time`.
* **Penalty kick** (5.3.5) after the multiple-defenders foul: the ball on the penalty mark,
  the keeper on its goal line and everybody else :attr:`~RuleSpec.penalty_behind` behind the
  ball (set by the simulation), then ``normal_start``. A goal counts; the game goes on with a
  goal kick for the defenders if the ball leaves the field elsewhere, moves away from the
  goal, is turned back by the keeper (its direction changed by 90 degrees or more) or is still
  in play after :attr:`~RuleSpec.penalty_time`.
* **Force start** (5.3.4) after no progress (8.1): both teams may play at once.
* **Stages** (4.4.1): two halves of ``duration / 2`` seconds of playing time (the clock runs
  only while a team may play the ball), the second started by the team that did not start
  the first; teams keep their ends (the simulated field is symmetric). The half-time break,
  timeouts, overtime and the shoot-out are not played. The match ends early when a team has
  10 goals and leads by more than one (4.4.3).

Fouls (8.4), each a game event against a team, every :attr:`~RuleSpec.fouls_per_card`-th of a
team giving it a yellow card: a yellow card takes one of its robots off the field for
:attr:`~RuleSpec.yellow_card_time` seconds of playing time, and a third running card is a red
card, for the rest of the match (5.5). The robot taken off is the team's highest-numbered
robot on the field other than its keeper (robot 0), and it comes back at the first stop after
its card expires. A team keeps at least one robot. Implemented:

* stopping fouls, then a free kick for the other team from where the ball was: a robot too
  close to the opponent defense area during stop or a free kick
  (``attacker_too_close_to_defense_area``), the ball kept in a defense area too long
  (``keeper_held_ball``), a double touch after a kick-off or free kick
  (``attacker_double_touched_ball``; 8.2);
* the multiple-defenders foul: a robot other than the keeper touching the ball while entirely
  inside its own defense area gives a penalty kick, without counting as a foul
  (``defender_in_defense_area``);
* non-stopping fouls: an attacker touching the ball while partly inside the opponent defense
  area (``attacker_touched_ball_in_defense_area``), a ball kicked faster than
  :attr:`~RuleSpec.ball_speed_limit` (``bot_kicked_ball_too_fast``), crashing
  (``bot_crash_unique``, ``bot_crash_drawn``);
* fouls while the ball is out of play: too close to the ball at an opponent kick-off or free
  kick (``defender_too_close_to_kick_point``), too fast during stop (``bot_too_fast_in_stop``),
  interfering with the opponent's ball placement (``bot_interfered_placement``);
* aimless kicks in Division B (6.2.3) and no progress (8.1).

Not implemented: pushing, ball holding, excessive dribbling, boundary crossing (the walls keep
the ball in), tipping over, robot substitutions beyond the cards', timeouts, and the
referee's discretion (unsporting behaviour, red cards for severe fouls).

Distances from a robot are from its nearest side (its centre minus its radius), as the rule book
measures them (2.1.3). Blue (team 0) defends the goal at ``x = -length / 2``. Keeper ids are
robot 0 of each team.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec
from soccer_env.presets.rules import HumanoidRuleSpec, RuleSpec
from soccer_env.presets.rules import rules as rule_preset
from soccer_env.sim.referee import ExitKind, classify_exit, free_kick_spot

__all__ = ["GameController", "GameOptions", "Frame", "Decision", "GameEvent", "TeamInfo",
           "COMMANDS", "STAGES", "PLACEMENTS", "FREE_KICK_RULES", "FOULS", "SITUATIONS",
           "GAME_KEYS", "game_config", "RefereeState", "segment_distance"]

#: Referee commands, as a team's software receives them.
COMMANDS = ("stop", "ball_placement", "prepare_kickoff", "prepare_penalty", "normal_start",
            "force_start", "direct_free")
#: Stages of a match.
STAGES = ("first_half", "second_half", "post_game")
#: Who places the ball: the teams' robots, or the referee.
PLACEMENTS = ("robots", "referee")
#: Free-kick rules: all direct (2025), or the 2019 edition's indirect ones.
FREE_KICK_RULES = ("2025", "2019")
#: Game events that are fouls counted towards cards.
FOULS = ("attacker_too_close_to_defense_area", "keeper_held_ball",
         "attacker_double_touched_ball", "attacker_touched_ball_in_defense_area",
         "bot_kicked_ball_too_fast", "bot_crash_unique", "bot_crash_drawn",
         "defender_too_close_to_kick_point", "bot_too_fast_in_stop",
         "bot_interfered_placement")

#: What a team's software makes of the command (:meth:`GameController.situation`): the
#: restart being prepared or taken, or open play.
SITUATIONS = ("stop", "placement", "kickoff", "penalty", "free_kick", "running")
#: Keys of the ``game`` argument's mapping form (:func:`game_config`).
GAME_KEYS = ("rules", "placement", "fouls", "cards", "half_time", "free_kicks")

#: A ball slower than this is stationary [m/s] (the rule book leaves it to the referee).
STATIONARY_SPEED = 0.05
#: Two robots closer than the sum of their radii plus this touch [m].
CONTACT_SLACK = 0.005
#: Goals that end a match early, and the lead needed (4.4.3).
EARLY_END_GOALS, EARLY_END_LEAD = 10, 1


class Frame(NamedTuple):
    """What the controller reads after a control step (truth, field frame).

    Attributes:
        time: simulated time [s].
        ball: ``(6,)`` ball ``x, y, z, vx, vy, vz`` [m, m/s].
        robots: ``(N, 6)`` robots ``x, y, theta, vx, vy, omega`` (blue first).
        touched: per robot, whether it touched the ball during the step.
        exit: where the whole ball first lay beyond a field line during the step (a
            :class:`~soccer_env.sim.world.BallExit`), or None.
    """

    time: float
    ball: np.ndarray
    robots: np.ndarray
    touched: Sequence[bool]
    exit: object | None = None


@dataclass(frozen=True)
class GameEvent:
    """One game event: ``kind`` (the SSL game controller's name), the team at fault or
    concerned (0 blue, 1 yellow, -1 none), the robot (-1 none) and where [m]."""

    kind: str
    team: int = -1
    robot: int = -1
    x: float = math.nan
    y: float = math.nan


@dataclass
class Decision:
    """What one step of the game flow asks of the simulation.

    Attributes:
        events: the step's game events.
        scorer: the team that scored a valid goal this step, or -1.
        exit_kind: how the ball left the field this step (``"goal"``, ``"touch"``,
            ``"goal_line"``, ``"over_bar"``, or None), as :func:`classify_exit` says.
        place_ball: put the ball there, at rest [m], or None.
        line_up: ``("kickoff", team)`` or ``("penalty", team)``: set both teams in that
            formation (the ball included), or None.
        send_off: robots to take off the field.
        bring_on: robots to bring back.
        clear: after placing the ball, move every robot not of team ``clear[1]`` (-1: every
            robot) whose centre lies nearer the ball's than ``clear[0]`` metres radially out
            to that distance; None for nothing.
        over: the match has ended.
    """

    events: list[GameEvent] = field(default_factory=list)
    scorer: int = -1
    exit_kind: str | None = None
    place_ball: tuple[float, float] | None = None
    line_up: tuple[str, int] | None = None
    send_off: list[int] = field(default_factory=list)
    bring_on: list[int] = field(default_factory=list)
    clear: tuple[float, int] | None = None
    over: bool = False


@dataclass
class TeamInfo:
    """What the referee keeps per team (the SSL referee message's team info).

    Attributes:
        goals: valid goals.
        fouls: the foul counter.
        yellow_cards: playing time left of each running yellow card [s].
        red_cards: red cards.
        placement_failures: the ball placement failure counter.
        can_place: whether the team may place the ball (this half).
        off: robots off the field (by cards).
        returning: robots whose card expired, back at the next stop.
    """

    goals: int = 0
    fouls: int = 0
    yellow_cards: list[float] = field(default_factory=list)
    red_cards: int = 0
    placement_failures: int = 0
    can_place: bool = True
    off: list[int] = field(default_factory=list)
    returning: list[int] = field(default_factory=list)


@dataclass(frozen=True)
class GameOptions:
    """How much of the game flow is played.

    Attributes:
        placement: ``"robots"`` (the teams place the ball; 5.2) or ``"referee"`` (the
            referee places it at once, as Division B teams may choose).
        fouls: detect fouls (and the cards they earn).
        cards: give yellow and red cards for fouls.
        half_time: play two halves (else one period of the whole duration).
        free_kicks: ``"2025"`` (all direct) or ``"2019"`` (indirect after minor offences).
    """

    placement: str = "robots"
    fouls: bool = True
    cards: bool = True
    half_time: bool = True
    free_kicks: str = "2025"

    def __post_init__(self) -> None:
        if self.placement not in PLACEMENTS:
            raise ValueError(f"placement must be one of {list(PLACEMENTS)}, got "
                             f"{self.placement!r}")
        if self.free_kicks not in FREE_KICK_RULES:
            raise ValueError(f"free_kicks must be one of {list(FREE_KICK_RULES)}, got "
                             f"{self.free_kicks!r}")
        for name in ("fouls", "cards", "half_time"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"{name} must be True or False, got "
                                 f"{getattr(self, name)!r}")


def game_config(game: Any, default: str = "ssl-2025-div-b"
                ) -> tuple[Any, GameOptions] | None:
    """The rule preset and options of an environment's ``game`` argument: None or False (no
    game flow), True (the ``default`` rules and options), a rule preset's name or spec
    (:data:`~soccer_env.presets.rules.RULES`), or a mapping with the keys :data:`GAME_KEYS`
    (``rules`` defaults to ``default``, the others to :class:`GameOptions`' defaults; they
    apply to SSL rules only)."""
    if game is None or game is False:
        return None
    if game is True:
        return rule_preset(default), GameOptions()
    if isinstance(game, Mapping):
        unknown = sorted(set(game) - set(GAME_KEYS), key=str)
        if unknown:
            raise ValueError(f"game has unknown key(s) {unknown}; allowed: {list(GAME_KEYS)}")
        spec = rule_preset(game.get("rules", default))
        options = {k: v for k, v in game.items() if k != "rules"}
        if options and not isinstance(spec, RuleSpec):
            raise ValueError(f"game options {sorted(options)} apply to SSL rules only; rules "
                             f"{spec.name!r} take none")
        return spec, GameOptions(**options)
    if isinstance(game, (str, RuleSpec, HumanoidRuleSpec)):
        return rule_preset(game), GameOptions()
    raise TypeError(f"game must be None, True, a rule preset's name or spec, or a mapping "
                    f"with the keys {list(GAME_KEYS)}, got {type(game).__name__}")


class RefereeState:
    """What both game controllers (this module's SSL one and
    :class:`~soccer_env.sim.humanoid_game.HumanoidGameController`) keep and show: the
    match's specs and robots, and the referee state a team's software receives."""

    def _init_referee(self, field: FieldSpec, ball: BallSpec, teams: Sequence[int],
                      radii: Sequence[float], duration: float,
                      rng: np.random.Generator) -> None:
        """Check the robots and the duration; the state before the start."""
        if not 0.0 < duration < math.inf:
            raise ValueError(f"duration must be a positive number of seconds, got {duration}")
        self.field, self.ball_spec = field, ball
        self.teams = np.asarray(teams, dtype=int)
        self.radii = np.asarray(radii, dtype=float)
        if self.radii.shape != self.teams.shape:
            raise ValueError(f"radii must have one entry per robot ({len(self.teams)}), got "
                             f"{self.radii.shape}")
        self.duration = float(duration)
        self.rng = rng
        #: Robot index of each team's keeper (its first robot), -1 for a team without robots.
        self.keepers = [int(np.flatnonzero(self.teams == t)[0]) if np.any(self.teams == t)
                        else -1 for t in (0, 1)]
        self.team_info = [TeamInfo(), TeamInfo()]
        self.command = "stop"
        self.command_team = -1
        self.designated: tuple[float, float] | None = None
        self.next_command: tuple[str, int] | None = None
        self.in_play = False
        self.time = 0.0
        self.first_kickoff = 0


class GameController(RefereeState):
    """The referee and game controller of one SSL match (see the module docstring).

    Args:
        field, ball: the match's specs.
        teams: ``(N,)`` team of each robot (0 blue, 1 yellow), blue first.
        radii: ``(N,)`` robot radii [m].
        rules: the rule preset.
        options: what is played.
        duration: playing time of the match [s] (two halves of half of it each).
        rng: draws the team that places the ball before a force start.

    Read-only state for the teams' observations: :attr:`command`, :attr:`command_team`,
    :attr:`designated`, :attr:`stage`, :attr:`stage_time_left`, :attr:`in_play`,
    :attr:`team_info`, :attr:`next_command`.
    """

    def __init__(self, field: FieldSpec, ball: BallSpec, teams: Sequence[int],
                 radii: Sequence[float], rules: RuleSpec, options: GameOptions,
                 duration: float, rng: np.random.Generator) -> None:
        self._init_referee(field, ball, teams, radii, duration, rng)
        self.rules, self.options = rules, options
        hx = field.half_length
        mark = hx - rules.penalty_mark_distance
        if not -hx < mark < hx:
            raise ValueError(f"rules {rules.name!r}: the penalty mark lies "
                             f"{rules.penalty_mark_distance} m from the goal, outside field "
                             f"{field.name!r} ({field.length} m long)")
        self._stages = list(STAGES) if options.half_time else ["first_half", "post_game"]
        self.stage = self._stages[0]
        self.stage_time_left = self.stage_duration
        # Kept across restarts: the ball's height since each team's last touch (7), each
        # team's last non-stopping foul (7), the last frame's robots (crashing), and whether
        # the coming free kick is indirect.
        self._after_touch: dict[int, float] = {0: 0.0, 1: 0.0}
        self._last_nonstop_foul = [-math.inf, -math.inf]
        self._prev_robots: np.ndarray | None = None
        self._pending_indirect = False
        self._exit: ExitKind | None = None
        self._reset_restart()

    # ------------------------------------------------------------------------------------
    # Public
    # ------------------------------------------------------------------------------------

    def start(self, kickoff_team: int, time: float = 0.0) -> Decision:
        """Begin the match with ``kickoff_team``'s kick-off (the simulation has lined the
        teams up)."""
        self.first_kickoff = int(kickoff_team)
        self.time = float(time)
        d = Decision()
        self._issue("prepare_kickoff", self.first_kickoff, (0.0, 0.0), d, line_up=False)
        return d

    @property
    def clock_running(self) -> bool:
        """Whether playing time passes: a team may play the ball (4.4.1)."""
        return self.command in ("normal_start", "force_start", "direct_free")

    def robots_allowed(self, team: int) -> int:
        """How many robots ``team`` may have on the field."""
        info = self.team_info[team]
        return int(np.sum(self.teams == team)) - len(info.yellow_cards) - info.red_cards

    def situation(self) -> tuple[str, int]:
        """What the command means for the teams: ``(kind, team)`` with ``kind`` one of
        :data:`SITUATIONS` and ``team`` the team taking the restart or placing the ball (-1
        for stop and open play). A penalty kick stays ``"penalty"`` while its ball is in
        play (only the kicker and the keeper may play it)."""
        cmd = self.command
        if cmd == "stop":
            return "stop", -1
        if cmd == "ball_placement":
            return "placement", self.command_team
        if cmd == "prepare_kickoff":
            return "kickoff", self.command_team
        if cmd == "prepare_penalty" or (self._penalty and cmd == "normal_start"):
            return "penalty", self._kick_team
        if not self.in_play and cmd == "normal_start":
            return "kickoff", self._kick_team
        if not self.in_play and cmd == "direct_free":
            return "free_kick", self._kick_team
        return "running", -1

    @property
    def restart_team(self) -> int:
        """The team whose restart is being prepared or waits to be taken (-1: none, open
        play or a force start)."""
        kind, team = self.situation()
        if kind in ("kickoff", "penalty", "free_kick"):
            return -1 if kind == "penalty" and self.in_play else team
        if self.next_command is not None:
            return self.next_command[1]
        return -1

    @property
    def barred_robot(self) -> int:
        """The robot that may not touch the ball until another robot has (the kicker of a
        kick-off or free kick once the ball is in play, 8.2), or -1."""
        if self.in_play and self._kicker >= 0 and not self._touched_by_other:
            return self._kicker
        return -1

    @property
    def indirect(self) -> bool:
        """Whether the coming or running free kick is indirect and a goal by its team would
        not count yet (2019 rules)."""
        if self.next_command is not None:
            return self._pending_indirect
        return self._indirect and not self._indirect_ok

    @property
    def playing_time_left(self) -> float:
        """Playing time left in the match [s] (this stage's and the stages after it)."""
        stages = self._stages[self._stages.index(self.stage) + 1:]
        return self.stage_time_left + self.stage_duration * sum(
            s != "post_game" for s in stages)

    def step(self, frame: Frame) -> Decision:
        """Referee one control step (see the module docstring)."""
        d = Decision()
        dt = max(0.0, float(frame.time) - self.time)
        self.time = float(frame.time)
        ball = np.asarray(frame.ball, dtype=float)
        robots = np.asarray(frame.robots, dtype=float)
        touched = [bool(t) for t in frame.touched]
        self._command_time += dt
        if self.clock_running:
            self._run_clocks(dt, d)
        # How the ball left the field this step, classified once for every rule that asks.
        self._exit = (None if frame.exit is None else
                      classify_exit(frame.exit, self.field, self.ball_spec))
        if self._exit is not None:
            d.exit_kind = self._exit.kind
        if self.in_play or self.command == "force_start":
            self._referee_play(frame, ball, robots, touched, dt, d)
        else:
            self._referee_restart(frame, ball, robots, touched, dt, d)
        # After the simulation moves robots or the ball for the referee, the next frame's
        # motion is not theirs.
        self._prev_robots = None if (d.line_up or d.send_off or d.bring_on) else robots
        self._prev_ball_speed = math.sqrt(float(ball[3]) ** 2 + float(ball[4]) ** 2
                                          + float(ball[5]) ** 2)
        if not d.over and self.clock_running and self.stage_time_left <= 0.0 \
                and not (self._penalty and self.in_play):
            self._end_stage(d)
        return d

    # ------------------------------------------------------------------------------------
    # Clocks and stages
    # ------------------------------------------------------------------------------------

    @property
    def stage_duration(self) -> float:
        """Playing time of one stage [s]."""
        return self.duration / 2.0 if self.options.half_time else self.duration

    def _run_clocks(self, dt: float, d: Decision) -> None:
        self.stage_time_left = max(0.0, self.stage_time_left - dt)
        for info in self.team_info:
            left = [c - dt for c in info.yellow_cards]
            expired = sum(c <= 0.0 for c in left)
            info.yellow_cards = [c for c in left if c > 0.0]
            for _ in range(expired):
                if info.off:
                    info.returning.append(info.off.pop())

    def _end_stage(self, d: Decision) -> None:
        k = self._stages.index(self.stage) + 1
        self.stage = self._stages[k]
        if self.stage == "post_game":
            self._set_command("stop", -1)
            self.in_play = False
            d.over = True
            return
        self.stage_time_left = self.stage_duration
        for info in self.team_info:  # placement rights are per half (5.2)
            info.can_place = True
            info.placement_failures = 0
        d.events.append(GameEvent("stage_changed"))
        self._stop(d, ("prepare_kickoff", 1 - self.first_kickoff), (0.0, 0.0), placer=None)

    # ------------------------------------------------------------------------------------
    # Commands
    # ------------------------------------------------------------------------------------

    def _reset_restart(self) -> None:
        """Forget what belonged to the previous restart."""
        self._command_time = 0.0
        self._kick_point: tuple[float, float] | None = None
        self._kicker = -1
        self._kick_team = -1
        self._indirect = False
        self._indirect_ok = False
        self._penalty = False
        self._penalty_dir: np.ndarray | None = None
        self._placer = -1
        self._placement_left = 0.0
        self._placement_first: tuple[str, int] | None = None
        self._interference: dict[int, float] = {}
        self._interference_counted = False
        self._stop_speed_fouled: set[int] = set()
        self._progress_anchor: np.ndarray | None = None
        self._progress_time = 0.0
        self._held_since: dict[int, float] = {}
        self._held_start: dict[int, tuple[float, float]] = {}
        self._last_touch = -1
        self._last_touch_point: tuple[float, float] | None = None
        self._crossed_half = False
        self._last_foul: dict[tuple[int, str], float] = {}
        self._touched_by_other = False
        self._prev_ball_speed = 0.0

    def _set_command(self, command: str, team: int) -> None:
        self.command, self.command_team = command, team
        self._command_time = 0.0

    def _issue(self, command: str, team: int, position: tuple[float, float] | None,
               d: Decision, line_up: bool = True) -> None:
        """Issue a restart command (after stop or placement)."""
        self._reset_restart()
        self.designated = position
        self.next_command = None
        self.in_play = False
        if command == "prepare_kickoff":
            self._set_command("prepare_kickoff", team)
            if line_up:
                d.line_up = ("kickoff", team)
            self._kick_team = team
            self._kick_point = (0.0, 0.0)
        elif command == "prepare_penalty":
            self._set_command("prepare_penalty", team)
            d.line_up = ("penalty", team)
            self._kick_team = team
            self._penalty = True
            mark = self._penalty_mark(team)
            self._kick_point = mark
            self.designated = mark
        elif command == "direct_free":
            self._set_command("direct_free", team)
            self._kick_team = team
            # Where the ball lies when the kick is issued (within the placement tolerance of
            # the designated position): read from the first frame.
            self._kick_point = None
            self._indirect = self._pending_indirect
        elif command == "force_start":
            self._set_command("force_start", -1)
            self.in_play = True
        else:  # pragma: no cover - programming error
            raise ValueError(f"cannot issue {command!r}")
        self._pending_indirect = False

    def _penalty_mark(self, team: int) -> tuple[float, float]:
        """The penalty mark ``team`` shoots from (blue attacks +x)."""
        hx = self.field.half_length
        goal = hx if team == 0 else -hx
        return (goal - math.copysign(self.rules.penalty_mark_distance, goal), 0.0)

    def _stop(self, d: Decision, next_command: tuple[str, int],
              position: tuple[float, float] | None, placer: int | None,
              ball: np.ndarray | None = None, indirect: bool = False,
              out: bool = False) -> None:
        """Stop the game; the ball goes to ``position`` (placed by ``placer``'s robots, or
        by the referee for None), then ``next_command`` follows. ``out``: the free kick
        follows the ball leaving the field (it goes to the other team when ``placer`` may not
        place; 5.2)."""
        self._reset_restart()
        self.in_play = False
        self.next_command = next_command
        self.designated = position
        self._pending_indirect = indirect
        for info in self.team_info:  # cards expired: back at this stop
            d.bring_on.extend(info.returning)
            info.returning = []
        if position is not None and placer is not None and ball is not None and \
                self.options.placement == "robots" and self._needs_placement(ball, position):
            if self.team_info[placer].can_place:
                self._start_placement(placer, next_command)
                return
            if out and self.team_info[1 - placer].can_place:
                # A team that may not place loses the free kick to the other (5.2).
                self.next_command = ("direct_free", 1 - placer)
                self._start_placement(1 - placer, self.next_command)
                return
        self._set_command("stop", -1)
        if position is not None and (ball is None or self._needs_placement(ball, position)):
            d.place_ball = position

    def _start_placement(self, team: int, next_command: tuple[str, int]) -> None:
        self._set_command("ball_placement", team)
        self._placer = team
        self._placement_left = self.rules.placement_time
        if self._placement_first is None:
            self._placement_first = next_command
        self._interference = {}
        self._interference_counted = False

    def _needs_placement(self, ball: np.ndarray, position: tuple[float, float]) -> bool:
        """Whether the ball must be placed before the restart (5.2)."""
        r = self.rules
        bx, by = float(ball[0]), float(ball[1])
        near = math.hypot(bx - position[0], by - position[1]) < r.placement_skip_distance
        inside = abs(bx) <= self.field.half_length and abs(by) <= self.field.half_width
        clear = min(self._defense_distance(bx, by, t) for t in (0, 1)) >= \
            r.placement_skip_defense
        still = math.hypot(float(ball[3]), float(ball[4])) < STATIONARY_SPEED
        return not (near and inside and clear and still)

    # ------------------------------------------------------------------------------------
    # Geometry (field frame; blue defends x < 0)
    # ------------------------------------------------------------------------------------

    def _defense_box(self, team: int) -> tuple[float, float, float, float]:
        """``team``'s own defense area: ``x0, x1, y0, y1`` [m]."""
        f = self.field
        hx, hw = f.half_length, 0.5 * f.defense_width
        if team == 0:
            return -hx, -hx + f.defense_depth, -hw, hw
        return hx - f.defense_depth, hx, -hw, hw

    def _defense_distance(self, x: float, y: float, team: int) -> float:
        """Distance from ``(x, y)`` to ``team``'s defense area (0 inside) [m]."""
        x0, x1, y0, y1 = self._defense_box(team)
        dx = max(x0 - x, 0.0, x - x1)
        dy = max(y0 - y, 0.0, y - y1)
        return math.hypot(dx, dy)

    def _inside_defense(self, x: float, y: float, team: int, margin: float = 0.0) -> bool:
        """Whether ``(x, y)`` lies at least ``margin`` inside ``team``'s defense area."""
        x0, x1, y0, y1 = self._defense_box(team)
        return x0 + margin <= x <= x1 - margin and y0 + margin <= y <= y1 - margin

    def _valid_free_kick(self, x: float, y: float) -> tuple[float, float]:
        """The nearest valid free-kick position to ``(x, y)``: at least ``line_margin``
        inside the field lines and ``defense_margin`` from either defense area (5.3.3)."""
        r, f = self.rules, self.field
        lx, ly = f.half_length - r.line_margin, f.half_width - r.line_margin
        x, y = float(np.clip(x, -lx, lx)), float(np.clip(y, -ly, ly))
        for team in (0, 1):
            x0, x1, y0, y1 = self._defense_box(team)
            x0, x1 = x0 - r.defense_margin, x1 + r.defense_margin
            y0, y1 = y0 - r.defense_margin, y1 + r.defense_margin
            if x0 < x < x1 and y0 < y < y1:
                # Out of the enlarged box by the shorter way that stays in the field.
                options = []
                if team == 0:
                    options.append((x1, y))
                else:
                    options.append((x0, y))
                if y1 <= ly:
                    options.append((x, y1))
                if y0 >= -ly:
                    options.append((x, y0))
                x, y = min(options, key=lambda p: math.hypot(p[0] - x, p[1] - y))
        return x, y

    def _gap(self, robots: np.ndarray, i: int, x: float, y: float) -> float:
        """Distance from robot ``i``'s nearest side to ``(x, y)`` [m]."""
        return math.hypot(robots[i, 0] - x, robots[i, 1] - y) - self.radii[i]

    def _on_field(self, i: int) -> bool:
        t = int(self.teams[i])
        return i not in self.team_info[t].off

    # ------------------------------------------------------------------------------------
    # Fouls and cards
    # ------------------------------------------------------------------------------------

    def _foul(self, d: Decision, kind: str, team: int, robot: int, x: float, y: float,
              count: bool = True) -> bool:
        """Record a foul of ``team`` (unless one of the same kind by the team lies within
        the grace period); returns whether it counted."""
        key = (team, kind)
        if self.time - self._last_foul.get(key, -math.inf) < self.rules.grace_period:
            return False
        self._last_foul[key] = self.time
        d.events.append(GameEvent(kind, team, robot, x, y))
        if not count:
            return True
        info = self.team_info[team]
        info.fouls += 1
        if self.options.cards and info.fouls % self.rules.fouls_per_card == 0:
            self._card(d, team)
        return True

    def _card(self, d: Decision, team: int) -> None:
        """A yellow card for ``team`` (a red one when it has enough running; 5.5)."""
        info = self.team_info[team]
        red = len(info.yellow_cards) >= self.rules.cards_for_red
        if red:
            info.red_cards += 1
        else:
            info.yellow_cards.append(self.rules.yellow_card_time)
        d.events.append(GameEvent("red_card" if red else "yellow_card", team))
        if info.returning:  # a robot waiting to come back stays off instead
            info.off.append(info.returning.pop())
            return
        members = [int(i) for i in np.flatnonzero(self.teams == team) if int(i) not in info.off]
        candidates = [i for i in members if i != self.keepers[team]]
        if len(members) <= 1 or not candidates:
            return  # a team keeps at least one robot
        robot = max(candidates)
        info.off.append(robot)
        d.send_off.append(robot)

    def _stopping_foul(self, d: Decision, kind: str, team: int, robot: int, x: float,
                       y: float, ball: np.ndarray, indirect: bool = False) -> None:
        """A stopping foul of ``team``: stop, then a free kick for the other team from
        ``(x, y)`` (8.4.1)."""
        if self._foul(d, kind, team, robot, x, y):
            spot = self._valid_free_kick(x, y)
            self._stop(d, ("direct_free", 1 - team), spot, 1 - team, ball,
                       indirect=indirect and self.options.free_kicks == "2019")

    # ------------------------------------------------------------------------------------
    # Ball in play
    # ------------------------------------------------------------------------------------

    def _referee_play(self, frame: Frame, ball: np.ndarray, robots: np.ndarray,
                      touched: list[bool], dt: float, d: Decision) -> None:
        bx, by, bz = float(ball[0]), float(ball[1]), float(ball[2])
        fouls = self.options.fouls
        toucher = [i for i, t in enumerate(touched) if t]
        # The ball's height since each team's last touch (7), and who touched it last.
        for t in (0, 1):
            self._after_touch[t] = max(self._after_touch[t], bz)
        for i in toucher:
            self._after_touch[int(self.teams[i])] = bz
        if self._indirect and any(int(self.teams[i]) == self._kick_team and
                                  (i != self._kicker or self._touched_by_other)
                                  for i in toucher):
            self._indirect_ok = True
        # Double touch (8.2): the kicker again before anyone else.
        if self._kicker >= 0 and toucher:
            others = [i for i in toucher if i != self._kicker]
            if self._kicker in toucher and not self._touched_by_other and not others:
                if fouls:
                    self._stopping_foul(d, "attacker_double_touched_ball",
                                        int(self.teams[self._kicker]), self._kicker, bx, by,
                                        ball, indirect=True)
                    return
            if others:
                self._touched_by_other = True
                self._kicker = -1
        if self._penalty and self._referee_penalty(frame, ball, toucher, d):
            return
        self._note_touches(toucher, bx, by)
        if frame.exit is not None:
            self._ball_out(frame, ball, d)
            return
        if fouls and self._referee_touches(ball, robots, toucher, d):
            return
        if fouls:
            self._referee_crashes(robots, d)
        if self._penalty:
            return
        if fouls and self._keeper_held(ball, dt, d):
            return
        self._no_progress(ball, d)

    def _note_touches(self, toucher: list[int], bx: float, by: float) -> None:
        """Who touched the ball last and where, and whether the ball crossed the halfway
        line since (for aimless kicks; a ball touched on the halfway line, as at a kick-off,
        does not cross it)."""
        if toucher:
            self._last_touch = toucher[-1]
            self._last_touch_point = (bx, by)
            self._crossed_half = False
        elif self._last_touch_point is not None:
            tx = self._last_touch_point[0]
            if abs(tx) > self.ball_spec.radius and (bx > 0.0) != (tx > 0.0):
                self._crossed_half = True

    def _referee_touches(self, ball: np.ndarray, robots: np.ndarray, toucher: list[int],
                         d: Decision) -> bool:
        """Fouls of the robots that touched the ball; True if the game stopped."""
        bx, by = float(ball[0]), float(ball[1])
        for i in toucher:
            t = int(self.teams[i])
            x, y, rad = float(robots[i, 0]), float(robots[i, 1]), float(self.radii[i])
            if i != self.keepers[t] and self._inside_defense(x, y, t, margin=rad):
                d.events.append(GameEvent("defender_in_defense_area", t, i, bx, by))
                self._stop(d, ("prepare_penalty", 1 - t), None, placer=None)
                return True
            if self._defense_distance(x, y, 1 - t) < rad:
                self._nonstop_foul(d, "attacker_touched_ball_in_defense_area", t, i, bx, by)
        self._speed_fouls(ball, toucher, d)
        return False

    def _speed_fouls(self, ball: np.ndarray, toucher: list[int], d: Decision) -> None:
        """A robot that touched the ball this step and left it faster than the limit, in
        3-D (8.4.2)."""
        speed = math.sqrt(float(ball[3]) ** 2 + float(ball[4]) ** 2 + float(ball[5]) ** 2)
        if speed > self.rules.ball_speed_limit and speed > self._prev_ball_speed:
            for i in toucher:
                self._nonstop_foul(d, "bot_kicked_ball_too_fast", int(self.teams[i]), i,
                                   float(ball[0]), float(ball[1]))

    def _nonstop_foul(self, d: Decision, kind: str, team: int, robot: int, x: float,
                      y: float) -> None:
        if self._foul(d, kind, team, robot, x, y):
            self._last_nonstop_foul[team] = self.time

    def _referee_crashes(self, robots: np.ndarray, d: Decision) -> None:
        """Crashing (8.4.2): robots of different teams that came into contact this step."""
        prev = self._prev_robots
        if prev is None or prev.shape != robots.shape:
            return
        r = self.rules
        blue = np.flatnonzero(self.teams == 0)
        yellow = np.flatnonzero(self.teams == 1)
        for i in blue:
            for j in yellow:
                if not (self._on_field(int(i)) and self._on_field(int(j))):
                    continue
                reach = self.radii[i] + self.radii[j] + CONTACT_SLACK
                now = math.hypot(*(robots[j, 0:2] - robots[i, 0:2]))
                before = math.hypot(*(prev[j, 0:2] - prev[i, 0:2]))
                if now > reach or before <= reach:
                    continue
                u = (prev[j, 0:2] - prev[i, 0:2]) / max(before, 1e-9)
                closing = float(np.dot(prev[i, 3:5] - prev[j, 3:5], u))
                if closing <= r.crash_speed:
                    continue
                si, sj = math.hypot(*prev[i, 3:5]), math.hypot(*prev[j, 3:5])
                x, y = (robots[i, 0:2] + robots[j, 0:2]) / 2
                if abs(si - sj) < r.crash_both_margin:
                    for k in (int(i), int(j)):
                        self._nonstop_foul(d, "bot_crash_drawn", int(self.teams[k]), k, x, y)
                else:
                    k = int(i) if si > sj else int(j)
                    self._nonstop_foul(d, "bot_crash_unique", int(self.teams[k]), k, x, y)

    def _keeper_held(self, ball: np.ndarray, dt: float, d: Decision) -> bool:
        """The ball kept in a defense area too long (8.4.1); True if the game stopped."""
        bx, by = float(ball[0]), float(ball[1])
        for t in (0, 1):
            if self._inside_defense(bx, by, t):
                if t not in self._held_since:
                    self._held_since[t] = 0.0
                    self._held_start[t] = (bx, by)
                self._held_since[t] += dt
                if self._held_since[t] > self.rules.keeper_held_time:
                    x, y = self._held_start[t]
                    self._stopping_foul(d, "keeper_held_ball", t, self.keepers[t], x, y, ball)
                    return True
            else:
                self._held_since.pop(t, None)
        return False

    def _no_progress(self, ball: np.ndarray, d: Decision) -> None:
        """No progress (8.1): the ball making no headway for too long."""
        p = np.asarray(ball[0:2], dtype=float)
        if self._progress_anchor is None or \
                math.hypot(*(p - self._progress_anchor)) > self.rules.no_progress_distance:
            self._progress_anchor = p
            self._progress_time = self.time
            return
        if self.time - self._progress_time > self.rules.no_progress_time:
            d.events.append(GameEvent("no_progress_in_game", -1, -1, float(p[0]),
                                      float(p[1])))
            spot = self._valid_free_kick(float(p[0]), float(p[1]))
            placer = int(self.rng.integers(2))
            self._stop(d, ("force_start", -1), spot, placer, ball)

    def _ball_out(self, frame: Frame, ball: np.ndarray, d: Decision) -> None:
        """Goals and the ball leaving the field (6, 7)."""
        ex = frame.exit
        kind = self._exit
        last = self._last_touch
        last_team = int(self.teams[last]) if last >= 0 else -1
        if kind.kind == "goal":
            s = kind.scorer
            valid = (self._after_touch[s] <= self.rules.goal_ball_height
                     and self.time - self._last_nonstop_foul[s] > self.rules.goal_foul_window
                     and not (self._indirect and not self._indirect_ok
                              and self._kick_team == s))
            if valid:
                self._goal(s, ex, d)
                return
            d.events.append(GameEvent("invalid_goal", s, -1, ex.x, ex.y))
        if kind.kind == "touch":
            d.events.append(GameEvent("ball_left_field_touch_line", last_team, last, ex.x,
                                      ex.y))
            team = 1 - last_team if last_team >= 0 else (0 if ex.x > 0 else 1)
            spot = free_kick_spot(ex, kind, self.field, self.rules.line_margin)
            self._stop(d, ("direct_free", team), self._valid_free_kick(*spot), team, ball,
                       indirect=self.options.free_kicks == "2019", out=True)
            return
        # Over a goal line outside the goal (or an invalid goal / over the bar).
        end = kind.end if kind.end else (1 if ex.x > 0 else -1)
        defender = 1 if end > 0 else 0  # blue defends x < 0
        side = math.copysign(1.0, ex.y) if ex.y != 0.0 else 1.0
        hy = self.field.half_width - self.rules.line_margin
        aimless = (self.rules.division == "B" and last_team == 1 - defender
                   and self._crossed_half and self._last_touch_point is not None)
        if aimless:
            d.events.append(GameEvent("aimless_kick", last_team, last, ex.x, ex.y))
            spot = self._valid_free_kick(*self._last_touch_point)
            self._stop(d, ("direct_free", defender), spot, defender, ball,
                       indirect=self.options.free_kicks == "2019", out=True)
            return
        d.events.append(GameEvent("ball_left_field_goal_line", last_team, last, ex.x, ex.y))
        if last_team == defender:  # corner kick for the attackers
            x = end * (self.field.half_length - self.rules.line_margin)
            team = 1 - defender
        else:  # goal kick (also when nobody touched it)
            x = end * (self.field.half_length - self.rules.goal_kick_distance)
            team = defender
        self._stop(d, ("direct_free", team), self._valid_free_kick(x, side * hy), team, ball,
                   out=True)

    def _goal(self, scorer: int, ex: object, d: Decision) -> None:
        info = self.team_info[scorer]
        info.goals += 1
        d.scorer = scorer
        d.events.append(GameEvent("goal", scorer, self._last_touch, ex.x, ex.y))
        other = self.team_info[1 - scorer].goals
        if info.goals >= EARLY_END_GOALS and info.goals - other > EARLY_END_LEAD:
            self.stage = "post_game"
            self._set_command("stop", -1)
            self.in_play = False
            d.over = True
            return
        self._stop(d, ("prepare_kickoff", 1 - scorer), (0.0, 0.0), placer=None)

    def _referee_penalty(self, frame: Frame, ball: np.ndarray, toucher: list[int],
                         d: Decision) -> bool:
        """A penalty kick in play (5.3.5); True if it ended this step without a goal
        (a goal is :meth:`_ball_out`'s)."""
        team = self._kick_team
        if frame.exit is not None:
            kind = self._exit
            if kind.kind == "goal" and kind.scorer == team:
                self._goal(team, frame.exit, d)
                return True
        goal_dir = 1.0 if team == 0 else -1.0
        v = np.asarray(ball[3:5], dtype=float)
        defender = 1 - team
        keeper = self.keepers[defender]
        over = False
        if v @ v > STATIONARY_SPEED ** 2:
            if self._penalty_dir is not None and keeper in toucher and \
                    float(v @ self._penalty_dir) <= 0.0:
                over = True  # turned back by the keeper
            elif v[0] * goal_dir < -STATIONARY_SPEED:
                over = True  # the ball moved away from the goal
            self._penalty_dir = v / math.sqrt(float(v @ v))
        if self._command_time > self.rules.penalty_time or frame.exit is not None:
            over = True
        if over:
            hx = self.field.half_length - self.rules.goal_kick_distance
            spot = self._valid_free_kick(goal_dir * hx, self.field.half_width
                                         - self.rules.line_margin)
            d.events.append(GameEvent("penalty_kick_failed", team, -1, float(ball[0]),
                                      float(ball[1])))
            self._stop(d, ("direct_free", defender), spot, defender, ball)
            return True
        return False

    # ------------------------------------------------------------------------------------
    # Ball out of play
    # ------------------------------------------------------------------------------------

    def _referee_restart(self, frame: Frame, ball: np.ndarray, robots: np.ndarray,
                         touched: list[bool], dt: float, d: Decision) -> None:
        cmd = self.command
        if cmd == "ball_placement":
            self._referee_placement(ball, robots, dt, d)
        elif cmd == "stop":
            self._referee_stop(ball, robots, d)
        elif cmd in ("prepare_kickoff", "prepare_penalty"):
            # The simulation lined the teams up: the normal start follows at once.
            self._set_command("normal_start", self.command_team)
            self._kick_point = (float(ball[0]), float(ball[1]))
        elif cmd in ("normal_start", "direct_free"):
            self._referee_kick(frame, ball, robots, touched, d)

    def _referee_kick(self, frame: Frame, ball: np.ndarray, robots: np.ndarray,
                      touched: list[bool], d: Decision) -> None:
        """A kick-off, free kick or penalty before the ball is in play."""
        r = self.rules
        bx, by = float(ball[0]), float(ball[1])
        team = self._kick_team
        if self._kick_point is None:
            self._kick_point = (bx, by)
        toucher = [i for i, t in enumerate(touched) if t]
        for i in toucher:
            if self._kicker < 0 and int(self.teams[i]) == team:
                self._kicker = i
        self._note_touches(toucher, bx, by)
        if self.options.fouls:
            self._speed_fouls(ball, toucher, d)
        moved = math.hypot(bx - self._kick_point[0], by - self._kick_point[1])
        limit = (r.penalty_time if self._penalty else
                 r.kickoff_time if self.command == "normal_start" else r.free_kick_time)
        if self.options.fouls and moved < r.ball_in_play_distance:
            kx, ky = self._kick_point
            for i in range(len(self.teams)):
                if int(self.teams[i]) == team or not self._on_field(i):
                    continue
                if self._gap(robots, i, kx, ky) < r.stop_distance and not self._penalty:
                    if self._foul(d, "defender_too_close_to_kick_point", int(self.teams[i]),
                                  i, bx, by):
                        self._command_time = 0.0  # the kicking team's timer restarts
            if self.command == "direct_free" and self._command_time > r.grace_period and \
                    self._too_close_to_defense(ball, robots, d):
                return
        if moved >= r.ball_in_play_distance or self._command_time > limit:
            self.in_play = True
            self._touched_by_other = False
            if moved < r.ball_in_play_distance:
                self._kicker = -1  # in play by time: nobody kicked
            self._progress_anchor = None
            if frame.exit is not None:
                self._ball_out(frame, ball, d)

    def _too_close_to_defense(self, ball: np.ndarray, robots: np.ndarray,
                              d: Decision) -> bool:
        """A robot too close to the opponent defense area during stop or a free kick
        (8.4.1, after the grace period); True if the game stopped."""
        for i in range(len(self.teams)):
            t = int(self.teams[i])
            if not self._on_field(i):
                continue
            gap = self._defense_distance(float(robots[i, 0]), float(robots[i, 1]), 1 - t) \
                - self.radii[i]
            if gap < self.rules.defense_area_distance:
                self._stopping_foul(d, "attacker_too_close_to_defense_area", t, i,
                                    float(ball[0]), float(ball[1]), ball)
                return True
        return False

    def _referee_stop(self, ball: np.ndarray, robots: np.ndarray, d: Decision) -> None:
        """Stop: the speed limit, then the next command once robots keep their distance."""
        r = self.rules
        if self.options.fouls and self._command_time > r.grace_period:
            for i in range(len(self.teams)):
                if i in self._stop_speed_fouled or not self._on_field(i):
                    continue
                if math.hypot(float(robots[i, 3]), float(robots[i, 4])) > r.stop_speed:
                    self._stop_speed_fouled.add(i)
                    self._foul(d, "bot_too_fast_in_stop", int(self.teams[i]), i,
                               float(robots[i, 0]), float(robots[i, 1]))
            if self.next_command and self.next_command[0] == "direct_free" and \
                    self._too_close_to_defense(ball, robots, d):
                return
        if self.next_command is None:
            return
        bx, by = float(ball[0]), float(ball[1])
        ready = all(self._gap(robots, i, bx, by) >= r.stop_distance
                    for i in range(len(self.teams)) if self._on_field(i))
        if (ready and self._command_time >= r.placement_min_time) or \
                self._command_time >= r.stage_pause:
            cmd, team = self.next_command
            self._issue(cmd, team, self.designated, d)

    def _referee_placement(self, ball: np.ndarray, robots: np.ndarray, dt: float,
                           d: Decision) -> None:
        """Ball placement by ``self._placer`` (5.2, 8.4.3)."""
        r = self.rules
        team = self._placer
        target = self.designated
        bx, by = float(ball[0]), float(ball[1])
        self._placement_left -= dt
        # Interference: the other team near the segment from the ball to the target.
        for i in range(len(self.teams)):
            if int(self.teams[i]) == team or not self._on_field(i):
                self._interference.pop(i, None)
                continue
            gap = segment_distance(float(robots[i, 0]), float(robots[i, 1]), bx, by,
                                    *target) - self.radii[i]
            if gap < r.placement_interference_distance:
                self._interference[i] = self._interference.get(i, 0.0) + dt
                if self._interference[i] > r.grace_period:
                    self._interference[i] = 0.0
                    self._placement_left += r.placement_interference_penalty
                    if self.options.fouls and not self._interference_counted:
                        self._interference_counted = True
                        self._foul(d, "bot_interfered_placement", int(self.teams[i]), i,
                                   float(robots[i, 0]), float(robots[i, 1]))
            else:
                self._interference.pop(i, None)
        nxt = self.next_command
        clearance = (r.placement_clearance if nxt[0] == "direct_free" and nxt[1] == team
                     else r.stop_distance)
        placed = (math.hypot(bx - target[0], by - target[1]) <= r.placement_tolerance
                  and math.hypot(float(ball[3]), float(ball[4])) < STATIONARY_SPEED
                  and all(self._gap(robots, i, bx, by) >= clearance
                          for i in range(len(self.teams)) if self._on_field(i)))
        info = self.team_info[team]
        if placed and self._command_time >= r.placement_min_time:
            info.placement_failures = max(0, info.placement_failures - 1)
            d.events.append(GameEvent("placement_succeeded", team, -1, bx, by))
            self._issue(nxt[0], nxt[1], target, d)
            return
        if self._placement_left > 0.0:
            return
        info.placement_failures += 1
        if info.placement_failures >= r.max_placement_failures:
            info.can_place = False
        d.events.append(GameEvent("placement_failed", team, -1, bx, by))
        first = self._placement_first
        other = 1 - team
        if nxt[0] in ("direct_free", "force_start") and self.team_info[other].can_place and \
                first == nxt:
            # The free kick goes to the other team, which places in turn.
            self.next_command = ("direct_free", other)
            self._pending_indirect = self.options.free_kicks == "2019"
            self._start_placement(other, self.next_command)
            self._placement_first = first
            return
        # Both failed (or the other may not place): the referee places, and the original
        # command follows.
        self.next_command = first
        self._set_command("stop", -1)
        d.place_ball = target


def segment_distance(px: float, py: float, ax: float, ay: float, bx: float, by: float
                      ) -> float:
    """Distance from ``(px, py)`` to the segment from ``(ax, ay)`` to ``(bx, by)`` [m]."""
    dx, dy = bx - ax, by - ay
    n = dx * dx + dy * dy
    s = 0.0 if n < 1e-18 else min(1.0, max(0.0, ((px - ax) * dx + (py - ay) * dy) / n))
    return math.hypot(px - ax - s * dx, py - ay - s * dy)
