"""The game block at the end of every match observation (:class:`GameRows`): the score, the
clock and the restart (:data:`GAME_NAMES`) and, when the match plays the game flow, the
referee's state (:data:`GAME_FLOW_NAMES`), each in the agent's team frame ("ours" being the
agent's team), with the bounds of the observation space.

The bounds come from where the values do: the designated position's from the field preset's
walled area, the robots allowed on the field and the barred robot's number from
:data:`~soccer_env.sim.world.MAX_TEAM_SIZE`; counts that no preset limits (goals, cards,
fouls) have the wide bounds below, which only a pathological match reaches (values are clipped
to the bounds).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from soccer_env.observations import SLOT_PREFIX, other_robots
from soccer_env.presets import FieldSpec
from soccer_env.sim.world import MAX_TEAM_SIZE

__all__ = ["GameRows", "GAME_NAMES", "GAME_FLOW_NAMES", "GOALS_BOUND", "CARDS_BOUND",
           "FOULS_BOUND", "game_bounds", "slot_names"]

#: Game-state entries at the end of every match observation: the match time left as a
#: fraction of ``match_duration``, goals for, goals against, and +1 / -1 while a restart
#: awarded to the agent's own team / the opponents waits for its first touch (0 otherwise).
GAME_NAMES = ("game.time_left", "game.goals_for", "game.goals_against", "game.restart")

#: The referee state after :data:`GAME_NAMES` when the match plays the game flow
#: (``game=...``), in the team frame, "ours" being the agent's team: the situation as a
#: one-hot (:data:`~soccer_env.sim.game.SITUATIONS`, with the team taking the restart or
#: placing the ball), whether the free kick is indirect, the team of the command that follows
#: the stop or the placement (+1 ours, -1 theirs, 0 none), the designated position (a flag,
#: then ``x, y`` [m], 0 when none), the second half flag, the stage's playing time left as a
#: fraction of the stage, running yellow cards, red cards, fouls and robots allowed on the
#: field of both teams, whether the team may place the ball, which of the team's robots may
#: not touch the ball again before another robot has (its number in the team plus one, 0 for
#: none: the kicker of a restart, SSL rules 8.2), and whether the agent's robot is on the
#: field (0 while a card or a removal penalty keeps it off).
GAME_FLOW_NAMES = (
    "game.stop", "game.placement_ours", "game.placement_theirs", "game.kickoff_ours",
    "game.kickoff_theirs", "game.penalty_ours", "game.penalty_theirs", "game.free_kick_ours",
    "game.free_kick_theirs", "game.running", "game.indirect", "game.next_team",
    "game.target_set", "game.target_x", "game.target_y", "game.second_half",
    "game.stage_time_left", "game.yellow_ours", "game.yellow_theirs", "game.red_ours",
    "game.red_theirs", "game.fouls_ours", "game.fouls_theirs", "game.allowed_ours",
    "game.allowed_theirs", "game.can_place", "game.barred", "game.on_field",
)
#: After :data:`GAME_FLOW_NAMES`, one entry per other robot's slot of the observation (the
#: agent's team-mates in robot order, then the opponents: its ``mate<j>.*`` and ``opp<j>.*``
#: entries): 1 while that robot is on the field, 0 while a card or a removal penalty keeps it
#: off (its pose entries then show where it waits). The names are ``game.slot<j>.on_field``
#: here (:data:`~soccer_env.observations.SLOT_PREFIX`); each agent's observation names them
#: after its slots, ``game.mate<j>.on_field`` and ``game.opp<j>.on_field``
#: (:meth:`~soccer_env.observations.ObservationBuilder.names_for`).

#: Column of each entry of :data:`GAME_FLOW_NAMES`.
_FLOW = {name: k for k, name in enumerate(GAME_FLOW_NAMES)}

#: Observation bound on a team's goals.
GOALS_BOUND = 1000.0
#: Observation bound on a team's running yellow cards and its red cards (a rule preset counts
#: up to 1000 cards, :class:`~soccer_env.presets.rules.RuleSpec`'s ``cards_for_red``).
CARDS_BOUND = 1000.0
#: Observation bound on a team's fouls.
FOULS_BOUND = 1e6


def slot_names(others: int) -> tuple[str, ...]:
    """The names of the slots' on-field entries for ``others`` other robots."""
    return tuple(f"{SLOT_PREFIX}{j}.on_field" for j in range(others))


def game_bounds(field: FieldSpec, flow: bool, others: int = 0
                ) -> tuple[tuple[float, ...], tuple[float, ...], tuple[str, ...]]:
    """The lower and upper bounds and the names of the game block: :data:`GAME_NAMES`, then
    with the game flow (``flow``) :data:`GAME_FLOW_NAMES` (the designated position within the
    walled area of ``field`` [m]) and the on-field flags of the ``others`` slots
    (:func:`slot_names`)."""
    low, high = (0.0, 0.0, 0.0, -1.0), (1.0, GOALS_BOUND, GOALS_BOUND, 1.0)
    if not flow:
        return low, high, GAME_NAMES
    lx = field.half_length + field.boundary
    ly = field.half_width + field.boundary
    team = float(MAX_TEAM_SIZE)
    # The situation's one-hot and the indirect flag, then the next team, the designated
    # position, the second half and the stage's time left; the counts; the last flags.
    flow_low = [0.0] * 11 + [-1.0, 0.0, -lx, -ly, 0.0, 0.0] + [0.0] * 11
    flow_high = [1.0] * 11 + [1.0, 1.0, lx, ly, 1.0, 1.0] + [CARDS_BOUND] * 4 + \
        [FOULS_BOUND, FOULS_BOUND] + [team] * 2 + [1.0, team, 1.0]
    flow_low += [0.0] * others
    flow_high += [1.0] * others
    return (low + tuple(flow_low), high + tuple(flow_high),
            GAME_NAMES + GAME_FLOW_NAMES + slot_names(others))


def _situation_column(kind: str, ours: bool) -> int:
    """The column of the situation ``kind`` (:data:`~soccer_env.sim.game.SITUATIONS`) of
    the own team (``ours``) or the opponents in :data:`GAME_FLOW_NAMES`."""
    if kind in ("stop", "running"):
        return _FLOW[f"game.{kind}"]
    return _FLOW[f"game.{kind}_{'ours' if ours else 'theirs'}"]


class GameRows:
    """Every robot's game block, ``(N, G)``, each in its team's frame.

    Args:
        teams: every robot's team (0 blue, 1 yellow).
        n_blue: blue's robots (yellow's robot ``i`` is its team's number ``i - n_blue``).
        match_duration: the match's (playing) time [s].
    """

    def __init__(self, teams: list[int], n_blue: int, match_duration: float) -> None:
        self.teams = teams
        self.n_blue = n_blue
        self.match_duration = match_duration
        self._others = np.array(other_robots(teams), dtype=np.int64).reshape(len(teams), -1)

    def simple(self, time: float, score: list[int], restart: int) -> np.ndarray:
        """The block of a match with the simple referee (:data:`GAME_NAMES`) at ``time`` [s]
        with the ``score`` (blue's, yellow's goals) and the ``restart`` team (-1: none)."""
        blue, yellow = score
        flag = 0.0 if restart < 0 else (1.0 if restart == 0 else -1.0)
        time_left = max(0.0, 1.0 - time / self.match_duration)
        per_team = np.array([(time_left, blue, yellow, flag),
                             (time_left, yellow, blue, -flag)])
        return per_team[self.teams]

    def flow(self, game: Any, score: list[int], restart: int, off_field: list[int]
             ) -> np.ndarray:
        """The block of a match that plays the game flow (:data:`GAME_NAMES`, then
        :data:`GAME_FLOW_NAMES` and the slots' on-field flags) from its ``game`` controller,
        the ``score``, the ``restart`` team and the robots ``off_field``."""
        flag = 0.0 if restart < 0 else (1.0 if restart == 0 else -1.0)
        time_left = min(1.0, max(0.0, game.playing_time_left / self.match_duration))
        situation = game.situation()
        nxt = game.next_command[1] if game.next_command is not None else -1
        barred = game.barred_robot
        width = len(GAME_NAMES) + len(GAME_FLOW_NAMES)
        rows = np.zeros((2, width))
        for t in (0, 1):
            sign = 1.0 if t == 0 else -1.0  # the team frame turns yellow's half a turn
            rows[t, 0:len(GAME_NAMES)] = (time_left, score[t], score[1 - t], flag * sign)
            referee = self._referee(game, t, situation, nxt, barred)
            rows[t, len(GAME_NAMES):] = list(referee.values())
        on = np.ones(len(self.teams))
        on[list(off_field)] = 0.0
        out = np.concatenate([rows[self.teams], on[self._others]], axis=1)
        out[:, width - 1] = on  # game.on_field
        return out

    def _referee(self, g: Any, t: int, situation: tuple[str, int], nxt: int, barred: int
                 ) -> dict[str, float]:
        """Team ``t``'s :data:`GAME_FLOW_NAMES` entries, in its frame, from the game
        controller ``g``, its ``situation()``, the team of its next command (``nxt``, -1:
        none) and its barred robot (-1: none)."""
        sign = 1.0 if t == 0 else -1.0
        kind, team = situation
        target = g.designated
        ours, theirs = g.team_info[t], g.team_info[1 - t]
        flow = dict.fromkeys(GAME_FLOW_NAMES, 0.0)
        flow[GAME_FLOW_NAMES[_situation_column(kind, team == t)]] = 1.0
        flow["game.indirect"] = float(g.indirect)
        flow["game.next_team"] = 0.0 if nxt < 0 else (1.0 if nxt == t else -1.0)
        if target is not None:
            flow["game.target_set"] = 1.0
            flow["game.target_x"], flow["game.target_y"] = sign * target[0], sign * target[1]
        flow["game.second_half"] = float(g.stage == "second_half")
        flow["game.stage_time_left"] = min(1.0, max(0.0, g.stage_time_left / g.stage_duration))
        flow["game.yellow_ours"] = len(ours.yellow_cards)
        flow["game.yellow_theirs"] = len(theirs.yellow_cards)
        flow["game.red_ours"], flow["game.red_theirs"] = ours.red_cards, theirs.red_cards
        flow["game.fouls_ours"], flow["game.fouls_theirs"] = ours.fouls, theirs.fouls
        flow["game.allowed_ours"] = g.robots_allowed(t)
        flow["game.allowed_theirs"] = g.robots_allowed(1 - t)
        flow["game.can_place"] = float(ours.can_place)
        if barred >= 0 and self.teams[barred] == t:
            flow["game.barred"] = 1 + barred - (0 if t == 0 else self.n_blue)
        return flow
