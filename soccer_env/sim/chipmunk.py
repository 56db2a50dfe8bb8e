"""Chipmunk's C functions, the one place the package reaches into pymunk's internals.

The hot paths call them directly because pymunk 7's public API has no equivalent at the same
cost: its property wrappers cost 0.6-0.8 microseconds per access against 0.2-0.3 for the C
call (a Goalkeeper step makes a dozen such accesses); ``Space.step`` adds about 3
microseconds of Python housekeeping per substep over ``cpSpaceStep`` on the space's handle;
and ``pymunk.batch``, which reads and writes whole spaces, costs more than these calls for the
few bodies of a world. The package pins pymunk 7, whose internals these are; a pymunk release
that moves them breaks this import alone.
"""

from pymunk._chipmunk import lib

__all__ = ["lib"]
