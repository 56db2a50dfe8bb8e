"""The game controller's state as ``Referee`` messages (soccer_env.protocol.referee), sent over
loopback (127.0.0.1) while scripted teams play the SSL game flow: the commands read back are
the game controller's, in order, counted and time-stamped when given; the score and the
designated position follow the match; bad datagrams are refused with their reason."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("ssl_protocol")

from ssl_protocol.state import ssl_gc_referee_message_pb2 as referee_pb2  # noqa: E402

import soccer_env  # noqa: E402
from agents.scripted import ScriptedTeam  # noqa: E402
from soccer_env.protocol.referee import (  # noqa: E402
    REFEREE_PERIOD,
    RefereePublisher,
    read_referee,
)
from soccer_env.protocol.udp import receiver  # noqa: E402
from soccer_env.protocol.vision import PacketError  # noqa: E402

CMD = referee_pb2.Referee.Command


def test_a_game_flow_match_is_refereed_over_loopback():
    env = soccer_env.parallel_env(blue=2, yellow=2, game=True, match_duration=20.0,
                                  control_dt=1 / 30)
    obs, _ = env.reset(seed=5)
    game = env.unwrapped.game
    teams = [ScriptedTeam.for_env(env, side) for side in ("blue", "yellow")]
    sock = receiver(("127.0.0.1", 0), timeout=1.0)
    pub = RefereePublisher(sock.getsockname()[:2])
    pub.reset(clock=500.0)
    given, messages = [], []
    try:
        for _ in range(900):  # 30 s of match time
            time = env.unwrapped.world.time
            key = (game.command, game.command_team)
            if not given or given[-1][0] != key:
                given.append((key, time))
            if pub.publish(game, tuple(env.unwrapped.score), time):
                messages.append(read_referee(sock.recv(65_536)))
            actions = {}
            for t in teams:
                actions.update(t(obs))
            obs, *_ = env.step(actions)
            if not env.agents:
                break
    finally:
        pub.close()
        sock.close()
    assert len(given) >= 4  # a kick-off, play, and at least one stoppage
    commands = []
    for m in messages:
        if not commands or commands[-1][0] != m.command_counter:
            commands.append((m.command_counter, m.command, m.command_timestamp))
    assert [c[0] for c in commands] == list(range(len(given)))
    for (_, command, stamp), ((name, team), t) in zip(commands, given):
        want = name.upper() if name in ("stop", "normal_start", "force_start") else \
            f"{name.upper()}_{('BLUE', 'YELLOW')[team]}"
        assert CMD.Name(command) == want
        assert stamp == round((500.0 + t) * 1e6)
    # between changes, one message every 100 ms
    stamps = np.array([m.packet_timestamp for m in messages]) / 1e6
    assert np.diff(stamps).max() <= REFEREE_PERIOD + 1 / 30 + 1e-6
    last = messages[-1]
    assert (last.blue.score, last.yellow.score) == tuple(env.unwrapped.score)
    assert not last.blue_team_on_positive_half


@pytest.mark.parametrize("data, reason", [
    (b"\xff\xff\xff", "malformed"),
    (referee_pb2.Referee(packet_timestamp=1).SerializePartialToString(), "incomplete"),
    (b"\x00" * 20_000, "oversized"),
])
def test_bad_referee_datagrams_are_refused_with_their_reason(data, reason):
    with pytest.raises(PacketError) as exc:
        read_referee(data)
    assert exc.value.reason == reason
