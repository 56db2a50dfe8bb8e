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


def test_a_shipped_keeper_plays_the_served_shots(capsys):
    # free ports for the client's sockets: bound, read, released before it binds them
    probes = [RefereeReader(LOOPBACK) for _ in range(2)]
    ports = [r.address[1] for r in probes]
    for r in probes:
        r.close()
    server = SSLServer({"control_dt": 0.04}, "ssl-2012", ("127.0.0.1", ports[0]),
                       ("127.0.0.1", ports[1]), (LOOPBACK, LOOPBACK), LOOPBACK,
                       task="goalkeeper")

    def serve():
        server.reset(seed=5, clock=0.0)
        # until the client has bound its sockets, a step waits half a second, then goes on
        server.run(realtime=False, episodes=3, wait_for=("blue",), timeout=0.5)

    thread = threading.Thread(target=serve)
    try:
        thread.start()
        control = server.control_addresses[0]
        assert main(["--stepped", "--policy", "baseline:keeper-ppo-residual-ssl2012",
                     "--vision-address", f"127.0.0.1:{ports[0]}",
                     "--referee-address", f"127.0.0.1:{ports[1]}",
                     "--control-address", f"{control[0]}:{control[1]}",
                     "--duration", "100", "--timeout", "5"]) == 0
    finally:
        thread.join()
        server.close()
    out = capsys.readouterr().out
    assert "playing baseline:keeper-ppo-residual-ssl2012 (goalkeeper)" in out
    # the client joins during the first shot (its start went out before the client listened)
    assert " shots, score 0:" in out and "refused none; dropped none" in out
    assert len(server.outcomes) == 3 and server.received[0] > 3 * 10 and server.missed < 20


@pytest.mark.parametrize("argv, message", [
    (["--duration", "0"], "--duration must be in"),
    (["--timeout", "0"], "--timeout must be in"),
    (["--control-address", "127.0.0.1:0"], "--control-address port must be an integer in 1"),
    (["--vision-address", "here:1"], "--vision-address must be (IPv4 host, port)"),
    (["--obs-mode", "truth", "--loopback", "--vision-address", "127.0.0.1:0",
      "--referee-address", "127.0.0.1:0"], "obs_mode must be 'perceived' or 'raw'"),
])
def test_bad_options_are_refused(argv, message, capsys):
    with pytest.raises(SystemExit):
        main(argv)
    assert message in capsys.readouterr().err
