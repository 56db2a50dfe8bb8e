"""The RoboCup SSL league's network protocols (the ``ssl`` extra): SSL-Vision packets from and
to the package's detection frames (:mod:`soccer_env.protocol.vision`).

The message classes come from ``soccer-env-ssl-protocol`` (``ssl_protocol``), generated from
the league's official ``.proto`` files and licensed GPL-3.0 as they are; nothing outside this
subpackage and :mod:`agents.live` (the client) imports them, and nothing else in the package
imports either, so the package runs without the extra.
"""

from __future__ import annotations

__all__: list[str] = []
