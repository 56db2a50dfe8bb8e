"""A team's own robots predicted from the commands it sent them (a Smith predictor).

Overhead vision reports a robot's pose late (the ``ssl-2012`` preset: 80 ms from capture to
the team, and the command the team sends then takes effect 40 ms later). A constant-velocity
tracker (:class:`~estimators.kalman.RobotTracker`) bridges those 120 ms with the velocity it
has estimated, which is wrong whenever the robot accelerates, brakes or turns: the team's own
commands are why it does, and a controller that closes its loop on the late pose overshoots
and circles its target. SSL teams therefore predict their own robots from the commands they
sent since the latest detection (as a Smith predictor does for any loop with a dead time).

:class:`CommandHistory` keeps a team's recent commands, each with the time it takes effect;
:func:`drive_poses` predicts the robots from their latest filtered pose and velocity through
those commands with the drive of an omnidirectional robot:

* a command holds a body-frame velocity ``(vx, vy)`` [m/s] (norm capped at ``max_speed``) and a
  turn rate ``omega`` [rad/s] (capped at ``max_angular_speed``) for ``dt`` seconds from its
  start; its field-frame target is ``(vx, vy)`` rotated by the heading expected at the
  middle of its span (``theta + omega dt / 2`` from where the robot is at its start);
* over every substep ``h`` the velocity moves towards the target by at most
  ``max_acceleration h`` (a vector step) and the turn rate by at most
  ``max_angular_acceleration h``, and the pose moves by the new velocity times ``h``
  (semi-implicit Euler, as the physics engine integrates);
* before the history's first command (or with none recorded), from ``origin`` on, the robots
  stand still (what a command channel delivers before the first command arrives); a robot
  last updated before ``origin`` keeps the tracker's constant-velocity prediction.

Collisions and lost commands are not modelled: the next detection corrects them, with the
vision's delay.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..checks import check_count
from ..compiled import kernel
from ..exact import wrap_angle

__all__ = ["CommandHistory", "drive_poses"]


@kernel
def _step_towards(v: float, target: float, limit: float) -> float:
    """``v`` moved towards ``target`` by at most ``limit``."""
    d = target - v
    if d > limit:
        return v + limit
    if d < -limit:
        return v - limit
    return target


@kernel
def drive_poses(out: np.ndarray, robots: np.ndarray, state: np.ndarray, times: np.ndarray,
                seen: np.ndarray, t: float, starts: np.ndarray, commands: np.ndarray,
                origin: float, dt: float, h: float, limits: np.ndarray) -> None:
    """Overwrite the rows ``robots`` ``(r,)`` of ``out`` ``(n, 6)`` (``x, y, theta, vx, vy,
    omega``) with those robots driven from their latest update to ``t`` [s] (see the module
    docstring).

    ``state`` ``(n, 5, 3)``, ``times`` and ``seen`` ``(n,)`` are one
    :class:`~estimators.kalman.RobotTracker`'s arrays (per axis ``p, v, P00, P01, P11``);
    ``starts`` ``(K,)`` the commands' start times in increasing order, ``commands``
    ``(K, r, 3)`` their body-frame ``vx, vy, omega``; ``dt`` [s] how long each holds; ``h``
    [s] the longest substep; ``limits`` ``(max_speed, max_acceleration, max_angular_speed,
    max_angular_acceleration)``. Robots never seen, or already updated at ``t`` or later,
    keep their rows."""
    vmax, amax, wmax, alpha = limits[0], limits[1], limits[2], limits[3]
    K = starts.shape[0]
    for j in range(robots.shape[0]):
        i = robots[j]
        s = times[i]
        if not seen[i] or s >= t or s < origin:
            continue
        x, y, th = state[i, 0, 0], state[i, 0, 1], state[i, 0, 2]
        vx, vy, w = state[i, 1, 0], state[i, 1, 1], state[i, 1, 2]
        c = 0  # the first command not yet started
        while c < K and starts[c] <= s:
            c += 1
        while s < t:
            if c == 0:  # before the first command: standing still
                end, cx, cy, cw = starts[0] if K else t, 0.0, 0.0, 0.0
            else:
                end = starts[c - 1] + dt
                cx, cy, cw = commands[c - 1, j, 0], commands[c - 1, j, 1], commands[c - 1, j, 2]
                if c < K and starts[c] < end:
                    end = starts[c]
            if end <= s:  # a gap between commands: the last one holds
                end = starts[c] if c < K else t
            if end > t:
                end = t
            speed = math.hypot(cx, cy)
            if speed > vmax:
                cx, cy = cx * vmax / speed, cy * vmax / speed
            cw = min(max(cw, -wmax), wmax)
            span = end - s
            mid = th + 0.5 * span * cw
            tx = math.cos(mid) * cx - math.sin(mid) * cy
            ty = math.sin(mid) * cx + math.cos(mid) * cy
            n_sub = max(1, int(math.ceil(span / h - 1e-9)))
            hs = span / n_sub
            for _ in range(n_sub):
                dx, dy = tx - vx, ty - vy
                dv = math.hypot(dx, dy)
                step = amax * hs
                if dv > step:
                    vx, vy = vx + dx * step / dv, vy + dy * step / dv
                else:
                    vx, vy = tx, ty
                w = _step_towards(w, cw, alpha * hs)
                x += vx * hs
                y += vy * hs
                th += w * hs
            s = end
            while c < K and starts[c] <= s:
                c += 1
        out[i, 0], out[i, 1], out[i, 2] = x, y, wrap_angle(th)
        out[i, 3], out[i, 4], out[i, 5] = vx, vy, w


class CommandHistory:
    """A team's recent commands, each with the time it takes effect (see the module
    docstring), and the drive that turns them into poses.

    Args:
        robots: the team's robots, as the tracker indexes them.
        dt: how long each command holds [s] (the control step).
        keep: how many commands to keep (the newest); enough to span the vision's delay plus
            the prediction's lead and a few camera frames.
        limits: ``(max_speed, max_acceleration, max_angular_speed,
            max_angular_acceleration)`` of the robots [m/s, m/s^2, rad/s, rad/s^2].
        substep: the longest integration substep [s].
    """

    def __init__(self, robots: Sequence[int], dt: float, keep: int,
                 limits: Sequence[float], substep: float = 1.0 / 240.0) -> None:
        self.robots = np.asarray(robots, dtype=np.int64).reshape(-1)
        check_count("keep", keep, 1, 100_000)
        for name, v in (("dt", dt), ("substep", substep), *zip(
                ("max_speed", "max_acceleration", "max_angular_speed",
                 "max_angular_acceleration"), limits)):
            if not (math.isfinite(v) and v > 0.0):
                raise ValueError(f"{name} must be finite and > 0, got {v!r}")
        if len(limits) != 4:
            raise ValueError(f"limits must be 4 figures, got {len(limits)}")
        self.dt, self.keep, self.substep = float(dt), int(keep), float(substep)
        self.limits = np.array(limits, dtype=np.float64)
        self.reset(-math.inf)

    def reset(self, origin: float) -> None:
        """Forget the commands: from ``origin`` [s] on the robots stand still until the
        first command recorded takes effect."""
        self.origin = float(origin)
        self._starts = np.zeros(0)
        self._commands = np.zeros((0, len(self.robots), 3))

    def record(self, start: float, commands: np.ndarray) -> None:
        """The team's body-frame ``vx, vy, omega`` ``(r, 3)`` (or ``(r, k >= 3)``, of
        which the first three columns are read) taking effect at ``start`` [s], after the
        previous command (unchecked: the environment's own, validated commands)."""
        row = np.asarray(commands, dtype=np.float64)[:, 0:3]
        if len(self._starts) >= self.keep:
            self._starts[:-1] = self._starts[1:]
            self._commands[:-1] = self._commands[1:]
            self._starts[-1], self._commands[-1] = start, row
        else:
            self._starts = np.append(self._starts, start)
            self._commands = np.concatenate([self._commands, row[None]])

    def drive(self, out: np.ndarray, state: np.ndarray, times: np.ndarray, seen: np.ndarray,
              t: float) -> np.ndarray:
        """``out`` (a tracker's ``(n, 6)`` estimate at ``t``) with the team's robots driven
        to ``t`` by :func:`drive_poses` from the tracker's arrays (in place; returned)."""
        drive_poses(out, self.robots, state, times, seen, float(t), self._starts,
                    self._commands, self.origin, self.dt, self.substep, self.limits)
        return out
