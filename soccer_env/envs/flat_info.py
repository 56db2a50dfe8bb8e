"""Flat infos (``info_mode="flat"``): numbers only, under keys fixed for the environment.

The default infos (``info_mode="full"``) hold nested dicts (the truth and the belief per
robot, the drawn shot) and strings (``outcome``, ``event``; :data:`NO_OUTCOME` and
:data:`NO_EVENT`, the empty string, while nothing is to report: never None). Libraries that
turn every
info into a tensor or an array (TorchRL's ``PettingZooWrapper``, some vectorised loggers)
need instead one flat mapping of numbers whose keys do not change from one step to the next.
With ``info_mode="flat"`` every environment gives that: a ``dict[str, float]`` with the same
keys, in the same order, at every reset and every step, every value a finite
``numpy.float64`` (a subclass of Python's ``float`` that also has the ``dtype`` which TorchRL's
info readers ask for; flags are 0.0 or 1.0, codes whole numbers).

Keys of every environment (the agent's own robot for ``robot_*``; field frame, SI units):

==========================================  ===============================================
``time``                                    simulated time of the episode [s]
``truth_ball_x``, ``truth_ball_y``          the ball's true position [m]
``truth_ball_z``                            its height [m] (a chip in flight)
``truth_ball_vx``, ``truth_ball_vy``        its true velocity [m/s]
``truth_robot_x``, ``truth_robot_y``,       the agent's true pose [m, rad]
``truth_robot_theta``
``estimate_ball_x``, ``estimate_ball_y``,   the ball as the agent's perception believes it
``estimate_ball_vx``, ``estimate_ball_vy``  at the present time [m, m/s] (the truth in truth
                                            mode)
``estimate_robot_x``, ``estimate_robot_y``, the agent's believed own pose [m, rad]
``estimate_robot_theta``
``ball_error``                              distance from the believed to the true ball [m]
``robot_fallen``                            1.0 while the agent's humanoid lies or gets up
                                            (always 0.0 for SSL robots)
``reward_<term>``                           each reward term of the step, as in the full
                                            info's ``reward_terms`` (all zero at reset)
==========================================  ===============================================

Goalkeeper-v0 adds ``outcome`` (code below), ``is_success`` (1.0 at the last step of a save,
else 0.0), ``shot_fired``, ``keeper_touched``, ``shot_speed`` [m/s] and ``shot_chip``;
Shootout-v0 adds ``outcome``, ``is_success`` (1.0 at the last step of a goal) and
``keeper_touched``; the match adds ``event`` (code below), ``score_blue`` and
``score_yellow`` (:data:`MATCH_KEYS`, :func:`flat_match`), and with the game flow its referee
state (:data:`FLAT_GAME_KEYS`). ``env.flat_info_keys``
(``env.unwrapped.flat_info_keys`` through Gymnasium's wrappers) lists an environment's keys.

:data:`OUTCOME_CODES` (``outcome``: 0 while the episode goes on) and :data:`EVENT_CODES`
(``event``: what ended the ball's play this step, 0 for nothing):

=====  ==============  ===============
code   outcome         event
=====  ==============  ===============
0      (running)       (none)
1      ``goal``        ``goal``
2      ``stopped``     ``touch``
3      ``cleared``     ``goal_line``
4      ``out``         ``over_bar``
5      ``saved``       ``invalid_goal`` (game flow: a goal the rules disallow)
=====  ==============  ===============
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np

from soccer_env.sim.game import COMMANDS

__all__ = ["INFO_MODES", "NO_OUTCOME", "NO_EVENT", "OUTCOME_CODES", "EVENT_CODES",
           "COMMON_KEYS", "MATCH_KEYS",
           "FLAT_GAME_KEYS", "flat_keys", "flat_common", "flat_match", "as_float64"]

#: The values of ``info_mode``: the rich default (nested dicts, strings) or flat numbers.
INFO_MODES = ("full", "flat")

#: ``info["outcome"]`` of the single-agent tasks while the episode goes on: the empty string
#: (false in a condition, as a string a tensor or array library takes like the outcomes'
#: names; the tasks' rules say None internally).
NO_OUTCOME = ""
#: ``info["event"]`` of the match at a step where nothing ended the ball's play: the empty
#: string.
NO_EVENT = ""

#: ``outcome`` of the single-agent tasks as a number (:data:`NO_OUTCOME`: the episode goes
#: on).
OUTCOME_CODES: dict[str, int] = {NO_OUTCOME: 0, "goal": 1, "stopped": 2, "cleared": 3,
                                 "out": 4, "saved": 5}
#: ``event`` of the match as a number (:data:`NO_EVENT`: nothing happened to the ball's play).
EVENT_CODES: dict[str, int] = {NO_EVENT: 0, "goal": 1, "touch": 2, "goal_line": 3,
                               "over_bar": 4, "invalid_goal": 5}

#: The keys every environment's flat info starts with, in order.
COMMON_KEYS = (
    "time",
    "truth_ball_x", "truth_ball_y", "truth_ball_z", "truth_ball_vx", "truth_ball_vy",
    "truth_robot_x", "truth_robot_y", "truth_robot_theta",
    "estimate_ball_x", "estimate_ball_y", "estimate_ball_vx", "estimate_ball_vy",
    "estimate_robot_x", "estimate_robot_y", "estimate_robot_theta",
    "ball_error", "robot_fallen",
)

#: The match's own keys, after the reward terms: the step's event (:data:`EVENT_CODES`) and
#: the score.
MATCH_KEYS = ("event", "score_blue", "score_yellow")
#: The flat info's keys of the game flow (``info_mode="flat"`` with ``game=...``), after
#: :data:`MATCH_KEYS`: the command (its index in :data:`~soccer_env.sim.game.COMMANDS`), its
#: team (-1 none, 0 blue, 1 yellow), whether the ball is in play, the stage's playing time
#: left [s], and per team the fouls, running yellow cards and red cards.
FLAT_GAME_KEYS = ("game_command", "game_command_team", "game_in_play", "game_stage_time_left",
                  "game_fouls_blue", "game_yellow_cards_blue", "game_red_cards_blue",
                  "game_fouls_yellow", "game_yellow_cards_yellow", "game_red_cards_yellow")


def flat_keys(reward_terms: Iterable[str], task_keys: Iterable[str]) -> tuple[str, ...]:
    """The flat info keys of an environment with these reward terms and task entries."""
    return (*COMMON_KEYS, *(f"reward_{t}" for t in reward_terms), *task_keys)


def flat_common(state: Any, belief: Any, robot: int, fallen: bool,
                terms: dict[str, float]) -> dict[str, float]:
    """The common entries of robot ``robot``'s flat info at ``state`` (a
    :class:`~soccer_env.state.WorldState`) with its present ``belief`` (a
    :class:`~soccer_env.state.Belief`, or the state itself in truth mode; the perception
    starts every belief from its first sighting or a prior, so its values are finite) and
    the step's reward ``terms``."""
    ball, pose = state.ball, state.robots[robot]
    bx, by, bz, bvx, bvy = (float(ball[0]), float(ball[1]), float(ball[2]), float(ball[3]),
                            float(ball[4]))
    rx, ry, rt = float(pose[0]), float(pose[1]), float(pose[2])
    eball, epose = belief.ball, belief.robots[robot]
    ex, ey = float(eball[0]), float(eball[1])
    info = {
        "time": float(state.time),
        "truth_ball_x": bx, "truth_ball_y": by, "truth_ball_z": bz,
        "truth_ball_vx": bvx, "truth_ball_vy": bvy,
        "truth_robot_x": rx, "truth_robot_y": ry, "truth_robot_theta": rt,
        "estimate_ball_x": ex, "estimate_ball_y": ey,
        "estimate_ball_vx": float(eball[3]), "estimate_ball_vy": float(eball[4]),
        "estimate_robot_x": float(epose[0]), "estimate_robot_y": float(epose[1]),
        "estimate_robot_theta": float(epose[2]),
        "ball_error": math.hypot(ex - bx, ey - by),
        "robot_fallen": 1.0 if fallen else 0.0,
    }
    for name, value in terms.items():
        info[f"reward_{name}"] = float(value)
    return info


def flat_match(event: str | None, score: list[int], game: Any) -> dict[str, float]:
    """The match's own flat entries, the same for every agent: :data:`MATCH_KEYS` for the
    step's ``event`` (None or :data:`NO_EVENT`: none) and the ``score`` (blue's, yellow's
    goals) and, with a ``game`` controller (None: the simple referee),
    :data:`FLAT_GAME_KEYS`."""
    code = EVENT_CODES[NO_EVENT if event is None else event]
    out = {"event": float(code), "score_blue": float(score[0]),
           "score_yellow": float(score[1])}
    if game is not None:
        out.update(game_command=float(COMMANDS.index(game.command)),
                   game_command_team=float(game.command_team),
                   game_in_play=float(game.in_play),
                   game_stage_time_left=float(game.stage_time_left))
        for t, name in enumerate(("blue", "yellow")):
            info = game.team_info[t]
            out[f"game_fouls_{name}"] = float(info.fouls)
            out[f"game_yellow_cards_{name}"] = float(len(info.yellow_cards))
            out[f"game_red_cards_{name}"] = float(info.red_cards)
    return out


def as_float64(info: dict[str, float]) -> dict[str, float]:
    """``info`` with every value a ``numpy.float64`` (in place; returned)."""
    f64 = np.float64
    for key, value in info.items():
        info[key] = f64(value)
    return info
