"""The single-robot tasks' outcome and reward rules: closed-form cases, and the rows kernels
that the batches run equal to the row rules that single environments run, bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from soccer_env.envs.task_rules import (
    EXIT_GOAL,
    EXIT_OUT,
    GOALKEEPER_OUTCOMES,
    NO_EXIT,
    SHOOTOUT_OUTCOMES,
    goal_distance,
    goalkeeper_outcome,
    goalkeeper_rows,
    goalkeeper_terms,
    match_rows,
    match_terms,
    shootout_outcome,
    shootout_rows,
    shootout_terms,
)

# half_length, mouth, goal_width, defense_depth, defense_width
GEOMETRY = (4.5, 0.521, 1.0, 1.0, 2.0)


@pytest.mark.parametrize("args,outcome", [
    ((EXIT_GOAL, True, False, 0.0, 0.0), "goal"),
    ((EXIT_OUT, False, True, 3.0, 0.0), "out"),
    ((NO_EXIT, False, False, 0.0, 0.0), None),  # not kicked yet: a resting ball is no save
    ((NO_EXIT, True, False, 0.03, 0.03), "stopped"),
    ((NO_EXIT, True, True, 0.03, 0.03), None),  # in the air: not stopped
    ((NO_EXIT, True, True, 0.2, 0.0), "cleared"),
    ((NO_EXIT, True, False, -2.0, 0.5), None),
])
def test_goalkeeper_outcomes(args, outcome):
    assert GOALKEEPER_OUTCOMES[goalkeeper_outcome(*args)] == outcome


@pytest.mark.parametrize("args,outcome", [
    ((EXIT_GOAL, False, False, 2.0, 0.0), "goal"),
    ((EXIT_OUT, True, False, 0.0, 0.0), "out"),
    ((NO_EXIT, False, False, 0.0, 0.0), None),  # untouched by the keeper
    ((NO_EXIT, True, False, -0.5, 0.0), "saved"),  # sent back
    ((NO_EXIT, True, False, 0.01, 0.02), "saved"),  # held
    ((NO_EXIT, True, True, -0.5, 0.0), None),  # in the air
    ((NO_EXIT, True, False, 1.0, 0.0), None),  # still on its way
])
def test_shootout_outcomes(args, outcome):
    assert SHOOTOUT_OUTCOMES[shootout_outcome(*args)] == outcome


def test_goalkeeper_terms_in_closed_form():
    # A ball at (0, 0) moving at (-2, 0.4) crosses the goal line x = -4.5 at y = 0.9, limited
    # to the mouth 0.521; the keeper at (-4, 0.1), 4.0012 m from the ball, inside its area.
    terms = goalkeeper_terms((0.0, 0.0, -2.0, 0.4), (-4.0, 0.1), (1.0, 0.0, -0.5),
                             (2.0, 0.5, 0.3, 1.0), GEOMETRY, 0.02)
    assert terms[0] == pytest.approx(-2.0 * (0.521 - 0.1) / 1.0 * 0.02)
    assert terms[1] == pytest.approx(-0.5 * math.hypot(4.0, 0.1) * 0.02)
    assert terms[2] == pytest.approx(-0.3 * (1.0 + 0.25) / 3.0 * 0.02)
    assert terms[3] == 0.0
    outside = goalkeeper_terms((0.0, 0.0, 1.0, 0.0), (-3.0, 0.0), (0.0, 0.0, 0.0),
                               (2.0, 0.0, 0.0, 1.0), GEOMETRY, 0.02)
    assert outside == (0.0, 0.0, 0.0, -0.02)  # ball moving away: no intercept term
    assert goalkeeper_terms((0.0, 0.0, -2.0, 0.4), (-4.0, 0.1), (1.0, 0.0, -0.5),
                            (0.0, 0.0, 0.0, 0.0), GEOMETRY, 0.02) == (0.0, 0.0, 0.0, 0.0)


def test_shootout_terms_in_closed_form():
    goal = (4.5, 0.0)
    progress, dist, cost, d = shootout_terms((1.5, 4.0), (0.5, 4.0), goal, 5.5, (0.0, 1.0, 0.0),
                                             (1.0, 0.5, 0.3), 0.02)
    assert d == 5.0 == goal_distance((1.5, 4.0), goal)
    assert progress == 0.5
    assert dist == pytest.approx(-0.5 * 1.0 * 0.02)
    assert cost == pytest.approx(-0.3 / 3.0 * 0.02)


def _rows(seed, n=400):
    rng = np.random.default_rng(seed)
    state = np.zeros((n, 2, 6))
    state[:, :, 0] = rng.uniform(-4.6, 4.6, (n, 2))
    state[:, :, 1] = rng.uniform(-3.1, 3.1, (n, 2))
    state[:, 0, 3:5] = rng.normal(0.0, 1.0, (n, 2)) * rng.choice([0.01, 1.0], (n, 1))
    exits = rng.choice([NO_EXIT, EXIT_GOAL, EXIT_OUT], n, p=[0.8, 0.1, 0.1])
    flags = rng.random((n, 3)) < [0.7, 0.2, 0.9]
    actions = rng.uniform(-1, 1, (n, 6))
    return state, exits, flags, actions


def test_goalkeeper_rows_equal_the_row_rule_bit_for_bit():
    state, exits, (flags), actions = _rows(1)
    fired, airborne, live = flags.T
    weights, dt = (2.0, 0.5, 0.1, 1.0), 0.016
    codes, rewards, terms_out = goalkeeper_rows(exits, fired, airborne, live, state, actions,
                                                weights, GEOMETRY, dt)
    for k in range(len(state)):
        b = state[k, 0]
        code = goalkeeper_outcome(exits[k], fired[k], airborne[k], b[3], b[4]) if live[k] \
            else 0
        assert codes[k] == code
        outcome = GOALKEEPER_OUTCOMES[code]
        terms = {"outcome": 0.0 if outcome is None else (-1.0 if outcome == "goal" else 1.0)}
        terms.update(zip("abcd", goalkeeper_terms(
            (b[0], b[1], b[3], b[4]), tuple(state[k, 1, :2]), tuple(actions[k, :3]), weights,
            GEOMETRY, dt)))
        assert rewards[k] == (float(sum(terms.values())) if live[k] else 0.0)
        assert terms_out[k].tolist() == (list(terms.values()) if live[k] else [0.0] * 5)
    assert {0, 1, 2, 3, 4} <= set(codes.tolist())


def test_shootout_rows_equal_the_row_rule_bit_for_bit():
    state, exits, flags, actions = _rows(2)
    touched, airborne, live = flags.T
    goal, weights, dt = (4.5, 0.0), (1.0, 0.5, 0.1), 0.016
    before = np.random.default_rng(3).uniform(0.0, 9.0, len(state))
    was = before.copy()
    codes, rewards, terms_out = shootout_rows(exits, touched, airborne, live, state, before,
                                              actions, goal, weights, dt)
    for k in range(len(state)):
        b = state[k, 0]
        code = shootout_outcome(exits[k], touched[k], airborne[k], b[3], b[4]) if live[k] \
            else 0
        assert codes[k] == code
        outcome = SHOOTOUT_OUTCOMES[code]
        *terms, d = shootout_terms((b[0], b[1]), tuple(state[k, 1, :2]), goal, was[k],
                                   tuple(actions[k, :3]), weights, dt)
        first = 0.0 if outcome is None else (1.0 if outcome == "goal" else -1.0)
        reward = float(sum([first, *terms]))
        assert rewards[k] == (reward if live[k] else 0.0)
        assert terms_out[k].tolist() == ([first, *terms] if live[k] else [0.0] * 4)
        assert before[k] == d
    assert {0, 1, 2, 3} <= set(codes.tolist())


def test_match_terms_in_closed_form_and_rows_equal_them():
    teams = np.array([0, 0, 1])
    robots = np.array([[1.0, 0.0, 0.0], [0.0, 3.0, 0.0], [-2.0, 0.0, 1.0]])
    terms = match_terms((0.0, 0.0), robots, teams, 1, 0.02, True, (10.0, 0.5), 0.016)
    np.testing.assert_array_equal(terms[:, 0], [-1.0, -1.0, 1.0])  # yellow scored
    np.testing.assert_allclose(terms[:, 1], [0.2, 0.2, -0.2])  # towards the yellow goal
    np.testing.assert_allclose(terms[:, 2], [-0.008, -0.024, -0.016])
    quiet = match_terms((0.0, 0.0), robots, teams, -1, 0.02, False, (10.0, 0.0), 0.016)
    assert not quiet.any()  # no goal, progress not counted, no distance scale
    rng = np.random.default_rng(4)
    state = rng.normal(0.0, 2.0, (50, 4, 6))
    scorers, dx = rng.integers(-1, 2, 50), rng.normal(0.0, 0.05, 50)
    count = rng.random(50) < 0.8
    rewards = match_rows(state, teams, scorers, dx, count, (3.0, 0.5), 0.016)
    for k in range(50):
        t = match_terms((state[k, 0, 0], state[k, 0, 1]), state[k, 1:], teams, scorers[k],
                        dx[k], count[k], (3.0, 0.5), 0.016)
        assert rewards[k].tolist() == [g + p + d for g, p, d in t.tolist()]
