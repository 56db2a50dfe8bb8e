"""A match served over loopback sockets (127.0.0.1 only): robot commands sent through the
simulation protocol move the robots and are answered with feedback, refused ones with an error;
bad datagrams are counted and dropped; the served cameras show the robots where they are; the
stepped mode gives the same packets for the same seed and commands."""

from __future__ import annotations

import math
import socket

import numpy as np
import pytest

pytest.importorskip("ssl_protocol")

from ssl_protocol.sim import ssl_simulation_robot_control_pb2 as control_pb2  # noqa: E402
from ssl_protocol.sim import ssl_simulation_robot_feedback_pb2 as feedback_pb2  # noqa: E402

from soccer_env.protocol.reader import VisionReader  # noqa: E402
from soccer_env.protocol.server import SSLServer  # noqa: E402
from soccer_env.protocol.udp import receiver  # noqa: E402

LOOPBACK = ("127.0.0.1", 0)
KWARGS = {"blue": 2, "yellow": 2, "control_dt": 1 / 60, "match_duration": 10.0}


def _server(vision_sock, referee_sock=None, **kw):
    referee = referee_sock.getsockname()[:2] if referee_sock is not None else ("127.0.0.1", 9)
    return SSLServer({**KWARGS, **kw}, "ssl-2012", vision_sock.getsockname()[:2], referee,
                     (LOOPBACK, LOOPBACK), LOOPBACK)


def _forward(robot_id: int, speed: float) -> bytes:
    control = control_pb2.RobotControl()
    cmd = control.robot_commands.add(id=robot_id)
    cmd.move_command.local_velocity.forward = speed
    cmd.move_command.local_velocity.left = 0.0
    cmd.move_command.local_velocity.angular = 0.0
    return control.SerializeToString()


def test_commands_through_the_protocol_drive_the_served_robots():
    reader = VisionReader((2, 2), LOOPBACK)
    server = _server(reader.sock)
    team = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    team.bind(LOOPBACK)
    team.settimeout(1.0)
    try:
        server.reset(seed=3, clock=0.0)
        start = server.world.snapshot().robots[0].copy()
        team.sendto(_forward(0, 1.0), server.control_addresses[0])
        server.step()
        response = feedback_pb2.RobotControlResponse.FromString(team.recv(65_536))
        assert [f.id for f in response.feedback] == [0] and not response.errors
        for _ in range(59):  # one second
            server.step()
        end = server.world.snapshot().robots[0]
        moved = end[:2] - start[:2]
        heading = np.array([math.cos(start[2]), math.sin(start[2])])
        # accelerating from rest to 1 m/s, then 1 m/s: a little under 1 m along the heading
        assert 0.7 < float(moved @ heading) < 1.0
        assert abs(float(moved @ np.array([-heading[1], heading[0]]))) < 0.05
        frames = reader.poll(timeout=0.5)
        seen = [pose for f in frames[-8:] for i, pose in zip(f.robot_ids, f.robots) if i == 0]
        assert seen and np.hypot(*(np.array(seen[-1][:2]) - end[:2])) < 0.2  # 120 ms late
        # a robot the team does not have, and a datagram that is not a command
        team.sendto(_forward(5, 1.0), server.control_addresses[1])
        team.sendto(b"\xff\xff\xff", server.control_addresses[1])
        server.step()
        response = feedback_pb2.RobotControlResponse.FromString(team.recv(65_536))
        assert [e.code for e in response.errors] == ["UNKNOWN_ROBOT"]
        assert server.refused == [0, 1] and server.dropped == {"malformed": 1}
        assert not server.commands[2:].any()  # the yellow robots were never commanded
    finally:
        team.close()
        server.close()
        reader.close()


def _packets(seed: int) -> list[bytes]:
    sock = receiver(LOOPBACK, timeout=0.5)
    server = _server(sock)
    out = []
    try:
        server.reset(seed=seed, clock=0.0)
        for k in range(90):
            if k == 10:
                server.commands[1] = [0.5, 0.0, 1.0, 0.0, 0.0, 0.0]
            server.step()
        server.vision.sock.sendto(b"end", sock.getsockname()[:2])
        while (data := sock.recv(65_536)) != b"end":
            out.append(data)
    finally:
        server.close()
        sock.close()
    return out


def test_the_stepped_server_gives_the_same_packets_for_the_same_seed():
    a, b, c = _packets(11), _packets(11), _packets(12)
    assert len(a) > 100 and a == b
    assert a != c


def test_bad_arguments_are_refused():
    with pytest.raises(ValueError, match="must not set \\['obs_mode'\\]"):
        SSLServer({"obs_mode": "perceived"})
    with pytest.raises(ValueError, match="humanoids"):
        SSLServer({"robot": "humanoid"}, vision_address=("127.0.0.1", 9),
                  referee_address=("127.0.0.1", 9), control_addresses=(LOOPBACK, LOOPBACK))
    with pytest.raises(ValueError, match="IPv4 host"):
        SSLServer({}, vision_address=("nowhere", 1))
    with pytest.raises(ValueError, match="referee_address port must be an integer in 1..65535"):
        SSLServer({}, vision_address=("127.0.0.1", 9), referee_address=("127.0.0.1", 0))


def test_simulator_control_places_the_ball_and_the_robots():
    from ssl_protocol.sim import ssl_simulation_control_pb2 as sim_pb2
    from ssl_protocol.state import ssl_gc_common_pb2 as common_pb2

    sock = receiver(LOOPBACK, timeout=0.5)
    server = _server(sock)
    user = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    user.bind(LOOPBACK)
    user.settimeout(1.0)
    try:
        server.reset(seed=2, clock=0.0)
        command = sim_pb2.SimulatorCommand()
        control = command.control
        control.teleport_ball.x, control.teleport_ball.y = 1.5, -0.5
        robot = control.teleport_robot.add(x=-1.0, y=1.0, orientation=0.5)
        robot.id.id, robot.id.team = 1, common_pb2.YELLOW
        missing = control.teleport_robot.add(x=0.0, y=0.0)
        missing.id.id, missing.id.team = 7, common_pb2.BLUE
        far = control.teleport_robot.add(x=50.0)
        far.id.id, far.id.team = 0, common_pb2.BLUE
        before = server.world.snapshot().robots[0].copy()
        user.sendto(command.SerializeToString(), server.simulator_address)
        server.read_controls()
        response = sim_pb2.SimulatorResponse.FromString(user.recv(65_536))
        assert [e.code for e in response.errors] == ["UNKNOWN_ROBOT", "OUT_OF_RANGE"]
        state = server.world.snapshot()
        np.testing.assert_allclose(state.ball[:2], [1.5, -0.5], atol=1e-6)
        np.testing.assert_allclose(state.robots[3, :3], [-1.0, 1.0, 0.5], atol=1e-6)
        np.testing.assert_array_equal(state.robots[0], before)  # refused: unchanged
        assert server.simulator_errors == 2
        user.sendto(b"\xff\xff", server.simulator_address)
        server.read_controls()
        assert server.dropped == {"malformed": 1}
    finally:
        user.close()
        server.close()
        sock.close()
