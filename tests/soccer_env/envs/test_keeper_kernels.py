"""The scripted keeper's compiled rules: the friction model's arithmetic bit for bit, closed
forms, and one rule for the single and the batched paths."""

from __future__ import annotations

import math

import numpy as np
import pytest

import soccer_env
from estimators import FrictionBallModel
from soccer_env.envs.keeper import (
    Guard,
    ScriptedGoalkeeper,
    guard_line_y,
    line_time,
    rolled_y,
)
from soccer_env.envs.steering import drive_velocity, turn_rate


@pytest.mark.parametrize("deceleration", [0.0, 0.3])
def test_line_time_and_rolled_y_are_the_friction_model_bit_for_bit(deceleration):
    """line_time and rolled_y: FrictionBallModel.time_to_line and predict's y, bit for bit
    (balls reaching the line, stopping short, moving away, on the line)."""
    model = FrictionBallModel(deceleration)
    rng = np.random.default_rng(11)
    for k in range(4000):
        state = np.concatenate([rng.uniform(-4.0, 4.0, 2), rng.normal(0.0, 3.0, 2)])
        x_line = float(state[0]) if k % 50 == 0 else float(rng.uniform(-4.5, 4.5))
        bx, by, vx, vy = state.tolist()
        t = float(model.time_to_line(state, x_line))
        assert line_time(deceleration, bx, vx, vy, x_line) == t
        if math.isfinite(t):
            assert rolled_y(deceleration, by, vx, vy, t) == float(model.predict(state, t)[1])


def test_guard_line_y_closed_forms():
    """Without friction a ball moving towards the goal crosses the guard line at ``by + vy / vx
    (x_g - bx)``; a ball at rest or moving away sets the keeper on the line from the ball to the
    goal centre; the target stays within the mouth."""
    g = Guard(guard_x=-4.3, goal_x=-4.5, half_goal=0.52, deceleration=0.0)
    assert guard_line_y(g, 0.0, 0.3, -2.0, -0.1) == pytest.approx(0.3 - 0.1 / 2.0 * 4.3)
    assert guard_line_y(g, 0.0, 0.9, 1.0, 0.0) == pytest.approx(0.9 * 0.2 / 4.5)
    assert guard_line_y(g, -4.4, 0.4, 0.0, 0.0) == 0.4  # behind the line: frac capped at 1
    assert guard_line_y(g, 0.0, 0.0, -2.0, 3.0) == 0.52
    # With friction a slow ball stops short: the keeper falls back on the line to the goal.
    g = g._replace(deceleration=0.5)
    assert guard_line_y(g, 0.0, 0.9, -0.5, 0.0) == pytest.approx(0.9 * 0.2 / 4.5)


def test_steering_closed_forms():
    """drive_velocity: the braking profile along the target direction in the body frame, zero
    at the target; turn_rate: ``gain err / omega_max`` clipped to [-1, 1]."""
    vx, vy = drive_velocity(0.0, 0.0, 1.0, 0.0, 0.0, 0.02, 3.0, 4.0, math.inf)
    assert (vx, vy) == (0.0, pytest.approx(math.sqrt(2.0 * 4.0 * 0.02)))
    vx, vy = drive_velocity(0.0, 0.0, 0.0, 1.0, 3.0, 0.0, 3.0, 4.0, 2.0)  # heading +y
    assert vx == pytest.approx(0.0, abs=1e-15) and vy == pytest.approx(-2.0)
    assert drive_velocity(1.0, 1.0, 1.0, 0.0, 1.0, 1.0 + 1e-7, 3.0, 4.0, math.inf) == (0.0, 0.0)
    assert turn_rate(1.0, 0.0, 0.1, 10.0, 8.0) == pytest.approx(0.08)
    assert turn_rate(1.0, 0.0, -3.0, 10.0, 8.0) == -1.0
    assert turn_rate(-1.0, 1e-12, -3.1, 10.0, 8.0) == pytest.approx(8.0 * (2 * math.pi - 3.1
                                                                            - math.pi) / 10.0)


def test_act_batch_is_call_row_by_row():
    """act_batch (ssl_keeper_rows) gives __call__'s actions bit for bit on observations drawn
    over the field, float32 and float64, and for an empty batch."""
    env = soccer_env.parallel_env(blue=1, yellow=1)
    names = env.builder.names_for(0)
    keeper = ScriptedGoalkeeper(env.field, env.ball_spec, env.robot_spec, names)
    rng = np.random.default_rng(12)
    n = 3000
    obs = rng.normal(0.0, 2.0, (n, len(names)))
    h = rng.uniform(-math.pi, math.pi, n)
    obs[:, names.index("self.ax")], obs[:, names.index("self.ay")] = np.cos(h), np.sin(h)
    obs[:, names.index("self.x")] = rng.uniform(-4.8, 0.0, n)
    obs[:, names.index("ball.vx")] *= rng.choice([0.0, 0.01, 1.0, 3.0], n)
    for rows in (obs, obs.astype(np.float32)):
        expected = np.stack([keeper(o) for o in rows])
        got = keeper.act_batch(rows)
        assert got.dtype == np.float32
        np.testing.assert_array_equal(got, expected)
    assert keeper.act_batch(obs[:0]).shape == (0, 6)
