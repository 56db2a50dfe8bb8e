"""The field geometry the SSL rules measure with (field frame, blue defends ``x < 0``): the
defense areas, valid free-kick positions, the penalty marks, and distances from robots and
segments [m].

Distances from a robot are from its nearest side (its centre minus its radius), as the rule
book measures them (2.1.3).
"""

from __future__ import annotations

import math

import numpy as np

from soccer_env.presets import FieldSpec
from soccer_env.presets.rules import RuleSpec

__all__ = ["defense_box", "defense_distance", "inside_defense", "valid_free_kick",
           "penalty_mark", "robot_gap", "segment_distance"]


def defense_box(field: FieldSpec, team: int) -> tuple[float, float, float, float]:
    """``team``'s own defense area: ``x0, x1, y0, y1`` [m]."""
    f = field
    hx, hw = f.half_length, 0.5 * f.defense_width
    if team == 0:
        return -hx, -hx + f.defense_depth, -hw, hw
    return hx - f.defense_depth, hx, -hw, hw


def defense_distance(field: FieldSpec, x: float, y: float, team: int) -> float:
    """Distance from ``(x, y)`` to ``team``'s defense area (0 inside) [m]."""
    x0, x1, y0, y1 = defense_box(field, team)
    dx = max(x0 - x, 0.0, x - x1)
    dy = max(y0 - y, 0.0, y - y1)
    return math.hypot(dx, dy)


def inside_defense(field: FieldSpec, x: float, y: float, team: int, margin: float = 0.0
                   ) -> bool:
    """Whether ``(x, y)`` lies at least ``margin`` inside ``team``'s defense area."""
    x0, x1, y0, y1 = defense_box(field, team)
    return x0 + margin <= x <= x1 - margin and y0 + margin <= y <= y1 - margin


def valid_free_kick(field: FieldSpec, rules: RuleSpec, x: float, y: float
                    ) -> tuple[float, float]:
    """The nearest valid free-kick position to ``(x, y)``: at least ``line_margin`` inside
    the field lines and ``defense_margin`` from either defense area (5.3.3)."""
    r, f = rules, field
    lx, ly = f.half_length - r.line_margin, f.half_width - r.line_margin
    x, y = float(np.clip(x, -lx, lx)), float(np.clip(y, -ly, ly))
    for team in (0, 1):
        x0, x1, y0, y1 = defense_box(field, team)
        x0, x1 = x0 - r.defense_margin, x1 + r.defense_margin
        y0, y1 = y0 - r.defense_margin, y1 + r.defense_margin
        if x0 < x < x1 and y0 < y < y1:
            # Out of the enlarged box by the shorter way that stays in the field.
            options = []
            if team == 0:
                options.append((x1, y))
            else:
                options.append((x0, y))
            if y1 <= ly:
                options.append((x, y1))
            if y0 >= -ly:
                options.append((x, y0))
            x, y = min(options, key=lambda p: math.hypot(p[0] - x, p[1] - y))
    return x, y


def penalty_mark(field: FieldSpec, rules: RuleSpec, team: int) -> tuple[float, float]:
    """The penalty mark ``team`` shoots from (blue attacks +x)."""
    hx = field.half_length
    goal = hx if team == 0 else -hx
    return (goal - math.copysign(rules.penalty_mark_distance, goal), 0.0)


def robot_gap(robots: np.ndarray, radii: np.ndarray, i: int, x: float, y: float) -> float:
    """Distance from robot ``i``'s nearest side to ``(x, y)`` [m] (``robots`` rows
    ``x, y, ...``, ``radii`` every robot's radius)."""
    return math.hypot(robots[i, 0] - x, robots[i, 1] - y) - radii[i]


def segment_distance(px: float, py: float, ax: float, ay: float, bx: float, by: float
                     ) -> float:
    """Distance from ``(px, py)`` to the segment from ``(ax, ay)`` to ``(bx, by)`` [m]."""
    dx, dy = bx - ax, by - ay
    n = dx * dx + dy * dy
    s = 0.0 if n < 1e-18 else min(1.0, max(0.0, ((px - ax) * dx + (py - ay) * dy) / n))
    return math.hypot(px - ax - s * dx, py - ay - s * dy)
