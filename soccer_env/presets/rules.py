"""Rule presets: the numbers of the game flow (:mod:`soccer_env.sim.game`), from the rule book
they come from (see :mod:`soccer_env.presets` for the conventions).

``RULES["ssl-2025-div-b"]`` and ``RULES["ssl-2025-div-a"]`` are the RoboCup Small Size League
rules, 2025 edition (https://robocup-ssl.github.io/ssl-rules/2025/sslrules.html), for the two
divisions (:class:`RuleSpec`, played by :class:`soccer_env.sim.game.GameController`);
``RULES["humanoid-2025-kid"]`` is the RoboCup Humanoid League Laws of the Game 2025, KidSize,
virtual competition where the two differ (https://github.com/RoboCup-Humanoid-TC/Rules;
:class:`HumanoidRuleSpec`, played by
:class:`soccer_env.sim.humanoid_game.HumanoidGameController`). The section or law of each
number is given beside it. Tell the two kinds apart with ``isinstance``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from estimators.registry import Registry
from soccer_env.validation import check_number, preset_table, resolve_preset

__all__ = ["RuleSpec", "HumanoidRuleSpec", "RULES", "rules"]


@dataclass(frozen=True)
class RuleSpec:
    """The numbers of one rule book (distances [m], speeds [m/s], times [s]).

    Attributes:
        name: the preset's name.
        division: ``"A"`` or ``"B"`` (aimless kicks exist in Division B only).
        stop_distance: distance every robot keeps from the ball during stop, and the defending
            team during a kick-off or free kick (5.1.1, 8.4.3).
        stop_speed: speed limit of every robot during stop (5.1.1, 8.4.3).
        grace_period: time robots get to comply after a command, and between two fouls of
            the same kind by the same team (8.4.2, 8.4.3).
        ball_in_play_distance: how far the ball must move after a kick-off, free kick or
            penalty kick to be in play (5.4, 8.2).
        kickoff_time: after a kick-off's normal start, the ball is in play anyway after this
            long (5.4).
        free_kick_time: likewise after a free kick (5.4: 5 s in Division A, 10 s in B).
        penalty_time: the game stops if the ball is still in play this long after a penalty
            kick's normal start (5.3.5).
        penalty_mark_distance: distance of the penalty mark from the opponent goal's centre
            (2.1.3: 8 m in Division A, 6 m in B).
        penalty_behind: how far behind the ball every robot but the kicker and the keeper
            stays during a penalty kick (5.3.5).
        placement_time: time a team has to place the ball (5.2).
        placement_min_time: the game continues no earlier than this after the placement
            command (5.2).
        placement_tolerance: the ball counts as placed within this distance of the
            designated position (5.2).
        placement_clearance: no robot may be nearer the placed ball than this when its own
            team's free kick follows (5.2).
        placement_skip_distance: no placement is needed if the ball lies within this distance
            of the designated position, inside the field, stationary and at least
            ``placement_skip_defense`` from every defense area (5.2).
        placement_skip_defense: see ``placement_skip_distance``.
        placement_interference_distance: robots of the non-placing team keep this distance
            from the segment between the ball and the designated position (8.4.3).
        placement_interference_penalty: time added to the placement timer per interference
            (8.4.3), once per interfering robot and placement (a robot wedged where it
            cannot leave does not extend the placement for ever).
        max_placement_failures: a team with this many placement failures may not place the
            ball for the rest of the half (5.2).
        line_margin: a free kick's ball lies at least this far inside the field lines (5.3.3).
        defense_margin: ... and at least this far from either defense area (5.3.3).
        goal_kick_distance: a goal kick's ball lies this far from the goal line (6.2.1).
        defense_area_distance: during stop and before a free kick is in play, robots keep
            this distance from the opponent defense area (8.4.1).
        ball_speed_limit: the fastest a robot may kick the ball, in 3-D (8.4.2).
        crash_speed: crashing: the relative speed along the line between two robots of
            different teams above which the faster one fouls (8.4.2).
        crash_both_margin: ... both foul when their speeds differ by less than this (8.4.2).
        goal_ball_height: a goal counts only if the ball was no higher than this after the
            scoring team's last touch (7).
        goal_foul_window: ... and the scoring team committed no non-stopping foul in this
            long before the goal (7).
        no_progress_time: the game is stopped and force-started after this long without
            progress while both teams may play the ball (8.1: 5 s in A, 10 s in B).
        no_progress_distance: the ball making less headway than this counts as no progress
            (the rule book leaves it to the referee; this is ours).
        keeper_held_time: the ball may not stay in a defense area longer than this (8.4.1:
            5 s in A, 10 s in B).
        fouls_per_card: every so many fouls of a team give it a yellow card (8.4).
        yellow_card_time: playing time a yellow card lasts (5.5.1).
        cards_for_red: a yellow card given while a team has this many yellow cards running
            becomes a red card (5.5.1).
        stage_pause: how long the game controller waits, at most, for robots to obey stop or a
            kick-off's positions before it continues anyway (5.1.2: up to 10 s after halt).
        source: the rule book.
        kind: ``"ssl"``, the robots the rules are for (as a robot spec's ``kind``).
    """

    name: str
    division: str
    stop_distance: float = 0.5
    stop_speed: float = 1.5
    grace_period: float = 2.0
    ball_in_play_distance: float = 0.05
    kickoff_time: float = 10.0
    free_kick_time: float = 10.0
    penalty_time: float = 10.0
    penalty_mark_distance: float = 6.0
    penalty_behind: float = 1.0
    placement_time: float = 30.0
    placement_min_time: float = 2.0
    placement_tolerance: float = 0.15
    placement_clearance: float = 0.05
    placement_skip_distance: float = 1.0
    placement_skip_defense: float = 0.7
    placement_interference_distance: float = 0.5
    placement_interference_penalty: float = 10.0
    max_placement_failures: int = 5
    line_margin: float = 0.2
    defense_margin: float = 1.0
    goal_kick_distance: float = 1.0
    defense_area_distance: float = 0.2
    ball_speed_limit: float = 6.5
    crash_speed: float = 1.5
    crash_both_margin: float = 0.3
    goal_ball_height: float = 0.15
    goal_foul_window: float = 2.0
    no_progress_time: float = 10.0
    no_progress_distance: float = 0.05
    keeper_held_time: float = 10.0
    fouls_per_card: int = 3
    yellow_card_time: float = 120.0
    cards_for_red: int = 2
    stage_pause: float = 10.0
    source: str = ""
    kind: str = "ssl"

    def __post_init__(self) -> None:
        if self.kind != "ssl":
            raise ValueError(f"kind must be 'ssl', got {self.kind!r}")
        if self.division not in ("A", "B"):
            raise ValueError(f"division must be 'A' or 'B', got {self.division!r}")
        for name in ("stop_distance", "stop_speed", "ball_in_play_distance", "kickoff_time",
                     "free_kick_time", "penalty_time", "penalty_mark_distance",
                     "penalty_behind", "placement_time", "placement_tolerance",
                     "placement_skip_distance", "placement_interference_distance",
                     "ball_speed_limit", "crash_speed", "goal_ball_height",
                     "no_progress_time", "no_progress_distance", "keeper_held_time",
                     "yellow_card_time", "stage_pause"):
            check_number(name, getattr(self, name), 1e-6, 1e4)
        for name in ("grace_period", "placement_min_time", "placement_clearance",
                     "placement_skip_defense", "placement_interference_penalty",
                     "line_margin", "defense_margin", "goal_kick_distance",
                     "defense_area_distance", "crash_both_margin", "goal_foul_window"):
            check_number(name, getattr(self, name), 0.0, 1e4)
        for name, lo in (("max_placement_failures", 1), ("fouls_per_card", 1),
                         ("cards_for_red", 1)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= 1000:
                raise ValueError(f"{name} must be an integer in [{lo}, 1000], got {value!r}")
        if not math.isfinite(self.placement_min_time) or \
                self.placement_min_time > self.placement_time:
            raise ValueError(f"placement_min_time ({self.placement_min_time}) must not exceed "
                             f"placement_time ({self.placement_time})")


@dataclass(frozen=True)
class HumanoidRuleSpec:
    """The numbers of the RoboCup Humanoid League Laws of the Game (distances [m], times [s]);
    law numbers are the rule book's, "Section II" its competition rules (game interruption
    procedure, removal penalty).

    Attributes:
        name: the preset's name.
        half_duration: playing time of each of the two equal periods; the clock never stops
            (Law 7: 10 minutes; the controller plays the match duration it is given).
        ball_in_play_distance: a kick-off's or game interruption's ball is in play once it
            moved this far (Laws 8 and 13, footnote for the virtual competition: 5 cm).
        in_play_time: ... or this long after the referee's signal (Laws 8 and 13: 10 s).
        opponent_distance: opponents of the team taking a game interruption (throw-in, goal
            kick, corner kick, free kick) stay at least this far from the ball until it is in
            play, measured between the centres of the ball and the robot (Law 13; Section II,
            game interruption procedure: 0.75 m in KidSize).
        removal_time: a removal penalty keeps the robot off the field this long (Law 13;
            Section II, removal penalty: 10 s since 2025, 30 s before).
        dropped_ball_time: a ball in play that moved less than ``dropped_ball_distance`` for
            this long is dropped at the centre mark (Law 8, virtual competition: 2 minutes).
        dropped_ball_distance: see ``dropped_ball_time`` (Law 8: 5 cm).
        line_inset: how far inside the field lines the referee puts the ball for a throw-in,
            a goal kick or a corner kick, which the laws put on the line (Laws 15-17); half
            the 0.05 m line width, as the league's virtual referee (hlvs_webots) does.
        source: the rule book.
        kind: ``"humanoid"``, the robots the rules are for (as a robot spec's ``kind``).
    """

    name: str
    half_duration: float = 600.0
    ball_in_play_distance: float = 0.05
    in_play_time: float = 10.0
    opponent_distance: float = 0.75
    removal_time: float = 10.0
    dropped_ball_time: float = 120.0
    dropped_ball_distance: float = 0.05
    line_inset: float = 0.025
    source: str = ""
    kind: str = "humanoid"

    def __post_init__(self) -> None:
        for name in ("half_duration", "ball_in_play_distance", "in_play_time",
                     "opponent_distance", "removal_time", "dropped_ball_time",
                     "dropped_ball_distance"):
            check_number(name, getattr(self, name), 1e-6, 1e4)
        check_number("line_inset", self.line_inset, 0.0, 1e4)
        if self.kind != "humanoid":
            raise ValueError(f"kind must be 'humanoid', got {self.kind!r}")


_SSL_2025 = "RoboCup Small Size League rules, 2025 edition"

RULES: Registry[RuleSpec | HumanoidRuleSpec] = preset_table("rules", {
    "ssl-2025-div-b": RuleSpec(
        name="ssl-2025-div-b", division="B", free_kick_time=10.0, no_progress_time=10.0,
        keeper_held_time=10.0, penalty_mark_distance=6.0,
        source=f"{_SSL_2025}, Division B"),
    "ssl-2025-div-a": RuleSpec(
        name="ssl-2025-div-a", division="A", free_kick_time=5.0, no_progress_time=5.0,
        keeper_held_time=5.0, penalty_mark_distance=8.0,
        source=f"{_SSL_2025}, Division A"),
    "humanoid-2025-kid": HumanoidRuleSpec(
        name="humanoid-2025-kid",
        source="RoboCup Humanoid League Laws of the Game 2025, KidSize (virtual competition "
               "where it differs)"),
})


def rules(spec: str | RuleSpec | HumanoidRuleSpec = "ssl-2025-div-b", **overrides: Any
          ) -> RuleSpec | HumanoidRuleSpec:
    """A rule preset by name (or a spec of either kind), with ``overrides`` of its fields
    (validated)."""
    return resolve_preset("rules", RULES, spec, overrides)
