"""The referee's per-step checks over every pair of robots, as compiled kernels
(:func:`contacts_started`): the part of the SSL fouls (:mod:`soccer_env.sim.game.fouls`) that
looks at every blue robot against every yellow one each step.

What a check finds is rare (a contact starts in a few steps of a match); the kernel only finds
the candidates, and the controller weighs each candidate with the rule's remaining tests in
plain Python, so that a foul is recorded exactly as before.
"""

from __future__ import annotations

import numpy as np

from estimators.compiled import kernel
from estimators.exact import hypot_exact

__all__ = ["contacts_started"]


@kernel
def contacts_started(robots: np.ndarray, prev: np.ndarray, teams: np.ndarray,
                     on_field: np.ndarray, radii: np.ndarray, slack: float,
                     out: np.ndarray) -> int:
    """The pairs of a blue and a yellow robot on the field that came into contact this step.

    Robots ``i`` (team 0) and ``j`` (team 1) touch when their centres are at most
    ``reach = r_i + r_j + slack`` apart [m]; a contact starts when they touch now
    (``robots``, rows ``x, y, ...``) and did not at the previous step (``prev``). The pairs
    are written to ``out`` (rows ``i, j``, at least ``n_blue * n_yellow`` of them) in the
    order blue robot, then yellow robot, ascending; returns how many.

    Args:
        robots: ``(N, >=2)`` robot rows now [m].
        prev: ``(N, >=2)`` the same robots at the previous step [m].
        teams: ``(N,)`` team of each robot (0 blue, 1 yellow).
        on_field: ``(N,)`` whether each robot plays (not sent off).
        radii: ``(N,)`` robot radii [m].
        slack: contact margin added to the radii [m].
        out: ``(K, 2)`` int64 output rows.
    """
    n = 0
    count = teams.shape[0]
    for i in range(count):
        if teams[i] != 0:
            continue
        for j in range(count):
            if teams[j] != 1 or not (on_field[i] and on_field[j]):
                continue
            reach = radii[i] + radii[j] + slack
            now = hypot_exact(robots[j, 0] - robots[i, 0], robots[j, 1] - robots[i, 1])
            before = hypot_exact(prev[j, 0] - prev[i, 0], prev[j, 1] - prev[i, 1])
            if now > reach or before <= reach:
                continue
            out[n, 0] = i
            out[n, 1] = j
            n += 1
    return n
