"""The outcome and reward rules of the tasks (Goalkeeper-v0, Shootout-v0 and the match's
rewards), each written once as a compiled kernel on one environment's numbers, and run over
rows of environments by a rows kernel that calls it: :class:`~soccer_env.envs.GoalkeeperEnv`,
:class:`~soccer_env.envs.ShootoutEnv` and the match call the row rules, their batched
counterparts (:mod:`soccer_env.envs.batched`, :mod:`soccer_env.envs.batched_match`) the rows
kernels, so a batch judges each environment exactly as a single one does.

Outcomes are codes, :data:`GOALKEEPER_OUTCOMES` and :data:`SHOOTOUT_OUTCOMES` their names (code
0: the episode goes on). Where the ball left the field is classified before the rule by
:func:`~soccer_env.sim.referee.classify_exit` and passed in as an exit code: :data:`NO_EXIT`,
:data:`EXIT_GOAL` (into the goal the task scores or concedes at) or :data:`EXIT_OUT`.
Positions in metres, velocities in m/s, the control step ``dt`` in seconds; actions are the
normalised ``(vx, vy, omega)`` the learner sent.
"""

from __future__ import annotations

import math

import numpy as np

from estimators.compiled import kernel

__all__ = ["NO_EXIT", "EXIT_GOAL", "EXIT_OUT", "GOALKEEPER_OUTCOMES", "SHOOTOUT_OUTCOMES",
           "GOALKEEPER_STOP_SPEED", "GOALKEEPER_CLEAR_SPEED", "INTERCEPT_MIN_SPEED",
           "SHOOTOUT_STOP_SPEED", "SHOOTOUT_CLEAR_SPEED", "action_cost_rate",
           "goalkeeper_outcome", "goalkeeper_terms", "goalkeeper_rows", "shootout_outcome",
           "goal_distance", "shootout_terms", "shootout_rows", "match_terms",
           "match_rows"]

#: Exit codes: the ball is on the field, went into the task's goal, or left elsewhere.
NO_EXIT, EXIT_GOAL, EXIT_OUT = 0, 1, 2
#: Goalkeeper-v0's outcomes by code (the goal and out codes are the exit codes).
GOALKEEPER_OUTCOMES = (None, "goal", "out", "stopped", "cleared")
#: Shootout-v0's outcomes by code.
SHOOTOUT_OUTCOMES = (None, "goal", "out", "saved")

#: Goalkeeper-v0: the ball counts as stopped below this speed [m/s].
GOALKEEPER_STOP_SPEED = 0.05
#: Goalkeeper-v0: the ball counts as cleared once it moves away from the goal faster than this
#: [m/s].
GOALKEEPER_CLEAR_SPEED = 0.1
#: The intercept shaping term applies while the ball moves towards the goal faster than this
#: [m/s].
INTERCEPT_MIN_SPEED = 0.05
#: Shootout-v0: a ball the keeper touched is saved once it moves back faster than this [m/s]
#: or slower than the stop speed [m/s].
SHOOTOUT_CLEAR_SPEED = 0.1
SHOOTOUT_STOP_SPEED = 0.05


@kernel
def action_cost_rate(a0: float, a1: float, a2: float) -> float:
    """``(vx^2 + vy^2 + omega^2) / 3`` of a normalised action (the action cost per second and
    unit scale)."""
    return (a0 * a0 + a1 * a1 + a2 * a2) / 3.0


@kernel
def goalkeeper_outcome(exit_code: int, fired: bool, airborne: bool, vx: float, vy: float
                       ) -> int:
    """Goalkeeper-v0's outcome code: the exit if the ball left the field; else, once the
    shot is fired, ``stopped`` (on the ground, slower than the stop speed) or ``cleared``
    (moving away from the goal, ``vx`` above the clear speed); else 0."""
    if exit_code != NO_EXIT:
        return exit_code
    if not fired:
        return 0
    if not airborne and vx * vx + vy * vy < GOALKEEPER_STOP_SPEED * GOALKEEPER_STOP_SPEED:
        return 3
    if vx > GOALKEEPER_CLEAR_SPEED:
        return 4
    return 0


@kernel
def goalkeeper_terms(ball: tuple[float, float, float, float], keeper: tuple[float, float],
                     action: tuple[float, float, float],
                     weights: tuple[float, float, float, float],
                     geometry: tuple[float, float, float, float, float], dt: float
                     ) -> tuple[float, float, float, float]:
    """Goalkeeper-v0's shaping terms ``(intercept, ball_distance, action_cost,
    outside_area)`` of a step (:data:`~soccer_env.envs.goalkeeper.GOALKEEPER_SHAPING`), each
    0 where its weight is 0.

    Args:
        ball: ``(x, y, vx, vy)``; keeper: ``(x, y)``; action: normalised ``(vx, vy,
            omega)``.
        weights: the scales of the four terms.
        geometry: ``(half_length, mouth, goal_width, defense_depth, defense_width)``, the
            mouth the half-width the intercept's crossing point is limited to.
        dt: the control step [s].
    """
    bx, by, vx, vy = ball
    kx, ky = keeper
    half_length, mouth, goal_width, depth, width = geometry
    w_int, w_dist, w_act, w_out = weights
    intercept = ball_distance = cost = outside = 0.0
    if w_int != 0.0:
        err = 0.0
        if vx < -INTERCEPT_MIN_SPEED:
            # Where the ball's line crosses the goal line, limited to the mouth (a ball barely
            # moving towards the goal would put it anywhere).
            y_cross = max(-mouth, min(mouth, by + vy * (-half_length - bx) / vx))
            err = abs(ky - y_cross) / goal_width
        intercept = -w_int * err * dt
    if w_dist != 0.0:
        ball_distance = -w_dist * math.hypot(bx - kx, by - ky) * dt
    if w_act != 0.0:
        cost = -w_act * action_cost_rate(action[0], action[1], action[2]) * dt
    if w_out != 0.0:
        inside = kx <= -half_length + depth and abs(ky) <= 0.5 * width
        outside = 0.0 if inside else -w_out * dt
    return intercept, ball_distance, cost, outside


@kernel
def goalkeeper_rows(exits: np.ndarray, fired: np.ndarray, airborne: np.ndarray,
                    live: np.ndarray, state: np.ndarray, actions: np.ndarray,
                    weights: tuple[float, float, float, float],
                    geometry: tuple[float, float, float, float, float], dt: float
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`goalkeeper_outcome`, the reward and the reward terms of every environment:
    ``state`` ``(n, 1 + N, >= 5)`` rows (the ball, then robot 0 the keeper), ``actions``
    ``(n, >= 3)``; where ``live`` is False the outcome is 0, the reward and the terms 0.
    The terms ``(n, 5)`` are the outcome's (-1 for a goal, +1 for any other end, 0 while the
    episode goes on), then :func:`goalkeeper_terms`' in its order; the reward is their sum
    from zero, as the single environment sums its terms."""
    n = state.shape[0]
    codes = np.zeros(n, dtype=np.int64)
    rewards = np.zeros(n)
    terms = np.zeros((n, 5))
    for k in range(n):
        if not live[k]:
            continue
        b = state[k, 0]
        code = goalkeeper_outcome(exits[k], fired[k], airborne[k], b[3], b[4])
        codes[k] = code
        shaping = goalkeeper_terms((b[0], b[1], b[3], b[4]), (state[k, 1, 0], state[k, 1, 1]),
                                   (float(actions[k, 0]), float(actions[k, 1]),
                                    float(actions[k, 2])), weights, geometry, dt)
        first = 0.0 if code == 0 else (-1.0 if code == 1 else 1.0)
        terms[k, 0] = first
        total = 0.0 + first
        for j in range(4):
            terms[k, 1 + j] = shaping[j]
            total += shaping[j]
        rewards[k] = total
    return codes, rewards, terms


@kernel
def shootout_outcome(exit_code: int, keeper_touched: bool, airborne: bool, vx: float,
                     vy: float) -> int:
    """Shootout-v0's outcome code: the exit if the ball left the field; else ``saved`` once
    the keeper touched the ball and it is on the ground, moving back towards the attacker
    (``vx`` below minus the clear speed) or slower than the stop speed; else 0."""
    if exit_code != NO_EXIT:
        return exit_code
    if keeper_touched and not airborne and (
            vx < -SHOOTOUT_CLEAR_SPEED
            or vx * vx + vy * vy < SHOOTOUT_STOP_SPEED * SHOOTOUT_STOP_SPEED):
        return 3
    return 0


@kernel
def goal_distance(ball: tuple[float, float], goal: tuple[float, float]) -> float:
    """The ball's distance [m] to the goal's centre (Shootout-v0's progress measure)."""
    return math.hypot(ball[0] - goal[0], ball[1] - goal[1])


@kernel
def shootout_terms(ball: tuple[float, float], attacker: tuple[float, float],
                   goal: tuple[float, float], before: float,
                   action: tuple[float, float, float], weights: tuple[float, float, float],
                   dt: float) -> tuple[float, float, float, float]:
    """Shootout-v0's shaping terms ``(ball_progress, ball_distance, action_cost)`` and the
    ball's distance to the goal's centre ``goal`` [m] (the next step's ``before``):
    ``ball_progress`` the scale times how much closer the ball came since ``before`` [m],
    ``ball_distance`` minus the scale times the attacker's distance to the ball per second,
    ``action_cost`` as Goalkeeper-v0's."""
    w_prog, w_dist, w_act = weights
    d = goal_distance(ball, goal)
    progress = w_prog * (before - d)
    ball_distance = -w_dist * math.hypot(ball[0] - attacker[0], ball[1] - attacker[1]) * dt
    cost = -w_act * action_cost_rate(action[0], action[1], action[2]) * dt
    return progress, ball_distance, cost, d


@kernel
def shootout_rows(exits: np.ndarray, touched: np.ndarray, airborne: np.ndarray,
                  live: np.ndarray, state: np.ndarray, before: np.ndarray,
                  actions: np.ndarray, goal: tuple[float, float],
                  weights: tuple[float, float, float], dt: float
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`shootout_outcome`, the reward and the reward terms of every environment
    (``state`` as in :func:`goalkeeper_rows`, robot 0 the attacker); ``before`` ((n,), in
    place) takes each ball's new distance to the goal. Where ``live`` is False the outcome is
    0, the reward and the terms 0. The terms ``(n, 4)`` are the outcome's (+1 for a goal, -1
    for any other end, 0 while the episode goes on), then :func:`shootout_terms`' in its
    order; the reward is their sum from zero."""
    n = state.shape[0]
    codes = np.zeros(n, dtype=np.int64)
    rewards = np.zeros(n)
    terms = np.zeros((n, 4))
    for k in range(n):
        b = state[k, 0]
        code = shootout_outcome(exits[k], touched[k], airborne[k], b[3], b[4]) \
            if live[k] else 0
        codes[k] = code
        progress, dist, cost, d = shootout_terms(
            (b[0], b[1]), (state[k, 1, 0], state[k, 1, 1]), goal, before[k],
            (float(actions[k, 0]), float(actions[k, 1]), float(actions[k, 2])), weights, dt)
        before[k] = d
        if live[k]:
            first = 0.0 if code == 0 else (1.0 if code == 1 else -1.0)
            terms[k, 0], terms[k, 1], terms[k, 2], terms[k, 3] = first, progress, dist, cost
            rewards[k] = 0.0 + first + progress + dist + cost
    return codes, rewards, terms


@kernel
def match_terms(ball: tuple[float, float], robots: np.ndarray, teams: np.ndarray,
                scorer: int, ball_dx: float, count_progress: bool,
                weights: tuple[float, float], dt: float) -> np.ndarray:
    """The match's reward terms of every robot ``(N, 3)``: ``goal`` (+1 for the scorer's
    team, -1 for the other, 0 without a goal: ``scorer`` -1), ``ball_progress`` (the scale
    times the ball's displacement ``ball_dx`` [m] along x this step, towards the yellow goal
    for the blue team (team 0) and the opposite for yellow; 0 unless ``count_progress``: no
    exit and no placement this step) and ``ball_distance`` (minus the scale times the
    robot's distance to the ball per second; ``robots`` ``(N, >= 2)`` positions [m]).
    ``weights`` are the scales ``(ball_progress, ball_distance)``, ``dt`` the control step
    [s]."""
    n = robots.shape[0]
    out = np.zeros((n, 3))
    w_prog, w_dist = weights
    dx = w_prog * ball_dx
    for i in range(n):
        if scorer >= 0:
            out[i, 0] = 1.0 if teams[i] == scorer else -1.0
        if w_prog != 0.0 and count_progress:
            out[i, 1] = dx if teams[i] == 0 else -dx
        if w_dist != 0.0:
            out[i, 2] = -w_dist * dt * math.hypot(robots[i, 0] - ball[0],
                                                  robots[i, 1] - ball[1])
    return out


@kernel
def match_rows(state: np.ndarray, teams: np.ndarray, scorers: np.ndarray,
               ball_dx: np.ndarray, count_progress: np.ndarray,
               weights: tuple[float, float], dt: float) -> np.ndarray:
    """The rewards ``(M, N)`` of ``M`` matches, ``state`` ``(M, 1 + N, >= 2)`` (the ball,
    then the robots): each robot's :func:`match_terms` summed in order, as the single match
    sums them."""
    m, n = state.shape[0], teams.shape[0]
    out = np.empty((m, n))
    for k in range(m):
        terms = match_terms((state[k, 0, 0], state[k, 0, 1]), state[k, 1:], teams,
                            scorers[k], ball_dx[k], count_progress[k], weights, dt)
        for i in range(n):
            out[k, i] = terms[i, 0] + terms[i, 1] + terms[i, 2]
    return out
