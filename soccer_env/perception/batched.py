"""The perception of many environments at once: :class:`FilteredPerceptionBatch`, the
``obs_mode="perceived"`` pipeline of SSL teams (:class:`~soccer_env.perception.overhead.
FilteredPerception`) for ``m`` environments as arrays.

The overhead cameras of every field capture in one array pass
(:class:`~soccer_env.sensors.overhead_batch.OverheadVisionBatch`), and the robot and ball filters of
every environment update together, one array operation per round of frames
(:class:`~estimators.RobotTrackerBatch`, :class:`~estimators.BallTrackerBatch`): round ``j``
takes every environment's ``j``-th frame of the step in capture-time order, as the single
pipeline consumes them. Environment ``k``'s beliefs are, bit for bit, those of a single
:class:`~soccer_env.perception.match.MatchPerception` fed the same truth from the same
generator (``tests/soccer_env/perception/test_batched.py``).

:func:`batch_refusal` says when a configuration needs the single pipelines instead: raw
observations, humanoids, the pixels detector, randomised sensor figures, belief features, two
SSL teams with different configurations, latency jitter (frames then arrive out of capture
order, which the batched ball filter does not replay) and the least-squares ball predictor.
"""

from __future__ import annotations

import numpy as np

from estimators import BallTracker, BallTrackerBatch, RobotTrackerBatch
from soccer_env.perception.match import MatchPerception
from soccer_env.perception.overhead import FilteredPerception
from soccer_env.sensors.overhead import OverheadVision
from soccer_env.sensors.overhead_batch import FrameBatch, OverheadVisionBatch

__all__ = ["FilteredPerceptionBatch", "batch_refusal", "MIN_BATCH"]

#: The fewest environments for which the batched environments perceive as one batch: below
#: it each environment's own pipeline is faster (the batch's cost is mostly a fixed number of
#: array operations per step). Measured on the perceived ``ssl-2012`` Goalkeeper: 8, 16, 32
#: and 64 environments ran at 0.35, 0.51, 0.78 and 1.31 times the per-environment pipelines'
#: rate. Both give the same beliefs.
MIN_BATCH = 48


def batch_refusal(perception: MatchPerception, m: int | None = None) -> str | None:
    """Why ``perception`` (an environment's, as built) cannot or, for ``m`` environments
    (fewer than :data:`MIN_BATCH`), should not run as a :class:`FilteredPerceptionBatch`;
    None when it can."""
    if m is not None and m < MIN_BATCH:
        return f"{m} environments (each one's own pipeline is faster below {MIN_BATCH})"
    if perception.obs_mode != "perceived":
        return f"obs_mode={perception.obs_mode!r} (only 'perceived' is batched)"
    if perception.reads_bodies:
        return "humanoid perception"
    if perception._randomized:
        return "randomised sensor figures"
    if perception.features:
        return "belief features"
    if perception.driven:
        return "robot_prediction='commands'"
    if len(perception._groups) != 1:
        return "two SSL teams with different perception"
    _, pipe, _ = perception._groups[0]
    if not isinstance(pipe, FilteredPerception):
        return f"{type(pipe).__name__}"
    if pipe.detector is not None or type(pipe.sensor) is not OverheadVision:
        return f"the {pipe.config.detector!r} detector"
    if pipe.vision_spec.latency_jitter != 0.0:
        return "latency jitter (frames out of capture order)"
    if type(pipe.ball_tracker) is not BallTracker:
        return f"the {pipe.config.ball_filter!r} ball filter"
    return None


class FilteredPerceptionBatch:
    """The perceived beliefs of ``m`` environments of one configuration (see the module
    docstring).

    Args:
        perception: one environment's :class:`MatchPerception` (as the single environment
            builds it; :func:`batch_refusal` must accept it): the configuration, the sensor
            and the filters' parameters are taken from it.
        m: environments.
    """

    def __init__(self, perception: MatchPerception, m: int) -> None:
        why = batch_refusal(perception)
        if why is not None:
            raise ValueError(f"this perception does not run batched: {why}")
        robots, pipe, _ = perception._groups[0]
        self.m = int(m)
        self.n_robots = pipe.n_robots
        s = pipe.sensor
        self.sensor = OverheadVisionBatch(s.spec, s.field, s.robot_spec, s.ball_spec,
                                          s.n_robots, self.m, s.cameras)
        one = pipe.robot_tracker
        self.robots = RobotTrackerBatch(self.m, one.n, measurement=s.robot_model)
        self.robots.q, self.robots.r, self.robots.var_v0 = (np.array(one.q), np.array(one.r),
                                                            one.var_v0)
        b = pipe.ball_tracker
        self.ball = BallTrackerBatch(self.m, b.config, b.measurement)
        self._capture_times = pipe._capture_times
        #: How far ahead of the present the observation's belief is predicted [s].
        self.ahead = pipe.ahead
        self._now = np.zeros(self.m)
        self._beliefs: tuple[np.ndarray, np.ndarray] | None = None
        self._present: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None

    def reset(self, rows, times, balls, robots, rngs: list[np.random.Generator]) -> None:
        """Start episodes in environments ``rows`` ``(d,)`` at ``times`` with the truth
        ``balls`` ``(d, 3)`` (``x, y, z``) and ``robots`` ``(d, N, 3)`` (poses), each
        drawing from its sensor generator in ``rngs`` (``MatchPerception.reset``)."""
        self.advance(start=(rows, times, balls, robots, rngs))

    def update(self, rows, times, balls, robots) -> None:
        """Advance environments ``rows`` to ``times`` with their truth (as :meth:`reset`)."""
        self.advance((rows, times, balls, robots))

    def advance(self, step: tuple | None = None, start: tuple | None = None) -> None:
        """:meth:`update` the environments of ``step`` (``(rows, times, balls, robots)``)
        and :meth:`reset` those of ``start`` (``(rows, times, balls, robots, rngs)``) in one
        pass; the two sets of rows must not meet."""
        if start is not None and len(start[0]):
            rows = np.asarray(start[0], dtype=np.int64)
            self.robots.reset(rows)
            self.ball.reset(rows)
        delivered, warm = self.sensor.advance(step, start)
        for part in (step, start):
            if part is not None and len(part[0]):
                self._now[np.asarray(part[0], dtype=np.int64)] = part[1]
        frames = (delivered if not warm.count else warm if not delivered.count
                  else FrameBatch.join([delivered, warm]))
        self._consume(frames)
        self._beliefs = self._present = None

    def beliefs(self) -> tuple[np.ndarray, np.ndarray]:
        """Every environment's belief for its observation, predicted to its present plus
        :attr:`ahead`: ``(ball (m, 6), robots (m, N, 6))`` (``x, y, 0, vx, vy, 0`` for the
        ball, zeros before its first detection), read only."""
        if self._beliefs is None:
            self._beliefs = self._estimate(self._now + self.ahead)
        return self._beliefs

    def present(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every environment's belief at its present time (what a single environment reports
        in ``info["estimate"]``): ``(times (m,) [s], ball (m, 6), robots (m, N, 6))``, laid
        out as :meth:`beliefs`' (the same arrays when nothing is predicted ahead), read
        only."""
        if self._present is None:
            if not self.ahead:
                ball, robots = self.beliefs()
            else:
                ball, robots = self._estimate(self._now)
            self._present = (self._now.copy(), ball, robots)
        return self._present

    def _estimate(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The filters' estimates at the times ``t`` ``(m,)`` [s]: ``(ball (m, 6), robots
        (m, N, 6))``, read only (the ball zeros before its first detection)."""
        est, known = self.ball.estimate(t)
        ball = np.zeros((self.m, 6))
        ball[:, 0:2], ball[:, 3:5] = est[:, 0:2], est[:, 2:4]
        ball[~known] = 0.0
        robots = self.robots.estimate(t)
        ball.flags.writeable = robots.flags.writeable = False
        return ball, robots

    def _consume(self, frames: FrameBatch) -> None:
        """``FilteredPerception.consume`` of every environment's frames: by capture time
        (delivery order among equals), robots first, then the ball, one round per frame."""
        count = frames.count
        if not count:
            return
        env = frames.env
        order = np.lexsort((np.arange(count), frames.t_capture, env))
        sorted_env = env[order]
        first = np.ones(count, dtype=bool)
        first[1:] = sorted_env[1:] != sorted_env[:-1]
        starts = np.nonzero(first)[0]
        rank = np.arange(count) - np.repeat(starts, np.diff(np.append(starts, count)))
        stamps = frames.t_capture if self._capture_times else frames.t_delivered
        has_ball = frames.ball_seen.any(axis=1)
        for j in range(int(rank.max()) + 1):
            idx = order[rank == j] if len(starts) < count else order
            k, i = np.nonzero(frames.robot_seen[idx])
            if len(k):
                f = idx[k]
                self.robots.update(env[f], i, frames.t_capture[f], frames.robots[f, i])
            b = idx[has_ball[idx]]
            if len(b):
                self.ball.update(env[b], stamps[b], frames.balls[b], frames.ball_seen[b],
                                 frames.robots[b], frames.robot_seen[b])
