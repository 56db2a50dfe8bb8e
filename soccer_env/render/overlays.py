"""What is drawn over the field (pygame), :class:`Overlays`: the robots in team colours with
a heading mark and their number, the humanoids' camera views and fallen bodies, the true ball
(with its shadow in flight), and what the team believes in cyan (the robots' outlines, the
ball and its velocity, 2-sigma ellipses of the position covariances, particle clouds, the
latest ball sighting).

Robots and the ball are drawn at least :data:`MIN_ROBOT_PX` and :data:`MIN_BALL_PX` of the
frame's width, larger than to scale on small frames. Each drawing adds the legend key of what
it drew in view to a list (:data:`~soccer_env.render.legend.LEGEND_LABELS`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from soccer_env.presets import BallSpec, RobotSpec
from soccer_env.render.colours import (
    BALL,
    BALL_EDGE,
    BALL_PARTICLE,
    BELIEF,
    CONE,
    ELLIPSE,
    MEASURED,
    POSE_PARTICLE,
    SHADOW,
    TEAM_COLOURS,
    Colour,
)
from soccer_env.render.geometry import ellipse_axes, ellipse_points
from soccer_env.render.text import Texts
from soccer_env.render.view import View
from soccer_env.sim.ssl import robot_outline
from soccer_env.state import Belief, WorldState

__all__ = ["Overlays", "MIN_ROBOT_PX", "MIN_BALL_PX", "PARTICLE_ALPHA", "VELOCITY_TIME"]

#: Smallest drawn robot radius and ball radius, as fractions of the frame's width.
MIN_ROBOT_PX = 1.0 / 80.0
MIN_BALL_PX = 1.0 / 130.0
#: Particles are blended over the frame with this opacity (ball tracker, localization).
PARTICLE_ALPHA = (0.55, 0.4)
#: The believed velocity is drawn as the distance covered in this time [s].
VELOCITY_TIME = 0.2


class Overlays:
    """Draws the robots, the ball and the belief where ``view`` puts them.

    Args:
        pg: the pygame module.
        view: the field view's transform.
        texts: the frame's fonts (the robots' numbers).
        robot: the robots' spec, one for all robots or one per robot.
        ball: the ball's spec.
    """

    def __init__(self, pg: Any, view: View, texts: Texts,
                 robot: RobotSpec | Sequence[RobotSpec], ball: BallSpec) -> None:
        self.pg, self.view, self.texts = pg, view, texts
        self.robot, self.ball = robot, ball
        self._specs = list(robot) if isinstance(robot, (list, tuple)) else None
        self._outlines: dict[RobotSpec, np.ndarray] = {}
        w = view.field_size[0]
        self._min_robot = MIN_ROBOT_PX * w
        #: The drawn ball's smallest radius [px].
        self.ball_px = max(3, int(round(MIN_BALL_PX * w)))

    # ------------------------------------------------------------------------------------
    # Sizes and shapes

    @property
    def specs(self) -> list[RobotSpec]:
        """The distinct specs given (one per robot, or the one of every robot)."""
        return self._specs if self._specs is not None else [self.robot]

    def spec(self, i: int) -> RobotSpec:
        """Robot ``i``'s spec."""
        return self.robot if self._specs is None else self._specs[i]

    def inflation(self, spec: RobotSpec) -> float:
        """How much a robot is drawn larger than to scale: to at least :data:`MIN_ROBOT_PX`
        of the frame's width."""
        return max(1.0, self._min_robot / (spec.radius * self.view.s))

    def drawn_radius(self, i: int) -> float:
        """Robot ``i``'s radius as drawn [px]: to scale, or larger where that would be under
        :data:`MIN_ROBOT_PX` of the frame's width."""
        spec = self.spec(i)
        return spec.radius * self.inflation(spec) * self.view.s

    def _outline(self, spec: RobotSpec) -> np.ndarray:
        """The footprint polygon of ``spec`` in its body frame."""
        key = spec  # (frozen dataclasses: equal specs share one outline)
        if key not in self._outlines:
            if spec.kind == "ssl":
                pts = robot_outline(spec, n_arc=12)
            else:
                a = np.linspace(0.0, 2.0 * math.pi, 16, endpoint=False)
                pts = np.column_stack([spec.radius * np.cos(a), spec.radius * np.sin(a)])
            self._outlines[key] = np.asarray(pts)
        return self._outlines[key]

    def _footprint(self, i: int, x: float, y: float, th: float, grow: float = 1.0
                   ) -> list[tuple[int, int]]:
        """Robot ``i``'s drawn footprint at ``(x, y, th)`` [m, m, rad], ``grow`` times its
        drawn size."""
        spec = self.spec(i)
        k = self.inflation(spec) * grow
        c, sn = k * math.cos(th), k * math.sin(th)
        out = self._outline(spec)
        pts = np.column_stack([x + c * out[:, 0] - sn * out[:, 1],
                               y + sn * out[:, 0] + c * out[:, 1]])
        return [tuple(p) for p in self.view.px_array(pts).tolist()]

    # ------------------------------------------------------------------------------------
    # The truth

    def robots(self, surf: Any, state: WorldState, heads: dict, overlays: bool,
               drawn: list[str]) -> None:
        """Every robot, with a humanoid's camera view (``heads``, drawn with the
        ``overlays``) and fallen body."""
        pg, view = self.pg, self.view
        px, s = view.px, view.s
        for i, ((x, y, th, *_), team) in enumerate(zip(state.robots.tolist(),
                                                       state.teams.tolist())):
            if i in heads:
                pan, hfov, reach, lying = heads[i]
                if overlays:
                    a0 = th + pan
                    cone = [px(x, y)] + [
                        px(x + reach * math.cos(a0 + k * 0.5 * hfov),
                           y + reach * math.sin(a0 + k * 0.5 * hfov)) for k in (-1, 0, 1)]
                    pg.draw.lines(surf, CONE, True, cone, 1)
                    if view.visible(cone):
                        drawn.append("camera")
                if lying is not None:
                    la, length = lying
                    end = px(x + length * math.cos(th + la), y + length * math.sin(th + la))
                    pg.draw.line(surf, TEAM_COLOURS[team], px(x, y), end,
                                 max(3, int(0.12 * s)))
                    if view.visible([px(x, y), end]):
                        drawn.append("fallen")
            spec = self.spec(i)
            pts = self._footprint(i, x, y, th)
            pg.draw.polygon(surf, TEAM_COLOURS[team], pts)
            pg.draw.polygon(surf, (0, 0, 0), pts, 1)
            d = getattr(spec, "front_distance", spec.radius) * self.inflation(spec)
            pg.draw.line(surf, (0, 0, 0), px(x, y),
                         px(x + math.cos(th) * d, y + math.sin(th) * d), 2)
            if view.visible(pts):
                drawn.append(f"team{team}")

    def ids(self, surf: Any, state: WorldState) -> None:
        """Every robot's number beside it, above and outwards (blue's to the left, yellow's to
        the right: apart where the teams meet), white outlined in black."""
        view = self.view
        for i, ((x, y, *_), name, team) in enumerate(zip(state.robots.tolist(), state.names,
                                                         state.teams.tolist())):
            spec = self.spec(i)
            r = spec.radius * view.s * self.inflation(spec)
            label = self.texts.render(name.rsplit("_", 1)[-1], outline=True, font="id")
            cx, cy = view.px(x, y)
            off = 0.75 * r
            left = cx - off - label.get_width() if team == 0 else cx + off
            left = min(max(0, left), surf.get_width() - label.get_width())  # (on screen)
            surf.blit(label, (int(left), int(cy - off - label.get_height() + 2)))

    def true_ball(self, surf: Any, state: WorldState) -> bool:
        """The true ball; returns whether it is in view."""
        pg, view = self.pg, self.view
        bx, by, bz = state.ball[0:3].tolist()
        r = max(self.ball_px, int(round(self.ball.radius * view.s)))
        centre = view.px(bx, by)
        if bz > 1e-3:  # in flight: shadow on the carpet, ball lifted and enlarged
            pg.draw.circle(surf, SHADOW, centre, r)
            centre = view.px(bx, by + 0.5 * bz)
            r = int(r * (1.0 + min(bz, 2.0)))
        pg.draw.circle(surf, BALL, centre, r)
        pg.draw.circle(surf, BALL_EDGE, centre, r, 1)
        return view.visible([centre], r)

    # ------------------------------------------------------------------------------------
    # The belief

    def belief(self, surf: Any, belief: Belief, drawn: list[str]) -> None:
        """What the team believes (see the module docstring)."""
        pg, view = self.pg, self.view
        px, s = view.px, view.s
        spread = getattr(belief, "spread", None)
        width = 2 if view.field_size[0] >= 480 else 1
        if spread is not None:
            self._spread(surf, belief, spread, width, drawn)
        for i, (x, y, th, *_) in enumerate(belief.robots.tolist()):
            # (a little larger than the robot: a belief on the truth leaves it visible)
            pts = self._footprint(i, x, y, th, 1.2)
            pg.draw.polygon(surf, BELIEF, pts, 1)
            if "belief_robots" not in drawn and view.visible(pts):
                drawn.append("belief_robots")
        if spread is None or spread.ball is not None:  # (a ball never seen is not drawn)
            bx, by = belief.ball[0:2].tolist()
            centre = px(bx, by)
            r = max(self.ball_px, int(round(self.ball.radius * s))) + 3
            pg.draw.circle(surf, BELIEF, centre, r, width)
            if view.visible([centre], r):
                drawn.append("belief_ball")
            vx, vy = belief.ball[3:5].tolist()
            end = px(bx + VELOCITY_TIME * vx, by + VELOCITY_TIME * vy)
            if math.hypot(end[0] - centre[0], end[1] - centre[1]) > r:
                pg.draw.line(surf, BELIEF, centre, end, width)
                if view.visible([centre, end]):
                    drawn.append("belief_velocity")
        quality = getattr(belief, "quality", None)
        measured = None if quality is None else quality.ball_measured
        if measured is not None:
            mx, my = px(float(measured[0]), float(measured[1]))
            k = max(3, self.ball_px)
            pg.draw.line(surf, MEASURED, (mx - k, my - k), (mx + k, my + k), 2)
            pg.draw.line(surf, MEASURED, (mx - k, my + k), (mx + k, my - k), 2)
            if view.visible([(mx, my)], k):
                drawn.append("measurement")

    def _spread(self, surf: Any, belief: Belief, spread: Any, width: int,
                drawn: list[str]) -> None:
        """The belief's particle clouds and 2-sigma ellipses (``width`` [px] lines); an
        ellipse hidden under the mark it surrounds, or unknown, is not drawn."""
        pg, view = self.pg, self.view
        s = view.s
        if spread.pose_particles is not None and len(spread.pose_particles):
            if self._dots(surf, spread.pose_particles[:, 0:2], POSE_PARTICLE,
                          PARTICLE_ALPHA[1]):
                drawn.append("pose_particles")
        if spread.ball_particles is not None and len(spread.ball_particles):
            if self._dots(surf, spread.ball_particles, BALL_PARTICLE, PARTICLE_ALPHA[0]):
                drawn.append("ball_particles")
        ring = max(self.ball_px, int(round(self.ball.radius * s))) + 3
        ellipses = ([(belief.ball[0:2], spread.ball, ring)] if spread.ball is not None
                    else [])
        ellipses += [(row[0:2], cov, self.spec(i).radius * s * self.inflation(self.spec(i)))
                     for i, (row, cov) in enumerate(zip(belief.robots, spread.robots))]
        for centre, cov, mark in ellipses:
            axes = ellipse_axes(cov)
            if axes is None or axes[0] * s <= mark:
                continue  # unknown, or hidden under the mark it surrounds
            pts = [tuple(p) for p in view.px_array(ellipse_points(centre, axes)).tolist()]
            pg.draw.lines(surf, ELLIPSE, True, pts, width)
            if "ellipses" not in drawn and view.visible(pts):
                drawn.append("ellipses")

    def _dots(self, surf: Any, xy: np.ndarray, colour: Colour, alpha: float) -> bool:
        """Blend 2 x 2 pixel dots of ``colour`` with opacity ``alpha`` at the field points
        ``xy`` ``(K, 2)`` [m]; returns whether any falls inside the view."""
        px = self.view.px_array(np.asarray(xy, dtype=np.float64))
        w, h = surf.get_size()
        inside = (px[:, 0] >= 0) & (px[:, 0] < w - 1) & (px[:, 1] >= 0) & (px[:, 1] < h - 1)
        px = px[inside]
        if not len(px):
            return False
        xs = np.concatenate([px[:, 0], px[:, 0] + 1, px[:, 0], px[:, 0] + 1])
        ys = np.concatenate([px[:, 1], px[:, 1], px[:, 1] + 1, px[:, 1] + 1])
        arr = self.pg.surfarray.pixels3d(surf)
        try:
            old = arr[xs, ys].astype(np.float32)
            arr[xs, ys] = (old + alpha * (np.asarray(colour, np.float32) - old)).astype(np.uint8)
        finally:
            del arr
        return True
