"""Top markers of robots seen from above (:class:`PatchPattern`).

Every robot seen from above carries, as in SSL-Vision's standard pattern and MiroSot, a team
patch at its centre (blue for team 0, yellow for team 1; radius 25 mm) and four player dots
(radius 20 mm) around it: two at the front, ``(35, +-54.8)`` mm in the body frame (``+x``
forward, ``+y`` left), and two at the back, ``(-54.8, +-35)`` mm, all 65 mm from the centre. The
front pair is 110 mm apart and the back pair 70 mm, so the layout shows the heading; the dots'
colours (pink or green) give the robot's number within its team (:data:`PATTERN_IDS`, 16
combinations). Robots of another size (humanoids seen from above) carry the pattern scaled by
``radius / 0.09 m``. Dimensions and positions are our reading of the SSL standard pattern; ids
0-11 follow the SSL rules of 2013 (figure 6, as transcribed by the RoboJackets team), ids 12-15
are the four remaining combinations in an order of ours.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import NamedTuple

from soccer_env.presets.images import COLOURS, RGB

__all__ = ["Patch", "PatchPattern", "PATTERN", "PATTERN_IDS", "patch_pattern"]

_TEAM_COLOUR = ("blue", "yellow")


class Patch(NamedTuple):
    """One coloured disc on a robot's top: centre ``x, y`` in the body frame [m] (``+x``
    forward, ``+y`` left), ``radius`` [m] and colour ``rgb``."""

    x: float
    y: float
    radius: float
    rgb: RGB


#: Player-dot colours per robot number (0-15), dots in the order front-left, front-right,
#: rear-right, rear-left (clockwise seen from above, starting front-left). 0-11: SSL rules
#: 2013, figure 6 (magenta = pink); 12-15: the remaining combinations (our order).
PATTERN_IDS: tuple[tuple[str, str, str, str], ...] = tuple(
    tuple("pink" if c == "m" else "green" for c in code)  # type: ignore[misc]
    for code in ("mmmg", "gmmg", "ggmg", "mgmg", "mmgm", "gmgm", "gggm", "mggm",
                 "gggg", "mmmm", "mmgg", "ggmm", "mgmm", "mggg", "gmmm", "gmgg")
)


@dataclass(frozen=True)
class PatchPattern:
    """Geometry of the top markers (module docstring), for a robot of ``reference_radius``.

    Attributes:
        centre_radius: radius of the team patch [m].
        dot_radius: radius of a player dot [m].
        dot_positions: body-frame centres of the four dots [m], in :data:`PATTERN_IDS` order.
        reference_radius: the robot radius these dimensions are for [m]; other robots get the
            pattern scaled by ``radius / reference_radius``.
    """

    centre_radius: float = 0.025
    dot_radius: float = 0.020
    dot_positions: tuple[tuple[float, float], ...] = (
        (0.035, 0.054772), (0.035, -0.054772), (-0.054772, -0.035), (-0.054772, 0.035))
    reference_radius: float = 0.09

    def patches(self, team: int, index: int, robot_radius: float | None = None,
                colours: Mapping[str, RGB] | None = None) -> list[Patch]:
        """The discs on robot ``index`` (0-15) of ``team`` (0 blue, 1 yellow): the team patch
        first, then the four dots; scaled to ``robot_radius`` [m] if given."""
        if team not in (0, 1):
            raise ValueError(f"team must be 0 (blue) or 1 (yellow), got {team!r}")
        if not 0 <= index < len(PATTERN_IDS):
            raise ValueError(f"index must be in [0, {len(PATTERN_IDS) - 1}], got {index!r}")
        pal = COLOURS if colours is None else colours
        k = 1.0 if robot_radius is None else robot_radius / self.reference_radius
        out = [Patch(0.0, 0.0, k * self.centre_radius, pal[_TEAM_COLOUR[team]])]
        for (x, y), name in zip(self.dot_positions, PATTERN_IDS[index]):
            out.append(Patch(k * x, k * y, k * self.dot_radius, pal[name]))
        return out

    @staticmethod
    def identify(dot_colours: Sequence[str]) -> int | None:
        """The robot number whose dots (front-left, front-right, rear-right, rear-left) have
        these colour names, or None."""
        try:
            return PATTERN_IDS.index(tuple(dot_colours))
        except ValueError:
            return None


#: The default pattern (SSL standard pattern dimensions).
PATTERN = PatchPattern()


def patch_pattern(team: int, index: int, robot_radius: float | None = None
                  ) -> list[tuple[float, float, float, RGB]]:
    """``(offset_x, offset_y, radius, rgb)`` [m, m, m, RGB] of the discs on robot ``index`` of
    ``team``, body frame, team patch first (:class:`PatchPattern`)."""
    return [tuple(p) for p in PATTERN.patches(team, index, robot_radius)]  # type: ignore
