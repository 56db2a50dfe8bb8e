"""A match served over the league's protocols: :class:`SSLServer`.

The server owns an SSL match (:func:`soccer_env.parallel_env` with truth observations: what a
team sees comes out of the served cameras, not the environment's observation) and, per step of
``control_dt``:

1. reads every ``RobotControl`` datagram waiting on each team's robot-control socket, applies
   it (:func:`~soccer_env.protocol.robot_control.apply_robot_control`; a robot keeps its last
   command until another comes) and answers the sender with a ``RobotControlResponse``, and
   every ``SimulatorCommand`` on the simulator-control socket (teleporting the ball and the
   robots: :func:`~soccer_env.protocol.simulator_control.apply_simulator_command`), answered
   with a ``SimulatorResponse``;
2. steps the match with those commands (as actions of the match's robot model; robots off
   the field stand, as in the match);
3. publishes what the cameras delivered by then (:class:`~soccer_env.protocol.publisher.
   VisionPublisher`: the vision preset's rate, latency, noise, drops, occlusion and false
   balls) and, under the game flow, the game controller's ``Referee`` messages
   (:class:`~soccer_env.protocol.referee.RefereePublisher`).

:meth:`SSLServer.run` paces this in real time (``realtime=True``: step ``k`` at wall time
``clock + k * control_dt``, each packet sent at the wall time of its delivery) or steps as fast
as it can (stepped: the same episode for the same seed and the same commands, whatever the
machine). A datagram that is not a ``RobotControl`` is counted under its reason in
:attr:`SSLServer.dropped`, logged once per reason and dropped.

The addresses default to the league's (vision 224.5.23.2:10006, referee 224.5.23.1:10003,
robot control on ports 10301 blue and 10302 yellow and simulator control on port 10300 of every
interface); the package's tests
and examples bind and send to 127.0.0.1 only.
"""

from __future__ import annotations

import socket
import time
from collections import Counter
from collections.abc import Mapping
from typing import Any

import numpy as np

import soccer_env
from soccer_env.protocol.datagrams import PacketError, drop
from soccer_env.protocol.publisher import VisionPublisher
from soccer_env.protocol.referee import RefereePublisher
from soccer_env.protocol.robot_control import apply_robot_control, read_robot_control
from soccer_env.protocol.simulator_control import apply_simulator_command, read_simulator_command
from soccer_env.protocol.udp import (
    BLUE_CONTROL_PORT,
    MAX_DATAGRAM,
    REFEREE_ADDRESS,
    SIMULATION_CONTROL_PORT,
    VISION_ADDRESS,
    YELLOW_CONTROL_PORT,
    check_address,
    receiver,
)
from soccer_env.sim.commands import SSLRobot

__all__ = ["SSLServer"]

#: Keyword arguments the server sets on the match itself.
_OWN_KWARGS = ("obs_mode", "perception", "render_mode")


class SSLServer:
    """An SSL match served over UDP (module docstring).

    Args:
        env_kwargs: the match's keyword arguments (:func:`soccer_env.parallel_env`: team
            sizes, field, ``game``, ``control_dt``, ``match_duration``, ...), SSL robots only.
        vision: the served cameras' vision preset.
        vision_address: where the vision packets go.
        referee_address: where the referee messages go.
        control_addresses: where each team's robot control is read, ``(blue, yellow)``.
        simulator_address: where simulator control (teleporting the ball and the robots,
            :mod:`~soccer_env.protocol.simulator_control`) is read.
    """

    def __init__(self, env_kwargs: Mapping[str, Any] | None = None, vision: Any = "ssl-2012",
                 vision_address: tuple[str, int] = VISION_ADDRESS,
                 referee_address: tuple[str, int] = REFEREE_ADDRESS,
                 control_addresses: tuple[tuple[str, int], tuple[str, int]] = (
                     ("0.0.0.0", BLUE_CONTROL_PORT), ("0.0.0.0", YELLOW_CONTROL_PORT)),
                 simulator_address: tuple[str, int] = ("0.0.0.0", SIMULATION_CONTROL_PORT)
                 ) -> None:
        kwargs = dict(env_kwargs or {})
        clash = sorted(set(kwargs) & set(_OWN_KWARGS))
        if clash:
            raise ValueError(f"env_kwargs must not set {clash}: the served match's teams see "
                             "through the served cameras")
        if len(control_addresses) != 2:
            raise ValueError(f"control_addresses must be (blue, yellow) addresses, got "
                             f"{control_addresses!r}")
        check_address(vision_address, "vision_address", bind=False)
        check_address(referee_address, "referee_address", bind=False)
        for name, a in zip(("blue control address", "yellow control address",
                            "simulator_address"), (*control_addresses, simulator_address)):
            check_address(a, name)
        self.env = soccer_env.parallel_env(**kwargs)
        u = self.env.unwrapped
        self.world = u.world
        if self.world.humanoid_indices:
            self.env.close()
            raise ValueError("the SSL protocols serve matches of SSL robots; this match has "
                             "humanoids")
        self.model = SSLRobot(self.world.robot_spec)
        self.vision = VisionPublisher(self.world, vision, vision_address)
        self.referee = RefereePublisher(referee_address)
        self.controls = [receiver(a) for a in (*control_addresses, simulator_address)]
        for s in self.controls:
            s.setblocking(False)
        #: The addresses the robot control is read on, ``(blue, yellow)``, and the
        #: simulator control.
        self.control_addresses = tuple(s.getsockname()[:2] for s in self.controls[:2])
        self.simulator_address = self.controls[2].getsockname()[:2]
        self.commands = np.zeros((self.world.n_robots, 6))
        #: Datagrams dropped, by reason; commands received, and refused, by team.
        self.dropped: Counter = Counter()
        self.received = [0, 0]
        self.refused = [0, 0]
        #: Errors answered to simulator control.
        self.simulator_errors = 0
        self.clock = 0.0
        self.steps = 0
        self._headings: np.ndarray | None = None

    @property
    def time(self) -> float:
        """The match's time [s]."""
        return float(self.world.time)

    def reset(self, seed: int | None = None, clock: float | None = None) -> None:
        """Start a match from ``seed``; ``clock`` is the wall time [s] its time 0 stands for
        (default: now). The served cameras draw their noise from a generator of their own,
        seeded with ``(seed, 7)``."""
        self.env.reset(seed=seed)
        self.clock = time.time() if clock is None else float(clock)
        rng = np.random.default_rng(None if seed is None else [int(seed), 7])
        self.vision.reset(rng, self.clock)
        self.referee.reset(self.clock)
        self.commands[:] = 0.0
        self.steps = 0
        self._publish()

    def read_controls(self) -> int:
        """Apply every robot-control datagram waiting, answering each; the number applied."""
        applied = 0
        self._headings = None  # read once, when the first command comes
        for team, sock in enumerate(self.controls):
            while True:
                try:
                    data, sender = sock.recvfrom(MAX_DATAGRAM + 1)
                except (BlockingIOError, InterruptedError):
                    break
                applied += self._control(team, data, sender, sock)
        return applied

    def _control(self, team: int, data: bytes, sender: Any, sock: socket.socket) -> int:
        """Apply one datagram of ``team``'s robot control (team 2: simulator control)."""
        try:
            control = (read_robot_control if team < 2 else read_simulator_command)(data)
        except PacketError as exc:
            drop(self.dropped, exc, "a control datagram")
            return 0
        if team == 2:
            response = apply_simulator_command(control, self.world)
            self.simulator_errors += len(response.errors)
            sock.sendto(response.SerializeToString(), sender)
            return 1
        w = self.world
        first, size = (0, w.n_blue) if team == 0 else (w.n_blue, w.n_yellow)
        if self._headings is None:
            self._headings = w.snapshot().robots[:, 2]
        response = apply_robot_control(control, self.commands, first, size, self._headings,
                                       np.asarray(w.touched, dtype=bool))
        self.received[team] += 1
        self.refused[team] += len(response.errors)
        sock.sendto(response.SerializeToString(), sender)
        return 1

    def step(self) -> bool:
        """Read the commands waiting, step the match once, publish; False once the match is
        over (then :meth:`reset`)."""
        self.read_controls()
        if not self.env.agents:
            return False
        actions = self.model.actions(self.commands)
        names = self.env.unwrapped.possible_agents
        self.env.step({a: actions[i] for i, a in enumerate(names) if a in self.env.agents})
        self.steps += 1
        self.vision.step()
        self._publish()
        return bool(self.env.agents)

    def _publish(self) -> None:
        self.vision.publish(self.time)
        game = self.env.unwrapped.game
        if game is not None:
            self.referee.publish(game, tuple(self.env.unwrapped.score), self.time)

    def run(self, duration: float | None = None, realtime: bool = True) -> int:
        """Step until the match ends or ``duration`` seconds of match time have passed; in
        real time each step waits for its wall time and each camera frame is sent at the wall
        time of its delivery. The steps taken."""
        dt = float(self.world.control_dt)
        end = np.inf if duration is None else self.time + float(duration)
        taken = 0
        while self.env.agents and self.time < end - 1e-9:
            if realtime:
                self._wait_until(self.clock + self.time + dt)
            self.step()
            taken += 1
        return taken

    def _wait_until(self, wall: float) -> None:
        """Sleep until wall time ``wall``, sending each camera frame when it is delivered."""
        while True:
            now = time.time()
            due = self.vision.next_delivery()
            if due is not None and self.clock + due <= now:
                self.vision.publish(now - self.clock)
                continue
            nxt = wall if due is None else min(wall, self.clock + due)
            if nxt <= now:
                return
            time.sleep(nxt - now)

    def close(self) -> None:
        self.vision.close()
        self.referee.close()
        for s in self.controls:
            s.close()
        self.env.close()
