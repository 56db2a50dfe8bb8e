"""The simulation protocol's robot control (soccer_env.protocol.robot_control): local and
global velocities, kicks, chips and the dribbler become the world's commands; a robot the team
does not have, wheel velocities and numbers out of range are refused with an error and change
nothing; robots no command names keep theirs."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("ssl_protocol")

from ssl_protocol.sim import ssl_simulation_robot_control_pb2 as control_pb2  # noqa: E402

from soccer_env.protocol.robot_control import (  # noqa: E402
    apply_robot_control,
    read_robot_control,
)
from soccer_env.protocol.vision import PacketError  # noqa: E402

HEADINGS = np.array([0.0, math.pi / 2, 0.3, -1.0])  # blue 0, 1, yellow 0, 1


def _control(*commands) -> bytes:
    control = control_pb2.RobotControl()
    for c in commands:
        control.robot_commands.add().CopyFrom(c)
    return control.SerializeToString()


def _local(id, forward=0.0, left=0.0, angular=0.0, **kw):
    cmd = control_pb2.RobotCommand(id=id, **kw)
    cmd.move_command.local_velocity.forward = forward
    cmd.move_command.local_velocity.left = left
    cmd.move_command.local_velocity.angular = angular
    return cmd


def _apply(data, first=0, commands=None, contact=None):
    commands = np.full((4, 6), 7.0) if commands is None else commands
    response = apply_robot_control(read_robot_control(data), commands, first, 2, HEADINGS,
                                   contact)
    return commands, response


def test_local_velocity_kick_chip_and_dribbler_become_the_command():
    commands, response = _apply(_control(
        _local(0, 1.5, -0.5, 2.0, kick_speed=4.0, dribbler_speed=1000.0),
        _local(1, kick_speed=3.0, kick_angle=45.0)), first=2,
        contact=np.array([False, False, True, False]))
    np.testing.assert_allclose(commands[2], [1.5, -0.5, 2.0, 4.0, 0.0, 1.0])
    np.testing.assert_allclose(commands[3], [0.0, 0.0, 0.0, 3.0, 1.0, 0.0])
    np.testing.assert_array_equal(commands[:2], 7.0)  # the other team's rows untouched
    assert not response.errors
    assert [(f.id, f.dribbler_ball_contact) for f in response.feedback] == [(0, True),
                                                                            (1, False)]


def test_global_velocity_is_turned_into_the_body_frame_by_the_heading():
    cmd = control_pb2.RobotCommand(id=1)
    cmd.move_command.global_velocity.x = 1.0
    cmd.move_command.global_velocity.y = 0.0
    cmd.move_command.global_velocity.angular = 0.5
    commands, _ = _apply(_control(cmd))
    # robot 1 faces +y: a field velocity along +x is to its right (body -y)
    np.testing.assert_allclose(commands[1, :3], [0.0, -1.0, 0.5], atol=1e-7)
    stand = control_pb2.RobotCommand(id=0)  # no move command: the robot stands
    commands, _ = _apply(_control(stand))
    np.testing.assert_array_equal(commands[0], 0.0)
    np.testing.assert_array_equal(commands[1], 7.0)  # not named: keeps its command


@pytest.mark.parametrize("command, code", [
    (_local(2, 1.0), "UNKNOWN_ROBOT"),
    (_local(1, float("nan")), "OUT_OF_RANGE"),
    (_local(1, 30.0), "OUT_OF_RANGE"),
    (_local(1, angular=1e4), "OUT_OF_RANGE"),
    (_local(1, kick_speed=-1.0), "OUT_OF_RANGE"),
    (_local(1, kick_speed=float("inf")), "OUT_OF_RANGE"),
    (control_pb2.RobotCommand(id=1, move_command=control_pb2.RobotMoveCommand(
        wheel_velocity=control_pb2.MoveWheelVelocity(front_right=1, back_right=1,
                                                     back_left=1, front_left=1))),
     "UNSUPPORTED_MOVE"),
])
def test_commands_that_cannot_apply_are_refused_and_change_nothing(command, code):
    commands, response = _apply(_control(_local(0, 0.5), command))
    assert [e.code for e in response.errors] == [code]
    assert f"robot {command.id}" in response.errors[0].message
    np.testing.assert_allclose(commands[0, :3], [0.5, 0.0, 0.0])  # the good one applies
    np.testing.assert_array_equal(commands[1:], 7.0)


@pytest.mark.parametrize("data, reason", [
    (b"\x0a\x05\xff\xff", "malformed"),
    (control_pb2.RobotControl(robot_commands=[control_pb2.RobotCommand()])
     .SerializePartialToString(), "incomplete"),
    (b"\x00" * 20_000, "oversized"),
])
def test_bad_datagrams_raise_with_their_reason(data, reason):
    with pytest.raises(PacketError) as exc:
        read_robot_control(data)
    assert exc.value.reason == reason
