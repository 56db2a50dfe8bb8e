"""A team's radio: robots broadcast what they believe over a lossy link with latency.

Xu et al.'s (2012) humanoids share their pose estimates and ball sightings over a self-organising
ZigBee network that robots join and leave. :class:`TeamRadio` models that link:

* a robot that has joined broadcasts a :class:`Message` (its pose estimate and, if it sees the
  ball, its sighting as a line from itself towards the ball, with the capture time stamp);
* every other member receives it ``latency + U(0, jitter)`` seconds later, or not at all with
  probability ``loss`` (independently per receiver, as broadcast packets are lost);
* a silent robot (fallen, getting up) sends nothing; a robot that leaves neither sends nor
  receives, and messages in flight to it are dropped;
* every draw comes from the generator the radio is given.

Times in seconds, positions in metres, angles in radians (field frame).
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass

import numpy as np

from soccer_env.presets.sensors import RadioSpec, radio

__all__ = ["Message", "TeamRadio"]


@dataclass(frozen=True)
class Message:
    """What a robot broadcasts.

    Attributes:
        sender: the robot's name.
        stamp: when its content was true (the camera frame's capture time) [s].
        pose: its pose estimate ``(x, y, theta)``.
        sighting: None, or ``(x0, y0, angle, range)``: the line from ``(x0, y0)`` (its
            estimated position) at ``angle`` towards the ball, and the estimated range.
        sway: how much its torso swayed at the capture, 0 (standing) to 1 (its walk's full
            sway), which scales its camera's errors.
    """

    sender: str
    stamp: float
    pose: tuple[float, float, float]
    sighting: tuple[float, float, float, float] | None = None
    sway: float = 1.0


class TeamRadio:
    """The link between one team's robots (see the module docstring).

    Args:
        spec: a :class:`RadioSpec` or a name of :data:`RADIO_PRESETS`.
        rng: the generator of the link's draws.
    """

    def __init__(self, spec: RadioSpec | str, rng: np.random.Generator) -> None:
        if isinstance(spec, str):
            spec = radio(spec)
        if not isinstance(rng, np.random.Generator):
            raise TypeError("rng must be a numpy.random.Generator")
        self.spec, self.rng = spec, rng
        self.members: set[str] = set()
        self.silent: set[str] = set()
        # Messages in flight per receiver: heaps of (arrival, sequence number, message).
        self._queues: dict[str, list[tuple[float, int, Message]]] = {}
        self._seq = 0
        self.sent = self.delivered = self.lost = 0

    def join(self, name: str) -> None:
        """``name`` joins the network (it receives what is sent from now on)."""
        self.members.add(name)

    def leave(self, name: str) -> None:
        """``name`` leaves: it no longer sends or receives; its undelivered messages are
        dropped."""
        self.members.discard(name)
        self.silent.discard(name)
        self._queues.pop(name, None)

    def set_silent(self, name: str, silent: bool = True) -> None:
        """A fallen robot (or one getting up) sends nothing while silent."""
        if name not in self.members:
            raise ValueError(f"{name!r} has not joined the radio; members: "
                             f"{sorted(self.members)}")
        (self.silent.add if silent else self.silent.discard)(name)

    def broadcast(self, message: Message, now: float) -> int:
        """Send ``message`` at time ``now``; returns the number of receivers it will reach
        (0 from a silent robot or a non-member)."""
        if message.sender not in self.members or message.sender in self.silent:
            return 0
        if not math.isfinite(now):
            raise ValueError(f"now must be finite, got {now!r}")
        receivers = sorted(self.members - {message.sender})
        if not receivers:
            return 0
        self.sent += 1
        spec = self.spec
        # Per receiver: lost with probability ``loss``, else late by ``latency + jitter u``
        # (plain floats: a handful of receivers).
        lost = self.rng.random(len(receivers)).tolist()
        delay = self.rng.random(len(receivers)).tolist()
        reached = 0
        for name, u, v in zip(receivers, lost, delay):
            if u < spec.loss:
                self.lost += 1
                continue
            self._seq += 1
            heapq.heappush(self._queues.setdefault(name, []),
                           (now + (spec.latency + spec.jitter * v), self._seq, message))
            reached += 1
        return reached

    def receive(self, name: str, now: float) -> list[Message]:
        """The messages that reached ``name`` by time ``now``, in order of arrival."""
        queue = self._queues.get(name) if name in self.members else None
        if not queue:
            return []
        out = []
        while queue and queue[0][0] <= now:
            out.append(heapq.heappop(queue)[2])
        self.delivered += len(out)
        return out
