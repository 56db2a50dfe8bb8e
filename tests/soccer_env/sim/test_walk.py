"""The humanoid walk engine in the physics: speed and acceleration limits against closed
forms, the timed kick, dives and falls, get-up time, odometry, sway, head servos, mixed
worlds."""

from __future__ import annotations

import math

import numpy as np
import pytest

from soccer_env import presets
from soccer_env.sim.commands import HumanoidRobot
from soccer_env.sim.walk import DIVE
from soccer_env.sim.world import World

H = presets.robot("humanoid")
FIELD = presets.field("humanoid-kid")
BALL = presets.ball(FIELD.ball)
DT = 1.0 / 60.0


def world(n_blue: int = 1, n_yellow: int = 0, poses=None, ball=(3.0, 2.0), seed=0,
          robot=H) -> World:
    w = World(FIELD, BALL, robot, n_blue, n_yellow, DT)
    if poses is None:
        poses = [[-2.0 + 1.0 * i, 0.0, 0.0] for i in range(n_blue + n_yellow)]
    w.reset(np.array(poses, dtype=float), ball, np.random.default_rng(seed))
    return w


def command(n: int, **cols: float) -> np.ndarray:
    c = np.zeros((n, 6))
    for k, v in cols.items():
        c[:, ("vx", "vy", "omega", "motion", "pan", "tilt").index(k)] = v
    return c


def test_walks_at_the_forward_limit_after_the_acceleration_ramp():
    w = world()
    steps = 240
    for _ in range(steps):
        w.step(command(1, vx=5.0))  # asks for far more than the robot can walk
    v, a = H.max_forward_speed, H.max_acceleration
    t = steps * DT
    expected = v * v / (2 * a) + v * (t - v / a)  # ramp, then cruise
    assert w.robot_array()[0, 3] == pytest.approx(v, rel=1e-3)
    assert w.robot_array()[0, 0] - (-2.0) == pytest.approx(expected, abs=0.02)


def test_backward_sideways_and_turn_limits_and_the_speed_ellipsoid():
    for cols, index, limit in (({"vx": -1.0}, 3, H.max_backward_speed),
                               ({"vy": 1.0}, 4, H.max_sideways_speed),
                               ({"omega": 9.0}, 5, H.max_turn_speed)):
        w = world()
        for _ in range(240):
            w.step(command(1, **cols))
        assert abs(w.robot_array()[0, index]) == pytest.approx(limit, rel=0.02), cols
    # Forward and sideways at full speed together: scaled onto the ellipsoid.
    w = world()
    for _ in range(300):
        w.step(command(1, vx=H.max_forward_speed, vy=H.max_sideways_speed))
    vx, vy = w.robot_array()[0, 3:5]
    assert (vx / H.max_forward_speed) ** 2 + (vy / H.max_sideways_speed) ** 2 == \
        pytest.approx(1.0, abs=0.02)
    assert vx / H.max_forward_speed == pytest.approx(vy / H.max_sideways_speed, rel=0.02)


def test_action_map_scales_per_axis_and_maps_the_head_and_dive():
    model = HumanoidRobot(H)
    c = model.commands(np.array([[1.0, -1.0, 0.5, 0.0, 1.0, -1.0],
                                 [-1.0, 0.0, 0.0, -0.9, -1.0, 1.0],
                                 [0.0, 0.0, 0.0, 0.4, 0.0, 0.0]]))
    assert c[0, 0:3] == pytest.approx([H.max_forward_speed, -H.max_sideways_speed,
                                       0.5 * H.max_turn_speed])
    assert c[0, 4:6] == pytest.approx([H.head_pan_limit, H.head_tilt_min])
    assert c[1, 0] == pytest.approx(-H.max_backward_speed)
    assert c[1, 3] == DIVE
    assert c[1, 4:6] == pytest.approx([-H.head_pan_limit, H.head_tilt_max])
    assert c[2, 3] == pytest.approx(0.4 * H.kick_max_speed)
    pan, tilt = 0.3, 0.5
    a4, a5 = model.action_for_head(pan, tilt)
    assert model.commands(np.array([[0, 0, 0, 0, a4, a5]]))[0, 4:6] == pytest.approx([pan, tilt])


def ball_at_foot(robot_x: float = -2.0) -> tuple[float, float]:
    return robot_x + H.radius + BALL.radius + 0.03, 0.02


def test_kick_fires_at_the_strike_time_with_the_ball_at_the_foot():
    w = world(ball=ball_at_foot())
    w.step(command(1, motion=2.0))
    fired_after = None
    for k in range(2, 120):
        w.step(command(1))
        if math.hypot(*w.ball_array()[3:5]) > 0.0:
            fired_after = k
            break
    assert fired_after == pytest.approx(H.kick_fire_time / DT, abs=1)
    vx, vy = w.ball_array()[3:5]
    assert math.hypot(vx, vy) == pytest.approx(2.0, abs=1e-9)  # launched at the step's end
    assert abs(math.atan2(vy, vx)) < 4 * H.kick_direction_sigma
    assert w.humanoid_state()["blue_0"]["kicks"] == 1


def test_kick_misses_a_ball_that_is_not_at_the_foot_and_the_robot_stands_while_kicking():
    w = world(ball=(-2.0 + 0.6, 0.0))  # half a metre ahead
    for _ in range(5):
        w.step(command(1, vx=1.0))
    w.step(command(1, vx=1.0, motion=1.0))
    kicking = []
    for _ in range(round(H.kick_duration / DT)):
        w.step(command(1, vx=1.0))
        kicking.append(w.humanoid_state()["blue_0"]["kicking"])
    assert all(kicking[:-2]) and not kicking[-1]
    assert w.humanoid_state()["blue_0"]["kicks"] == 0
    assert math.hypot(*w.ball_array()[3:5]) == 0.0
    # While kicking the gait came to a stop, then walks again.
    state = w.humanoid_state()["blue_0"]
    assert not state["kicking"]


def test_head_servos_turn_at_the_servo_speed_within_the_limits():
    w = world()
    w.step(command(1, pan=2.0 * H.head_pan_limit, tilt=-3.0))
    st = w.humanoid_state()["blue_0"]
    assert st["pan"] == pytest.approx(H.head_speed * DT)
    assert st["tilt"] == pytest.approx(-H.head_speed * DT)
    for _ in range(200):
        w.step(command(1, pan=2.0 * H.head_pan_limit, tilt=-3.0))
    st = w.humanoid_state()["blue_0"]
    assert st["pan"] == pytest.approx(H.head_pan_limit)
    assert st["tilt"] == pytest.approx(H.head_tilt_min)


def test_sway_only_while_walking():
    w = world()
    for _ in range(30):
        w.step(command(1))
    assert w.humanoid_state()["blue_0"]["sway"] == (0.0, 0.0)
    sways = []
    for _ in range(120):
        w.step(command(1, vx=1.0))
        sways.append(w.humanoid_state()["blue_0"]["sway"])
    sways = np.array(sways)
    assert np.abs(sways[:, 0]).max() == pytest.approx(H.sway_pan, rel=0.1)
    assert np.abs(sways[:, 1]).max() == pytest.approx(H.sway_tilt, rel=0.1)


def test_odometry_tracks_the_walk_with_errors_that_grow_in_turns():
    def run(seed: int, omega: float) -> tuple[float, float]:
        w = world(seed=seed)
        start = w.robot_array()[0, 0:3].copy()
        pose = start.copy()
        for _ in range(300):
            w.step(command(1, vx=1.0, omega=omega))
            dx, dy, dth = w.humanoid_state()["blue_0"]["odometry"]
            th = pose[2] + 0.5 * dth
            pose += (math.cos(th) * dx - math.sin(th) * dy, math.sin(th) * dx + math.cos(th) * dy,
                     dth)
        true = w.robot_array()[0, 0:3]
        return (math.hypot(*(pose[0:2] - true[0:2])),
                abs(math.remainder(pose[2] - true[2], 2 * math.pi)))
    straight = np.array([run(s, 0.0) for s in range(12)])
    turning = np.array([run(s, 0.8) for s in range(12)])
    walked = H.max_forward_speed * 5.0
    assert np.median(straight[:, 0]) < 0.15 * walked  # a few per cent of the distance
    assert np.median(straight[:, 0]) > 0.0  # but not exact
    assert np.mean(turning[:, 1]) > 3 * np.mean(straight[:, 1])  # turns slip most


def test_hard_collisions_fell_robots_gentle_ones_do_not():
    # Two robots walking into each other at full speed: 0.6 m/s closing speed.
    falls = 0
    for seed in range(5):
        w = world(1, 1, poses=[[-1.0, 0.0, 0.0], [1.0, 0.0, math.pi]], seed=seed)
        for _ in range(400):
            w.step(command(2, vx=1.0))
        st = w.humanoid_state()
        falls += st["blue_0"]["falls"] + st["yellow_0"]["falls"]
    assert falls >= 5
    # One robot creeping into a standing one at 0.05 m/s never falls.
    w = world(1, 1, poses=[[-0.3, 0.0, 0.0], [0.0, 0.0, math.pi]])
    for _ in range(600):
        w.step(np.array([[0.05, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]))
    st = w.humanoid_state()
    assert st["blue_0"]["falls"] == st["yellow_0"]["falls"] == 0


def test_fall_probability_grows_with_the_impact():
    w = world()
    p = [w.walk.fall_probability(0, v) for v in np.linspace(0.0, 1.0, 21)]
    assert p[0] == 0.0 and p[-1] == 1.0
    assert all(b >= a for a, b in zip(p, p[1:]))
    assert w.walk.fall_probability(0, 0.5 * (H.fall_speed_min + H.fall_speed_certain)) == \
        pytest.approx(0.5)


def test_a_fallen_robot_neither_acts_nor_sees_until_it_has_got_up():
    w = world()
    w.walk.fall(0, w.time)
    down = round(H.get_up_time / DT)
    for _ in range(down - 2):
        w.step(command(1, vx=1.0, pan=1.0))
        st = w.humanoid_state()["blue_0"]
        assert st["fallen"] and st["odometry"] == (0.0, 0.0, 0.0)
    assert abs(w.robot_array()[0, 0] - (-2.0)) < 0.01
    for _ in range(60):
        w.step(command(1, vx=1.0))
    assert not w.humanoid_state()["blue_0"]["fallen"]
    assert w.robot_array()[0, 3] > 0.1  # walking again


def test_a_dive_lays_the_body_across_the_goal_and_blocks_a_ball():
    # Keeper at the goal line, ball rolling at its left side 0.35 m away.
    x0 = -FIELD.half_length + 0.2
    w = world(poses=[[x0, 0.0, 0.0]], ball=(x0 + 1.5, 0.35))
    w.step(command(1, vy=1.0, motion=DIVE))
    assert w.humanoid_state()["blue_0"]["fallen"]
    for _ in range(round(H.fall_time / DT) + 1):
        w.step(command(1))
    w.set_ball(x0 + 1.5, 0.35, -2.0, 0.0)
    for _ in range(90):
        w.step(command(1))
    assert w.ball_array()[0] > x0  # the lying body stopped it in front of the goal line
    assert w.ball_exit is None


def test_the_same_seed_gives_the_same_falls_and_odometry():
    def run(seed):
        w = world(1, 1, poses=[[-1.0, 0.0, 0.0], [1.0, 0.0, math.pi]], seed=seed)
        out = []
        for _ in range(500):
            w.step(command(2, vx=1.0, omega=0.2))
            out.append(w.robot_array().copy())
        return np.array(out), w.humanoid_state()
    a, sa = run(3)
    b, sb = run(3)
    np.testing.assert_array_equal(a, b)
    assert sa == sb


def test_mixed_world_of_ssl_and_humanoid_robots():
    ssl = presets.robot("ssl")
    w = World(FIELD, BALL, [ssl, H], 1, 1, DT)
    w.reset(np.array([[-1.0, 0.0, 0.0], [1.0, 2.0, math.pi]]), (0.0, -2.0))
    for _ in range(120):
        w.step(np.array([[1.0, 0, 0, 0, 0, 0], [1.0, 0, 0, 0, 0, 0]]))
    r = w.robot_array()
    assert r[0, 3] == pytest.approx(1.0, abs=0.01)  # the SSL robot drives at 1 m/s
    assert abs(r[1, 3]) == pytest.approx(H.max_forward_speed, rel=0.02)  # walks at its limit
    assert list(w.humanoid_state()) == ["yellow_0"]


def test_bad_humanoid_specs_are_rejected():
    with pytest.raises(ValueError, match="fall_speed_certain"):
        presets.robot("humanoid", fall_speed_certain=0.1)
    with pytest.raises(ValueError, match="kick_fire_time"):
        presets.robot("humanoid", kick_fire_time=2.0)
    with pytest.raises(ValueError, match=r"robot must be one robot spec or 2"):
        World(FIELD, BALL, [H], 1, 1, DT)
