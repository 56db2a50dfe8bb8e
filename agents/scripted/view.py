"""What a scripted robot reads of its observation: entries found by name, in its team frame.

A robot's observation (the layout of :mod:`soccer_env.observations`) is egocentric: its own
pose in the team frame (``self.x``, ``self.y`` [m]; ``self.ax``, ``self.ay`` =
``(cos h, -sin h)`` of its heading ``h``), and the ball, team-mates and opponents as offsets in
its body frame (``ball.dx``, ``mate0.dx``, ``opp0.dx``, ... [m]; ``ball.vx`` ... [m/s]). An
offset ``(u, v)`` in the body frame is the point

    ``(x, y) = (px + c u - s v, py + s u + c v)``

of the team frame, with ``(c, s) = (cos h, sin h)``; a velocity ``(u, v)`` is
``(c u - s v, s u + c v)``. The team frame attacks ``+x`` on either side.

:class:`ObservationView` finds the entries once, by name, and turns an observation (a
sequence) into a :class:`Frame`, the opponents' positions and the team's positions; the
batched path reads observation rows in a kernel with the same arithmetic
(:func:`~agents.scripted.open_play.open_play_rows`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

from soccer_env.envs.match import GAME_FLOW_NAMES

__all__ = ["Frame", "ObservationView", "FRAME_ENTRIES"]

#: The entries every scripted robot reads, in the order :meth:`ObservationView.frame` takes
#: them: own position [m], own heading as ``(cos h, -sin h)``, the ball's offset [m] and
#: velocity [m/s] in the body frame.
FRAME_ENTRIES = ("self.x", "self.y", "self.ax", "self.ay", "ball.dx", "ball.dy", "ball.vx",
                 "ball.vy")


class Frame(NamedTuple):
    """One robot's view of itself and the ball in the team frame."""

    #: Own position [m].
    px: float
    py: float
    #: ``cos`` and ``sin`` of the own heading.
    c: float
    s: float
    #: The ball's position [m].
    bx: float
    by: float
    #: The ball's velocity [m/s].
    bvx: float
    bvy: float
    #: The ball's offset in the robot's body frame (``dx`` > 0: in front) [m].
    dx: float
    dy: float

class ObservationView:
    """The entries of a team's observations that a scripted robot reads, found by name.

    Args:
        names: the entry names of the team's observations (``env.builder.names_for(team)``).
        team_size: robots in the team; the names must list ``team_size - 1`` team-mates.

    Raises:
        ValueError: names lacking an entry of :data:`FRAME_ENTRIES` or listing another number
            of team-mates.
    """

    def __init__(self, names: Sequence[str], team_size: int) -> None:
        index = {n: i for i, n in enumerate(names)}
        #: Every entry's index by name.
        self.index = index
        missing = [n for n in FRAME_ENTRIES if n not in index]
        if missing:
            raise ValueError(f"names lack the entries {missing}; pass the observation's entry "
                             "names (env.builder.names_for(team))")
        #: Indices of :data:`FRAME_ENTRIES`.
        self.frame_index = [index[n] for n in FRAME_ENTRIES]
        n_mates = sum(1 for n in names if n.startswith("mate") and n.endswith(".dx"))
        if n_mates != team_size - 1:
            raise ValueError(f"the observation names list {n_mates} team-mates, a team of "
                             f"{team_size} needs {team_size - 1}")
        #: ``(dx, dy)`` indices of each team-mate, in robot order skipping the robot itself.
        self.mates = [(index[f"mate{j}.dx"], index[f"mate{j}.dy"]) for j in range(n_mates)]
        n_opps = sum(1 for n in names if n.startswith("opp") and n.endswith(".dx"))
        #: ``(dx, dy)`` indices of each opponent.
        self.opponents = [(index[f"opp{j}.dx"], index[f"opp{j}.dy"]) for j in range(n_opps)]
        #: Entries in an observation.
        self.size = len(names)
        #: Indices of the game flow's referee state (:data:`GAME_FLOW_NAMES`) by name, or
        #: None when the observations do not carry it.
        self.game = ({n: index[n] for n in GAME_FLOW_NAMES}
                     if all(n in index for n in GAME_FLOW_NAMES) else None)
        self.team_size = int(team_size)

    def frame(self, o: Sequence[float]) -> Frame:
        """The robot and the ball in the team frame from one observation."""
        return _team_frame(*(o[i] for i in self.frame_index))

    def opponents_of(self, o: Sequence[float], f: Frame) -> list[tuple[float, float]]:
        """The opponents' positions ``[(x, y), ...]`` in the team frame [m]."""
        return _points(o, f, self.opponents)

    def mates_of(self, o: Sequence[float], f: Frame) -> list[tuple[float, float]]:
        """The team-mates' positions ``[(x, y), ...]`` in the team frame [m], in robot order
        skipping the robot itself."""
        return _points(o, f, self.mates)

    def team_positions(self, o: Sequence[float], index: int, f: Frame
                       ) -> tuple[list[float], list[float]]:
        """The team's robots in the team frame, indexed by robot (robot ``index``, whose
        observation ``o`` is, included) [m]."""
        px, py, c, s = f.px, f.py, f.c, f.s
        xs, ys = [0.0] * self.team_size, [0.0] * self.team_size
        xs[index], ys[index] = px, py
        for j, (ix, iy) in enumerate(self.mates):
            k = j if j < index else j + 1
            mx, my = o[ix], o[iy]
            xs[k], ys[k] = px + c * mx - s * my, py + s * mx + c * my
        return xs, ys


def _team_frame(px: float, py: float, c: float,
                neg_s: float, dx: float, dy: float,
                bvx_b: float, bvy_b: float) -> Frame:
    """The :class:`Frame` of the entries :data:`FRAME_ENTRIES` (floats)."""
    s = -neg_s  # self.ay is -sin(heading)
    # Ball in the team frame.
    bx, by = px + c * dx - s * dy, py + s * dx + c * dy
    bvx, bvy = c * bvx_b - s * bvy_b, s * bvx_b + c * bvy_b
    return Frame(px, py, c, s, bx, by, bvx, bvy, dx, dy)


def _points(o: Sequence[float], f: Frame, pairs: Sequence[tuple[int, int]]
            ) -> list[tuple[float, float]]:
    """The body-frame offsets at the index ``pairs`` of ``o`` as team-frame points [m]."""
    px, py, c, s = f.px, f.py, f.c, f.s
    return [(px + c * mx - s * my, py + s * mx + c * my)
            for mx, my in ((o[ix], o[iy]) for ix, iy in pairs)]
