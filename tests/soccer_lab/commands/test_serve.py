"""``soccer-env serve``: a stepped match served on loopback addresses only (127.0.0.1), its
summary line, and refused options."""

from __future__ import annotations

import pytest

pytest.importorskip("ssl_protocol")

from soccer_env.protocol.udp import receiver  # noqa: E402
from soccer_lab.commands.serve import main, parse_address  # noqa: E402


def test_a_stepped_match_is_served_and_summed_up(capsys):
    vision = receiver(("127.0.0.1", 0), timeout=1.0)
    port = vision.getsockname()[1]
    try:
        assert main(["--stepped", "--duration", "2", "--blue", "1", "--yellow", "1",
                     "--vision-address", f"127.0.0.1:{port}",
                     "--referee-address", f"127.0.0.1:{port}",
                     "--blue-control", "127.0.0.1:0", "--yellow-control", "127.0.0.1:0",
                     "--simulator-control", "127.0.0.1:0"]) == 0
        assert len(vision.recv(65_536)) > 0
    finally:
        vision.close()
    out = capsys.readouterr().out
    assert "serving: vision to ('127.0.0.1'" in out and "stepped" in out
    assert "served 120 steps (2.0 s of match time)" in out


@pytest.mark.parametrize("argv, message", [
    (["--blue", "12"], "--blue must be in 0..11"),
    (["--duration", "0"], "--duration must be in"),
    (["--control-hz", "5"], "--control-hz must be in"),
    (["--vision-address", "localhost:10006"], "--vision-address must be (IPv4 host, port)"),
    (["--blue-control", "127.0.0.1"], "--blue-control must be HOST:PORT"),
    (["--yellow-control", "127.0.0.1:99999"], "port must be an integer in 0..65535"),
    (["--vision-address", "127.0.0.1:0"], "--vision-address port must be an integer in 1..65535"),
])
def test_bad_options_are_refused_naming_the_option(argv, message, capsys):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


def test_addresses_parse_as_host_and_port():
    assert parse_address("127.0.0.1:10006", "--x") == ("127.0.0.1", 10006)
    with pytest.raises(ValueError, match="--x must be HOST:PORT"):
        parse_address("127.0.0.1:", "--x")


def test_every_vision_and_referee_address_given_gets_every_packet(capsys):
    socks = [receiver(("127.0.0.1", 0), timeout=1.0) for _ in range(4)]
    ports = [s.getsockname()[1] for s in socks]
    try:
        assert main(["--stepped", "--duration", "1", "--blue", "1", "--yellow", "1",
                     "--vision-address", f"127.0.0.1:{ports[0]}",
                     "--vision-address", f"127.0.0.1:{ports[1]}",
                     "--referee-address", f"127.0.0.1:{ports[2]}",
                     "--referee-address", f"127.0.0.1:{ports[3]}",
                     "--blue-control", "127.0.0.1:0", "--yellow-control", "127.0.0.1:0",
                     "--simulator-control", "127.0.0.1:0"]) == 0
        first = [s.recv(65_536) for s in socks]
        assert first[0] == first[1] and first[2] == first[3]
    finally:
        for s in socks:
            s.close()
    assert "served 60 steps (1.0 s of match time)" in capsys.readouterr().out
