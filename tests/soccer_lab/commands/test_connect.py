"""``soccer-env connect`` against a stepped server on loopback (127.0.0.1 only): a shipped
keeper plays its shots through the sockets with its own settings; bad options are refused
naming the option."""

from __future__ import annotations

import threading

import pytest

pytest.importorskip("ssl_protocol")

from soccer_env.protocol.reader import RefereeReader  # noqa: E402
from soccer_env.protocol.server import SSLServer  # noqa: E402
from soccer_lab.commands.connect import main  # noqa: E402

LOOPBACK = ("127.0.0.1", 0)


def _connect(kwargs: dict, vision: str, task: str, team: str, argv: list[str], seed: int,
             episodes: int | None = None) -> SSLServer:
    """Serve ``task`` stepped in a thread and run ``soccer-env connect argv`` as ``team``
    against it; the closed server."""
    # free ports for the client's sockets: bound, read, released before it binds them
    probes = [RefereeReader(LOOPBACK) for _ in range(2)]
    ports = [r.address[1] for r in probes]
    for r in probes:
        r.close()
    server = SSLServer(kwargs, vision, ("127.0.0.1", ports[0]), ("127.0.0.1", ports[1]),
                       (LOOPBACK, LOOPBACK), LOOPBACK, task=task)

    def serve():
        server.reset(seed=seed, clock=0.0)
        # until the client has bound its sockets, a step waits half a second, then goes on
        server.run(realtime=False, episodes=episodes, wait_for=(team,), timeout=0.5)

    thread = threading.Thread(target=serve)
    try:
        thread.start()
        control = server.control_addresses[("blue", "yellow").index(team)]
        assert main([*argv, "--stepped", "--vision-address", f"127.0.0.1:{ports[0]}",
                     "--referee-address", f"127.0.0.1:{ports[1]}",
                     "--control-address", f"{control[0]}:{control[1]}",
                     "--duration", "100", "--timeout", "5"]) == 0
    finally:
        thread.join()
        server.close()
    return server


def test_a_shipped_keeper_plays_the_served_shots(capsys):
    server = _connect({"control_dt": 0.04}, "ssl-2012", "goalkeeper", "blue",
                      ["--policy", "baseline:keeper-ppo-residual-ssl2012"], 5, episodes=3)
    out = capsys.readouterr().out
    assert "playing baseline:keeper-ppo-residual-ssl2012 (goalkeeper)" in out
    # the client joins during the first shot (its start went out before the client listened)
    assert " shots, score 0:" in out and "refused none; dropped none" in out
    assert len(server.outcomes) == 3 and server.received[0] > 3 * 10 and server.missed < 20


def test_a_shipped_team_plays_a_served_match_with_its_own_settings(capsys):
    # the shipped team's match: 2 vs 2, 30 commands a second (its eval_kwargs)
    server = _connect({"blue": 2, "yellow": 2, "match_duration": 3.0, "control_dt": 1 / 30},
                      "realistic", "match", "yellow",
                      ["--task", "match", "--team", "yellow", "--policy", "ssl-team-2v2",
                       "--perception", "realistic"], 2)
    out = capsys.readouterr().out
    assert "playing ssl-team-2v2 (match, yellow)" in out and "refused none" in out
    assert server.received == [0, server.received[1]] and server.received[1] > 60


@pytest.mark.parametrize("argv, message", [
    (["--duration", "0"], "--duration must be in"),
    (["--timeout", "0"], "--timeout must be in"),
    (["--control-address", "127.0.0.1:0"], "--control-address port must be an integer in 1"),
    (["--vision-address", "here:1"], "--vision-address must be (IPv4 host, port)"),
    (["--obs-mode", "truth", "--loopback", "--vision-address", "127.0.0.1:0",
      "--referee-address", "127.0.0.1:0"], "obs_mode must be 'perceived' or 'raw'"),
    (["--task", "match", "--env-kwarg", "game=true", "--loopback", "--vision-address",
      "127.0.0.1:0", "--referee-address", "127.0.0.1:0"], "game flow"),
])
def test_bad_options_are_refused(argv, message, capsys):
    with pytest.raises(SystemExit):
        main(argv)
    assert message in capsys.readouterr().err
