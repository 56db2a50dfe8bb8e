"""A match or a task served over the league's protocols: :class:`SSLServer`.

The server owns what it serves (:mod:`~soccer_env.protocol.served`: an SSL match, or the
keeper's or the shootout's task, with true observations: what a team sees comes out of the
served cameras, not the environment's observation) and, per step of ``control_dt``:

1. reads every ``RobotControl`` datagram waiting on each team's robot-control socket, applies
   it (:func:`~soccer_env.protocol.robot_control.apply_robot_control`; a robot keeps its last
   command until another comes) and answers the sender with a ``RobotControlResponse``, and
   every ``SimulatorCommand`` on the simulator-control socket (teleporting the ball and the
   robots: :func:`~soccer_env.protocol.simulator_control.apply_simulator_command`), answered
   with a ``SimulatorResponse``;
2. steps with those commands (as actions of the robot model; they take effect after the
   vision preset's actuation latency, as in process; robots off the field stand, as in the
   match);
3. publishes what the cameras delivered by then (:class:`~soccer_env.protocol.publisher.
   VisionPublisher`: the vision preset's rate, latency, noise, drops, occlusion and false
   balls) and the referee's ``Referee`` messages
   (:class:`~soccer_env.protocol.referee.RefereePublisher`: the game controller's under the
   game flow, else :class:`~soccer_env.protocol.referee.PlainGame`'s).

:meth:`SSLServer.run` paces this in real time (``realtime=True``: step ``k`` at wall time
``clock + k * control_dt``, each packet sent at the wall time of its delivery) or steps as fast
as the teams it waits for send their commands (stepped: the same episode for the same seed and
the same commands, whatever the machine; a referee message after every step carries its time,
as the game controller's CI mode does). A task serves one shot after another, seeded ``seed``,
``seed + 1``, ... (:attr:`SSLServer.outcomes`). A datagram that is not a ``RobotControl`` is
counted under its reason in :attr:`SSLServer.dropped`, logged once per reason and dropped.

The addresses default to the league's (vision 224.5.23.2:10006, referee 224.5.23.1:10003,
robot control on ports 10301 blue and 10302 yellow and simulator control on port 10300 of every
interface); the package's tests and examples bind and send to 127.0.0.1 only.
"""

from __future__ import annotations

import select
import socket
import time
from collections import Counter
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from soccer_env.presets.sensors import vision as vision_preset
from soccer_env.protocol.datagrams import PacketError, drop
from soccer_env.protocol.publisher import VisionPublisher
from soccer_env.protocol.referee import RefereePublisher
from soccer_env.protocol.robot_control import apply_robot_control, read_robot_control
from soccer_env.protocol.served import served
from soccer_env.protocol.simulator_control import apply_simulator_command, read_simulator_command
from soccer_env.protocol.udp import (
    BLUE_CONTROL_PORT,
    MAX_DATAGRAM,
    REFEREE_ADDRESS,
    SIMULATION_CONTROL_PORT,
    VISION_ADDRESS,
    YELLOW_CONTROL_PORT,
    check_address,
    destinations,
    receiver,
)
from soccer_env.sim.commands import SSLRobot

__all__ = ["SSLServer"]

#: Keyword arguments the server sets on the match itself.
_OWN_KWARGS = ("obs_mode", "perception", "render_mode")
#: The teams, in the order of the robot-control sockets.
_TEAMS = ("blue", "yellow")


class SSLServer:
    """A match or a task served over UDP (module docstring).

    Args:
        env_kwargs: the served environment's keyword arguments (the match's,
            :func:`soccer_env.parallel_env`: team sizes, field, ``game``, ``control_dt``,
            ``match_duration``, ...; or the task's), SSL robots only.
        vision: the served cameras' vision preset (also the robots' actuation latency and
            command loss).
        vision_address: where the vision packets go (a list of addresses: to each, e.g. one
            per team's software on loopback).
        referee_address: where the referee messages go (likewise).
        control_addresses: where each team's robot control is read, ``(blue, yellow)``.
        simulator_address: where simulator control (teleporting the ball and the robots,
            :mod:`~soccer_env.protocol.simulator_control`) is read.
        task: what is served (:data:`~soccer_env.protocol.served.SERVED`): ``"match"``,
            ``"goalkeeper"`` or ``"shootout"`` (robot control commands the task's learner,
            blue robot 0; the task plays the rest, one shot an episode, back to back).
    """

    def __init__(self, env_kwargs: Mapping[str, Any] | None = None, vision: Any = "ssl-2012",
                 vision_address: Any = VISION_ADDRESS,
                 referee_address: Any = REFEREE_ADDRESS,
                 control_addresses: tuple[tuple[str, int], tuple[str, int]] = (
                     ("0.0.0.0", BLUE_CONTROL_PORT), ("0.0.0.0", YELLOW_CONTROL_PORT)),
                 simulator_address: tuple[str, int] = ("0.0.0.0", SIMULATION_CONTROL_PORT),
                 task: str = "match") -> None:
        kwargs = dict(env_kwargs or {})
        clash = sorted(set(kwargs) & set(_OWN_KWARGS))
        if clash:
            raise ValueError(f"env_kwargs must not set {clash}: the served match's teams see "
                             "through the served cameras")
        if len(control_addresses) != 2:
            raise ValueError(f"control_addresses must be (blue, yellow) addresses, got "
                             f"{control_addresses!r}")
        destinations(vision_address, "vision_address")
        destinations(referee_address, "referee_address")
        for name, a in zip(("blue control address", "yellow control address",
                            "simulator_address"), (*control_addresses, simulator_address)):
            check_address(a, name)
        spec = vision_preset(vision)
        self.served = served(task, kwargs, spec)
        self.task = task
        self.env = self.served.env
        self.world = self.served.world
        self.model = SSLRobot(self.world.robot_spec)
        self.vision = VisionPublisher(self.world, spec, vision_address)
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
        #: Steps a stepped run took without a team's command (it waited ``timeout``).
        self.missed = 0
        #: A task's outcome of every shot served, in order.
        self.outcomes: list[str] = []
        self.clock = 0.0
        self.steps = 0
        self.seed: int | None = None
        self._headings: np.ndarray | None = None
        self._realtime = False
        self._last_shot = np.inf  # the shots a run serves

    @property
    def time(self) -> float:
        """The episode's time [s]."""
        return float(self.world.time)

    def reset(self, seed: int | None = None, clock: float | None = None) -> None:
        """Start a match (a task: its first shot) from ``seed``; ``clock`` is the wall time
        [s] its time 0 stands for (default: now). The served cameras draw their noise from a
        generator of their own, seeded with ``(seed, 7)``. A task's later shots are seeded
        ``seed + 1``, ``seed + 2``, ..."""
        self.outcomes = []
        self._start(seed, time.time() if clock is None else float(clock), count_on=False)

    def _start(self, seed: int | None, clock: float, count_on: bool) -> None:
        self.seed = seed
        self.served.reset(seed)
        self.clock = clock
        rng = np.random.default_rng(None if seed is None else [int(seed), 7])
        self.vision.reset(rng, self.clock)
        self.referee.reset(self.clock, count_on)
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
        first = 0 if team == 0 else w.n_blue
        if self._headings is None:
            self._headings = w.snapshot().robots[:, 2]
        response = apply_robot_control(control, self.commands, first, self.served.sizes[team],
                                       self._headings, np.asarray(w.touched, dtype=bool))
        self.received[team] += 1
        self.refused[team] += len(response.errors)
        sock.sendto(response.SerializeToString(), sender)
        return 1

    def wait_for(self, teams: Sequence[str], timeout: float = 1.0) -> bool:
        """Apply the datagrams waiting until a ``RobotControl`` of each of ``teams``
        (``"blue"``, ``"yellow"``) has come, for up to ``timeout`` seconds of wall time;
        whether they all came (else :attr:`missed` counts the step)."""
        index = [_TEAMS.index(t) for t in teams]
        before = list(self.received)
        deadline = time.monotonic() + timeout
        while True:
            self.read_controls()
            waiting = [self.controls[i] for i in index if self.received[i] == before[i]]
            if not waiting:
                return True
            left = deadline - time.monotonic()
            if left <= 0 or not select.select(waiting, [], [], left)[0]:
                self.missed += 1
                return False

    def step(self) -> bool:
        """Read the commands waiting, step once, publish; False once the match is over (then
        :meth:`reset`). A task's next shot starts as soon as one is over (in :meth:`run`,
        unless it was the last of its ``episodes``)."""
        self.read_controls()
        if not self.served.running:
            return False
        outcome = self.served.step(self.model.actions(self.commands))
        self.steps += 1
        self.vision.step()
        if outcome is None or self.served.kind != "task":
            self._publish()
        else:  # the shot is over: its last frames, then the next shot's referee message only
            self.vision.publish(self.time)
            self.outcomes.append(outcome)
            if len(self.outcomes) >= self._last_shot:  # the run's last: STOP, the score
                self.served.finish()
                game, score = self.served.referee()
                self.referee.publish(game, score, self.time, force=True)
                return False
            # Stepped, the next shot's time 0 comes one step after this one's end.
            clock = (time.time() if self._realtime
                     else self.clock + self.time + float(self.world.control_dt))
            nxt = None if self.seed is None else self.seed + 1
            self._start(nxt, clock, count_on=True)
        return self.served.running

    def _publish(self) -> None:
        self.vision.publish(self.time)
        game, score = self.served.referee()
        # Stepped, a message every step stamps the step's time, as the game controller's CI
        # mode does for a simulator that sets the time.
        self.referee.publish(game, score, self.time, force=not self._realtime)

    def run(self, duration: float | None = None, realtime: bool = True,
            episodes: int | None = None, wait_for: Sequence[str] = (),
            timeout: float = 1.0) -> int:
        """Step until the match ends (a task: ``episodes`` shots are over, default no end),
        or ``duration`` seconds of served time have passed; the steps taken.

        In real time each step waits for its wall time and each camera frame is sent at the
        wall time of its delivery. Stepped, each step first waits up to ``timeout`` [s] for a
        command from each of the teams ``wait_for`` (:meth:`wait_for`; none: as fast as it
        can), and a referee message goes out after every step, stamped with its time."""
        for t in wait_for:
            if t not in _TEAMS:
                raise ValueError(f"wait_for must name teams of {list(_TEAMS)}, got {t!r}")
        self._realtime = bool(realtime)
        dt = float(self.world.control_dt)
        left = np.inf if duration is None else float(duration)
        goal = np.inf if episodes is None else len(self.outcomes) + int(episodes)
        self._last_shot = goal
        taken = 0
        try:
            while self.served.running and left > 1e-9 and len(self.outcomes) < goal:
                if realtime:
                    self._wait_until(self.clock + self.time + dt)
                elif wait_for:
                    self.wait_for(wait_for, timeout)
                self.step()
                taken += 1
                left -= dt
        finally:
            self._last_shot = np.inf
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
