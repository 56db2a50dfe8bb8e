"""The static arena of a world: boundary walls, goals, out-of-play sensors, and the collision
types of every shape of the world."""

from __future__ import annotations

import pymunk

from soccer_env.presets import FieldSpec

__all__ = ["add_walls", "BALL", "ROBOT", "WALL", "OUT", "HUMANOID", "MIN_GOAL_WALL",
           "BOUNDARY_WALL"]

#: Collision types: the ball, SSL robots, walls, the out-of-play sensors, humanoids (standing
#: or lying).
BALL, ROBOT, WALL, OUT, HUMANOID = 1, 2, 3, 4, 5
#: Minimum thickness [m] of goal walls in the physics. Real SSL goal walls are 2 cm thick; a
#: wall that thin could be tunnelled by a fast ball in one substep, so walls are grown outward
#: (the goal keeps its inner size).
MIN_GOAL_WALL = 0.05
#: Thickness [m] of the boundary walls, grown outward from the walled area.
BOUNDARY_WALL = 1.0


def add_walls(space: pymunk.Space, field: FieldSpec, ball_radius: float,
              body: pymunk.Body | None = None) -> None:
    """Add the static arena to ``space``: boundary walls ``field.boundary`` beyond the lines,
    the goals (side and back walls, at least :data:`MIN_GOAL_WALL` thick, grown outward) and
    the out-of-play sensors just past the goal and touch lines, on ``body`` (default the
    space's static body; a static body placed elsewhere carries the arena there)."""
    body = space.static_body if body is None else body
    f = field
    hx, hy = f.half_length, f.half_width
    wx, wy = hx + f.boundary, hy + f.boundary
    t = BOUNDARY_WALL
    boxes = [
        (-wx - t, wy, wx + t, wy + t),  # top
        (-wx - t, -wy - t, wx + t, -wy),  # bottom
        (wx, -wy, wx + t, wy),  # right
        (-wx - t, -wy, -wx, wy),  # left
    ]
    side = max(f.goal_wall_thickness, MIN_GOAL_WALL)
    back = min(max(f.goal_wall_thickness, MIN_GOAL_WALL), f.boundary - f.goal_depth)
    gw = 0.5 * f.goal_width
    for s in (-1.0, 1.0):
        x0, x1 = s * hx, s * (hx + f.goal_depth)
        x2 = s * (hx + f.goal_depth + back)
        boxes.append((min(x1, x2), -gw - side, max(x1, x2), gw + side))  # back wall
        boxes.append((min(x0, x2), gw, max(x0, x2), gw + side))  # left side wall
        boxes.append((min(x0, x2), -gw - side, max(x0, x2), -gw))  # right side wall
    for x0, y0, x1, y1 in boxes:
        shape = pymunk.Poly(body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
        shape.elasticity = f.wall_restitution
        shape.friction = 1.0
        shape.collision_type = WALL
        space.add(shape)
    # Sensors beyond the lines: the ball overlaps one exactly when its centre is more than
    # one radius past a goal line or touch line, i.e. the whole ball is out. Their "begin"
    # callback records the substep at which that first happens, at no cost per substep.
    d = 2.0 * ball_radius
    for x0, y0, x1, y1 in [(hx + d, -wy, wx, wy), (-wx, -wy, -hx - d, wy),
                           (-wx, hy + d, wx, wy), (-wx, -wy, wx, -hy - d)]:
        sensor = pymunk.Poly(body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
        sensor.sensor = True
        sensor.collision_type = OUT
        space.add(sensor)
