"""The law of motion of the kick-aware ball tracker and its least-squares fit: one
segment (a motion since a kick or a collision) of :class:`~estimators.KickAwareBall`.

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
from collections.abc import Callable

import numpy as np

__all__ = ["Segment", "SegmentFit", "travel", "travel_one", "still", "moving_on", "REST_SPEED",
           "CHI2_1DOF_95"]

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


def travel_one(tau: float, v0: float, v_switch: float, sliding: float, rolling: float
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


class Segment:
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
        known: the kick was told (:meth:`~estimators.KickAwareBall.kick`): the motion is never taken
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


class SegmentFit:
    """The two-phase law of motion of a :class:`Segment` and its least-squares fit (see the
    module docstring), for one tracker's settings (checked by
    :class:`~estimators.KickAwareBall`).

    Args:
        sliding: the sliding deceleration ``a_s`` [m/s^2].
        rolling: the rolling deceleration ``a_r`` [m/s^2].
        k_switch: the switch speed as a fraction of the kick speed.
        sigma_xy: the detections' noise per axis [m].
        gate: the chi-square quantile that tells motion from rest (in units of
            ``sigma_xy^2``).
        search: kick times tried while a segment is young.
        mu: the weak prior on the start velocity, in measurements' worth.
    """

    __slots__ = ("sliding", "rolling", "k_switch", "sigma_xy", "gate", "search", "mu")

    def __init__(self, sliding: float, rolling: float, k_switch: float, sigma_xy: float,
                 gate: float, search: int, mu: float) -> None:
        self.sliding, self.rolling, self.k_switch = sliding, rolling, k_switch
        self.sigma_xy, self.gate, self.search, self.mu = sigma_xy, gate, search, mu

    def state(self, seg: Segment, t: float) -> tuple[float, float, float, float]:
        """``(x, y, vx, vy)`` of motion ``seg`` at ``t``."""
        if seg.rest:
            return seg.p[0], seg.p[1], 0.0, 0.0
        v0 = math.hypot(*seg.w)
        s, v = travel_one(t - seg.tk, v0, seg.v_sw, self.sliding, self.rolling)
        ux, uy = seg.w[0] / v0, seg.w[1] / v0
        return seg.p[0] + ux * s, seg.p[1] + uy * s, ux * v, uy * v

    def gains(self, seg: Segment, t: float) -> tuple[float, float]:
        """``(g, h)`` at ``t``: position ``p + w g``, velocity ``w h``."""
        v0 = max(math.hypot(*seg.w), REST_SPEED)
        s, v = travel_one(t - seg.tk, v0, seg.v_sw, self.sliding, self.rolling)
        return s / v0, v / v0

    def spread(self, seg: Segment, t: float,
                gains: tuple[float, float] | None = None) -> tuple[float, float, float]:
        """Per axis ``(var p(t), cov(p(t), v(t)), var v(t))`` of motion ``seg`` (``gains``:
        its :meth:`gains` at ``t`` when the caller has them)."""
        a11, a12, a22 = seg.info
        s2 = self.sigma_xy ** 2
        if seg.rest:
            return s2 / a11, 0.0, 0.0
        det = a11 * a22 - a12 * a12
        c_pp, c_pw, c_ww = s2 * a22 / det, -s2 * a12 / det, s2 * a11 / det
        g, h = gains or self.gains(seg, t)
        return (max(c_pp + 2.0 * g * c_pw + g * g * c_ww, 0.0), h * (c_pw + g * c_ww),
                h * h * c_ww)

    def predicted(self, seg: Segment, t: float) -> tuple[float, float, float]:
        """Motion ``seg``'s position at ``t`` and the variance of a detection about it (the
        noise plus the fit's position variance, per axis)."""
        if seg.rest:
            s2 = self.sigma_xy ** 2
            return seg.p[0], seg.p[1], s2 + s2 / seg.info[0]
        # A moving segment is at least REST_SPEED fast: one travel gives its state and gains.
        v0 = math.hypot(*seg.w)
        s, v = travel_one(t - seg.tk, v0, seg.v_sw, self.sliding, self.rolling)
        var = self.spread(seg, t, (s / v0, v / v0))[0]
        return seg.p[0] + seg.w[0] / v0 * s, seg.p[1] + seg.w[1] / v0 * s, self.sigma_xy ** 2 + var

    def accumulate(self, seg: Segment, t: float, z: tuple[float, float]) -> None:
        g, _ = self.gains(seg, t)
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

    def switch(self, seg: Segment, v0: float) -> float:
        """The switch speed of motion ``seg`` started at speed ``v0``."""
        b = seg.bounce
        return self.k_switch * v0 if b is None or v0 > b[0] else b[1]

    def solve(self, seg: Segment) -> None:
        """The fit of a motion whose kick time is fixed, from its sums (plain floats)."""
        n, sg, sgg, szx, szy, szxg, szyg, _ = seg.sums
        lam = seg.prior[1]
        mx, my = seg.m
        a11, a12, a22 = lam + n, sg, sgg + self.mu
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
        self.settle(seg, gain, bx1, by1)

    def settle(self, seg: Segment, gain: float, bx1: float, by1: float) -> None:
        """Rest or motion from the drop of the residuals that the fit's velocity buys,
        ``gain`` [m^2] (see the module docstring); a ball at rest lies at the weighted mean
        ``(bx1, by1) / a11`` of its detections and prior. Then the switch speed."""
        speed = math.hypot(*seg.w)
        seg.rest = ((gain < self.gate * self.sigma_xy ** 2 and not seg.known)
                    or speed < REST_SPEED)
        if seg.rest:
            a11 = seg.info[0]
            seg.p = (bx1 / a11, by1 / a11)
        seg.v_sw = self.switch(seg, speed)

    def search_kick_time(self, seg: Segment) -> None:
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
            a22 = (g * g).sum(axis=1) + self.mu
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
        self.settle(seg, float(gain[j]) - (bx * bx + by * by) / a11, bx, by)

    def lock(self, seg: Segment) -> None:
        """Fix ``seg``'s kick time and keep its detections as sums from now on."""
        seg.t_lo = seg.t_hi = seg.tk
        prior_mean, _ = seg.prior
        seg.m = prior_mean(seg.tk)
        seg.sums = [0.0] * 8
        for ti, zi in zip(seg.times, seg.points):
            self.accumulate(seg, ti, zi)
        seg.times, seg.points = [], []
        self.solve(seg)



def still(point: tuple[float, float]) -> Callable[[float], tuple[float, float]]:
    """The prior mean of a kick from rest: the resting ball's point, whatever the time."""
    return lambda tk: point


def moving_on(seg: Segment, fit: SegmentFit) -> Callable[[float], tuple[float, float]]:
    """The prior mean of a bounce: where the old motion ``seg`` has the ball at the kick
    time."""
    return lambda tk: fit.state(seg, tk)[0:2]
