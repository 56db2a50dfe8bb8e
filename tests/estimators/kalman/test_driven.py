"""A team's own robots predicted through their commands (estimators.CommandHistory) against the
drive's closed form, the constant-velocity rows it leaves alone, and bad input."""

import math

import numpy as np
import pytest

from estimators import CommandHistory, RobotTracker

LIMITS = (3.0, 3.0, 10.0, 50.0)  # max speed, acceleration, turn rate, angular acceleration
DT = 0.02


def tracker_at_rest(n=3, poses=None):
    """Robots seen once at t = 0 (at rest: a first detection starts with zero velocity)."""
    tracker = RobotTracker(n, sigma_xy=0.001, sigma_theta=0.001)
    poses = np.zeros((n, 3)) if poses is None else np.asarray(poses, dtype=float)
    tracker.update(0.0, poses, np.arange(n))
    return tracker


def commanded(robots, command, until, origin=0.0, start=0.0):
    """A history of one command repeated every DT from ``start`` to ``until``."""
    history = CommandHistory(robots, DT, 1000, LIMITS, substep=1e-4)
    history.reset(origin)
    t = start
    while t < until - 1e-12:
        history.record(t, np.tile(command, (len(robots), 1)))
        t += DT
    return history


def test_a_step_command_from_rest_follows_the_acceleration_limit():
    """1 m/s forward from rest at 3 m/s^2: the speed ramps for 1/3 s, then holds, so
    x(t) = a t^2 / 2 while ramping and 1/6 + (t - 1/3) after (closed form)."""
    tracker = tracker_at_rest()
    history = commanded([0], (1.0, 0.0, 0.0), 1.0)
    for t in (0.2, 0.5, 0.8):
        est = tracker.estimate_driven(t, history)
        x = 1.5 * t * t if t < 1 / 3 else 1 / 6 + (t - 1 / 3)
        assert est[0, 0] == pytest.approx(x, abs=1e-3)
        assert abs(est[0, 1]) < 1e-12 and est[0, 3] == pytest.approx(min(3 * t, 1.0), abs=1e-3)


def test_a_body_frame_command_turns_with_the_robot():
    """Sideways (body-frame vy) at 0.5 m/s while turning at 2 rad/s, from rest at heading
    pi/2: the heading follows the turn rate (ramped at 50 rad/s^2) and the speed stays the
    command's, so the robot moves on a circle of radius v / omega."""
    tracker = tracker_at_rest(poses=[[0.0, 0.0, math.pi / 2]] * 3)
    history = commanded([0], (0.0, 0.5, 2.0), 2.0)
    est = tracker.estimate_driven(1.0, history)
    theta = math.pi / 2 + 2.0 * 1.0 - 2.0 * (2.0 / 50.0) / 2  # the ramp's lag
    assert est[0, 2] == pytest.approx(math.remainder(theta, 2 * math.pi), abs=1e-3)
    assert est[0, 5] == pytest.approx(2.0)
    assert math.hypot(est[0, 3], est[0, 4]) == pytest.approx(0.5, abs=1e-3)
    # Sideways to the left of a robot turning left: towards the circle's centre, so the
    # robot stays within 2 v / omega of where it started.
    assert math.hypot(est[0, 0], est[0, 1]) < 2 * 0.5 / 2.0 + 1e-3


def test_commands_are_capped_like_the_robot_and_only_the_team_is_driven():
    """A command above the speed limit drives at the limit; the other robots keep the
    constant-velocity rows of :meth:`RobotTracker.estimate` and unseen ones stay zeros."""
    tracker = RobotTracker(4, sigma_xy=0.001, sigma_theta=0.001)
    tracker.update(0.0, np.zeros((3, 3)), [0, 1, 2])
    tracker.update(0.1, [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.05, 0.0]], [0, 1, 2])
    history = CommandHistory([0, 1], DT, 1000, LIMITS)
    history.reset(0.0)
    for k in range(150):
        history.record(0.1 + k * DT, np.array([[5.0, 0.0, 0.0], [0.0, 0.0, 50.0]]))
    plain = tracker.estimate(3.0)
    est = tracker.estimate_driven(3.0, history)
    assert math.hypot(est[0, 3], est[0, 4]) == pytest.approx(3.0, abs=1e-6)
    assert est[1, 5] == pytest.approx(10.0, abs=1e-6)
    np.testing.assert_array_equal(est[2:], plain[2:])
    assert not est[3].any()


def test_before_the_first_command_the_robots_stand_still():
    """From ``origin`` to the first command the robots get none (they stand still): a robot
    moving at 1 m/s at its latest detection brakes at the acceleration limit."""
    tracker = RobotTracker(1, sigma_xy=1e-4, sigma_theta=1e-4, sigma_v0=0.0)
    for k in range(20):
        tracker.update(0.01 * k, [[0.01 * k, 0.0, 0.0]], [0])
    history = CommandHistory([0], DT, 50, LIMITS, substep=1e-4)
    history.reset(0.0)
    est = tracker.estimate_driven(0.19 + 0.5, history)
    v0 = tracker.v[0, 0]
    assert v0 > 0.9
    stop = v0 / 3.0  # braking time at 3 m/s^2
    assert est[0, 3] == 0.0
    assert est[0, 0] == pytest.approx(tracker.p[0, 0] + v0 * stop / 2, abs=2e-3)
    # No history before origin (a robot updated before it): the constant velocity.
    history.reset(1.0)
    np.testing.assert_array_equal(tracker.estimate_driven(1.2, history), tracker.estimate(1.2))


def test_the_history_keeps_the_newest_commands():
    history = CommandHistory([0], DT, 3, LIMITS)
    history.reset(0.0)
    for k in range(5):
        history.record(k * DT, np.array([[k, 0.0, 0.0, 1.0, 0.0, 0.0]]))
    tracker = tracker_at_rest(1)
    # Commands 2, 3, 4 kept (the oldest dropped): from t = 0 to 2 DT the robots stand still.
    still = tracker.estimate_driven(2 * DT, history)
    assert still[0, 0] == 0.0 and still[0, 3] == 0.0


@pytest.mark.parametrize("kwargs, match", [
    ({"keep": 0}, "keep"),
    ({"dt": 0.0}, "dt"),
    ({"dt": math.nan}, "dt"),
    ({"limits": (3.0, -1.0, 10.0, 50.0)}, "max_acceleration"),
    ({"limits": (3.0, 3.0, 10.0)}, "limits"),
    ({"substep": math.inf}, "substep"),
])
def test_bad_histories_are_refused(kwargs, match):
    args = {"robots": [0], "dt": DT, "keep": 10, "limits": LIMITS, **kwargs}
    with pytest.raises(ValueError, match=match):
        CommandHistory(**args)
