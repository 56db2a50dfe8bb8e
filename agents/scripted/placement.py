"""Ball placement by a scripted SSL team (SSL rules, 2025 edition), from the referee
state at the end of the placer's observation.

The placer (the field player nearest the ball; the keeper when it is alone) stops between the
designated position and the ball facing the ball, turns its dribbler on and backs off to the
designated position pulling the ball, which works against a wall too (a ball against a wall or
in a corner is taken facing the wall). Its ways to the ball and to the designated position go
round the goals (:class:`~agents.scripted.goals.GoalWalls`): a ball behind a goal line or in a
goal's corner is fetched through the field and the goal's mouth. With the ball within
:data:`PLACE_DONE` of the position it turns the dribbler off and backs away, to the free
kick's clearance when the free kick is its team's, else to the stop distance.

Positions are in the team frame [m], headings in radians, speeds in m/s.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from agents.scripted.geometry import MARGIN, TeamGeometry
from agents.scripted.goals import GoalWalls
from agents.scripted.motion import drive_and_turn
from agents.scripted.view import Frame
from soccer_env.presets.rules import RuleSpec

__all__ = ["BallPlacement", "PLACE_SPEED", "PLACE_DONE", "PLACE_DECELERATION"]

#: Speed [m/s] at which the placer pulls the ball, and within how far of the designated
#: position it releases it [m].
PLACE_SPEED, PLACE_DONE = 1.5, 0.05
#: Deceleration [m/s^2] of the placer carrying the ball, well within what the dribbler holds.
PLACE_DECELERATION = 1.0
#: Within this distance of a rolling ball [m] the placer aims at the ball itself, not where
#: the ball will be half a second later.
LEAD_FROM = 0.5


class BallPlacement:
    """The placer's play (see the module docstring).

    Args:
        geometry: the team's geometry.
        rules: the rules whose distances the placer keeps.
        game: the game block's entry indices by name
            (:attr:`~agents.scripted.view.ObservationView.game`).
    """

    def __init__(self, geometry: TeamGeometry, rules: RuleSpec, game: dict[str, int]) -> None:
        self.geometry, self.rules, self.game = geometry, rules, game
        #: The goals' walls, which the placer goes round.
        self.walls = GoalWalls(geometry.field, geometry.robot.radius)

    def act(self, o: Sequence[float], f: Frame) -> list[float]:
        """The placer's action from its observation ``o`` (its frame ``f``): fetch the ball
        from the designated position's side and pull it there with the dribbler."""
        g, geo, rules = self.game, self.geometry, self.rules
        r = geo.robot
        px, py, c, s, bx, by, bvx, bvy, dx, dy = f
        if o[g["game.target_set"]] < 0.5:
            return [0.0] * 6
        qx, qy = o[g["game.target_x"]], o[g["game.target_y"]]
        contact = geo.contact
        to_ball = math.hypot(bx - qx, by - qy)
        if to_ball <= PLACE_DONE:
            # Placed: release and back off along the line from the ball through the robot.
            ours = o[g["game.next_team"]] > 0.0
            away = (rules.placement_clearance if ours else rules.stop_distance) + r.radius \
                + MARGIN
            tx, ty = geo.away_from(px, py, bx, by, away)
            return drive_and_turn(r, f, tx, ty, math.atan2(by - py, bx - px), 0.5)
        ux, uy = self.pick_up_direction(bx, by, (bx - qx) / to_ball, (by - qy) / to_ball)
        face = math.atan2(uy, ux)
        heading_err = abs(math.remainder(face - math.atan2(s, c), 2.0 * math.pi))
        held = (r.front_distance - 0.01 < dx < contact + 0.02
                and abs(dy) < 0.5 * r.kicker_width)
        if held:
            # Carry the ball to the designated position without turning: the robot moves
            # as the ball must (the dribbler holds it against the front and damps its
            # sideways slip), slowing down on the braking profile.
            # The robot's centre goes where it stands when the ball is placed, round the
            # goals (a ball fetched from inside a goal comes out through the mouth).
            wx, wy = self.walls.route(px, py, qx + px - bx, qy + py - by)
            ex, ey = wx - px, wy - py
            norm = math.hypot(ex, ey) or 1.0
            speed = min(PLACE_SPEED, math.sqrt(2.0 * PLACE_DECELERATION * to_ball))
            wx, wy = ex / norm * speed, ey / norm * speed
            vx, vy = c * wx + s * wy, -s * wx + c * wy
            return [vx / r.max_speed, vy / r.max_speed, 0.0, 0.0, -1.0, 1.0]
        if bvx * bvx + bvy * bvy > 0.09 and math.hypot(bx - px, by - py) > LEAD_FROM:
            # A rolling ball, still far: meet it half a second ahead. Near it, leading would
            # chase a ball the robot itself pushes along.
            bx, by = bx + 0.5 * bvx, by + 0.5 * bvy
        # Stop between the designated position and the ball, facing the ball; then move in
        # until the ball is at the front.
        near = math.hypot(px - (bx - contact * ux), py - (by - contact * uy))
        if near < 0.08 and heading_err < 0.2:
            tx, ty, cap = bx - (contact - 0.01) * ux, by - (contact - 0.01) * uy, 0.3
        else:
            tx, ty = bx - (contact + 0.08) * ux, by - (contact + 0.08) * uy
            tx, ty = geo.around_ball(px, py, tx, ty, bx, by,
                                     r.radius + geo.ball.radius + 0.05, 0.05)
            cap = None
        lx = geo.field.half_length + geo.field.boundary - r.radius - 0.005
        ly = geo.field.half_width + geo.field.boundary - r.radius - 0.005
        tx, ty = self.walls.route(px, py, max(-lx, min(lx, tx)), max(-ly, min(ly, ty)))
        return drive_and_turn(r, f, tx, ty, face, cap, dribble=1.0)

    def pick_up_direction(self, bx: float, by: float, ux: float, uy: float
                          ) -> tuple[float, float]:
        """The direction ``(ux, uy)`` (unit) the placer faces to take the ball at ``(bx,
        by)``: from the designated position to the ball, turned by the least multiple of 15
        degrees that lets the robot's centre, a contact distance behind the ball, stay off the
        walls and the goals' walls (a ball against a wall or in a corner is taken facing the
        wall)."""
        geo = self.geometry
        f, r = geo.field, geo.robot
        wx = f.half_length + f.boundary - r.radius - 0.005
        wy = f.half_width + f.boundary - r.radius - 0.005
        contact = geo.contact
        a0 = math.atan2(uy, ux)
        for k in range(13):
            for sign in ((1.0,) if k == 0 else (1.0, -1.0)):
                a = a0 + sign * k * math.pi / 12.0
                cx, cy = bx - contact * math.cos(a), by - contact * math.sin(a)
                if abs(cx) <= wx and abs(cy) <= wy and self.walls.free(cx, cy, 0.005):
                    return math.cos(a), math.sin(a)
        # Wedged in a corner: face into it.
        nx = math.copysign(1.0, bx) if abs(bx) > wx - contact else 0.0
        ny = math.copysign(1.0, by) if abs(by) > wy - contact else 0.0
        n = math.hypot(nx, ny) or 1.0
        return nx / n, ny / n
