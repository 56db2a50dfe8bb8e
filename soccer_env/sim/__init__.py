"""The simulation: the pymunk world (ball, SSL robots, humanoids), the humanoids' walk engine,
the command channel from policies to robots, the referee's rules and head control.

Everything here works on the truth; the sensors read it (:mod:`soccer_env.sensors`), nothing
here reads a sensor or a belief except the head controller, which turns what a robot believes
into the targets of its head servos.
"""

from soccer_env.sim.world import COMMAND_FIELDS, BallExit, World, idle_commands

__all__ = ["World", "BallExit", "COMMAND_FIELDS", "idle_commands"]
