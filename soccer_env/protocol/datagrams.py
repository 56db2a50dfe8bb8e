"""Datagrams of the league's protocols read safely: :func:`parse` and :class:`PacketError`.

Every datagram is checked before use: its size (:data:`MAX_PACKET_BYTES`), that it parses as
the message expected, and that it carries every required field. A datagram that fails raises
:class:`PacketError`, whose ``reason`` says which check failed, for the caller to count, log
once and drop; the checks of each message's numbers are the callers'.
"""

from __future__ import annotations

import logging
from collections import Counter
from typing import TypeVar

from google.protobuf.message import DecodeError, Message

__all__ = ["MAX_PACKET_BYTES", "PacketError", "parse", "drop", "LOGGER"]

#: Where dropped datagrams are reported, once per reason.
LOGGER = logging.getLogger("soccer_env.protocol")

#: The largest datagram read [bytes]. The league's packets are a few kilobytes (an SSL-Vision
#: detection frame of 22 robots and a few balls under 1.5 kB, the geometry with its field
#: lines under 4 kB); one UDP datagram holds at most 65,507.
MAX_PACKET_BYTES = 16_384

M = TypeVar("M", bound=Message)


class PacketError(ValueError):
    """A datagram that cannot be used; ``reason`` says why (for a count per reason)."""

    def __init__(self, reason: str, detail: str) -> None:
        super().__init__(f"{reason}: {detail}")
        self.reason = reason


def parse(data: bytes, message: type[M]) -> M:
    """``data`` parsed as a ``message`` (a protobuf message class) and checked; raises
    :class:`PacketError` with reason ``"oversized"``, ``"malformed"`` (does not parse) or
    ``"incomplete"`` (a required field missing)."""
    if len(data) > MAX_PACKET_BYTES:
        raise PacketError("oversized", f"{len(data)} bytes, at most {MAX_PACKET_BYTES}")
    out = message()
    try:
        out.ParseFromString(bytes(data))
    except DecodeError as exc:
        raise PacketError("malformed", f"not a {message.__name__} ({exc})") from None
    if not out.IsInitialized():
        missing = ", ".join(out.FindInitializationErrors())
        raise PacketError("incomplete", f"required fields missing: {missing}")
    return out


def drop(dropped: Counter, exc: PacketError, what: str) -> None:
    """Count a datagram refused with ``exc`` under its reason in ``dropped``, logging it
    (``what`` names the datagram's kind) the first time that reason occurs."""
    if not dropped[exc.reason]:
        LOGGER.warning("dropped %s (%s); further ones with this reason are counted, not logged",
                       what, exc)
    dropped[exc.reason] += 1
