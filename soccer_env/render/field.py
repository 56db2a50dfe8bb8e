"""The field drawn to scale (pygame): the carpet, the lines, the centre circle, the defense
areas, the goals and the walls."""

from __future__ import annotations

from typing import Any

from soccer_env.presets import FieldSpec
from soccer_env.render.colours import CARPET, GOAL, LINE, WALL
from soccer_env.render.view import View

__all__ = ["draw_field"]


def draw_field(pg: Any, surf: Any, view: View, field: FieldSpec) -> None:
    """Draw ``field`` on the surface ``surf`` where ``view`` puts it (lines at least a pixel
    wide, the goals' walls two)."""
    f, s, px = field, view.s, view.px
    hx, hy = f.half_length, f.half_width
    lw = max(1, int(round(f.line_width * s)))
    surf.fill(CARPET)
    x0, y0 = px(-hx, hy)
    x1, y1 = px(hx, -hy)
    pg.draw.rect(surf, LINE, (x0, y0, x1 - x0, y1 - y0), lw)
    pg.draw.line(surf, LINE, px(0, hy), px(0, -hy), lw)
    pg.draw.circle(surf, LINE, px(0, 0), int(f.center_circle_radius * s), lw)
    dw, dd = 0.5 * f.defense_width, f.defense_depth
    for sgn in (-1, 1):
        xa, xb = sgn * hx, sgn * (hx - dd)
        pts = [px(xa, dw), px(xb, dw), px(xb, -dw), px(xa, -dw)]
        pg.draw.lines(surf, LINE, False, pts, lw)
        gw, gd = 0.5 * f.goal_width, f.goal_depth
        gx = sgn * (hx + gd)
        goal = [px(sgn * hx, gw), px(gx, gw), px(gx, -gw), px(sgn * hx, -gw)]
        pg.draw.lines(surf, GOAL, False, goal, max(2, int(f.goal_wall_thickness * s)))
    wx0, wy0 = px(-view.ox, view.oy)
    wx1, wy1 = px(view.ox, -view.oy)
    pg.draw.rect(surf, WALL, (wx0, wy0, wx1 - wx0, wy1 - wy0), 3)
