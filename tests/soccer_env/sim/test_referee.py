"""Where a ball out of play left the field, as both game controllers and the simple referee
read it (:mod:`soccer_env.sim.referee`)."""

from __future__ import annotations

import pytest

from soccer_env import presets
from soccer_env.sim.referee import classify_exit, defending_team, exit_end, exit_side
from soccer_env.sim.world import BallExit

FIELD, BALL = presets.field("ssl-div-b"), presets.ball("ssl")


@pytest.mark.parametrize("x, y, end, side, defender", [
    (FIELD.half_length + 0.1, 0.9, 1, 1.0, 1),      # over the goal line at +x, upper side
    (-FIELD.half_length - 0.1, -0.9, -1, -1.0, 0),  # over the goal line at -x, lower side
    (1.0, -FIELD.half_width - 0.1, 1, -1.0, 1),     # a touch line in the +x half
    (-1.0, FIELD.half_width + 0.1, -1, 1.0, 0),     # a touch line in the -x half
    (-1.0, 0.0, -1, 1.0, 0),                        # no side: the +y side
])
def test_the_end_side_and_defenders_of_an_exit(x, y, end, side, defender):
    ex = BallExit(x, y, 0.0, 1.0)
    kind = classify_exit(ex, FIELD, BALL)
    assert exit_end(ex, kind) == end
    assert exit_side(ex) == side
    assert defending_team(exit_end(ex, kind)) == defender
