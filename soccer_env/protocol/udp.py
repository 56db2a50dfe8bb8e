"""UDP sockets for the league's protocols: a sender to an address (a multicast group or one
host) and a receiver bound to one, with the league's default addresses.

The defaults are the league's, for users on their own network: SSL-Vision publishes on the
multicast group 224.5.23.2, port 10006 (simulators often 10020), the game controller's referee
messages on 224.5.23.1:10003, and the simulation protocol listens on ports 10300 (simulator
control), 10301 (blue robot control) and 10302 (yellow). A multicast address is joined on
``interface`` (default: any); any other address is sent to or bound as it is. The package's
tests and examples use 127.0.0.1 only.
"""

from __future__ import annotations

import ipaddress
import socket
import struct
from typing import Any

__all__ = ["VISION_ADDRESS", "REFEREE_ADDRESS", "SIMULATION_CONTROL_PORT", "BLUE_CONTROL_PORT",
           "YELLOW_CONTROL_PORT", "MAX_DATAGRAM", "check_address", "sender", "receiver"]

#: SSL-Vision's multicast group and port.
VISION_ADDRESS = ("224.5.23.2", 10006)
#: The game controller's referee messages.
REFEREE_ADDRESS = ("224.5.23.1", 10003)
#: The simulation protocol's ports: simulator control, and robot control per team.
SIMULATION_CONTROL_PORT, BLUE_CONTROL_PORT, YELLOW_CONTROL_PORT = 10300, 10301, 10302
#: The largest UDP payload over IPv4 [bytes].
MAX_DATAGRAM = 65_507


def check_address(address: tuple[str, int], name: str = "address", bind: bool = True
                  ) -> tuple[str, int]:
    """``address`` as ``(host, port)`` with an IPv4 host and a port in 0..65535 for an address
    to bind (0: any free port), 1..65535 for one to send to (``bind=False``); raises
    ``ValueError`` naming ``name`` otherwise."""
    try:
        host, port = address
        ipaddress.IPv4Address(host)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be (IPv4 host, port), got {address!r}") from None
    low = 0 if bind else 1
    if isinstance(port, bool) or not isinstance(port, int) or not low <= port <= 65535:
        raise ValueError(f"{name} port must be an integer in {low}..65535, got {port!r}")
    return str(host), int(port)


def destinations(address: Any, name: str = "address") -> list[tuple[str, int]]:
    """The addresses to send to: one ``(host, port)`` or a non-empty list of them (each
    checked by :func:`check_address`; all on loopback or none, as one sending socket serves
    them, see :func:`sender`)."""
    many = isinstance(address, list) or (isinstance(address, tuple) and address
                                         and isinstance(address[0], (tuple, list)))
    out = [check_address(tuple(a), name, bind=False) for a in address] if many \
        else [check_address(address, name, bind=False)]
    if not out:
        raise ValueError(f"{name} must be an address or a non-empty list of addresses")
    loop = {ipaddress.IPv4Address(h).is_loopback for h, _ in out}
    if len(loop) > 1:
        raise ValueError(f"{name}: the addresses must all be on loopback (127.0.0.0/8) or "
                         f"none, got {out}")
    return out


def _multicast(host: str) -> bool:
    return ipaddress.IPv4Address(host).is_multicast


def sender(address: tuple[str, int], interface: str = "0.0.0.0", ttl: int = 1
           ) -> socket.socket:
    """A UDP socket for sending to ``address``: to a multicast group it sends through
    ``interface`` with ``ttl`` hops and loops back to this host; to a loopback address it is
    bound to 127.0.0.1 (a free port), so that nothing listens beyond this host."""
    host, _ = check_address(address, bind=False)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
    if ipaddress.IPv4Address(host).is_loopback:
        sock.bind(("127.0.0.1", 0))
    elif _multicast(host):
        sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, ttl)
        sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)
        sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_IF, socket.inet_aton(interface))
    return sock


def receiver(address: tuple[str, int], interface: str = "0.0.0.0",
             timeout: float | None = None) -> socket.socket:
    """A UDP socket bound to ``address`` (port 0: a free port, see ``getsockname()``): for a
    multicast group, bound to the group's port on every address and a member of the group on
    ``interface``; otherwise bound to the host given. ``timeout`` [s] for ``recv``."""
    host, port = check_address(address)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
    if _multicast(host):
        # Several programs on a host listen to one group: they share its port. A unicast
        # socket does not: with the option two sockets could be given the same free port,
        # and one would take the other's datagrams.
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(("", port))
        membership = struct.pack("4s4s", socket.inet_aton(host), socket.inet_aton(interface))
        sock.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, membership)
    else:
        sock.bind((host, port))
    sock.settimeout(timeout)
    return sock
