"""Policies on live SSL protocols: :class:`~agents.live.client.SSLClient` reads SSL-Vision
and the referee from any source, runs the package's perception and a policy, and sends robot
control (needs the ``ssl`` extra)."""

from agents.live.client import CLIENT_TASKS, SSLClient
from agents.live.lockstep import LockedMatch, locked_match, play_locked

__all__ = ["CLIENT_TASKS", "SSLClient", "play_locked", "locked_match", "LockedMatch"]
