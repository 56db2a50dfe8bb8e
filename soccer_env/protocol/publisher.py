"""A world's cameras published as SSL-Vision: :class:`VisionPublisher`.

It runs an overhead camera system of its own (:class:`~soccer_env.sensors.overhead.
OverheadVision` on a vision preset, seeded on its own) on the snapshots of a simulated world,
and sends each camera frame as an ``SSL_WrapperPacket`` (:func:`~soccer_env.protocol.vision.
detection_packet`) when it is delivered: at episode time ``t_delivered`` (stepped: as soon as
the world has stepped past it; in real time: at wall time ``clock + t_delivered``). Every
camera counts its frames (``frame_number``); the geometry goes out at the start and then
every ``geometry_period`` seconds of episode time.
"""

from __future__ import annotations

import heapq
import math
import socket
from typing import Any

import numpy as np

from soccer_env.presets import VisionSpec
from soccer_env.presets.sensors import vision as vision_preset
from soccer_env.protocol.udp import VISION_ADDRESS, destinations, sender
from soccer_env.protocol.vision import detection_packet, geometry_packet
from soccer_env.sensors.overhead import DetectionFrame, OverheadVision

__all__ = ["VisionPublisher"]


class VisionPublisher:
    """The cameras of ``world`` (a :class:`~soccer_env.sim.world.World`) published as
    SSL-Vision packets to ``address`` (module docstring).

    Args:
        world: the simulated world; :meth:`reset` after the world's reset, :meth:`step` after
            each of its steps.
        vision: the vision preset (name or spec) of the cameras: rate, latency, noise, drops,
            occlusion, false balls, camera overlap.
        address: where the packets go (default: SSL-Vision's multicast group and port), or
            a list of addresses, each sent every packet (several teams on loopback).
        geometry_period: seconds of episode time between geometry packets.
        penalty_mark: distance [m] from a goal's centre to its penalty mark, for the geometry.
        sock: a socket to send through (default: :func:`~soccer_env.protocol.udp.sender` to
            ``address``), closed by :meth:`close` only if this made it.
    """

    def __init__(self, world: Any, vision: str | VisionSpec = "ssl-2012",
                 address: tuple[str, int] = VISION_ADDRESS, geometry_period: float = 1.0,
                 penalty_mark: float | None = None, sock: socket.socket | None = None) -> None:
        self.spec = vision_preset(vision)
        if self.spec.frame_rate is None:
            raise ValueError(f"vision {self.spec.name!r} captures at every step (frame_rate "
                             "None); served vision needs cameras with a frame rate")
        if not (math.isfinite(geometry_period) and geometry_period > 0):
            raise ValueError(f"geometry_period must be a finite number of seconds > 0, got "
                             f"{geometry_period!r}")
        self.world = world
        #: Every address the packets go to (:func:`~soccer_env.protocol.udp.destinations`),
        #: and the first.
        self.addresses = destinations(address)
        self.address = self.addresses[0]
        self.geometry_period = float(geometry_period)
        self.cameras = OverheadVision(self.spec, world.field, world.robot_spec,
                                      world.ball_spec, world.n_robots)
        self._geometry = geometry_packet(world.field, world.ball_spec, world.robot_spec,
                                         penalty_mark).SerializeToString()
        self._own = sock is None
        self.sock = sender(self.address) if sock is None else sock
        self.clock = 0.0
        self._queue: list[tuple[float, int, bytes]] = []
        self._counts = [0] * len(self.cameras.cameras)
        self._next_geometry = 0.0
        self._seq = 0
        #: Packets sent, and of them geometry packets.
        self.sent = 0
        self.geometry_sent = 0

    def reset(self, rng: np.random.Generator, clock: float = 0.0) -> None:
        """Start an episode on the world's state: ``clock`` is the wall time [s] the
        episode's time 0 stands for (``t_capture``, ``t_sent``)."""
        self.clock = float(clock)
        self._queue.clear()
        self._counts = [0] * len(self.cameras.cameras)
        self._next_geometry = float(self.world.time)
        self._push(self.cameras.reset(self.world.snapshot(), rng))

    def step(self) -> None:
        """Capture what the cameras saw while the world stepped (sent when delivered)."""
        self._push(self.cameras.capture(self.world.snapshot()))

    def _push(self, frames: list[DetectionFrame]) -> None:
        n_blue = int(self.world.n_blue)
        for f in frames:
            cam = self.cameras.cameras[f.camera]
            packet = detection_packet(f, cam, self._counts[f.camera], n_blue, self.clock)
            self._counts[f.camera] += 1
            self._seq += 1
            heapq.heappush(self._queue, (f.t_delivered, self._seq, packet.SerializeToString()))

    def next_delivery(self) -> float | None:
        """Episode time [s] of the next frame's delivery (None: none waiting)."""
        return self._queue[0][0] if self._queue else None

    def due(self, t: float) -> list[bytes]:
        """The packets to send by episode time ``t`` [s], in order of delivery: frames
        delivered by then, and the geometry when its period has come round."""
        out = []
        if t >= self._next_geometry:
            out.append(self._geometry)
            self.geometry_sent += 1
            self._next_geometry += self.geometry_period * (
                1 + math.floor((t - self._next_geometry) / self.geometry_period))
        while self._queue and self._queue[0][0] <= t:
            out.append(heapq.heappop(self._queue)[2])
        return out

    def publish(self, t: float) -> int:
        """Send :meth:`due` ``(t)`` to the address; the number sent."""
        packets = self.due(t)
        for data in packets:
            for address in self.addresses:
                self.sock.sendto(data, address)
        self.sent += len(packets)
        return len(packets)

    def close(self) -> None:
        if self._own:
            self.sock.close()
