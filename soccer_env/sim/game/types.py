"""The vocabulary of the game flow, shared by the SSL
(:class:`~soccer_env.sim.game.controller.GameController`) and the humanoid
(:class:`~soccer_env.sim.humanoid_game.HumanoidGameController`) controllers: the commands,
stages and situations a team's software receives, what the controller reads each step
(:class:`Frame`) and what it asks of the simulation (:class:`Decision`, with its
:class:`GameEvent` list), the referee's per-team record (:class:`TeamInfo`), and the options
of the SSL flow (:class:`GameOptions`, :func:`game_config`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from soccer_env.presets.rules import HumanoidRuleSpec, RuleSpec
from soccer_env.presets.rules import rules as rule_preset

__all__ = ["Frame", "Decision", "GameEvent", "TeamInfo", "GameOptions", "game_config",
           "COMMANDS", "STAGES", "PLACEMENTS", "FREE_KICK_RULES", "FOULS", "SITUATIONS",
           "GAME_KEYS", "STATIONARY_SPEED", "CONTACT_SLACK", "EARLY_END_GOALS",
           "EARLY_END_LEAD"]

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

#: What a team's software makes of the command
#: (:meth:`~soccer_env.sim.game.controller.GameController.situation`): the restart being
#: prepared or taken, or open play.
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
            ``"goal_line"``, ``"over_bar"``, or None), as
            :func:`~soccer_env.sim.referee.classify_exit` says.
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

