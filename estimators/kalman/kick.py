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

**The law of motion of a segment.** A segment starts at time ``t_k`` at point ``p`` with
velocity ``w`` (speed ``v0 = |w|``, direction ``u = w / v0``). The ball slides with deceleration
``a_s`` until its speed falls to ``v_sw``, then rolls with ``a_r`` until it stops (the two-phase
model of the SSL teams, :class:`~estimators.models.FrictionBallModel` for the rolling phase).
After ``tau = t - t_k`` seconds it has travelled

    ``s(tau) = v0 tau - a_s tau^2 / 2``                                 for ``tau <= tau_1``,
    ``s(tau) = s(tau_1) + v_sw r - a_r r^2 / 2, r = min(tau - tau_1, v_sw / a_r)``  after,

with ``tau_1 = (v0 - v_sw) / a_s`` (0 when ``v0 <= v_sw``: the ball only rolls), and it is at
``p + u s(tau)`` (at ``p`` for ``tau <= 0``). After a kick ``v_sw = k_switch v0``; after a
bounce the ball keeps the phase it was in.

**The fit.** With ``g(tau) = s(tau) / v0`` the position is ``p + w g(tau)``: linear in
``(p, w)`` once ``g`` is fixed. So for a given kick time the fit alternates a linear least
squares for ``(p, w)`` (per axis the 2 x 2 normal equations
``[[lam + n, sum g], [sum g, sum g^2 + mu]] [p; w] = [lam m + sum z; sum z g]``) with
recomputing ``g`` from the new speed (three rounds; ``g`` depends on the speed only through the
switch and the stop). ``lam`` weighs the prior on the kick point, ``m``: where the previous
segment puts the ball at ``t_k`` (the mean of the resting ball's detections after a kick from
rest, as many measurements' worth as there were detections; a moving ball's predicted
position, worth one measurement, after a collision). ``mu = sigma^2 / (10 m/s / 3)^2`` is a
weak prior that keeps the speed finite when a segment has seen no motion yet. Detections
before ``t_k`` (``g = 0``) are measurements of ``p``.

**Rest or motion.** A segment whose velocity lowers the residuals by less than ``gate``
``sigma^2`` (the drop ``b^T N^-1 b - b_1^2 / (lam + n)`` per axis, summed; chi-square with 2
degrees of freedom if the ball lies still) is a ball at rest: it is reported at the weighted
mean of its detections and prior, with zero velocity. A resting segment that a detection
turns into a moving one is a kick found by the fit rather than by the gate: it starts a new
segment as any kick does.

The kick time is not measured: it lies between the last detection that agreed with the old
motion and the first that did not (for a ball at rest, up to ``kick_search`` seconds earlier,
since a slow kick moves the ball less than the noise in its first frame; such an earlier kick
time is charged the 95 % quantile of chi-square with one degree of freedom, so it must
explain the detections better). The fit is made for ``search`` kick times spread over that
interval; the segment's fit is their posterior mean (a uniform prior over the interval and the
Gaussian likelihood ``exp(-RSS / (2 sigma^2))`` of each), until the segment has ``lock``
detections; then the kick time is fixed. With a known kick time
(:meth:`KickAwareBall.kick`, e.g. the robot's own kick command) the search is skipped.

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

**Uncertainty.** ``covariance(t)`` is the linearised covariance of the fit: per axis
``sigma^2 N^-1`` (``N`` the normal matrix) mapped to position and velocity at ``t`` by
``[[1, g(tau)], [0, v(tau) / v0]]``; it leaves out the uncertainty of the kick time and of the
phase switch. A ball at rest has position variance ``sigma^2 / (lam + n)`` and none in its
velocity.

**Cost.** A young segment's fit evaluates the ``search`` kick times at once as arrays of
``search x n`` entries (numpy); once its kick time is fixed the segment keeps its detections
as running sums, each ``g`` frozen at the fit of its time (recursive least squares in plain
floats, a few dozen operations per detection), so a long motion costs no more per frame than
a short one.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..checks import check_real
from ..protocol import check_order, check_time
from .ball import CHI2_2DOF_999, MAX_SPEED_CHANGE, _points

__all__ = ["KickAwareBall", "travel"]

#: Speed below which a fitted ball counts as lying still [m/s] (a kick from rest rather than a
#: bounce, and the weak floor of the speed the fit linearises at).
REST_SPEED = 0.05


def travel(tau: np.ndarray, v0: np.ndarray, v_switch: np.ndarray, sliding: float,
           rolling: float) -> tuple[np.ndarray, np.ndarray]:
    """Distance travelled and speed ``(s, v)`` of the two-phase ball ``tau`` seconds after
    leaving its start at speed ``v0`` (see the module docstring): sliding at ``sliding``
    [m/s^2] down to ``v_switch`` [m/s], then rolling at ``rolling`` [m/s^2] until it stops;
    ``s = v = 0`` for ``tau < 0`` (before it starts). Arrays broadcast; units m, s."""
    before = np.asarray(tau) < 0.0
    tau = np.maximum(tau, 0.0)
    v0 = np.asarray(v0, dtype=np.float64)
    vs = np.minimum(np.asarray(v_switch, dtype=np.float64), v0)
    if sliding > 0.0:
        tau1 = (v0 - vs) / sliding
    else:  # no sliding deceleration: the sliding phase never ends
        tau1 = np.where(v0 > vs, np.inf, 0.0)
        vs = np.where(v0 > vs, v0, vs)
    t1 = np.minimum(tau, tau1)
    s = v0 * t1 - 0.5 * sliding * t1 * t1
    v = v0 - sliding * t1
    r = np.maximum(tau - tau1, 0.0)
    if rolling > 0.0:
        r = np.minimum(r, vs / rolling)
    s = s + np.where(tau > tau1, vs * r - 0.5 * rolling * r * r, 0.0)
    v = np.where(tau > tau1, np.maximum(vs - rolling * r, 0.0), v)
    return s, np.where(before, 0.0, v)


def _travel1(tau: float, v0: float, v_switch: float, sliding: float, rolling: float
             ) -> tuple[float, float]:
    """:func:`travel` for one time in plain floats."""
    if tau < 0.0:
        return 0.0, 0.0
    vs = min(v_switch, v0)
    if sliding > 0.0:
        tau1 = (v0 - vs) / sliding
    elif v0 > vs:
        tau1, vs = math.inf, v0
    else:
        tau1 = 0.0
    t1 = min(tau, tau1)
    s = v0 * t1 - 0.5 * sliding * t1 * t1
    if tau <= tau1:
        return s, v0 - sliding * t1
    r = tau - tau1
    if rolling > 0.0:
        r = min(r, vs / rolling)
    return s + vs * r - 0.5 * rolling * r * r, max(vs - rolling * r, 0.0)


class _Segment:
    """One motion: the prior on its start, its detections and its fitted law.

    Attributes:
        t_lo, t_hi: the interval of the start (kick) time; equal once it is fixed.
        t_agreed: the time of the old motion's last detection (kick times before it are
            searched too, but must explain the detections better).
        prior: ``(m, lam)``: ``m(t_k)`` the kick point's prior mean at a kick time ``t_k``,
            ``lam`` its weight in measurements (0: none).
        bounce: None after a kick from rest (``v_switch = k_switch v0``); otherwise the
            ball's speed before and its switch speed then [m/s] (inf: it rolled): a new
            motion no faster than before is a bounce and keeps the switch speed, a faster one
            a kick.
        times, points: the detections ``t``, ``(x, y)`` while the kick time is searched.
        sums: once the kick time is fixed, the detections as per-axis sums ``(n, sum g,
            sum g^2, sum zx, sum zy, sum zx g, sum zy g, sum |z|^2)``, each ``g`` taken at the
            fit of its time; None before.
        m: the prior mean at the fixed kick time.
        tk, p, w, v_sw: the fit: start time, start point, start velocity, switch speed.
        info: the normal matrix ``(a11, a12, a22)`` of the fit (the same for both axes).
        rest: the fit cannot tell the ball from one lying still at ``p`` (``w`` ignored).
        fused: detections fused.
        known: the kick was told (:meth:`KickAwareBall.kick`): the motion is never taken
            for rest.
    """

    __slots__ = ("t_lo", "t_hi", "t_agreed", "prior", "bounce", "times", "points", "sums",
                 "m", "tk", "p", "w", "v_sw", "info", "rest", "fused", "known")

    def __init__(self, t_lo: float, t_hi: float, prior, bounce,
                 t_agreed: float = -math.inf) -> None:
        self.t_lo, self.t_hi = t_lo, t_hi
        self.t_agreed = t_agreed
        self.prior = prior
        self.bounce = bounce
        self.times: list[float] = []
        self.points: list[tuple[float, float]] = []
        self.sums: list[float] | None = None
        self.m = (0.0, 0.0)
        self.tk = t_hi
        self.p = (0.0, 0.0)
        self.w = (0.0, 0.0)
        self.v_sw = math.inf
        self.info = (1.0, 0.0, 1.0)
        self.rest = True
        self.fused = 0
        self.known = False


#: 95 % quantile of the chi-square distribution with 1 degree of freedom.
CHI2_1DOF_95 = 3.841458820694124


class KickAwareBall:
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
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode)."""
        self._seg: _Segment | None = None
        self._previous: _Segment | None = None  # the motion a one-detection kick replaced
        self._pending: tuple[float, tuple[float, float]] | None = None
        self._kick_hint: float | None = None
        self._time = -math.inf
        self._last_fused = -math.inf
        self._last_agreed = -math.inf
        self.fused = self.rejected = self.segments = self.reverted = 0

    # ------------------------------------------------------------------------------------
    # Protocol

    @property
    def initialized(self) -> bool:
        return self._seg is not None

    @property
    def time(self) -> float:
        """Capture time of the latest processed frame (``-inf`` before the first)."""
        return self._time

    @property
    def last_fused(self) -> float:
        """Capture time of the latest detection fused (``-inf`` before the first) [s]."""
        return self._last_fused

    @property
    def since_start(self) -> int:
        """Detections fused since the current motion started (0 before the first)."""
        return 0 if self._seg is None else self._seg.fused

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
        self.update_frame(t, _points("detections", detections), [])

    def update_frame(self, t: float, detections: Sequence[Sequence[float]],
                     obstacles: Sequence[Sequence[float]] = ()) -> None:
        """:meth:`update` without its checks (a sensor's own, checked frames)."""
        self._time = max(self._time, t)
        if not detections:
            return
        seg = self._seg
        if seg is None:
            z = detections[0]
            self._seg = _Segment(t, t, (_still((0.0, 0.0)), 0.0), None)
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
        px, py, var = self._predicted(seg, t)
        reach = self.max_kick_speed * max(t - self._last_agreed, 0.0) + 3.0 * math.sqrt(var)
        near = math.hypot(best[0] - px, best[1] - py) <= reach
        if near and seg.t_lo < seg.t_hi and not seg.rest and self._refits(seg, t, best):
            return  # a young motion whose kick time was not yet clear
        self.rejected += 1
        pending = self._pending
        agree = pending is not None and math.hypot(
            best[0] - pending[1][0], best[1] - pending[1][1]) <= (
            MAX_SPEED_CHANGE * max(t - pending[0], 0.0) + 5.0 * self.sigma_xy)
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
            self._seg = fresh = _Segment(t0, t0, (_still(z0), 0.0), None)
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
        return np.array(self._state(seg, t))

    def covariance(self, t: float) -> np.ndarray | None:
        """The ``4 x 4`` covariance of ``(x, y, vx, vy)`` at ``t`` (see the module
        docstring; None before the first detection)."""
        t = check_time(t)
        seg = self._seg
        if seg is None:
            return None
        var_p, cov_pv, var_v = self._spread(seg, t)
        P = np.zeros((4, 4))
        for a in (0, 1):
            P[a, a], P[a, a + 2] = var_p, cov_pv
            P[a + 2, a], P[a + 2, a + 2] = cov_pv, var_v
        return P

    # ------------------------------------------------------------------------------------
    # The law of a motion

    def _state(self, seg: _Segment, t: float) -> tuple[float, float, float, float]:
        """``(x, y, vx, vy)`` of motion ``seg`` at ``t``."""
        if seg.rest:
            return seg.p[0], seg.p[1], 0.0, 0.0
        v0 = math.hypot(*seg.w)
        s, v = _travel1(t - seg.tk, v0, seg.v_sw, self.sliding, self.rolling)
        ux, uy = seg.w[0] / v0, seg.w[1] / v0
        return seg.p[0] + ux * s, seg.p[1] + uy * s, ux * v, uy * v

    def _gains(self, seg: _Segment, t: float) -> tuple[float, float]:
        """``(g, h)`` at ``t``: position ``p + w g``, velocity ``w h``."""
        v0 = max(math.hypot(*seg.w), REST_SPEED)
        s, v = _travel1(t - seg.tk, v0, seg.v_sw, self.sliding, self.rolling)
        return s / v0, v / v0

    def _spread(self, seg: _Segment, t: float,
                gains: tuple[float, float] | None = None) -> tuple[float, float, float]:
        """Per axis ``(var p(t), cov(p(t), v(t)), var v(t))`` of motion ``seg`` (``gains``:
        its :meth:`_gains` at ``t`` when the caller has them)."""
        a11, a12, a22 = seg.info
        s2 = self.sigma_xy ** 2
        if seg.rest:
            return s2 / a11, 0.0, 0.0
        det = a11 * a22 - a12 * a12
        c_pp, c_pw, c_ww = s2 * a22 / det, -s2 * a12 / det, s2 * a11 / det
        g, h = gains or self._gains(seg, t)
        return (max(c_pp + 2.0 * g * c_pw + g * g * c_ww, 0.0), h * (c_pw + g * c_ww),
                h * h * c_ww)

    def _predicted(self, seg: _Segment, t: float) -> tuple[float, float, float]:
        """Motion ``seg``'s position at ``t`` and the variance of a detection about it (the
        noise plus the fit's position variance, per axis)."""
        if seg.rest:
            s2 = self.sigma_xy ** 2
            return seg.p[0], seg.p[1], s2 + s2 / seg.info[0]
        # A moving segment is at least REST_SPEED fast: one travel gives its state and gains.
        v0 = math.hypot(*seg.w)
        s, v = _travel1(t - seg.tk, v0, seg.v_sw, self.sliding, self.rolling)
        var = self._spread(seg, t, (s / v0, v / v0))[0]
        return seg.p[0] + seg.w[0] / v0 * s, seg.p[1] + seg.w[1] / v0 * s, self.sigma_xy ** 2 + var

    def _match(self, seg: _Segment, detections, t: float):
        """``(agreeing, nearest, d2)``: the detections within the gate of motion ``seg`` at
        ``t``, the nearest detection and its squared Mahalanobis distance."""
        px, py, var = self._predicted(seg, t)
        agreeing, best, d2 = [], None, math.inf
        for z in detections:
            d = ((z[0] - px) ** 2 + (z[1] - py) ** 2) / var
            point = (float(z[0]), float(z[1]))
            if d <= self.gate:
                agreeing.append(point)
            if d < d2:
                best, d2 = point, d
        return agreeing, best, d2

    def _refits(self, seg: _Segment, t: float, z: tuple[float, float]) -> bool:
        """Whether detection ``z`` at ``t``, outside the gate of young motion ``seg`` (whose
        kick time is still searched: its prediction leaves that uncertainty out), fits it once
        refitted with it; if so it is fused, otherwise ``seg`` is left as it was."""
        saved = self._snapshot(seg)
        self._add(t, z)
        x, y, _, _ = self._state(seg, t)
        if ((z[0] - x) ** 2 + (z[1] - y) ** 2) / self.sigma_xy ** 2 <= self.gate:
            self._pending = None
            return True
        self._restore(seg, saved)
        return False

    def _snapshot(self, seg: _Segment) -> tuple[dict, tuple]:
        """What :meth:`_restore` needs to undo fusing detections into ``seg``."""
        saved = {name: getattr(seg, name) for name in _Segment.__slots__}
        saved["times"], saved["points"] = list(seg.times), list(seg.points)
        if seg.sums is not None:
            saved["sums"] = list(seg.sums)
        return saved, (self.fused, self._last_fused, self._last_agreed)

    def _restore(self, seg: _Segment, snapshot: tuple[dict, tuple]) -> None:
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
        speed_then = 0.0 if old.rest else _travel1(
            t_lo - old.tk, math.hypot(*old.w), old.v_sw, self.sliding, self.rolling)[1]
        rest = []
        t_agreed = t_lo
        if old.rest or speed_then < REST_SPEED:
            # A kick from rest: the resting ball's detections pin the start.
            if t_hi > t_lo:
                t_lo = max(t_lo - self.kick_search, old.tk)
            if old.sums is None:  # its latest detections may be the new motion's
                rest = [(ti, zi) for ti, zi in zip(old.times, old.points) if t_lo <= ti < t_hi]
            x, y, _, _ = self._state(old, t_lo)
            prior = _still((x, y)), float(max(old.fused - len(rest), 1))
            bounce = None
        else:
            prior = _on(old, self), 1.0
            bounce = (speed_then, old.v_sw if speed_then > old.v_sw else math.inf)
        self._seg = seg = _Segment(t_lo, t_hi, prior, bounce, t_agreed)
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
            self._search(seg)
            if seg.fused >= self.lock:
                self._lock(seg)
        else:
            self._accumulate(seg, t, z)
            self._solve(seg)

    def _lock(self, seg: _Segment) -> None:
        """Fix ``seg``'s kick time and keep its detections as sums from now on."""
        seg.t_lo = seg.t_hi = seg.tk
        prior_mean, _ = seg.prior
        seg.m = prior_mean(seg.tk)
        seg.sums = [0.0] * 8
        for ti, zi in zip(seg.times, seg.points):
            self._accumulate(seg, ti, zi)
        seg.times, seg.points = [], []
        self._solve(seg)

    def _accumulate(self, seg: _Segment, t: float, z: tuple[float, float]) -> None:
        g, _ = self._gains(seg, t)
        S = seg.sums
        zx, zy = z
        S[0] += 1.0
        S[1] += g
        S[2] += g * g
        S[3] += zx
        S[4] += zy
        S[5] += zx * g
        S[6] += zy * g
        S[7] += zx * zx + zy * zy

    def _switch(self, seg: _Segment, v0: float) -> float:
        """The switch speed of motion ``seg`` started at speed ``v0``."""
        b = seg.bounce
        return self.k_switch * v0 if b is None or v0 > b[0] else b[1]

    def _solve(self, seg: _Segment) -> None:
        """The fit of a motion whose kick time is fixed, from its sums (plain floats)."""
        n, sg, sgg, szx, szy, szxg, szyg, _ = seg.sums
        lam = seg.prior[1]
        mx, my = seg.m
        a11, a12, a22 = lam + n, sg, sgg + self._mu
        bx1, by1 = lam * mx + szx, lam * my + szy
        det = a11 * a22 - a12 * a12
        wx, wy = (a11 * szxg - a12 * bx1) / det, (a11 * szyg - a12 * by1) / det
        seg.p = ((a22 * bx1 - a12 * szxg) / det, (a22 * by1 - a12 * szyg) / det)
        seg.w = (wx, wy)
        seg.info = (a11, a12, a22)
        # Motion or rest: the drop of the residuals that the velocity buys (per axis
        # b^T A^-1 b - b1^2 / a11), against chi-square with 2 degrees of freedom.
        gain = ((bx1 * seg.p[0] + szxg * wx - bx1 * bx1 / a11)
                + (by1 * seg.p[1] + szyg * wy - by1 * by1 / a11))
        self._settle(seg, gain, bx1, by1)

    def _settle(self, seg: _Segment, gain: float, bx1: float, by1: float) -> None:
        """Rest or motion from the drop of the residuals that the fit's velocity buys,
        ``gain`` [m^2] (see the module docstring); a ball at rest lies at the weighted mean
        ``(bx1, by1) / a11`` of its detections and prior. Then the switch speed."""
        speed = math.hypot(*seg.w)
        seg.rest = ((gain < self.gate * self.sigma_xy ** 2 and not seg.known)
                    or speed < REST_SPEED)
        if seg.rest:
            a11 = seg.info[0]
            seg.p = (bx1 / a11, by1 / a11)
        seg.v_sw = self._switch(seg, speed)

    def _search(self, seg: _Segment) -> None:
        """Fit a young motion for ``search`` kick times at once and keep the best (see the
        module docstring)."""
        T = np.asarray(seg.times)
        Z = np.asarray(seg.points)
        tks = (np.linspace(seg.t_lo, seg.t_hi, self.search) if seg.t_lo < seg.t_hi
               else np.array([seg.t_lo]))
        prior_mean, lam = seg.prior
        M = np.array([prior_mean(float(tk)) for tk in tks])
        tau = T[None, :] - tks[:, None]
        if seg.fused <= 2 and lam > 0:  # start from the latest detection's distance
            dist = np.hypot(Z[-1, 0] - M[:, 0], Z[-1, 1] - M[:, 1])
            v0 = np.maximum(dist / np.maximum(T[-1] - tks, 1e-3), REST_SPEED)
        else:
            v0 = np.full(len(tks), max(math.hypot(*seg.w), REST_SPEED))
        b = seg.bounce
        zx, zy = Z[:, 0], Z[:, 1]
        a11 = lam + len(T)
        bx1, by1 = lam * M[:, 0] + zx.sum(), lam * M[:, 1] + zy.sum()
        for _ in range(3):
            vsw = self.k_switch * v0
            if b is not None:
                vsw = np.where(v0 > b[0], vsw, b[1])
            s, _ = travel(tau, v0[:, None], vsw[:, None], self.sliding, self.rolling)
            g = s / v0[:, None]
            a12 = g.sum(axis=1)
            a22 = (g * g).sum(axis=1) + self._mu
            bx2, by2 = g @ zx, g @ zy
            det = a11 * a22 - a12 * a12
            px, wx = (a22 * bx1 - a12 * bx2) / det, (a11 * bx2 - a12 * bx1) / det
            py, wy = (a22 * by1 - a12 * by2) / det, (a11 * by2 - a12 * by1) / det
            v0 = np.maximum(np.hypot(wx, wy), REST_SPEED)
        # Residual sum of squares, detections and priors: S_zz - b^T A^-1 b + lam |m|^2 (S_zz
        # is the same for every kick time). A kick before the last detection that agreed
        # with the old motion must explain the detections better by the 95 % quantile of
        # chi-square with one degree of freedom.
        gain = bx1 * px + bx2 * wx + by1 * py + by2 * wy
        rss = lam * (M[:, 0] ** 2 + M[:, 1] ** 2) - gain
        rss = rss + np.where(tks < seg.t_agreed, CHI2_1DOF_95 * self.sigma_xy ** 2,
                             0.0)
        # The posterior mean over the kick times (uniform prior, Gaussian likelihood).
        weight = np.exp(-(rss - rss.min()) / (2.0 * self.sigma_xy ** 2))
        weight /= weight.sum()
        j = int(np.argmax(weight))
        seg.tk = float(weight @ tks)
        seg.p = (float(weight @ px), float(weight @ py))
        seg.w = (float(weight @ wx), float(weight @ wy))
        seg.info = (float(a11), float(a12[j]), float(a22[j]))
        bx, by = float(bx1[j]), float(by1[j])
        self._settle(seg, float(gain[j]) - (bx * bx + by * by) / a11, bx, by)


def _still(point: tuple[float, float]):
    """The prior mean of a kick from rest: the resting ball's point, whatever the time."""
    return lambda tk: point


def _on(seg: _Segment, tracker: KickAwareBall):
    """The prior mean of a bounce: where the old motion ``seg`` has the ball at the kick
    time."""
    return lambda tk: tracker._state(seg, tk)[0:2]
