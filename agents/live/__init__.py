"""Policies on live SSL protocols: :class:`~agents.live.client.SSLClient` reads SSL-Vision
and the referee from any source, runs the package's perception and a policy, and sends robot
control (needs the ``ssl`` extra)."""

from agents.live.client import CLIENT_TASKS, SSLClient

__all__ = ["CLIENT_TASKS", "SSLClient"]
