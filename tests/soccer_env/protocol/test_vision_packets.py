"""SSL-Vision packets (soccer_env.protocol.vision): a camera frame of a served match goes out as
SSL-Vision sends it (millimetres, robots by colour and number, required fields present) and
comes back as the same frame; the field's geometry in whole millimetres; every bad datagram
refused with its reason."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("ssl_protocol")

from ssl_protocol.vision import ssl_vision_detection_pb2 as detection_pb2  # noqa: E402
from ssl_protocol.vision import ssl_vision_wrapper_pb2 as wrapper_pb2  # noqa: E402
from worlds import make_world, park  # noqa: E402

from soccer_env.presets import ball, field, robot  # noqa: E402
from soccer_env.presets.sensors import vision  # noqa: E402
from soccer_env.protocol.vision import (  # noqa: E402
    IMAGE_SIZE,
    MAX_PACKET_BYTES,
    PacketError,
    detection_frame,
    detection_packet,
    geometry_packet,
    pixel_of,
    read_packet,
)
from soccer_env.sensors.overhead import Camera, DetectionFrame, OverheadVision  # noqa: E402
from soccer_env.sim.world import idle_commands  # noqa: E402

CAMERA = Camera(2.0, 1.5, 4.0, -0.3, 4.5, -0.3, 3.3)
FRAME = DetectionFrame(1, 0.25, 0.37, ((0.5, -0.25), (3.0, 2.0)), (0, 2, 3),
                       ((1.0, 1.0, 0.5), (-2.0, 0.5, -3.0), (2.5, 1.25, 3.1)))


def test_a_frame_goes_out_as_ssl_vision_sends_it():
    packet = detection_packet(FRAME, CAMERA, frame_number=41, n_blue=2, clock=1000.0)
    d = packet.detection
    assert packet.IsInitialized()  # every required field, pixels included
    assert (d.frame_number, d.camera_id) == (41, 1)
    assert d.t_capture == pytest.approx(1000.25) and d.t_sent == pytest.approx(1000.37)
    assert [(b.x, b.y) for b in d.balls] == [(500.0, -250.0), (3000.0, 2000.0)]
    assert [(r.robot_id, r.x, r.y) for r in d.robots_blue] == [(0, 1000.0, 1000.0)]
    # world index 2 and 3 are the yellow team's robots 0 and 1
    assert [(r.robot_id, r.x) for r in d.robots_yellow] == [(0, -2000.0), (1, 2500.0)]
    assert d.robots_yellow[1].orientation == pytest.approx(3.1)
    assert all(0.0 < b.confidence <= 1.0 for b in d.balls)


def test_a_frame_read_back_is_the_frame_sent():
    data = detection_packet(FRAME, CAMERA, 41, n_blue=2, clock=1000.0).SerializeToString()
    back = detection_frame(read_packet(data), (2, 2), clock=1000.0)
    assert (back.camera, back.robot_ids) == (FRAME.camera, FRAME.robot_ids)
    assert back.t_capture == pytest.approx(FRAME.t_capture, abs=1e-9)
    assert back.t_delivered == pytest.approx(FRAME.t_delivered, abs=1e-9)
    # float32 on the wire: 1e-4 mm-scale rounding of millimetres
    np.testing.assert_allclose(back.balls, FRAME.balls, atol=1e-6)
    np.testing.assert_allclose(back.robots, FRAME.robots, atol=1e-6)


def test_pixels_of_a_top_down_pinhole_fill_the_image_with_the_cameras_area():
    u, v = pixel_of(CAMERA, CAMERA.x, CAMERA.y)
    assert (u, v) == (IMAGE_SIZE[0] / 2, IMAGE_SIZE[1] / 2)
    corners = [pixel_of(CAMERA, x, y) for x in (CAMERA.x_min, CAMERA.x_max)
               for y in (CAMERA.y_min, CAMERA.y_max)]
    assert all(-1e-9 <= u <= IMAGE_SIZE[0] + 1e-9 and -1e-9 <= v <= IMAGE_SIZE[1] + 1e-9
               for u, v in corners)
    assert any(math.isclose(u, IMAGE_SIZE[0]) or math.isclose(v, 0.0) for u, v in corners)
    u2, v2 = pixel_of(CAMERA, CAMERA.x + 1.0, CAMERA.y + 1.0)
    assert u2 > u and v2 < v  # x to the right, y up the image


def test_every_frame_of_the_simulated_cameras_goes_out_and_comes_back():
    """Four cameras (a Division B field), ``ssl-2012`` noise, drops and false balls: every
    frame of 2 s, packed and read back, is the frame, from whichever camera."""
    world = park(make_world(n_blue=2, n_yellow=2, field="ssl-div-b", control_dt=1 / 60))
    spec = vision("ssl-2012")
    cams = OverheadVision(spec, world.field, world.robot_spec, world.ball_spec,
                          world.n_robots)
    frames = cams.reset(world.snapshot(), np.random.default_rng(3))
    for _ in range(120):
        world.step(idle_commands(world.n_robots))
        frames.extend(cams.step(world.snapshot()))
    assert len(cams.cameras) == 4 and {f.camera for f in frames} == {0, 1, 2, 3}
    for k, frame in enumerate(frames):
        packet = detection_packet(frame, cams.cameras[frame.camera], k, n_blue=2, clock=50.0)
        back = detection_frame(read_packet(packet.SerializeToString()), (2, 2), clock=50.0)
        assert back.robot_ids == frame.robot_ids and len(back.balls) == len(frame.balls)
        np.testing.assert_allclose(np.reshape(back.robots, (-1, 3)),
                                   np.reshape(frame.robots, (-1, 3)), atol=1e-5)
        np.testing.assert_allclose(np.reshape(back.balls, (-1, 2)),
                                   np.reshape(frame.balls, (-1, 2)), atol=1e-5)
        assert back.t_capture == pytest.approx(frame.t_capture, abs=1e-6)


def test_the_geometry_in_whole_millimetres():
    f, b, r = field("ssl-div-b"), ball("ssl"), robot("ssl")
    packet = geometry_packet(f, b, r, penalty_mark=6.0)
    g = read_packet(packet.SerializeToString()).geometry.field
    assert (g.field_length, g.field_width) == (round(f.length * 1000), round(f.width * 1000))
    assert g.goal_width == round(f.goal_width * 1000)
    assert g.penalty_area_depth == round(f.defense_depth * 1000)
    assert g.goal_center_to_penalty_mark == 6000
    assert g.ball_radius == pytest.approx(b.radius * 1000)


def _bad(packet: wrapper_pb2.SSL_WrapperPacket) -> bytes:
    return packet.SerializePartialToString()


def _with(**changes) -> bytes:
    packet = detection_packet(FRAME, CAMERA, 1, n_blue=2)
    for path, value in changes.items():
        obj, name = packet.detection, path
        if "__" in path:
            kind, i, name = path.split("__")
            obj = getattr(packet.detection, kind)[int(i)]
        setattr(obj, name, value)
    return packet.SerializeToString()


@pytest.mark.parametrize("data, reason", [
    (b"\xff" * 40, "malformed"),
    (detection_packet(FRAME, CAMERA, 1, 2).SerializeToString()[:-7], "malformed"),
    (b"\x00" * (MAX_PACKET_BYTES + 1), "oversized"),
    (b"", "empty"),
    (_bad(wrapper_pb2.SSL_WrapperPacket(detection=detection_pb2.SSL_DetectionFrame(
        frame_number=1, camera_id=0))), "incomplete"),
    (_with(balls__0__x=float("nan")), "out of range"),
    (_with(balls__1__y=1e9), "out of range"),
    (_with(robots_blue__0__confidence=1.5), "out of range"),
    (_with(robots_yellow__0__robot_id=99), "out of range"),
    (_with(robots_yellow__1__orientation=float("inf")), "out of range"),
    (_with(t_capture=float("nan")), "out of range"),
])
def test_bad_datagrams_are_refused_with_their_reason(data, reason):
    with pytest.raises(PacketError) as exc:
        read_packet(data)
    assert exc.value.reason == reason


def test_a_robot_the_world_does_not_have_is_refused():
    packet = read_packet(detection_packet(FRAME, CAMERA, 1, n_blue=2).SerializeToString())
    with pytest.raises(PacketError, match="yellow robot 1; the team has 1") as exc:
        detection_frame(packet, (2, 1))
    assert exc.value.reason == "unknown robot"
    geometry = read_packet(geometry_packet(field("ssl-div-b"), ball("ssl"),
                                           robot("ssl")).SerializeToString())
    with pytest.raises(PacketError, match="no detection frame"):
        detection_frame(geometry, (2, 2))
