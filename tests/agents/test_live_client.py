"""The closed loop over loopback sockets (127.0.0.1 only): a served keeper task, our client's
perception and a policy on its packets, the policy's commands back through robot control.

The served shots are the in-process shots of the same seeds (an idle keeper concedes exactly
the same goals); the scripted keeper through the sockets saves as it does in process; the
stepped loop plays the same shots for the same seed; bad datagrams are counted and dropped
without stopping the client."""

from __future__ import annotations

import socket

import pytest

pytest.importorskip("ssl_protocol")

from agents.live import SSLClient, locked_match, play_locked  # noqa: E402
from agents.runs.evaluation import evaluate  # noqa: E402
from soccer_env.protocol.server import SSLServer  # noqa: E402

LOOPBACK = ("127.0.0.1", 0)
KWARGS = {"control_dt": 0.04, "obs_mode": "perceived", "perception": "ssl-2012"}


def _closed_loop(policy: str, shots: int, seed: int = 0, task: str = "goalkeeper",
                 bad: list[bytes] = ()):
    """``shots`` shots of ``task`` from ``seed`` served stepped, ``policy`` playing through
    the client; the server's outcomes and the client."""
    client = SSLClient(policy, task, KWARGS, LOOPBACK, LOOPBACK, ("127.0.0.1", 9))
    server = SSLServer({"control_dt": KWARGS["control_dt"]}, KWARGS["perception"],
                       client.vision.address, client.referee.address, (LOOPBACK, LOOPBACK),
                       LOOPBACK, task=task)
    client.control_address = server.control_addresses[0]
    try:
        server.reset(seed=seed, clock=0.0)
        noise = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        noise.bind(LOOPBACK)
        for data in bad:  # arrive before the first packets are read
            for address in (client.vision.address, client.referee.address):
                noise.sendto(data, address)
        noise.close()
        play_locked(server, [client], episodes=shots)
        assert server.missed == 0  # lock step: every step waited for the client's command
        return list(server.outcomes), client
    finally:
        server.close()
        client.close()


def _saves(outcomes: list[str]) -> int:
    return sum(o not in ("goal", "time limit") for o in outcomes)


def test_the_served_shots_are_the_in_process_shots_of_the_same_seeds():
    served, client = _closed_loop("idle", 30, seed=100)
    local = evaluate("idle", KWARGS, 30, 100)
    assert [o != "goal" for o in served] == local.saved
    assert client.shots == 30 and client.score == (0, served.count("goal"))
    assert client.sent > 30 * 5 and not client.errors


def test_the_scripted_keeper_saves_through_the_sockets_as_in_process():
    shots = 150
    served, _ = _closed_loop("scripted", shots, seed=1000)
    local = evaluate("scripted", KWARGS, shots, 1000)
    idle = evaluate("idle", KWARGS, shots, 1000)
    rate = _saves(served) / shots
    # a keeper that played blind would save what the idle one saves; the two loops draw
    # their camera noise from different streams, so the rates agree within sampling error
    assert rate > idle.save_rate + 0.1
    assert abs(rate - local.save_rate) < 0.1


def test_the_stepped_closed_loop_plays_the_same_shots_for_the_same_seed():
    a, _ = _closed_loop("scripted", 12, seed=7)
    b, _ = _closed_loop("scripted", 12, seed=7)
    assert a == b and len(a) == 12


def test_bad_datagrams_are_counted_and_dropped_and_the_client_plays_on():
    bad = [b"\xff\x00garbage", b"x" * 20_000, b"\x08" * 40]
    served, client = _closed_loop("scripted", 6, seed=3, bad=bad)
    assert len(served) == 6 and client.shots == 6
    assert sum(client.vision.dropped.values()) >= 2
    assert sum(client.referee.dropped.values()) >= 2


def test_the_shootout_is_played_through_the_client():
    served, client = _closed_loop("idle", 4, task="shootout")
    # an idle attacker never scores: every shot ends without a goal
    assert len(served) == 4 and "goal" not in served and client.shots == 4


@pytest.mark.parametrize("kwargs, message", [
    ({"task": "penalties"}, "task must be one of"),
    ({"team": "yellow"}, "team must be .blue. for a task"),
    ({"task": "match", "env_kwargs": {"game": True}}, "game flow"),
    ({"env_kwargs": {"obs_mode": "truth"}}, "obs_mode must be 'perceived' or 'raw'"),
    ({"env_kwargs": {"robot": "humanoid"}}, "humanoids"),
    ({"control_address": ("224.5.23.2", 0)}, "control_address port must be"),
    ({"policy": "nonsense.txt"}, "policy must be one of"),
])
def test_bad_arguments_are_refused(kwargs, message):
    args = {"vision_address": LOOPBACK, "referee_address": LOOPBACK,
            "control_address": ("127.0.0.1", 9), **kwargs}
    with pytest.raises(ValueError, match=message):
        SSLClient(**args)


def _served_match(blue: str, yellow: str, seed: int, duration: float = 30.0):
    """A 2 vs 2 match without the game flow through the sockets (``realistic`` cameras),
    each team played by a client of its own."""
    base = {"blue": 2, "yellow": 2, "match_duration": duration, "control_dt": 1 / 30}
    match = locked_match(blue, yellow, base, "realistic", seed)
    assert match.missed == 0 and not any(match.errors)
    return match


def test_match_teams_play_through_the_sockets_as_in_process():
    from agents.studies.matches import Side, play_match

    base = {"blue": 2, "yellow": 2, "match_duration": 30.0, "control_dt": 1 / 30}
    side = {"obs_mode": "perceived", "perception": {"vision": "realistic"}}
    served = [_served_match("scripted", "idle", seed).score for seed in (1, 2)]
    local = [play_match(base, Side("scripted", **side), Side("idle", **side), seed)["goals"]
             for seed in (1, 2)]
    # the scripted team scores against a team that stands, through the sockets as in process
    # (each counted from its own camera noise); the idle team never scores
    assert sum(s[0] for s in served) >= 3 and all(s[1] == 0 for s in served)
    assert abs(sum(s[0] for s in served) - sum(g[0] for g in local)) <= 4


def test_a_served_match_is_the_same_for_the_same_seed_and_reads_the_referee():
    a = _served_match("ssl-team-2v2", "scripted", 4, duration=8.0)
    b = _served_match("ssl-team-2v2", "scripted", 4, duration=8.0)
    assert a.score == b.score and a.steps == 8 * 30
    assert a.sent == (8 * 30 + 1, 8 * 30 + 1)  # every step's message and the last one
    view = a.views[1]
    assert view.score == a.score and view.time == pytest.approx(8.0)
