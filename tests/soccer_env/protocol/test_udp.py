"""The sockets of the protocols: a unicast receiver has its port to itself (two programs on a
host, or two tests, never share a free port and take each other's datagrams)."""

from __future__ import annotations

import pytest

from soccer_env.protocol.udp import destinations, receiver


def test_receivers_on_free_ports_never_share_one():
    socks = [receiver(("127.0.0.1", 0)) for _ in range(1000)]
    try:
        ports = [s.getsockname()[1] for s in socks]
        assert len(set(ports)) == len(ports)
    finally:
        for s in socks:
            s.close()


def test_destinations_take_one_address_or_a_list_on_one_kind_of_network():
    assert destinations(("127.0.0.1", 5)) == [("127.0.0.1", 5)]
    assert destinations([("127.0.0.1", 5), ("127.0.0.2", 6)]) == [("127.0.0.1", 5),
                                                                 ("127.0.0.2", 6)]
    with pytest.raises(ValueError, match="all be on loopback"):
        destinations([("127.0.0.1", 5), ("224.5.23.2", 10006)])
    with pytest.raises(ValueError, match="non-empty list"):
        destinations([])
    with pytest.raises(ValueError, match="vision_address port must be an integer in 1"):
        destinations([("127.0.0.1", 0)], "vision_address")
