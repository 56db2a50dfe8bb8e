"""A team's software on the league's protocols: :class:`SSLClient`.

The client reads live ``SSL_WrapperPacket`` s and ``Referee`` messages from any source that
speaks them (``soccer-env serve``, grSim, the ER-Force simulator, a real field), runs the
package's SSL perception on them (the pipeline of the environment the policy was made for:
its ball filter, its robot trackers, its prediction ahead by the actuation latency), builds
the policy's observation from the belief exactly as the environment does, and sends the
policy's commands through the simulation protocol's robot control.

What it plays (``task``; :mod:`agents.live.players`):

* ``"goalkeeper"`` or ``"shootout"``: the task's learner, blue robot 0, with a policy of
  :func:`~agents.runs.resolve.make_policy` (``"scripted"``, ``"baseline:NAME"``, a numpy
  policy file, a run folder). Each shot starts with the referee's ``PREPARE_PENALTY``: the
  pipeline starts afresh there (as the environment's does at its reset), from the frames
  delivered from that moment on.
* ``"match"``: every robot of one ``team`` of a match without the game flow, with a team
  policy (``"scripted"``, ``"idle"``, a shipped team, a numpy team file). Its observations'
  game block comes from the referee: the match time from the stage's time left, the score,
  and the team of a ``DIRECT_FREE`` restart not yet taken (how ``soccer-env serve`` sends the
  simple referee's restarts).

Time: every time is the source's (the packets' ``t_capture`` and ``t_sent``, the referee's
``packet_timestamp``), counted from the first referee message. :meth:`SSLClient.step` waits
for a referee message and acts at its time: against a stepped ``soccer-env serve`` (a message
after every step, as in the game controller's CI mode) the client runs in lock step with the
server and plays the same episode as in process for the same frames. :meth:`SSLClient.run`
in real time acts every control step at the present wall time (the source's clock must be
this machine's: a simulator on the same host, or a field whose vision is time-synchronised).
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Mapping
from typing import Any

import numpy as np
from ssl_protocol.sim import ssl_simulation_robot_feedback_pb2 as feedback_pb2
from ssl_protocol.state import ssl_gc_referee_message_pb2 as referee_pb2

from agents.live.players import TEAM_NAMES, RefereeView, TaskPlayer, TeamPlayer
from soccer_env.protocol.datagrams import PacketError, drop, parse
from soccer_env.protocol.reader import RefereeReader, VisionReader
from soccer_env.protocol.robot_control import robot_control
from soccer_env.protocol.udp import (
    BLUE_CONTROL_PORT,
    MAX_DATAGRAM,
    REFEREE_ADDRESS,
    VISION_ADDRESS,
    check_address,
    sender,
)

__all__ = ["CLIENT_TASKS", "SSLClient"]

#: What the client plays.
CLIENT_TASKS = ("goalkeeper", "shootout", "match")
_PREPARE = {referee_pb2.Referee.PREPARE_PENALTY_BLUE, referee_pb2.Referee.PREPARE_PENALTY_YELLOW}
_FREE = {referee_pb2.Referee.DIRECT_FREE_BLUE: 0, referee_pb2.Referee.DIRECT_FREE_YELLOW: 1}
US = 1e-6


class SSLClient:
    """The package's perception and a policy on live SSL protocols (module docstring).

    Args:
        policy: what acts: for a task :func:`~agents.runs.resolve.make_policy`'s references
            (or a callable from observation to action); for a match a team policy
            (:class:`~agents.live.players.TeamPlayer`).
        task: what is played (:data:`CLIENT_TASKS`).
        env_kwargs: the keyword arguments of the environment the policy was made for
            (``obs_mode`` "perceived", the default, or "raw"; ``perception``;
            ``control_dt``, which must be the source's): its perception runs on the packets.
        vision_address: where SSL-Vision is received.
        referee_address: where the referee messages are received.
        control_address: where the robot control goes (the simulator's team port).
        interface: the interface multicast groups are joined on.
        trust: passed to :func:`~agents.runs.resolve.make_policy`.
        team: the team played in a match, ``"blue"`` or ``"yellow"`` (a task's learner is
            blue).
    """

    def __init__(self, policy: Any = "scripted", task: str = "goalkeeper",
                 env_kwargs: Mapping[str, Any] | None = None,
                 vision_address: tuple[str, int] = VISION_ADDRESS,
                 referee_address: tuple[str, int] = REFEREE_ADDRESS,
                 control_address: tuple[str, int] = ("127.0.0.1", BLUE_CONTROL_PORT),
                 interface: str = "0.0.0.0", trust: bool = False, team: str = "blue") -> None:
        if task not in CLIENT_TASKS:
            raise ValueError(f"task must be one of {list(CLIENT_TASKS)}, got {task!r}")
        if team not in TEAM_NAMES or (task != "match" and team != "blue"):
            raise ValueError(f"team must be 'blue' for a task (its learner) and one of "
                             f"{list(TEAM_NAMES)} for a match, got {team!r}")
        kwargs = {"obs_mode": "perceived", **dict(env_kwargs or {})}
        if kwargs["obs_mode"] not in ("perceived", "raw"):
            raise ValueError(f"env_kwargs obs_mode must be 'perceived' or 'raw' (a live "
                             f"team sees through its cameras), got {kwargs['obs_mode']!r}")
        if "render_mode" in kwargs:
            raise ValueError("env_kwargs must not set render_mode: the client draws nothing")
        self.control_address = check_address(control_address, "control_address", bind=False)
        self.task = task
        self.player: TaskPlayer | TeamPlayer = (
            TeamPlayer(team, kwargs, policy) if task == "match"
            else TaskPlayer(task, kwargs, policy, trust))
        self.pipeline = self.player.pipeline
        w = self.player.world
        self.control_dt = float(w.control_dt)
        self._duration = float(getattr(self.player.env.unwrapped, "match_duration", 0.0))
        self.vision = VisionReader((w.n_blue, w.n_yellow), vision_address, interface=interface)
        self.referee = RefereeReader(referee_address, interface)
        self.sock = sender(self.control_address)
        self.sock.setblocking(False)
        #: The source's time [s] of the latest referee message, counted from the first.
        self.now: float | None = None
        self._origin: float | None = None
        self._start: tuple[int, int] | None = None  # the present shot's (counter, timestamp)
        self._since = 0.0  # frames delivered before this belong to an earlier shot
        #: What a match team reads of the referee.
        self.view = RefereeView(0.0, (0, 0), -1)
        #: Shots started, the latest score ``(blue, yellow)``, commands sent, the errors the
        #: source answered them with (by code), responses it could not read.
        self.shots = 0
        self.score = (0, 0)
        self.sent = 0
        self.errors: Counter = Counter()
        self.dropped: Counter = Counter()

    def _take(self, messages: list[Any]) -> None:
        """Follow the referee: the time, the score, and each shot's start."""
        for msg in messages:
            stamp = msg.packet_timestamp * US
            if self._origin is None:
                self._origin = stamp
                self.vision.clock = stamp
                self.pipeline.restart(0.0)
            self.now = stamp - self._origin
            self.score = (int(msg.blue.score), int(msg.yellow.score))
            self.view = RefereeView(max(0.0, self._duration - msg.stage_time_left * US),
                                    self.score, _FREE.get(msg.command, -1))
            key = (int(msg.command_counter), int(msg.command_timestamp))
            if msg.command in _PREPARE and key != self._start:
                self._start = key
                self._since = msg.command_timestamp * US - self._origin
                self.pipeline.restart(self._since)
                self.player.restart()
                self.shots += 1

    def _see(self, now: float) -> None:
        frames = [f for f in self.vision.poll() if f.t_delivered >= self._since - 1e-5]
        self.pipeline.consume(frames, now)

    def act(self, now: float) -> np.ndarray:
        """The policy's actions on the belief at ``now`` [s], sent as robot control; the
        physical commands sent ``(k, 6)``, robots :attr:`ids`."""
        seen, _ = self.pipeline.beliefs(now)
        commands = self.player.commands(seen, self.view)
        if getattr(self.pipeline, "history", None) is not None:
            self.pipeline.command(now + self.pipeline.ahead, commands)
        self.sock.sendto(robot_control(commands, self.player.ids).SerializeToString(),
                         self.control_address)
        self.sent += 1
        self._responses()
        return commands

    def _responses(self) -> None:
        while True:
            try:
                data = self.sock.recv(MAX_DATAGRAM + 1)
            except (BlockingIOError, InterruptedError, ConnectionRefusedError):
                return
            try:
                response = parse(data, feedback_pb2.RobotControlResponse)
            except PacketError as exc:
                drop(self.dropped, exc, "a robot-control response")
                continue
            for err in response.errors:
                self.errors[err.code] += 1

    def step(self, timeout: float = 1.0) -> bool:
        """Wait up to ``timeout`` [s] for the source's next referee message, take the frames
        delivered by its time and act at it; False if none came."""
        messages = self.referee.poll(timeout)
        if not messages:
            return False
        self._take(messages)
        assert self.now is not None
        self._see(self.now)
        self.act(self.now)
        return True

    def run(self, duration: float, realtime: bool = True, timeout: float = 1.0) -> int:
        """Play for ``duration`` seconds of the source's time: in real time one action every
        control step of wall time at the present (after the first referee message), else
        :meth:`step` after step (stopping early when the source falls silent for
        ``timeout``). The actions taken."""
        taken = 0
        if not realtime:
            first = None
            while self.step(timeout):
                taken += 1
                first = self.now if first is None else first
                if self.now - first >= duration - 1e-9:
                    break
            return taken
        while self._origin is None:
            messages = self.referee.poll(timeout)
            if not messages:
                return 0
            self._take(messages)
        end = time.time() + duration
        tick = time.time()
        while tick < end:
            self._take(self.referee.poll())
            now = time.time() - self._origin
            self._see(now)
            self.act(now)
            taken += 1
            tick += self.control_dt
            time.sleep(max(0.0, tick - time.time()))
        return taken

    @property
    def ids(self) -> list[int]:
        """The numbers, in the team, of the robots the client commands."""
        return list(self.player.ids)

    def close(self) -> None:
        for part in (self.vision, self.referee):
            part.close()
        self.sock.close()
        self.player.close()
