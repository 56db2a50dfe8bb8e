"""The game controller's state as the league's ``Referee`` message: :func:`referee_message`
and :class:`RefereePublisher`.

The SSL game controller of a match (:class:`~soccer_env.sim.game.controller.GameController`,
``env.game`` of a match with ``game=True``) maps onto the message one to one where the
package models the rule: the command (and the team it is for), the designated position of a
placement or free kick [mm], the next command, the stage and its time left [us], and per team
its score, fouls, yellow cards (with their time left [us]), red cards, placement failures and
whether it may still place the ball. Our world has blue attack ``+x`` in both halves, so
``blue_team_on_positive_half`` is false. What the package does not model goes out as the
protocol's neutral value: no ``HALT``, no timeouts (``timeouts`` and ``timeout_time`` 0), no
game events, team names ``"blue"`` and ``"yellow"``. Each team's keeper is its robot 0.

The game controller sends a message whenever the command changes and otherwise about every
100 ms; :class:`RefereePublisher` counts commands (``command_counter``) and stamps them with
the time they were given (``command_timestamp``).
"""

from __future__ import annotations

import math
import socket
from dataclasses import dataclass, field
from typing import Any

from ssl_protocol.state import ssl_gc_referee_message_pb2 as referee_pb2

from soccer_env.protocol.datagrams import PacketError, parse
from soccer_env.protocol.udp import REFEREE_ADDRESS, destinations, sender

__all__ = ["REFEREE_PERIOD", "TeamRecord", "PlainGame", "referee_message", "read_referee",
           "RefereePublisher"]

#: Seconds between referee messages while the command stays the same.
REFEREE_PERIOD = 0.1
#: Microseconds per second: the message's times are microseconds.
US = 1_000_000
_STAGES = {"first_half": "NORMAL_FIRST_HALF", "second_half": "NORMAL_SECOND_HALF",
           "post_game": "POST_GAME", "penalty_shootout": "PENALTY_SHOOTOUT"}
#: Commands given to a team, by our name: the message's name without its colour.
_TEAM_COMMANDS = {"ball_placement": "BALL_PLACEMENT", "prepare_kickoff": "PREPARE_KICKOFF",
                  "prepare_penalty": "PREPARE_PENALTY", "direct_free": "DIRECT_FREE"}
_TEAM_NAMES = ("blue", "yellow")


@dataclass
class TeamRecord:
    """A team's record in a :class:`PlainGame`: no cards, fouls or failed placements."""

    red_cards: int = 0
    yellow_cards: tuple[float, ...] = ()
    fouls: int = 0
    placement_failures: int = 0
    can_place: bool = True


@dataclass
class PlainGame:
    """The referee's state of what is served without a game controller, in the game
    controller's terms for :func:`referee_message`: a match without the game flow is one
    first half of ``FORCE_START`` (play on, no rules called); a keeper or shootout task is a
    ``PENALTY_SHOOTOUT`` whose every shot starts with ``PREPARE_PENALTY`` for the attacking
    team (``command_team``: 0 blue, 1 yellow) and goes on with ``NORMAL_START`` once it is
    taken."""

    stage: str = "first_half"
    stage_time_left: float = 0.0
    command: str = "force_start"
    command_team: int = 0
    next_command: tuple[str, int] | None = None
    designated: tuple[float, float] | None = None
    team_info: tuple[TeamRecord, TeamRecord] = field(
        default_factory=lambda: (TeamRecord(), TeamRecord()))


def _command(name: str, team: int) -> int:
    """The message's ``Command`` value of our command ``name`` for ``team`` (0 blue, 1
    yellow)."""
    if name in _TEAM_COMMANDS:
        return referee_pb2.Referee.Command.Value(
            f"{_TEAM_COMMANDS[name]}_{_TEAM_NAMES[team].upper()}")
    return referee_pb2.Referee.Command.Value(name.upper())


def referee_message(game: Any, score: tuple[int, int], time: float, clock: float,
                    command_counter: int, command_time: float) -> referee_pb2.Referee:
    """The ``Referee`` message of ``game`` (an SSL game controller) at episode time ``time``
    [s]; ``clock`` the wall time [s] of episode time 0; ``command_counter`` and
    ``command_time`` [s, episode time] the count of commands given so far and when the present
    one was (module docstring)."""
    msg = referee_pb2.Referee()
    msg.source_identifier = "soccer_env"
    msg.packet_timestamp = round((clock + time) * US)
    msg.stage = referee_pb2.Referee.Stage.Value(_STAGES[game.stage])
    msg.stage_time_left = round(game.stage_time_left * US)
    msg.command = _command(game.command, game.command_team)
    msg.command_counter = int(command_counter)
    msg.command_timestamp = round((clock + command_time) * US)
    if game.next_command is not None:
        msg.next_command = _command(*game.next_command)
    if game.designated is not None:
        msg.designated_position.x = float(game.designated[0]) * 1000.0
        msg.designated_position.y = float(game.designated[1]) * 1000.0
    msg.blue_team_on_positive_half = False
    for t, info in enumerate(game.team_info):
        team = msg.blue if t == 0 else msg.yellow
        team.name = _TEAM_NAMES[t]
        team.score = int(score[t])
        team.red_cards = int(info.red_cards)
        team.yellow_card_times.extend(max(0, round(s * US)) for s in info.yellow_cards)
        team.yellow_cards = len(info.yellow_cards)
        team.timeouts = team.timeout_time = 0
        team.goalkeeper = 0
        team.foul_counter = int(info.fouls)
        team.ball_placement_failures = int(info.placement_failures)
        team.can_place_ball = bool(info.can_place)
    return msg


def read_referee(data: bytes) -> referee_pb2.Referee:
    """Parse and check one ``Referee`` datagram; raises
    :class:`~soccer_env.protocol.datagrams.PacketError` (``"oversized"``, ``"malformed"``,
    ``"incomplete"``, or ``"out of range"`` for a designated position that is not finite)."""
    msg = parse(data, referee_pb2.Referee)
    if msg.HasField("designated_position") and not (
            math.isfinite(msg.designated_position.x)
            and math.isfinite(msg.designated_position.y)):
        raise PacketError("out of range", "the designated position is not finite")
    return msg


class RefereePublisher:
    """Sends a match's ``Referee`` messages to ``address`` (default: the league's multicast
    group and port; a list of addresses: to each): at every change of command and every
    :data:`REFEREE_PERIOD` seconds of episode time otherwise. ``sock``: a socket to send
    through (default: a new one, closed by :meth:`close`)."""

    def __init__(self, address: tuple[str, int] = REFEREE_ADDRESS,
                 sock: socket.socket | None = None) -> None:
        #: Every address the packets go to (:func:`~soccer_env.protocol.udp.destinations`),
        #: and the first.
        self.addresses = destinations(address)
        self.address = self.addresses[0]
        self._own = sock is None
        self.sock = sender(self.address) if sock is None else sock
        self.reset()

    def reset(self, clock: float = 0.0, count_on: bool = False) -> None:
        """A new episode whose time 0 is wall time ``clock`` [s]; with ``count_on`` the next
        of a series (a task's next shot): the command counter goes on, and the episode's
        first command counts as a new one."""
        self.clock = float(clock)
        self._command_time = 0.0
        self._next = -math.inf
        if count_on:
            self._last: tuple[str, int] | None = ("", -1)
            return
        self.counter = 0
        self._last = None
        self.sent = 0

    def publish(self, game: Any, score: tuple[int, int], time: float, force: bool = False
                ) -> bool:
        """Send the message of ``game`` (a game controller or a :class:`PlainGame`) at
        episode time ``time`` if the command changed, the period has come round or
        ``force``; whether one was sent."""
        key = (game.command, game.command_team)
        changed = key != self._last
        if changed:
            self.counter += 1 if self._last is not None else 0
            self._last, self._command_time = key, float(time)
        if not (changed or force) and time < self._next:
            return False
        msg = referee_message(game, score, time, self.clock, self.counter, self._command_time)
        data = msg.SerializeToString()
        for address in self.addresses:
            self.sock.sendto(data, address)
        self._next = float(time) + REFEREE_PERIOD
        self.sent += 1
        return True

    def close(self) -> None:
        if self._own:
            self.sock.close()
