"""SSL-Vision packets from and to detection frames.

A camera frame of the package (:class:`~soccer_env.sensors.overhead.DetectionFrame`: SI units,
robots by world index, blue first) becomes the ``detection`` of an ``SSL_WrapperPacket`` as
SSL-Vision sends it (:func:`detection_packet`): positions in millimetres, orientations in
radians, robots split by colour with their number in their team as ``robot_id``, times in
seconds (``t_capture``, ``t_sent``: the frame's capture and delivery, plus ``clock``, the wall
time of the episode's start). The field goes out as ``geometry``
(:func:`geometry_packet`).

Pixel coordinates, which the protocol requires, are those of an undistorted pinhole camera
looking straight down from the camera's position, its image of :data:`IMAGE_SIZE` pixels just
holding the camera's area (an assumption of ours: the package models detections, not images);
an object's height is not projected (the ground plane).

The other way (:func:`read_packet`, :func:`detection_frame`), every packet is checked before
use: its size (:data:`MAX_PACKET_BYTES`), that it parses and carries every required field, and
that its numbers are finite and in range. A packet that fails raises :class:`PacketError`,
whose ``reason`` says which check and what it found, for the caller to count, log and drop.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache

import numpy as np
from ssl_protocol.vision import ssl_vision_detection_pb2 as detection_pb2
from ssl_protocol.vision import ssl_vision_wrapper_pb2 as wrapper_pb2

from soccer_env.presets import BallSpec, FieldSpec, SSLRobotSpec
from soccer_env.protocol.datagrams import MAX_PACKET_BYTES, PacketError, parse
from soccer_env.sensors.overhead import Camera, DetectionFrame

__all__ = ["IMAGE_SIZE", "MAX_PACKET_BYTES", "MAX_COORDINATE_MM", "PacketError",
           "detection_packet", "geometry_packet", "read_packet", "detection_frame",
           "pixel_of"]

#: Millimetres per metre: the protocol's lengths are millimetres.
MM = 1000.0
#: The image of every camera [pixels] (width, height): an assumption of ours.
IMAGE_SIZE = (780, 580)
#: The largest coordinate accepted [mm]: beyond every division's field and its boundary.
MAX_COORDINATE_MM = 20_000.0
#: Robot numbers a team may have on the protocol (SSL-Vision's patterns number 0-15).
MAX_ROBOT_ID = 15


def pixel_of(camera: Camera, x: float, y: float) -> tuple[float, float]:
    """The pixel ``(u, v)`` of the ground point ``(x, y)`` [m] in ``camera``'s image: a pinhole
    looking straight down from ``(camera.x, camera.y)``, scaled so that the camera's area just
    fits :data:`IMAGE_SIZE` (``u`` grows with ``x``, ``v`` against ``y``, as image rows run)."""
    scale = _pixels_per_metre(camera)
    w, h = IMAGE_SIZE
    return 0.5 * w + scale * (x - camera.x), 0.5 * h - scale * (y - camera.y)


@lru_cache(maxsize=64)
def _pixels_per_metre(camera: Camera) -> float:
    """Pixels per metre on the ground of :func:`pixel_of`'s camera (its area just fits)."""
    reach_x = max(abs(camera.x_min - camera.x), abs(camera.x_max - camera.x), 1e-9)
    reach_y = max(abs(camera.y_min - camera.y), abs(camera.y_max - camera.y), 1e-9)
    return min(0.5 * IMAGE_SIZE[0] / reach_x, 0.5 * IMAGE_SIZE[1] / reach_y)


def detection_packet(frame: DetectionFrame, camera: Camera, frame_number: int, n_blue: int,
                     clock: float = 0.0) -> wrapper_pb2.SSL_WrapperPacket:
    """The ``SSL_WrapperPacket`` of one camera frame (module docstring): ``frame_number`` the
    camera's count of frames, ``n_blue`` the blue team's size (world indices from it are
    yellow), ``clock`` the wall time [s] the episode's time 0 stands for. Every detection has
    confidence 1 (the package's detections carry none)."""
    packet = wrapper_pb2.SSL_WrapperPacket()
    d = packet.detection
    d.frame_number = int(frame_number)
    d.camera_id = int(frame.camera)
    d.t_capture = clock + float(frame.t_capture)
    d.t_sent = clock + float(frame.t_delivered)
    for bx, by in np.reshape(frame.balls, (-1, 2)):
        ball = d.balls.add()
        ball.confidence = 1.0
        ball.x, ball.y = bx * MM, by * MM
        ball.pixel_x, ball.pixel_y = pixel_of(camera, bx, by)
    for index, (x, y, theta) in zip(frame.robot_ids, frame.robots):
        blue = index < n_blue
        robot = (d.robots_blue if blue else d.robots_yellow).add()
        robot.confidence = 1.0
        robot.robot_id = int(index if blue else index - n_blue)
        robot.x, robot.y, robot.orientation = x * MM, y * MM, theta
        robot.pixel_x, robot.pixel_y = pixel_of(camera, x, y)
    return packet


def geometry_packet(field: FieldSpec, ball: BallSpec, robot: SSLRobotSpec,
                    penalty_mark: float | None = None) -> wrapper_pb2.SSL_WrapperPacket:
    """The ``SSL_WrapperPacket`` of the field's geometry: its sizes in whole millimetres, the
    ball's radius and the robots' largest radius [mm], and with ``penalty_mark`` [m] the
    distance from a goal's centre to its penalty mark. No camera calibrations and no field
    lines (both optional in the protocol)."""
    packet = wrapper_pb2.SSL_WrapperPacket()
    f = packet.geometry.field
    f.field_length = round(field.length * MM)
    f.field_width = round(field.width * MM)
    f.goal_width = round(field.goal_width * MM)
    f.goal_depth = round(field.goal_depth * MM)
    f.boundary_width = round(field.boundary * MM)
    f.penalty_area_depth = round(field.defense_depth * MM)
    f.penalty_area_width = round(field.defense_width * MM)
    f.center_circle_radius = round(field.center_circle_radius * MM)
    f.line_thickness = round(field.line_width * MM)
    f.goal_height = round(field.goal_height * MM)
    f.ball_radius = ball.radius * MM
    f.max_robot_radius = robot.radius * MM
    if penalty_mark is not None:
        f.goal_center_to_penalty_mark = round(penalty_mark * MM)
    return packet


def read_packet(data: bytes) -> wrapper_pb2.SSL_WrapperPacket:
    """Parse one datagram as an ``SSL_WrapperPacket`` and check it (module docstring).

    Raises :class:`PacketError` with reason ``"oversized"``, ``"malformed"`` (does not parse),
    ``"incomplete"`` (a required field missing), ``"empty"`` (neither detection nor geometry)
    or ``"out of range"`` (a number not finite or beyond the field, a confidence outside
    [0, 1], a robot number beyond 15)."""
    packet = parse(data, wrapper_pb2.SSL_WrapperPacket)
    if not packet.HasField("detection") and not packet.HasField("geometry"):
        raise PacketError("empty", "neither a detection frame nor geometry")
    if packet.HasField("detection"):
        _check_detection(packet.detection)
    return packet


def _check_detection(d: detection_pb2.SSL_DetectionFrame) -> None:
    """Raise :class:`PacketError` ``"out of range"`` for a detection frame's bad numbers."""
    for name in ("t_capture", "t_sent"):
        if not math.isfinite(getattr(d, name)):
            raise PacketError("out of range", f"{name} is {getattr(d, name)}")
    objects = [("ball", b) for b in d.balls] + [("blue robot", r) for r in d.robots_blue] \
        + [("yellow robot", r) for r in d.robots_yellow]
    for kind, o in objects:
        if not (math.isfinite(o.x) and math.isfinite(o.y)
                and abs(o.x) <= MAX_COORDINATE_MM and abs(o.y) <= MAX_COORDINATE_MM):
            raise PacketError("out of range", f"a {kind} at ({o.x}, {o.y}) mm, beyond "
                                              f"{MAX_COORDINATE_MM:g} mm or not finite")
        if not 0.0 <= o.confidence <= 1.0:
            raise PacketError("out of range", f"a {kind}'s confidence {o.confidence}, not "
                                              "in [0, 1]")
        if kind != "ball" and (o.robot_id > MAX_ROBOT_ID
                               or not math.isfinite(o.orientation)):
            raise PacketError("out of range", f"a {kind} numbered {o.robot_id} facing "
                                              f"{o.orientation} rad (numbers 0-{MAX_ROBOT_ID},"
                                              " a finite orientation)")


def detection_frame(packet: wrapper_pb2.SSL_WrapperPacket, team_sizes: Sequence[int],
                    clock: float = 0.0) -> DetectionFrame:
    """The detection frame of a checked packet (:func:`read_packet`) as the package's
    perception takes it: metres, robots by world index (blue ``0 .. n_blue - 1``, then
    yellow), times less ``clock`` [s]; ``team_sizes`` ``(n_blue, n_yellow)``. Robots without
    a ``robot_id`` or numbered beyond their team's size raise :class:`PacketError` ``"unknown
    robot"`` (the caller's world has no such robot)."""
    if not packet.HasField("detection"):
        raise PacketError("empty", "the packet has no detection frame")
    d = packet.detection
    n_blue, n_yellow = (int(n) for n in team_sizes)
    ids, poses = [], []
    for robots, offset, size, colour in ((d.robots_blue, 0, n_blue, "blue"),
                                         (d.robots_yellow, n_blue, n_yellow, "yellow")):
        for r in robots:
            if not r.HasField("robot_id") or r.robot_id >= size:
                number = r.robot_id if r.HasField("robot_id") else "no number"
                raise PacketError("unknown robot", f"{colour} robot {number}; the team has "
                                                   f"{size}")
            ids.append(offset + int(r.robot_id))
            poses.append((r.x / MM, r.y / MM, r.orientation))
    balls = tuple((b.x / MM, b.y / MM) for b in d.balls)
    return DetectionFrame(int(d.camera_id), d.t_capture - clock, d.t_sent - clock, balls,
                          tuple(ids), tuple(poses))
