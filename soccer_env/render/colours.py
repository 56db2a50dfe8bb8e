"""The colours of a rendered frame (RGB, 0-255), shared by what draws the field, the overlays
and the legend's swatches."""

from __future__ import annotations

__all__ = ["TEAM_COLOURS", "OVERLAY_COLOURS", "CARPET", "WALL", "LINE", "GOAL", "BALL",
           "BALL_EDGE", "SHADOW", "BELIEF", "ELLIPSE", "BALL_PARTICLE", "POSE_PARTICLE",
           "MEASURED", "CONE", "BAR", "TEXT", "DIM", "PAUSED", "Colour"]

#: An RGB colour.
Colour = tuple[int, int, int]

#: Blue's and yellow's robots.
TEAM_COLOURS: tuple[Colour, Colour] = ((40, 100, 255), (245, 215, 0))
CARPET: Colour = (24, 120, 48)
WALL: Colour = (90, 60, 30)
LINE: Colour = (235, 235, 235)
GOAL: Colour = (60, 60, 60)
BALL: Colour = (255, 120, 0)
BALL_EDGE: Colour = (60, 30, 0)
#: A flying ball's shadow on the carpet.
SHADOW: Colour = (10, 60, 20)
#: What the team believes: robots' outlines, the ball and its velocity.
BELIEF: Colour = (0, 230, 255)
#: The 2-sigma ellipses (a paler cyan than the belief's outlines).
ELLIPSE: Colour = (160, 255, 250)
BALL_PARTICLE: Colour = (0, 230, 255)
POSE_PARTICLE: Colour = (255, 150, 235)
#: The latest ball sighting.
MEASURED: Colour = (255, 40, 200)
#: A humanoid's head camera view.
CONE: Colour = (205, 205, 205)
#: The info bar's background, its text, its dimmed text and the paused line.
BAR: Colour = (22, 26, 30)
TEXT: Colour = (240, 240, 240)
DIM: Colour = (170, 175, 180)
PAUSED: Colour = (255, 210, 60)
#: The colours of what is drawn over the field (RGB), by legend key (the belief's robots,
#: ball and velocity share ``"belief"``).
OVERLAY_COLOURS: dict[str, Colour] = {"ball": BALL, "belief": BELIEF, "ellipses": ELLIPSE,
                                      "ball_particles": BALL_PARTICLE,
                                      "pose_particles": POSE_PARTICLE, "measurement": MEASURED,
                                      "camera": CONE}
