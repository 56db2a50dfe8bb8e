"""The closed-form motion of a ball rolling on carpet: the ball model of Zhao et al. (2012) (Zhao,
Wang, Li 2012)."""

from __future__ import annotations

import numpy as np

from ..checks import MAX_COORDINATE, MAX_SPEED, check_real

__all__ = ["FrictionBallModel"]


def _states(state) -> np.ndarray:
    """``state`` as a float array of shape ``(..., 4)`` of finite rows ``(px, py, vx, vy)``
    with positions within :data:`~estimators.checks.MAX_COORDINATE` [m] and velocity
    components within :data:`~estimators.checks.MAX_SPEED` [m/s]; ``ValueError`` naming
    ``state`` otherwise."""
    try:
        arr = np.asarray(state, dtype=np.float64)
    except (TypeError, ValueError):
        arr = None
    if arr is None or arr.ndim < 1 or arr.shape[-1] != 4 or not np.all(np.isfinite(arr)) or \
            np.any(np.abs(arr[..., :2]) > MAX_COORDINATE) or \
            np.any(np.abs(arr[..., 2:]) > MAX_SPEED):
        raise ValueError(f"state must be finite (px, py, vx, vy) rows of shape (..., 4), "
                         f"positions within {MAX_COORDINATE:g} m and velocities within "
                         f"{MAX_SPEED:g} m/s, got {state!r}"[:300])
    return arr


class FrictionBallModel:
    """A ball decelerating at a constant ``deceleration`` against its velocity until it stops.

    This is the ball model of Zhao, Wang and Li (2012): carpet friction is a
    constant deceleration ``a_f`` opposite to the motion, so between collisions the ball moves
    in a straight line, decelerates uniformly and stops instead of reversing. For a state
    ``(px, py, vx, vy)`` with speed ``v`` and direction ``u = (vx, vy) / v``, after ``dt``
    seconds:

    * if ``dt < v / a``: ``p' = p + u (v dt - a dt^2 / 2)``, ``v' = u (v - a dt)``;
    * otherwise the ball has stopped at ``p + u v^2 / (2 a)`` with zero velocity.

    The closed form is exact for any ``dt``, unlike Euler integration. States may be batched:
    arrays of shape ``(..., 4)``. Units: metres, seconds.

    Args:
        deceleration: ``a_f`` [m/s^2], >= 0 (Zhao et al. 2012 measured 0.23 m/s^2).
    """

    def __init__(self, deceleration: float) -> None:
        self.deceleration = check_real("deceleration", deceleration, 0.0, unit=" m/s^2")

    def predict(self, state: np.ndarray, dt: float | np.ndarray) -> np.ndarray:
        """State ``(..., 4)`` after ``dt`` seconds (``dt`` broadcasts against the batch).
        ``ValueError`` naming ``state`` for rows that are not finite, positions beyond
        :data:`~estimators.checks.MAX_COORDINATE` [m] or velocities beyond
        :data:`~estimators.checks.MAX_SPEED` [m/s], and naming ``state and dt`` where the
        prediction itself leaves float range (a ball that never stops, ``deceleration = 0``,
        after ``dt = inf``)."""
        state = _states(state)
        try:
            dt = np.asarray(dt, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError(f"dt must be a time in seconds, got {dt!r}") from None
        if np.any(np.isnan(dt)) or np.any(dt < 0):
            raise ValueError(f"dt must be >= 0 s (inf: until the ball stops), got {dt!r}")
        p, v = state[..., 0:2], state[..., 2:4]
        speed = np.linalg.norm(v, axis=-1, keepdims=True)
        a = self.deceleration
        t_stop = np.where(a > 0, speed / max(a, 1e-300), np.inf)
        t = np.minimum(dt[..., None] if dt.ndim else dt, t_stop)
        direction = np.divide(v, speed, out=np.zeros_like(v), where=speed > 0)
        with np.errstate(over="ignore", invalid="ignore"):
            travelled = speed * t - 0.5 * a * t * t
            new_speed = np.maximum(speed - a * t, 0.0)
            out = np.concatenate([p + direction * travelled, direction * new_speed], axis=-1)
        if not np.isfinite(out).all():
            raise ValueError(f"state and dt must keep the prediction finite: at deceleration "
                             f"{a:g} m/s^2 the ball rolls beyond float range in dt={dt!r} s")
        return out

    def stop_time(self, state: np.ndarray) -> np.ndarray:
        """Seconds until the ball stops (``inf`` without friction), shape ``(...)``."""
        speed = np.linalg.norm(_states(state)[..., 2:4], axis=-1)
        if self.deceleration == 0.0:
            return np.where(speed > 0, np.inf, 0.0)
        return speed / self.deceleration

    def stop_position(self, state: np.ndarray) -> np.ndarray:
        """Where the ball comes to rest, shape ``(..., 2)``: without friction a moving ball
        never does, and each coordinate it moves along is ``+-inf`` (one it does not move
        along stays where it is); a ball at rest stays where it is."""
        state = _states(state)
        if self.deceleration > 0.0:
            return self.predict(state, self.stop_time(state))[..., 0:2]
        p, v = state[..., 0:2], state[..., 2:4]
        # Not p + v * inf: a zero velocity component would give 0 * inf = NaN.
        return np.where(v != 0.0, np.copysign(np.inf, v), p)

    def time_to_line(self, state: np.ndarray, x_line: float) -> np.ndarray:
        """Seconds until the ball reaches the line ``x = x_line``, ``inf`` if it stops first
        or moves away from it; shape ``(...)``.

        Solves ``x + u_x (v t - a t^2 / 2) = x_line`` for the smallest ``t`` in
        ``[0, v / a]``.
        """
        state = _states(state)
        x_line = check_real("x_line", x_line, unit=" m")
        x, vx = state[..., 0], state[..., 2]
        speed = np.linalg.norm(state[..., 2:4], axis=-1)
        a = self.deceleration
        dist = x_line - x
        with np.errstate(divide="ignore", invalid="ignore"):
            # Distance along the path needed to cover ``dist`` along x.
            s = dist * speed / vx
            if a == 0.0:
                t = s / speed
            else:
                disc = speed * speed - 2.0 * a * s
                t = (speed - np.sqrt(disc)) / a
            ok = (vx != 0) & (s >= 0) & ((a == 0.0) | (speed * speed - 2.0 * a * s >= 0))
        return np.where(ok, np.where(dist == 0, 0.0, t), np.inf)
