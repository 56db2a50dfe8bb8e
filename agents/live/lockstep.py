"""A stepped server and live clients in one process, in lock step: :func:`play_locked`, and a
whole match played so through loopback sockets, :func:`locked_match`."""

from __future__ import annotations

import threading
from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

from agents.live.client import SSLClient

__all__ = ["play_locked", "locked_match", "LockedMatch"]


def play_locked(server: Any, clients: Sequence[SSLClient], episodes: int | None = None,
                timeout: float = 5.0) -> int:
    """Run the stepped ``server`` (a :class:`~soccer_env.protocol.server.SSLServer`, reset,
    sending to the clients' addresses) until its match ends or ``episodes`` of its task's
    shots are over, each step waiting up to ``timeout`` [s] for a command of every team a
    client plays, and each of ``clients`` (already pointed at the server's control addresses)
    acting on every referee message; returns the server's steps. The server and every client
    run in threads of their own: each waits on its sockets, so they take turns."""
    teams = sorted({("blue", "yellow")[c.player.team] for c in clients})
    steps: list[int] = []
    serving = threading.Thread(target=lambda: steps.append(server.run(
        realtime=False, episodes=episodes, wait_for=teams, timeout=timeout)))
    serving.start()

    def play(client: SSLClient) -> None:
        # A client stops once the server has stopped and nothing more is waiting.
        while client.step(timeout=0.2) or serving.is_alive():
            pass

    players = [threading.Thread(target=play, args=(c,)) for c in clients]
    for p in players:
        p.start()
    for p in (*players, serving):
        p.join()
    return steps[0] if steps else 0


class LockedMatch(NamedTuple):
    """What :func:`locked_match` reports: the final ``score`` (blue's, yellow's goals), the
    server's ``steps`` and ``missed`` steps (waited for in vain), and per client (blue,
    yellow) the commands ``sent``, the errors the server answered (by code) and the last
    :class:`~agents.live.players.RefereeView` read."""

    score: tuple[int, int]
    steps: int
    missed: int
    sent: tuple[int, int]
    errors: tuple[dict[str, int], dict[str, int]]
    views: tuple[Any, Any]


def locked_match(blue: Any, yellow: Any, env_kwargs: Mapping[str, Any], vision: str,
                 seed: int) -> LockedMatch:
    """One match without the game flow through loopback sockets, in lock step: a stepped
    :class:`~soccer_env.protocol.server.SSLServer` of ``env_kwargs`` (team sizes,
    ``match_duration``, ``control_dt``) on ``vision`` cameras, reset with ``seed``, and one
    :class:`~agents.live.client.SSLClient` per team playing the team policies ``blue`` and
    ``yellow`` on its own perception of those cameras."""
    from soccer_env.protocol.server import SSLServer

    here = ("127.0.0.1", 0)
    kwargs = {**env_kwargs, "perception": vision}
    clients: list[SSLClient] = []
    server = None
    try:
        for policy, team in ((blue, "blue"), (yellow, "yellow")):
            clients.append(SSLClient(policy, "match", kwargs, here, here, ("127.0.0.1", 9),
                                     team=team))
        server = SSLServer(dict(env_kwargs), vision, [c.vision.address for c in clients],
                           [c.referee.address for c in clients], (here, here), here)
        for c, address in zip(clients, server.control_addresses):
            c.control_address = address
        server.reset(seed=seed, clock=0.0)
        steps = play_locked(server, clients)
        score = tuple(int(g) for g in server.env.unwrapped.score)
        return LockedMatch((score[0], score[1]), steps, server.missed,
                           (clients[0].sent, clients[1].sent),
                           (dict(clients[0].errors), dict(clients[1].errors)),
                           (clients[0].view, clients[1].view))
    finally:
        if server is not None:
            server.close()
        for c in clients:
            c.close()
