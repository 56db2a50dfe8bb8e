"""Physics against closed-form expectations."""

import math

import numpy as np
import pymunk
import pytest
from worlds import make_world, park, run

from soccer_env import presets
from soccer_env.presets import GRAVITY
from soccer_env.sim.world import World, idle_commands


def ball_track(world, steps, commands=None):
    cmd = idle_commands(world.n_robots) if commands is None else commands
    out = []
    for _ in range(steps):
        world.step(cmd)
        out.append((world.time, *world.ball_array()))
    return np.array(out)  # t, x, y, z, vx, vy, vz


@pytest.mark.parametrize("field", ["ssl-div-b", "ssl-2012"])
def test_rolling_deceleration_matches_preset(field):
    w = park(make_world(field=field))
    a = w.ball_spec.rolling_deceleration
    v0 = 1.5
    w.set_ball(-3.0, 0.5, v0, 0.0)  # rolling (not sliding)
    track = ball_track(w, int(1.2 * v0 / a / w.control_dt))
    t, x, vx = track[:, 0], track[:, 1], track[:, 4]
    moving = vx > 0.05
    slope = np.polyfit(t[moving], vx[moving], 1)[0]
    assert -slope == pytest.approx(a, rel=0.05)
    # It stops where v0^2 / (2 a) says, and never reverses.
    assert x[-1] - (-3.0) == pytest.approx(v0**2 / (2 * a), rel=0.05)
    assert vx.min() >= 0.0 and vx[-1] == 0.0
    assert np.all(np.diff(x) >= -1e-12)


def test_two_phase_deceleration_after_a_kick(world):
    bs = world.ball_spec
    v0 = 3.0
    world.set_ball(-4.0, 0.5, v0, 0.0, sliding=True)
    assert world.ball_sliding
    track = ball_track(world, 180)
    assert not world.ball_sliding
    t, speed = track[:, 0], np.hypot(track[:, 4], track[:, 5])
    slide = speed > bs.k_switch * v0 + 0.05
    roll = (speed < bs.k_switch * v0 - 0.05) & (speed > 0.1)
    assert -np.polyfit(t[slide], speed[slide], 1)[0] == pytest.approx(bs.sliding_deceleration,
                                                                      rel=0.05)
    assert -np.polyfit(t[roll], speed[roll], 1)[0] == pytest.approx(bs.rolling_deceleration,
                                                                     rel=0.05)


def ball_at_mouth(world, i=0, offset=0.0):
    """Place the ball touching robot i's flat front, ``offset`` sideways."""
    x, y, th = world.robot_array()[i, 0:3]
    d = world.robot_spec.front_distance + world.ball_spec.radius + 1e-4
    c, s = math.cos(th), math.sin(th)
    world.set_ball(x + c * d - s * offset, y + s * d + c * offset)


def kick_cmd(n, power, chip=False, i=0):
    cmd = idle_commands(n)
    cmd[i, 3] = power
    cmd[i, 4] = 1.0 if chip else 0.0
    return cmd


@pytest.mark.parametrize("speed", [1.0, 3.0, 5.0, 6.5])
def test_kick_speed_matches_command(speed):
    w = park(make_world(control_dt=1e-3, physics_dt=1e-3), poses=[(0.0, 0.0, 0.7)])
    ball_at_mouth(w)
    w.step(kick_cmd(1, speed))
    vx, vy = w.ball_array()[3:5]
    assert math.hypot(vx, vy) == pytest.approx(speed, rel=0.02)
    assert math.atan2(vy, vx) == pytest.approx(0.7, abs=1e-6)
    assert w.kicked[0]


def test_kick_speed_is_capped():
    w = park(make_world(control_dt=1e-3, physics_dt=1e-3), poses=[(0.0, 0.0, 0.0)])
    assert w.robot_spec.kicker_max_speed > w.robot_spec.kick_speed_cap == 6.5
    ball_at_mouth(w)
    w.step(kick_cmd(1, w.robot_spec.kicker_max_speed))
    assert math.hypot(*w.ball_array()[3:5]) == pytest.approx(6.5, rel=0.02)


def test_configured_cap_applies():
    w = park(make_world(control_dt=1e-3, physics_dt=1e-3, kick_speed_cap=4.0),
             poses=[(0.0, 0.0, 0.0)])
    ball_at_mouth(w)
    w.step(kick_cmd(1, 8.0))
    assert math.hypot(*w.ball_array()[3:5]) == pytest.approx(4.0, rel=0.02)


def test_kick_only_from_the_front_within_kicker_width():
    w = park(make_world(control_dt=1e-3, physics_dt=1e-3), poses=[(0.0, 0.0, 0.0)])
    half = w.robot_spec.kicker_width / 2
    ball_at_mouth(w, offset=half + 0.005)  # touching the front, outside the kicker
    w.step(kick_cmd(1, 5.0))
    assert math.hypot(*w.ball_array()[3:5]) < 0.5 and not w.kicked[0]
    # Ball touching the robot's back: no kick either.
    r = w.robot_spec.radius + w.ball_spec.radius + 1e-4
    w.set_ball(-r, 0.0)
    run(w, 5, kick_cmd(1, 5.0))
    assert math.hypot(*w.ball_array()[3:5]) < 0.5 and not any(w.kicked)


def test_kicker_cooldown():
    w = park(make_world(control_dt=1e-3, physics_dt=1e-3), poses=[(0.0, 0.0, 0.0)])
    ball_at_mouth(w)
    w.step(kick_cmd(1, 2.0))
    assert w.kicked[0]
    ball_at_mouth(w)
    w.step(kick_cmd(1, 2.0))
    assert not w.kicked[0]  # still recharging
    run(w, int(w.robot_spec.kick_cooldown / w.control_dt))
    ball_at_mouth(w)
    w.step(kick_cmd(1, 2.0))
    assert w.kicked[0]


def test_chip_flight_time_and_distance():
    w = park(make_world(control_dt=1e-3, physics_dt=1e-3), poses=[(-3.0, 0.0, 0.0)])
    rs = w.robot_spec
    ball_at_mouth(w)
    x0 = w.ball_array()[0]
    power = 4.0
    w.step(kick_cmd(1, power, chip=True))
    t0 = w.time - w.control_dt  # the kick fired in the first substep of that step
    v = min(power, rs.kick_speed_cap)
    vz, vxy = v * math.sin(rs.chip_angle), v * math.cos(rs.chip_angle)
    flight = 2 * vz / GRAVITY
    heights = []
    while True:
        w.step(idle_commands(1))
        heights.append(w.ball_height)
        if w.ball_height == 0.0:
            break
    assert max(heights) == pytest.approx(vz**2 / (2 * GRAVITY), rel=0.02)
    assert w.time - t0 == pytest.approx(flight, rel=0.01)
    assert w.ball_array()[0] - x0 == pytest.approx(vxy * flight, rel=0.01)
    # First bounce of the fixed-loss model: vertical speed times damping_z, horizontal speed
    # times damping_xy_first, so the next apex is damping_z^2 times as high.
    bs = w.ball_spec
    assert w.ball_array()[3] == pytest.approx(vxy * bs.chip_damping_xy_first, rel=0.01)
    second = []
    while w.ball_airborne and len(second) < 2000:
        w.step(idle_commands(1))
        second.append(w.ball_height)
    assert max(second) == pytest.approx(bs.chip_damping_z**2 * vz**2 / (2 * GRAVITY), rel=0.05)


def test_chip_passes_over_robots_but_flat_kick_does_not():
    poses = [(-3.0, 0.0, 0.0), (-2.2, 0.0, math.pi)]  # a blocker 0.8 m ahead
    for chip, passes in ((True, True), (False, False)):
        w = park(make_world(n_blue=1, n_yellow=1), poses=poses)
        ball_at_mouth(w)
        run(w, 1, kick_cmd(2, 5.0, chip=chip))
        run(w, 60)
        beyond = w.ball_array()[0] > -2.2
        assert beyond == passes


@pytest.mark.parametrize("robot", ["ssl", "ssl-2012"])
def test_robot_speed_and_acceleration_limits(robot):
    w = park(make_world(robot=robot), poses=[(-3.0, 0.0, 0.0)])
    rs = w.robot_spec
    cmd = idle_commands(1)
    cmd[0, 0:2] = (rs.max_speed, rs.max_speed)  # diagonal: norm must be capped
    speeds = []
    for _ in range(int(1.5 * rs.max_speed / rs.max_acceleration / w.control_dt)):
        w.step(cmd)
        speeds.append(math.hypot(*w.robot_array()[0, 3:5]))
    speeds = np.array(speeds)
    accel = np.diff(np.concatenate([[0.0], speeds])) / w.control_dt
    assert accel.max() <= rs.max_acceleration * 1.02
    assert accel[:5].mean() == pytest.approx(rs.max_acceleration, rel=0.02)
    assert speeds.max() <= rs.max_speed * 1.01
    assert speeds[-1] == pytest.approx(rs.max_speed, rel=0.01)
    vx, vy = w.robot_array()[0, 3:5]
    assert math.atan2(vy, vx) == pytest.approx(math.pi / 4, abs=0.01)


def test_turn_rate_and_angular_acceleration_limits():
    w = park(make_world(), poses=[(-3.0, 0.0, 0.0)])
    rs = w.robot_spec
    cmd = idle_commands(1)
    cmd[0, 2] = 2 * rs.max_angular_speed
    omegas = []
    for _ in range(120):
        w.step(cmd)
        omegas.append(w.robot_array()[0, 5])
        assert -math.pi <= w.robot_array()[0, 2] <= math.pi
    omegas = np.array(omegas)
    alpha = np.diff(np.concatenate([[0.0], omegas])) / w.control_dt
    assert alpha.max() <= rs.max_angular_acceleration * 1.02
    assert omegas[-1] == pytest.approx(rs.max_angular_speed, rel=0.01)


def test_body_frame_command_moves_sideways():
    w = park(make_world(), poses=[(-3.0, 0.0, math.pi / 2)])  # facing +y
    cmd = idle_commands(1)
    cmd[0, 0] = 1.0  # forward
    run(w, 60, cmd)
    x, y = w.robot_array()[0, 0:2]
    assert y > 0.3 and abs(x + 3.0) < 0.01


@pytest.mark.parametrize("speed", [1.0, 3.0])
def test_ball_restitution_against_wall(speed):
    w = park(make_world())
    e = w.field.wall_restitution  # the ball's own restitution is 1
    wall_y = w.field.half_width + w.field.boundary
    w.set_ball(0.0, wall_y - 0.3, 0.0, speed)
    before = after = None
    for _ in range(60):
        w.step(idle_commands(1))
        vy = w.ball_array()[4]
        if vy > 0:
            before = vy
        elif before is not None:
            after = -vy
            break
    assert after == pytest.approx(e * before, rel=0.1)


def test_ball_bounces_off_robot_with_robot_restitution():
    w = park(make_world(), poses=[(0.0, 0.0, math.pi)])  # back of the robot faces +x
    w.set_ball(1.0, 0.0, -2.0, 0.0)
    vx = [w.ball_array()[3]]
    for _ in range(60):
        w.step(idle_commands(1))
        vx.append(w.ball_array()[3])
    vx = np.array(vx)
    before, after = vx[vx < 0][-1], vx.max()
    # A 46 g ball against a 2.5 kg robot held by its motors: nearly a fixed wall.
    assert after == pytest.approx(-w.robot_spec.restitution * before, rel=0.15)
    assert w.last_touch == 0


def test_dribbler_holds_ball_while_backing_off():
    for dribble in (True, False):
        w = park(make_world(), poses=[(0.0, 0.0, 0.0)])
        ball_at_mouth(w)
        cmd = idle_commands(1)
        cmd[0, 0] = -1.0  # drive backwards, accelerating at 3 m/s^2, up to 1 m/s
        cmd[0, 5] = 1.0 if dribble else 0.0
        run(w, 60, cmd)
        rx, ry = w.robot_array()[0, 0:2]
        bx, by = w.ball_array()[0:2]
        gap = math.hypot(bx - rx, by - ry) - (w.robot_spec.front_distance + w.ball_spec.radius)
        if dribble:
            assert gap < 0.01 and rx < -0.3
        else:
            assert gap > 0.2


def test_dribbled_ball_can_be_stolen():
    # Blue holds the ball; yellow drives through it from the side with its full force.
    w = park(make_world(n_blue=1, n_yellow=1),
             poses=[(0.0, 0.0, 0.0), (0.1, -0.6, math.pi / 2)])
    ball_at_mouth(w)
    cmd = idle_commands(2)
    cmd[0, 5] = 1.0
    cmd[1, 0] = 1.0
    run(w, 90, cmd)
    rx, ry = w.robot_array()[0, 0:2]
    bx, by = w.ball_array()[0:2]
    assert math.hypot(bx - rx, by - ry) > 0.2


def test_headings_stay_wrapped_while_spinning():
    w = park(make_world(), poses=[(0.0, 0.0, 3.0)])
    cmd = idle_commands(1)
    cmd[0, 2] = w.robot_spec.max_angular_speed
    for _ in range(600):
        w.step(cmd)
        assert -math.pi <= w.robot_array()[0, 2] <= math.pi


def test_direct_chipmunk_step_equals_pymunk_step():
    """The world calls cpSpaceStep directly; it must match pymunk's Space.step exactly."""
    def trajectory(direct):
        f = presets.field("ssl-div-b")
        w = park(World(f, presets.ball(f.ball), presets.robot("ssl"), 2, 2, direct_step=direct))
        rng = np.random.default_rng(0)
        w.set_ball(-1.0, 0.5, 3.0, -1.0, sliding=True)
        out = []
        for _ in range(200):
            w.step(rng.uniform(-1, 1, (4, 6)) * (3, 3, 10, 6, 1, 1))
            out.append(np.concatenate([w.ball_array(), w.robot_array().ravel()]))
        return np.array(out)

    np.testing.assert_array_equal(trajectory(True), trajectory(False))


def test_same_inputs_same_trajectory_after_different_history():
    w = park(make_world(n_blue=2, n_yellow=1))
    rng = np.random.default_rng(1)
    actions = rng.uniform(-1, 1, (150, 3, 6)) * (3, 3, 10, 6, 1, 1)

    def episode():
        park(w)
        w.set_ball(0.5, 0.2, -2.0, 0.4, sliding=True)
        out = []
        for a in actions:
            w.step(a)
            out.append(np.concatenate([w.ball_array(), w.robot_array().ravel()]))
        return np.array(out)

    first = episode()
    run(w, 77, rng.uniform(-1, 1, (3, 6)) * 3)  # unrelated history
    np.testing.assert_array_equal(first, episode())


def test_world_snapshot_is_immutable_copy(world):
    snap = world.snapshot()
    run(world, 3)
    with pytest.raises(ValueError):
        snap.robots[0, 0] = 1.0
    assert snap.time == 0.0 and world.time > 0.0


def test_pymunk_version_pinned():
    assert pymunk.version.startswith("7.")


@pytest.mark.parametrize("n_blue,n_yellow", [(1, 0), (2, 1), (3, 3)])
def test_direct_and_batch_state_reads_agree(n_blue, n_yellow):
    w = park(make_world(n_blue, n_yellow))
    w.set_ball(0.0, 0.0, 2.0, 1.0, sliding=True)
    rng = np.random.default_rng(0)
    run(w, 20, rng.uniform(-1, 1, (w.n_robots, 6)) * (3, 3, 10, 0, 0, 0))
    w.read_state(batch=False)
    direct = w.snapshot()
    w.read_state(batch=True)
    batch = w.snapshot()
    np.testing.assert_array_equal(direct.robots, batch.robots)
    np.testing.assert_array_equal(direct.ball, batch.ball)

