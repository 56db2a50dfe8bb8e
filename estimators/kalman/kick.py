"""A kick-aware ball tracker: each motion since a kick or a collision fitted as a whole.

A recursive filter (:class:`~estimators.BallTracker`) learns a kicked ball's new velocity over
many frames: its velocity noise must be small for steady tracking, so after a kick it either
waits for a reset or converges slowly, and with 25 mm noise at 25 Hz the direction of a shot
stays uncertain for a third of a second. But between kicks and collisions a ball on carpet
follows a known law (it slides, then rolls, each at a constant deceleration), and before a
kick it lies still, so the point it is kicked from is known as well as every detection of
the resting ball together can say. :class:`KickAwareBall` uses both: it splits the detections
into *segments*, one per motion, and fits each segment's law of motion to all of the
segment's detections at once (a nonlinear least-squares smoother over the friction model,
whose fit at the newest detection is the filtered estimate), started at the kick point and
the kick time.

**Segments.** A detection is the ball if its squared Mahalanobis distance from the current
segment's prediction (variance ``sigma^2`` plus the fit's position variance) is within
``gate``. One that is not, near enough that the ball could have got there from the predicted
position at up to ``max_kick_speed``, is first offered to a young segment whose kick time is
still searched (its prediction leaves that uncertainty out); if the refit does not explain it
either, it starts a new segment at once (a kick or a bounce where the ball is), whose kick
point prior is the old segment's position at the kick time. If the next detection agrees
with the old motion instead, the new one is dropped again (``reverted``). A detection too far
for a kick waits for a second one that agrees with it: then the ball is elsewhere and a new
track starts from the two, with no prior (a lone spurious detection is dropped).

The law of a motion and its fit are :mod:`estimators.kalman.segments`; the gate, the
agreement of two far detections and the track quality are the shared parts of
:mod:`estimators.tracking`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..checks import check_points, check_real
from ..protocol import check_order, check_time
from ..tracking import (
    CHI2_2DOF_999,
    MAX_SPEED_CHANGE,
    Gate,
    TrackInitiator,
    TrackQualityMixin,
    TrackTimes,
)
from .segments import REST_SPEED, Segment, SegmentFit, moving_on, still, travel, travel_one

__all__ = ["KickAwareBall", "travel"]


class KickAwareBall(TrackQualityMixin):
    """Kick-aware ball tracker for overhead-camera detections (see the module docstring).

    Follows the tracker protocol (:class:`~estimators.protocol.Tracker`) and
    :class:`~estimators.protocol.TrackQuality`, as :class:`~estimators.BallTracker`:
    ``update(t, detections, obstacles=None)`` with the capture time ``t`` [s] and the frame's
    ball detections ``(k, 2)`` [m], ``estimate(t) -> (x, y, vx, vy)``, ``covariance(t)``,
    ``reset()``.

    Args:
        sliding_deceleration: ``a_s`` [m/s^2], >= 0.
        rolling_deceleration: ``a_r`` [m/s^2], >= 0.
        k_switch: the speed at which a kicked ball starts rolling, as a fraction of its kick
            speed, in (0, 1].
        sigma_xy: the detections' noise per axis [m], > 0.
        gate: squared Mahalanobis distance beyond which a detection is not the current
            motion's (default: the 99.9 % quantile of chi-square with 2 degrees of freedom).
        max_kick_speed: fastest change of velocity a kick or bounce makes [m/s]: a detection
            the ball could have reached from its predicted position at this speed starts a
            new motion at once.
        kick_search: how long before the last detection of a resting ball that still agreed
            with rest the kick may have happened [s].
        search: kick times tried while a segment is young, >= 1.
        lock: detections after which a segment's kick time is fixed, >= 1.

    Attributes:
        fused, rejected, segments, reverted: counters: detections fused, detections not fused
            (outliers), motions started after the first (kicks and collisions), motions
            dropped again because the next detection agreed with the old one.
    """

    def __init__(self, sliding_deceleration: float = 3.0, rolling_deceleration: float = 0.3,
                 k_switch: float = 0.64, sigma_xy: float = 0.025,
                 gate: float = CHI2_2DOF_999, max_kick_speed: float = MAX_SPEED_CHANGE,
                 kick_search: float = 0.06, search: int = 8, lock: int = 6) -> None:
        self.sliding = check_real("sliding_deceleration", sliding_deceleration, 0.0, 100.0,
                                  unit=" m/s^2")
        self.rolling = check_real("rolling_deceleration", rolling_deceleration, 0.0, 100.0,
                                  unit=" m/s^2")
        self.k_switch = check_real("k_switch", k_switch, 0.0, 1.0, low_open=True)
        self.sigma_xy = check_real("sigma_xy", sigma_xy, 0.0, 10.0, low_open=True, unit=" m")
        self.gate = check_real("gate", gate, 0.0, low_open=True)
        self.max_kick_speed = check_real("max_kick_speed", max_kick_speed, 0.0, 100.0,
                                         unit=" m/s")
        self.kick_search = check_real("kick_search", kick_search, 0.0, 1.0, unit=" s")
        for name, value in (("search", search), ("lock", lock)):
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
                raise ValueError(f"{name} must be an integer >= 1, got {value!r}")
        self.search, self.lock = int(search), int(lock)
        # Weak prior on the start velocity, in measurements' worth: w ~ N(0, (10/3 m/s)^2).
        self._mu = (self.sigma_xy / (MAX_SPEED_CHANGE / 3.0)) ** 2
        self._fit = SegmentFit(self.sliding, self.rolling, self.k_switch, self.sigma_xy,
                               self.gate, self.search, self._mu)
        self._gate = Gate(self.gate, self.max_kick_speed)
        self._initiator = TrackInitiator(self.sigma_xy)
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode)."""
        self._seg: Segment | None = None
        self._previous: Segment | None = None  # the motion a one-detection kick replaced
        self._pending: tuple[float, tuple[float, float]] | None = None
        self._kick_hint: float | None = None
        self._time = -math.inf
        self._last_fused = -math.inf
        self._last_agreed = -math.inf
        self.fused = self.rejected = self.segments = self.reverted = 0

    # ------------------------------------------------------------------------------------
    # Protocol

    @property
    def _track(self) -> TrackTimes:
        """The track's times: the latest frame's, the latest fused detection's, and the
        detections fused since the current motion started."""
        return TrackTimes(self._time, self._last_fused,
                          0 if self._seg is None else self._seg.fused)

    @property
    def kick_time(self) -> float | None:
        """When the current motion started [s]: its fitted kick time (the first detection's
        time for the first motion; None before the first detection)."""
        return None if self._seg is None else self._seg.tk

    @property
    def at_rest(self) -> bool | None:
        """Whether the ball is taken to lie still (None before the first detection)."""
        return None if self._seg is None else self._seg.rest

    def kick(self, t: float) -> None:
        """Tell the tracker that the ball was kicked (or hit) at time ``t`` [s], e.g. by the
        team's own robot: the first detection after ``t`` starts a new motion at exactly
        ``t``, without waiting for a detection that disagrees with the old one."""
        self._kick_hint = check_time(t)

    def update(self, t: float, detections, obstacles=None) -> None:
        """Process one frame captured at ``t`` with ball detections ``(k, 2)`` (k may be 0);
        ``obstacles`` (the robots seen) is accepted for the protocol's sake and not used."""
        t = check_time(t)
        check_order(t, self._time)
        self.update_frame(t, check_points("detections", detections), [])

    def update_frame(self, t: float, detections: Sequence[Sequence[float]],
                     obstacles: Sequence[Sequence[float]] = ()) -> None:
        """:meth:`update` without its checks (a sensor's own, checked frames)."""
        self._time = max(self._time, t)
        if not detections:
            return
        seg = self._seg
        if seg is None:
            z = detections[0]
            self._seg = Segment(t, t, (still((0.0, 0.0)), 0.0), None)
            self._add(t, (float(z[0]), float(z[1])))
            return
        if t < seg.tk:  # a late frame from before the current motion: too late to use
            return
        hint = self._kick_hint
        if hint is not None and t > hint:
            self._kick_hint = None
            if hint >= seg.tk:
                self._previous = None
                nearest = self._match(seg, detections, t)[1]
                self._new_motion(hint, hint, t, nearest, known=True)
                return
        agreeing, best, _ = self._match(seg, detections, t)
        if agreeing:
            self._pending = None
            before = self._snapshot(seg) if seg.rest else None
            for z in agreeing:
                self._add(t, z)
            if before is not None and not seg.rest:
                # A resting ball that the fit now finds moving (it moved less than the gate):
                # a kick, with its kick time and point searched as for any other.
                self._restore(seg, before)
                self._previous = None
                self._new_motion(self._last_agreed, t, t, agreeing[0])
                for z in agreeing[1:]:
                    self._add(t, z)
                return
            if seg.fused >= 2:
                self._previous = None
            return
        previous = self._previous
        if previous is not None:
            back, _, _ = self._match(previous, detections, t)
            if back:  # the one-detection kick was a spurious detection: back to the old motion
                self._seg, self._previous = previous, None
                self.reverted += 1
                for z in back:
                    self._add(t, z)
                return
        # Not the current motion: a kick or bounce where the ball is, or a spurious detection.
        px, py, var = self._fit.predicted(seg, t)
        near = self._gate.reaches(math.hypot(best[0] - px, best[1] - py),
                                  t - self._last_agreed, math.sqrt(var))
        if near and seg.t_lo < seg.t_hi and not seg.rest and self._refits(seg, t, best):
            return  # a young motion whose kick time was not yet clear
        self.rejected += 1
        pending = self._pending
        agree = pending is not None and self._initiator.agrees(pending[0], pending[1], t, best)
        if near:
            self._pending = None
            self._previous = seg
            counts = (self.fused, self._last_fused, self._last_agreed, self.segments)
            self._new_motion(self._last_agreed, t, t, best)
            if self._seg.rest and seg.rest:  # no kick after all: a rare noise draw
                self.fused, self._last_fused, self._last_agreed, self.segments = counts
                self._seg, self._previous = seg, None
                self.rejected -= 1
                self._add(t, best)
        elif agree:  # the ball is elsewhere: a new track from the two detections alone
            self._pending = self._previous = None
            t0, z0 = pending
            self._seg = fresh = Segment(t0, t0, (still(z0), 0.0), None)
            fresh.times, fresh.points = [t0], [z0]
            fresh.fused = 1
            self.segments += 1
            self._add(t, best)
        else:
            self._pending = (t, best)

    def estimate(self, t: float) -> np.ndarray | None:
        """State ``(x, y, vx, vy)`` at time ``t`` from the current motion's fit (None before
        the first detection)."""
        t = check_time(t)
        seg = self._seg
        if seg is None:
            return None
        return np.array(self._fit.state(seg, t))

    def _covariance(self, t: float) -> np.ndarray:
        """The ``4 x 4`` covariance of ``(x, y, vx, vy)`` at ``t``: the linearised
        covariance of the current motion's fit (see :mod:`estimators.kalman.segments`)."""
        var_p, cov_pv, var_v = self._fit.spread(self._seg, t)
        P = np.zeros((4, 4))
        for a in (0, 1):
            P[a, a], P[a, a + 2] = var_p, cov_pv
            P[a + 2, a], P[a + 2, a + 2] = cov_pv, var_v
        return P

    # ------------------------------------------------------------------------------------
    # Detections and motions

    def _match(self, seg: Segment, detections, t: float):
        """``(agreeing, nearest, d2)``: the detections within the gate of motion ``seg`` at
        ``t``, the nearest detection and its squared Mahalanobis distance."""
        px, py, var = self._fit.predicted(seg, t)
        agreeing, best, d2 = [], None, math.inf
        for z in detections:
            d = ((z[0] - px) ** 2 + (z[1] - py) ** 2) / var
            point = (float(z[0]), float(z[1]))
            if self._gate.admits(d):
                agreeing.append(point)
            if d < d2:
                best, d2 = point, d
        return agreeing, best, d2

    def _refits(self, seg: Segment, t: float, z: tuple[float, float]) -> bool:
        """Whether detection ``z`` at ``t``, outside the gate of young motion ``seg`` (whose
        kick time is still searched: its prediction leaves that uncertainty out), fits it once
        refitted with it; if so it is fused, otherwise ``seg`` is left as it was."""
        saved = self._snapshot(seg)
        self._add(t, z)
        x, y, _, _ = self._fit.state(seg, t)
        if self._gate.admits(((z[0] - x) ** 2 + (z[1] - y) ** 2) / self.sigma_xy ** 2):
            self._pending = None
            return True
        self._restore(seg, saved)
        return False

    def _snapshot(self, seg: Segment) -> tuple[dict, tuple]:
        """What :meth:`_restore` needs to undo fusing detections into ``seg``."""
        saved = {name: getattr(seg, name) for name in Segment.__slots__}
        saved["times"], saved["points"] = list(seg.times), list(seg.points)
        if seg.sums is not None:
            saved["sums"] = list(seg.sums)
        return saved, (self.fused, self._last_fused, self._last_agreed)

    def _restore(self, seg: Segment, snapshot: tuple[dict, tuple]) -> None:
        saved, counts = snapshot
        for name, value in saved.items():
            setattr(seg, name, value)
        self.fused, self._last_fused, self._last_agreed = counts

    # ------------------------------------------------------------------------------------
    # Motions

    def _new_motion(self, t_lo: float, t_hi: float, t: float, z: tuple[float, float],
                    known: bool = False) -> None:
        """Start a new motion, kicked between ``t_lo`` and ``t_hi`` where the old one had the
        ball, seen at ``z`` at ``t`` (``known``: a kick told, at ``t_lo = t_hi``)."""
        old = self._seg
        speed_then = 0.0 if old.rest else travel_one(
            t_lo - old.tk, math.hypot(*old.w), old.v_sw, self.sliding, self.rolling)[1]
        rest = []
        t_agreed = t_lo
        if old.rest or speed_then < REST_SPEED:
            # A kick from rest: the resting ball's detections pin the start.
            if t_hi > t_lo:
                t_lo = max(t_lo - self.kick_search, old.tk)
            if old.sums is None:  # its latest detections may be the new motion's
                rest = [(ti, zi) for ti, zi in zip(old.times, old.points) if t_lo <= ti < t_hi]
            x, y, _, _ = self._fit.state(old, t_lo)
            prior = still((x, y)), float(max(old.fused - len(rest), 1))
            bounce = None
        else:
            prior = moving_on(old, self._fit), 1.0
            bounce = (speed_then, old.v_sw if speed_then > old.v_sw else math.inf)
        self._seg = seg = Segment(t_lo, t_hi, prior, bounce, t_agreed)
        seg.known = known
        seg.times = [ti for ti, _ in rest]
        seg.points = [zi for _, zi in rest]
        self.segments += 1
        self._add(t, z)

    def _add(self, t: float, z: tuple[float, float]) -> None:
        """Fuse detection ``z`` at ``t`` into the current motion and refit it."""
        seg = self._seg
        seg.fused += 1
        self.fused += 1
        self._last_fused = max(self._last_fused, t)
        self._last_agreed = max(self._last_agreed, t)
        if seg.sums is None:
            i = len(seg.times)
            while i > 0 and seg.times[i - 1] > t:
                i -= 1
            seg.times.insert(i, t)
            seg.points.insert(i, z)
            self._fit.search_kick_time(seg)
            if seg.fused >= self.lock:
                self._fit.lock(seg)
        else:
            self._fit.accumulate(seg, t, z)
            self._fit.solve(seg)
