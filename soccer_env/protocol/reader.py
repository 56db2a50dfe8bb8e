"""SSL-Vision and the referee read from the network: :class:`VisionReader` and
:class:`RefereeReader`.

It reads the datagrams waiting on its socket, checks each (:func:`~soccer_env.protocol.vision.
read_packet`), keeps the latest geometry and returns the detection frames in the package's
units and robot order (:func:`~soccer_env.protocol.vision.detection_frame`). A datagram that
fails a check is counted under its reason in :attr:`VisionReader.dropped`, logged the first time
its reason occurs (logger ``soccer_env.protocol``), and dropped; reading goes on.
"""

from __future__ import annotations

import socket
from collections import Counter
from collections.abc import Sequence
from typing import Any

from soccer_env.protocol.datagrams import LOGGER, PacketError, drop
from soccer_env.protocol.referee import read_referee
from soccer_env.protocol.udp import MAX_DATAGRAM, REFEREE_ADDRESS, VISION_ADDRESS, receiver
from soccer_env.protocol.vision import detection_frame, read_packet
from soccer_env.sensors.overhead import DetectionFrame

__all__ = ["VisionReader", "RefereeReader", "LOGGER"]


class VisionReader:
    """SSL-Vision packets received on ``address`` as detection frames (module docstring).

    Args:
        team_sizes: ``(n_blue, n_yellow)`` of the world the frames are for (robots numbered
            beyond them are refused: reason ``"unknown robot"``).
        address: where to listen (default: SSL-Vision's multicast group and port; port 0 binds
            a free port, :attr:`address` then holds it).
        clock: the wall time [s] the caller's time 0 stands for (subtracted from the packets'
            times).
        interface: the interface a multicast group is joined on.
        sock: a bound socket to read from instead (not closed by :meth:`close`).
    """

    def __init__(self, team_sizes: Sequence[int], address: tuple[str, int] = VISION_ADDRESS,
                 clock: float = 0.0, interface: str = "0.0.0.0",
                 sock: socket.socket | None = None) -> None:
        sizes = tuple(team_sizes)
        if len(sizes) != 2 or not all(isinstance(n, int) and 0 <= n <= 16 for n in sizes):
            raise ValueError(f"team_sizes must be (n_blue, n_yellow), integers in 0..16, got "
                             f"{team_sizes!r}")
        self.team_sizes = sizes
        self.clock = float(clock)
        self._own = sock is None
        self.sock = receiver(address, interface) if sock is None else sock
        #: The address bound (host, port).
        self.address = self.sock.getsockname()[:2]
        #: The latest ``SSL_GeometryData`` received (None: none yet).
        self.geometry: Any = None
        #: Datagrams dropped, by reason.
        self.dropped: Counter = Counter()
        #: Datagrams read, and of them detection frames returned.
        self.received = 0
        self.frames = 0

    def poll(self, timeout: float = 0.0) -> list[DetectionFrame]:
        """The detection frames of every datagram waiting, after waiting up to ``timeout``
        [s] for the first (0: only what is there)."""
        out: list[DetectionFrame] = []
        if timeout > 0:
            self.sock.settimeout(timeout)
        else:
            self.sock.setblocking(False)
        first = True
        while True:
            try:
                data = self.sock.recv(MAX_DATAGRAM + 1)
            except (BlockingIOError, TimeoutError):
                break
            if first:
                self.sock.setblocking(False)
                first = False
            self.received += 1
            frame = self._frame(data)
            if frame is not None:
                out.append(frame)
        self.frames += len(out)
        return out

    def _frame(self, data: bytes) -> DetectionFrame | None:
        """The frame of one datagram (None: geometry only, or dropped)."""
        try:
            packet = read_packet(data)
            if packet.HasField("geometry"):
                self.geometry = packet.geometry
            if not packet.HasField("detection"):
                return None
            return detection_frame(packet, self.team_sizes, self.clock)
        except PacketError as exc:
            drop(self.dropped, exc, "an SSL-Vision datagram")
            return None

    def close(self) -> None:
        if self._own:
            self.sock.close()


class RefereeReader:
    """The game controller's ``Referee`` messages received on ``address`` (default: the
    league's multicast group and port; port 0 binds a free port, :attr:`address` then holds
    it). A datagram that fails :func:`~soccer_env.protocol.referee.read_referee` is counted
    in :attr:`dropped` under its reason, logged the first time, and dropped."""

    def __init__(self, address: tuple[str, int] = REFEREE_ADDRESS,
                 interface: str = "0.0.0.0") -> None:
        self.sock = receiver(address, interface)
        self.address = self.sock.getsockname()[:2]
        self.dropped: Counter = Counter()
        #: Messages read and accepted.
        self.received = 0

    def poll(self, timeout: float = 0.0) -> list[Any]:
        """The messages waiting, after waiting up to ``timeout`` [s] for the first."""
        out: list[Any] = []
        self.sock.settimeout(timeout if timeout > 0 else None)
        if timeout <= 0:
            self.sock.setblocking(False)
        while True:
            try:
                data = self.sock.recv(MAX_DATAGRAM + 1)
            except (BlockingIOError, TimeoutError):
                break
            self.sock.setblocking(False)
            try:
                out.append(read_referee(data))
            except PacketError as exc:
                drop(self.dropped, exc, "a referee datagram")
        self.received += len(out)
        return out

    def close(self) -> None:
        self.sock.close()
