"""The scripted SSL team's ways round the goals and out of a placement's corridor, and its
keeper under the game flow."""

from __future__ import annotations

import numpy as np
import pytest

import soccer_env
from agents.scripted import ScriptedTeam
from agents.scripted.geometry import TeamGeometry
from agents.scripted.goals import GoalWalls, segment_gap

FIELD = soccer_env.presets.field("ssl-div-b")
ROBOT = soccer_env.presets.robot("ssl")
BALL = soccer_env.presets.ball("ssl")
HX = FIELD.half_length


def follow(walls, start, target, legs=6):
    """The points a robot passes driving from ``start`` to ``target`` by the route."""
    points = [start]
    while points[-1] != target and len(points) <= legs:
        points.append(tuple(walls.route(*points[-1], *target)))
    return points


def test_segment_gap_is_zero_for_crossing_segments_and_the_end_distance_otherwise():
    assert segment_gap((0, 0), (1, 1), (0, 1), (1, 0)) == 0.0
    assert segment_gap((0, 0), (1, 0), (2, 0), (3, 0)) == pytest.approx(1.0)
    assert segment_gap((0, 0), (1, 0), (0.5, 0.3), (0.5, 2.0)) == pytest.approx(0.3)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_route_goes_round_a_goal_through_the_field(sign):
    """Beside a goal behind its line, to the other side of it: in front of the posts, each
    leg clear of every goal wall, ending at the target."""
    walls = GoalWalls(FIELD, ROBOT.radius)
    start, target = (sign * (HX + 0.17), -0.75), (sign * (HX + 0.17), 1.3)
    assert not walls.clear(start, target)
    points = follow(walls, start, target)
    assert points[-1] == target
    assert 3 <= len(points) <= 4
    for a, b in zip(points, points[1:]):
        assert walls.clear(a, b, walls.radius + walls.half_wall)
    assert all(abs(x) < HX for x, _ in points[1:-1])  # the way round runs through the field


def test_route_leaves_a_goal_through_its_mouth():
    walls = GoalWalls(FIELD, ROBOT.radius)
    start, target = (HX + 0.1, 0.4), (3.4, 2.7)  # in a goal's corner, out to the touch line
    points = follow(walls, start, target)
    assert points[-1] == target
    assert abs(points[1][1]) < 0.5 * FIELD.goal_width  # first out of the mouth
    for a, b in zip(points[1:], points[2:]):
        assert walls.clear(a, b)


def test_route_is_the_target_when_the_way_is_clear():
    walls = GoalWalls(FIELD, ROBOT.radius)
    assert walls.route(0.0, 0.0, 2.0, 1.0) == (2.0, 1.0)
    assert walls.free(0.0, 0.0) and not walls.free(HX + 0.05, 0.5 * FIELD.goal_width)


def test_leave_segment_finds_a_way_out_between_a_wall_and_the_corridor():
    """A robot in the run-off area beside a ball on the touch line, inside the corridor of the
    opponents' placement: its way out lies inside the walls and clear of the corridor."""
    geo = TeamGeometry(FIELD, BALL, ROBOT)
    ball, target, dist = (-3.26, -3.04), (-3.25, -2.8), 0.7
    robot = (-3.55, -3.18)
    sideways = geo.off_segment(*robot, *ball, *target, dist)
    assert abs(sideways[1]) > geo.lim_y  # the plain rule drives into the wall
    x, y = geo.leave_segment(*robot, *ball, *target, dist)
    assert abs(x) <= geo.lim_x and abs(y) <= geo.lim_y
    assert geo.off_segment(x, y, *ball, *target, dist) == (x, y)
    # Outside the corridor already: stays.
    assert geo.leave_segment(0.0, 0.0, *ball, *target, dist) == (0.0, 0.0)


def test_keeper_catches_instead_of_kicking_under_the_game_flow():
    """With the game flow the guarding keeper never kicks and keeps its dribbler on (without
    it, it plays the goalkeeper's action: test_team.py)."""
    env = soccer_env.parallel_env(blue=2, yellow=2, match_duration=30.0, game=True)
    obs, _ = env.reset(seed=3)
    teams = [ScriptedTeam.for_env(env, c) for c in ("blue", "yellow")]
    guarded = 0
    while env.agents and env.world.time < 25.0:
        act = {**teams[0](obs), **teams[1](obs)}
        bx = float(env.world.ball_array()[0])
        if env.game.in_play and bx > -HX + FIELD.defense_depth + 0.3:  # blue's keeper guards
            guarded += 1
            assert act["blue_0"][3] == 0.0 and act["blue_0"][5] == 1.0
            one = teams[0].open_play.keeper_guard(list(obs["blue_0"]))
            np.testing.assert_allclose(one, act["blue_0"], atol=1e-6)
        obs, *_ = env.step(act)
    assert guarded > 100


@pytest.mark.parametrize("x,y,heading,armed", [
    (-0.12, 0.0, 0.0, True),    # lined up
    (-0.12, 0.06, 0.0, True),   # believed off by more than half the kicker's width
    (-0.13, 0.0, 0.2, True),    # facing 0.2 rad off the kick's direction
    (-0.30, 0.0, 0.0, True),    # lined up, further back
    (0.12, 0.0, np.pi, False),  # in front of the ball
    (-0.12, 0.15, 0.0, False),  # beside the kicker
    (-0.12, 0.0, 0.6, False),   # facing away from the kick's direction
])
def test_the_kicker_of_a_restart_is_armed_whenever_the_ball_is_in_front_of_it(x, y, heading,
                                                                             armed):
    """A robot that sees its own pose a few centimetres off through late, noisy vision and
    touches the ball kicks it, rather than pushing it into play and being barred from it."""
    from agents.scripted.view import Frame

    env = soccer_env.parallel_env(blue=2, yellow=2, game=True)
    env.reset(seed=0)
    team = ScriptedTeam.for_env(env, "blue")
    c, s = np.cos(heading), np.sin(heading)
    dx, dy = -x, -y  # the ball at the centre, in the world frame from the robot
    f = Frame(x, y, c, s, 0.0, 0.0, 0.0, 0.0, c * dx + s * dy, -s * dx + c * dy)
    action = team.restarts.take_kick(1, f, [-4.3, x], [0.0, y], [])
    assert (action[3] > 0.0) == armed
    env.close()
