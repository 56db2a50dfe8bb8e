"""Game rules: goals, saves, outs, restarts, kick-offs, and the walls that keep the ball in."""

import math

import gymnasium as gym
import numpy as np
import pytest
from worlds import make_world, park

import soccer_env
from soccer_env.sim.referee import STOP_DISTANCE, classify_exit, place_kickoff
from soccer_env.sim.world import idle_commands


def straight_shot(speed=4.0, y=0.0, chip=False, x=-2.0, delay=0.0):
    return {"speed": (speed, speed), "chip_speed": (speed, speed),
            "chip_probability": 1.0 if chip else 0.0, "wide_probability": 0.0,
            "delay": (delay, delay), "x_range": (x, x), "y_range": (y, y)}


def keeper_env(shots, **kw):
    env = gym.make("soccer_env/Goalkeeper-v0", shots=shots, **kw)
    return env


def play(env, policy, max_steps=600):
    """Run the current episode (already reset) to its end."""
    for _ in range(max_steps):
        obs, reward, term, trunc, info = env.step(policy(env))
        if term or trunc:
            return reward, term, info
    raise AssertionError("episode did not end")


def move_keeper(env, y):
    w = env.unwrapped.world
    x = w.robot_array()[0, 0]
    w.set_robot(0, x, y, 0.0)


def test_shot_into_empty_goal_scores():
    env = keeper_env(straight_shot(speed=4.0, y=0.0))
    env.reset(seed=1)
    env.unwrapped.world.set_robot(0, -3.0, 2.5, 0.0)  # keeper far away from its goal
    for _ in range(300):
        _, reward, term, trunc, info = env.step(np.zeros(6, np.float32))
        if term:
            break
    assert term and not trunc
    assert info["outcome"] == "goal" and reward == -1.0 and info["is_success"] is False


def test_keeper_on_the_line_stops_a_straight_shot():
    env = keeper_env(straight_shot(speed=5.0, y=0.0))
    obs, info = env.reset(seed=2)
    move_keeper(env, info["shot"]["target"][1])  # in the path of the shot
    reward, term, info = play(env, lambda e: np.zeros(6, np.float32))
    assert term and info["outcome"] in ("stopped", "cleared") and reward == 1.0
    assert info["is_success"] and info["keeper_touched"]


def test_wide_shot_is_out_and_counts_as_save():
    shots = straight_shot(speed=5.0)
    shots.update(wide_probability=1.0, wide_margin=0.1)
    env = keeper_env(shots)
    env.reset(seed=3)
    env.unwrapped.world.set_robot(0, -3.0, 2.5, 0.0)
    reward, term, info = play(env, lambda e: np.zeros(6, np.float32))
    assert info["outcome"] == "out" and reward == 1.0


def test_chip_over_the_bar_is_not_a_goal():
    f = soccer_env.presets.field("ssl-div-b")
    w = park(make_world())
    # A chip that is still high when it reaches the goal line.
    w.set_ball(-f.half_length + 0.6, 0.0, -3.0, 0.0, z=0.0, vz=2.5)
    for _ in range(120):
        w.step(idle_commands(1))
        if w.ball_exit is not None:
            break
    kind = classify_exit(w.ball_exit, f, w.ball_spec)
    assert kind.kind == "over_bar" and kind.scorer == -1


def test_chip_that_lands_before_the_line_and_rolls_in_scores():
    f = soccer_env.presets.field("ssl-div-b")
    w = park(make_world())
    w.set_ball(-f.half_length + 2.0, 0.0, -3.0, 0.0, z=0.0, vz=1.5)
    for _ in range(240):
        w.step(idle_commands(1))
        if w.ball_exit is not None:
            break
    kind = classify_exit(w.ball_exit, f, w.ball_spec)
    assert kind.kind == "goal" and kind.scorer == 1  # yellow scores in blue's goal


def test_match_goal_scores_rewards_and_kicks_off():
    env = soccer_env.parallel_env(blue=2, yellow=2)
    env.reset(seed=0)
    w = env.world
    w.set_ball(3.5, 0.1, 5.0, 0.0, sliding=True)  # towards yellow's goal: blue scores
    for _ in range(60):
        obs, rew, term, trunc, info = env.step({a: np.zeros(6) for a in env.agents})
        if info["blue_0"]["event"] == "goal":
            break
    assert info["blue_0"]["score"] == {"blue": 1, "yellow": 0}
    assert rew["blue_0"] == rew["blue_1"] == 1.0 and rew["yellow_0"] == rew["yellow_1"] == -1.0
    assert sum(rew.values()) == 0.0
    np.testing.assert_allclose(info["blue_0"]["truth"]["ball_position"], (0.0, 0.0))
    # Yellow conceded, so yellow kicks off: its kick-off taker is just behind the ball.
    assert obs["yellow_0"][-1] == 1.0 and obs["blue_0"][-1] == -1.0
    assert obs["blue_0"][-3] == 1.0 and obs["yellow_0"][-2] == 1.0  # goals for / against
    poses = info["blue_0"]["truth"]["robot_pose"]
    assert all(p[0] < 0 for n, p in poses.items() if n.startswith("blue"))
    assert all(p[0] > 0 for n, p in poses.items() if n.startswith("yellow"))


@pytest.mark.parametrize("toucher,expected", [("blue_0", 1), ("yellow_0", 0)])
def test_ball_over_touch_line_gives_free_kick_to_other_team(toucher, expected):
    env = soccer_env.parallel_env(blue=1, yellow=1)
    env.reset(seed=0)
    w = env.world
    i = env.possible_agents.index(toucher)
    w.set_robot(i, 1.0, 2.5, math.pi / 2)
    w.set_robot(1 - i, -1.0, -2.0, 0.0)
    w.set_ball(1.0, 2.5 + w.robot_spec.front_distance + w.ball_spec.radius + 1e-3)
    w.last_touch = -1
    cmd = {a: np.zeros(6) for a in env.agents}
    cmd[toucher] = np.array([0.0, 0, 0, 0.5, 0, 0])  # kick it out
    for _ in range(60):
        obs, rew, term, trunc, info = env.step(cmd)
        cmd[toucher] = np.zeros(6)
        if info[toucher]["event"]:
            break
    assert info[toucher]["event"] == "touch"
    assert env.restart_team == expected
    bx, by = info[toucher]["truth"]["ball_position"]
    assert by == pytest.approx(3.0 - 0.2) and abs(bx - 1.0) < 0.1
    for n, (x, y, _) in info[toucher]["truth"]["robot_pose"].items():
        team = 0 if n.startswith("blue") else 1
        if team != expected:
            assert math.hypot(x - bx, y - by) >= STOP_DISTANCE


def test_match_clock_terminates_all_agents():
    env = soccer_env.parallel_env(blue=1, yellow=1, match_duration=0.5)
    env.reset(seed=0)
    steps = 0
    while env.agents:
        obs, rew, term, trunc, info = env.step({a: np.zeros(6) for a in env.agents})
        steps += 1
    assert steps == 30 and all(term.values()) and not any(trunc.values())


def test_max_cycles_truncates():
    env = soccer_env.parallel_env(blue=1, yellow=1, max_cycles=5)
    env.reset(seed=0)
    for _ in range(5):
        obs, rew, term, trunc, info = env.step({a: np.zeros(6) for a in env.agents})
    assert all(trunc.values()) and not any(term.values()) and env.agents == []


@pytest.mark.slow
def test_ball_never_leaves_the_walls():
    """10^5 random steps (drives, flat and chip kicks, dribbling) of a 3 vs 3 match."""
    env = soccer_env.parallel_env(blue=3, yellow=3, match_duration=1e6)
    env.reset(seed=0)
    w = env.world
    f = env.field
    lim_x = f.half_length + f.boundary - w.ball_spec.radius + 1e-3
    lim_y = f.half_width + f.boundary - w.ball_spec.radius + 1e-3
    rng = np.random.default_rng(0)
    acts = rng.uniform(-1, 1, (100_000, 6, 6))
    events = 0
    for k in range(100_000):
        infos = env.step(dict(zip(env.agents, acts[k])))[-1]
        x, y, z = w.ball_array()[0:3]
        assert abs(x) <= lim_x and abs(y) <= lim_y and z >= 0.0, (k, x, y, z)
        events += bool(infos["blue_0"]["event"])
        # Keep play going near the walls: every 2000 steps throw the ball at a random wall.
        if k % 2000 == 1999:
            ang = rng.uniform(-math.pi, math.pi)
            w.set_ball(rng.uniform(-3, 3), rng.uniform(-2, 2), 6.5 * math.cos(ang),
                       6.5 * math.sin(ang), sliding=True)
    assert events > 20  # the ball did reach the lines and walls many times


@pytest.mark.parametrize("field", ["ssl-2012", "ssl-div-b", "ssl-div-a", "humanoid-2012"])
def test_kickoff_formations_are_legal(field):
    """11 vs 11 kick-offs: each team in its half, no overlapping robots, the kick-off taker
    next to the ball and the other team outside the centre circle."""
    env = soccer_env.parallel_env(blue=11, yellow=11, field=field)
    w, f = env.world, env.field
    r = w.robot_spec.radius
    for seed in range(50):
        team = seed % 2
        p = place_kickoff(w, team, np.random.default_rng(seed), 0.1)
        gaps = np.hypot(*(p[:, None, :2] - p[None, :, :2]).transpose(2, 0, 1))
        assert (gaps + 9 * np.eye(22)).min() >= 2 * r
        assert (p[:11, 0] < 0).all() and (p[11:, 0] > 0).all()
        assert (np.abs(p[:, 0]) <= f.half_length).all() and (np.abs(p[:, 1]) <= f.half_width).all()
        dist = np.hypot(p[:, 0], p[:, 1])
        kicking = slice(0, 11) if team == 0 else slice(11, 22)
        other = slice(11, 22) if team == 0 else slice(0, 11)
        assert dist[kicking].min() < 0.2
        assert dist[other].min() >= f.center_circle_radius
