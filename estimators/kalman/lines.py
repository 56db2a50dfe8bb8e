"""A humanoid team's ball tracker that sees a kick: a Kalman filter fed each robot's sighting
line at its capture time, with each observer's localization error in its state and a kick
hypothesis beside the track.

The particle trackers of Xu et al. (2012) (:class:`~estimators.ParticleBallTracker`) are fed
the team's *fused* point: the robot's fresh line with the team-mates' latest lines, each moved
to the frame's time by the tracker's velocity. After a kick that velocity is still the resting
ball's zero, so the team-mates' lines hold the fused point near the kick point, and the tracker
learns of the kick only when enough fused points have left its gate. This tracker takes the
lines one by one instead, each at the time it was captured, moves nothing by a stale velocity,
and opens a kick hypothesis as soon as a line leaves where the resting ball should be seen.

**State.** ``x = (px, py, vx, vy, b_1, beta_1, ..., b_m, beta_m)``: the ball [m, m/s] and, per
observer ``j`` (the robots whose lines it takes), the error of its localization as its lines
show it: a position bias ``b_j`` [m] and a heading bias ``beta_j`` [rad]. A robot's pose
estimate is off by a few centimetres and degrees that change slowly, so its consecutive lines
share that error. Fused as white noise (as the fusion does), it hides a kick: a team-mate 0.4 m
from the ball sees it move 7 cm in its first frame after the kick, well above its camera's
noise but not above its localization error. In the state, the biases are learnt from where the
observers disagree while the ball rests, and a line is compared with where *that observer* has
been seeing the ball. Priors ``b_j ~ N(0, s_p^2 I)``, ``beta_j ~ N(0, s_theta^2)`` (the
localization's errors); they wander, over short times, as random walks of
``bias_drift_xy^2`` [m^2/s] and ``bias_drift_theta^2`` [rad^2/s], and revert to zero
(Ornstein-Uhlenbeck processes whose stationary spread is the prior's), so that over a long
match they never wander further than a localization's error does.

**Motion.** Between lines the ball rolls under uniform deceleration ``a`` along its motion,
stopping rather than reversing (``tau = min(dt, s / a)``, ``p' = p + u (s tau - a tau^2 / 2)``,
``v' = u (s - a tau)``); a kicked ball first slides, decelerating by ``sliding_deceleration``
``a_s`` until its speed is down to ``k_switch`` of its speed after the kick (the two-phase
friction law, 5/7 for a solid ball), which for a speed ``s`` at ``t`` of a ball kicked at
``t_k`` and still sliding is ``s + a_s (t - t_k)``; its covariance follows the
constant-velocity model with white acceleration noise ``accel_sigma``:
``A P A^T + s_a^2 B B^T``, ``A = [[I, dt I], [0, I]]``, ``B = [dt^2 / 2 I; dt I]`` (the
deceleration is left out of the spread).

**A sighting line** is what a robot's head camera gives: from the observer's estimated
position ``o`` at capture along the estimated heading plus the detection's bearing, ``phi``,
with the ground projection's range ``r`` (not finite: the bearing alone). With the direction
``u = (cos phi, sin phi)`` and normal ``n = (-sin phi, cos phi)``, a pose error ``(b, beta)``
moves the sighted point by ``b + r beta n``, so:

* with a range, the point ``z = o + r u`` measures ``h(x) = p + b_j + r beta_j n`` with white
  noise ``R = s_r^2 u u^T + s_c^2 n n^T + f^2 I`` (``s_b`` and ``k`` the line's own where it
  brings them: a robot standing still does not sway): along the line the range error
  ``s_r = max(k_0, k r) r`` (a tilt or pixel error ``e`` moves a ground point at ``r`` by
  about ``r^2 e / h``: relatively ``k r``, at least ``k_0``), across it the bearing noise
  ``s_c = r s_b``, and a floor ``f`` per axis;
* bearing only, ``h(x) = n . (p + b_j - o) + d beta_j`` is measured as 0 with variance
  ``d^2 s_b^2 + f^2``, ``d`` the predicted ball's distance from ``o``.

Both are linear in ``x``; the update is Kalman's (:mod:`.line_kernels`).

**Time order.** Lines arrive late and out of order (a team-mate's over the radio, 30-50 ms
after the robot's own of the same moment). The tracker keeps the lines of the last ``history``
seconds with its state before each; a line older than the newest rewinds to the state before
it, and it and every later line are processed again in capture order. Older lines are dropped
(``late``).

**Kicks.** A line whose squared Mahalanobis distance ``d2 = y^T S^-1 y`` from the track
exceeds ``suspect`` (chi-square, 99 %) opens a *kick hypothesis* beside the track: the track
kicked at an unknown moment ``t_k`` of the last ``kick_window`` seconds by an unknown velocity
change ``dv ~ N(0, kick_sigma^2 I)``. The kick time is searched over the logged lines' times:
for each candidate the track without a kick up to ``t_k`` (its covariance's velocity block
grown by ``kick_sigma^2 I``), then every line since fused; the candidate whose lines are most
likely wins. From then on every line updates each hypothesis it *agrees* with
(``d2 <= gate``, chi-square 99.9 %) and adds to the log-likelihood ratio
``L = sum (log N(y_k; 0, S_k) - log N(y_t; 0, S_t))`` (each ``d2`` capped at ``2 gate``, so
that one outlier weighs a bounded amount), which starts at the winning candidate's advantage
over no kick less ``log`` of the candidates' number: the kick is *committed* (the track becomes
the kicked one) once ``L >= decide``; it is *dropped* (an outlier opened it) once
``L <= -decide``; undecided after ``history`` seconds, the sign of ``L`` decides. A line
agreeing with neither opens a new kick hypothesis in place of the old one.

The belief reported (:meth:`estimate`, :meth:`covariance`) is the kick hypothesis while
``L >= 0`` if the robot's *own* sighting opened it or lines of two observers agree with it;
otherwise the track. A hypothesis a team-mate's line opened is committed only once a second
observer's line agrees with it (a robot whose localization has failed sees the ball, for
itself, wherever its lines say, and would otherwise move the whole team's belief there).

**Starts.** The first line with a range starts the track at its point, at rest with velocity
``N(0, init_speed_sigma^2 I)``; so does the first after ``lost_after`` seconds without an
agreeing line (the observers' biases carry over). Bearing-only lines start nothing.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from ..checks import check_positive
from ..protocol import check_time
from ..tracking import CHI2_2DOF_999, TrackQualityMixin, TrackTimes
from .line_kernels import (
    BALL,
    SLOT,
    drift_predict,
    kick_prior,
    kick_search,
    line_step,
    phase,
    rolled,
)

__all__ = ["SightingNoise", "LineBallTracker", "CHI2_2DOF_99"]

#: 99 % quantile of the chi-square distribution with 2 degrees of freedom, ``-2 ln 0.01``.
CHI2_2DOF_99 = 9.210340371976182

#: The standard deviation of a start's position before its first line [m]: nothing known.
_UNKNOWN = 100.0


class SightingNoise(NamedTuple):
    """The error model of a team's sighting lines (see the module docstring).

    Attributes:
        bearing_sigma: the bearing error ``s_b`` [rad] (pixel noise and the head's sway).
        range_per_metre: the relative range error per metre of range ``k`` [1/m].
        range_sigma_rel: the least relative range error ``k_0``.
        pose_sigma_xy: the observers' position error per axis ``s_p`` [m] (the biases'
            prior).
        pose_sigma_theta: the observers' heading error ``s_theta`` [rad] (the biases'
            prior).
        floor: the least white standard deviation per axis ``f`` [m].
    """

    bearing_sigma: float
    range_per_metre: float = 0.0
    range_sigma_rel: float = 0.05
    pose_sigma_xy: float = 0.0
    pose_sigma_theta: float = 0.0
    floor: float = 0.02


class _Hypothesis(NamedTuple):
    """A Kalman track: state and covariance at ``t``; the capture time of its latest agreeing
    line; lines fused since the tracker's latest start; when it was kicked (NaN: not known to
    be, so it rolls)."""

    x: np.ndarray
    P: np.ndarray
    t: float
    fused_at: float
    since_start: int
    kicked_at: float = math.nan


class _State(NamedTuple):
    """Everything a line changes (immutable, so the replay log keeps it without copies):
    the track, the kick hypothesis (or None), when and by whose sighting it was opened, the
    log-likelihood ratio ``L``, and which observers' lines agreed with it (a bit per
    observer)."""

    track: _Hypothesis | None = None
    kick: _Hypothesis | None = None
    opened_at: float = -math.inf
    own: bool = False
    score: float = 0.0
    seen_by: int = 0


class _Line(NamedTuple):
    """A line: its capture time, whether the robot's own, and its :data:`LINE` row."""

    t: float
    own: bool
    row: np.ndarray


class LineBallTracker(TrackQualityMixin):
    """Kick-aware Kalman tracking of a team's sighting lines (see the module docstring).

    Args:
        noise: the lines' error model (:class:`SightingNoise`).
        deceleration: the ball's rolling deceleration ``a`` [m/s^2].
        sliding_deceleration: a kicked ball's deceleration while it slides [m/s^2] (0: no
            sliding phase).
        k_switch: a kicked ball slides until its speed is down to this share of its speed
            after the kick, in (0, 1].
        accel_sigma: the white acceleration noise ``s_a`` [m/s^2].
        kick_sigma: the velocity change a kick makes, per axis ``sqrt(J)`` [m/s].
        init_speed_sigma: the velocity's spread at a start [m/s].
        gate: the squared Mahalanobis distance beyond which a line does not agree.
        suspect: the squared Mahalanobis distance beyond which a line opens a kick hypothesis
            (at most ``gate``).
        decide: the log-likelihood ratio that commits or drops a kick hypothesis.
        lost_after: seconds without an agreeing line after which the next line restarts.
        history: seconds of lines kept for replay (and the longest a kick stays undecided).
        kick_window: how far back the kick time is searched [s] (at most ``history``).
        observers: the robots whose lines it takes (each has its bias in the state): their
            integer names (e.g. robot indices), or a count ``n`` for ``0 .. n-1``.
        bias_drift_xy: how fast the observers' position biases wander [m/sqrt(s)].
        bias_drift_theta: how fast their heading biases wander [rad/sqrt(s)].
        biases: keep the observers' pose errors in the state (False: add them to each line's
            white noise instead, as the fusion does; for ablations).

    Attributes:
        fused, rejected, kicks, resets, late: lines agreeing with a hypothesis, lines agreeing
            with none, kicks committed, restarts after the first start, and lines dropped as
            older than ``history`` (a replayed line is counted again).
    """

    #: The tracker takes sighting lines (:meth:`line`), not fused points.
    takes_lines = True

    def __init__(self, noise: SightingNoise, *, deceleration: float = 0.0,
                 sliding_deceleration: float = 0.0, k_switch: float = 5.0 / 7.0,
                 accel_sigma: float = 1.0, kick_sigma: float = 3.0,
                 init_speed_sigma: float = 2.0, gate: float = CHI2_2DOF_999,
                 suspect: float = CHI2_2DOF_99, decide: float = 3.0,
                 lost_after: float = 2.0, history: float = 0.5, kick_window: float = 0.25,
                 observers: int | Sequence[int] = 6, bias_drift_xy: float = 0.05,
                 bias_drift_theta: float = math.radians(1.0), biases: bool = True) -> None:
        if not isinstance(noise, SightingNoise):
            raise TypeError(f"noise must be a SightingNoise, got {type(noise).__name__}")
        for name in SightingNoise._fields:
            check_positive(f"noise.{name}", getattr(noise, name),
                           allow_zero=name not in ("bearing_sigma", "floor"))
        self.noise = noise
        self.deceleration = check_positive("deceleration", deceleration, allow_zero=True)
        self.sliding_deceleration = check_positive("sliding_deceleration",
                                                   sliding_deceleration, allow_zero=True)
        self.k_switch = check_positive("k_switch", k_switch)
        if self.k_switch > 1.0:
            raise ValueError(f"k_switch must be in (0, 1], got {k_switch!r}")
        self.accel_sigma = check_positive("accel_sigma", accel_sigma)
        self.kick_sigma = check_positive("kick_sigma", kick_sigma)
        self.init_speed_sigma = check_positive("init_speed_sigma", init_speed_sigma)
        self.gate = check_positive("gate", gate)
        self.suspect = check_positive("suspect", suspect)
        if self.suspect > self.gate:
            raise ValueError(f"suspect must be at most gate ({self.gate:g}), got {suspect!r}")
        self.decide = check_positive("decide", decide)
        self.lost_after = check_positive("lost_after", lost_after)
        self.history = check_positive("history", history)
        self.kick_window = check_positive("kick_window", kick_window, allow_zero=True)
        if self.kick_window > self.history:
            raise ValueError(f"kick_window must be at most history ({self.history:g} s), "
                             f"got {kick_window!r}")
        ids = _observer_ids(observers)
        #: The observers' bias slots: the index of each one's first entry in the state.
        self.slots = {j: BALL + SLOT * k for k, j in enumerate(ids)}
        self.observers = len(ids)
        self.bias_drift_xy = check_positive("bias_drift_xy", bias_drift_xy, allow_zero=True)
        self.bias_drift_theta = check_positive("bias_drift_theta", bias_drift_theta,
                                               allow_zero=True)
        self.biases = bool(biases)
        pose = noise.pose_sigma_xy ** 2, noise.pose_sigma_theta ** 2
        # Biases in the state: their priors and walks; else none, the pose errors white.
        none = (0.0, 0.0)
        prior, white = (pose, none) if self.biases else (none, pose)
        walk = (self.bias_drift_xy ** 2, self.bias_drift_theta ** 2) if self.biases else none
        # The time update's noise (drift_predict's q, q_xy, q_theta, s2_xy, s2_theta) and the
        # model row of the kernels (line_kernels.MODEL).
        self._q = (self.accel_sigma ** 2, *walk, *prior)
        self._model = np.array([self.deceleration, self.sliding_deceleration, self.k_switch,
                                *self._q[0:3], noise.range_sigma_rel, noise.floor, *white,
                                *prior])
        m = BALL + SLOT * self.observers
        # The state before any line: nothing known of the ball, the biases at their priors.
        self._prior_x = np.zeros(m)
        diag = np.empty(m)
        diag[0:2], diag[2:4] = _UNKNOWN ** 2, self.init_speed_sigma ** 2
        for s in range(BALL, m, SLOT):
            diag[s:s + 2], diag[s + 2] = prior
        self._prior_P = np.diag(diag)
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode): the ball and the observers' biases."""
        self._state = _State()
        # Per line in capture order: its time, the line, the state before it and the track's
        # log-likelihood of it (0 without a track).
        self._log: list[tuple[float, _Line, _State, float]] = []
        self.fused = self.rejected = self.kicks = self.resets = self.late = 0

    # ------------------------------------------------------------------------------------

    @property
    def _reported(self) -> _Hypothesis | None:
        """The hypothesis the belief is (see the module docstring)."""
        s = self._state
        if s.kick is not None and s.score >= 0.0 and (s.own or _two(s.seen_by)):
            return s.kick
        return s.track

    @property
    def _track(self) -> TrackTimes:
        h = self._reported
        return TrackTimes() if h is None else TrackTimes(h.t, h.fused_at, h.since_start)

    @property
    def kick_pending(self) -> bool:
        """Whether a kick hypothesis is open beside the track."""
        return self._state.kick is not None

    @property
    def particles(self) -> np.ndarray:
        """No particles: ``(0, 4)`` (for callers that draw a tracker's particles)."""
        return np.zeros((0, 4))

    def bias(self, observer: int) -> np.ndarray | None:
        """The reported track's estimate of ``observer``'s localization error as its lines
        show it, ``(bx, by, beta)`` [m, m, rad] (the prior's zeros until its lines tell);
        None before the track or for a robot not among the observers."""
        h, slot = self._reported, self.slots.get(observer)
        return None if h is None or slot is None else h.x[slot:slot + SLOT].copy()

    def estimate(self, t: float) -> np.ndarray | None:
        """The ball ``(px, py, vx, vy)`` [m, m/s] at ``t`` [s], moved by the rolling motion
        when ``t`` is later than the track's time; None before the first start. A new
        array."""
        t = check_time(t)
        h = self._reported
        if h is None:
            return None
        if not t > h.t:
            return h.x[0:BALL].copy()
        return rolled(h.x, t - h.t, self.deceleration, *self._phase(h))

    def _covariance(self, t: float) -> np.ndarray:
        h = self._reported
        P = h.P[0:BALL, 0:BALL].copy()
        dt = t - h.t
        if dt > 0.0:
            P = drift_predict(h.x[0:BALL], P, dt, self.deceleration, *self._phase(h),
                              self._q[0], 0.0, 0.0, 0.0, 0.0)[1]
        return P

    # ------------------------------------------------------------------------------------

    def update_line(self, t: float, origin, angle: float, range_: float, own: bool = True,
                    observer: int = 0, bearing_sigma: float | None = None,
                    range_per_metre: float | None = None) -> None:
        """A sighting line captured at ``t`` [s] by robot ``observer`` (one of the
        tracker's): from ``origin`` ``(x, y)`` [m] at ``angle`` [rad] in the field frame,
        ``range_`` [m] along it (NaN or inf: the bearing only); ``own``: the robot's own
        sighting (a team-mate's otherwise); ``bearing_sigma`` [rad] and ``range_per_metre``
        [1/m]: this line's errors where they differ from the :class:`SightingNoise`'s (a
        standing robot's camera does not sway)."""
        t = check_time(t)
        try:
            ox, oy = (float(v) for v in origin)
            a, r = float(angle), float(range_)
        except (TypeError, ValueError):
            raise ValueError(f"origin must be (x, y) and angle, range_ numbers, got "
                             f"{origin!r}, {angle!r}, {range_!r}") from None
        if not (math.isfinite(ox) and math.isfinite(oy) and math.isfinite(a)):
            raise ValueError(f"origin and angle must be finite, got {origin!r}, {angle!r}")
        if not (r > 0.0 or math.isnan(r)):
            raise ValueError(f"range_ must be > 0 (NaN or inf: bearing only), got {range_!r}")
        if isinstance(observer, bool) or observer not in self.slots:
            raise ValueError(f"observer must be one of the tracker's observers "
                             f"{list(self.slots)}, got {observer!r}")
        sb = (self.noise.bearing_sigma if bearing_sigma is None
              else check_positive("bearing_sigma", bearing_sigma))
        k = (self.noise.range_per_metre if range_per_metre is None
             else check_positive("range_per_metre", range_per_metre, allow_zero=True))
        self.line(t, ox, oy, a, r, bool(own), int(observer), sb, k)

    def line(self, t: float, ox: float, oy: float, angle: float, range_: float, own: bool,
             observer: int = 0, bearing_sigma: float | None = None,
             range_per_metre: float | None = None) -> None:
        """:meth:`update_line` without its checks, for a pipeline's own lines (finite floats;
        ``range_`` > 0, NaN or inf; ``observer`` one of the tracker's; the sigmas > 0 or
        None)."""
        n = self.noise
        new = _Line(t, own, np.array([
            t, ox, oy, angle, range_, self.slots[observer],
            n.bearing_sigma if bearing_sigma is None else bearing_sigma,
            n.range_per_metre if range_per_metre is None else range_per_metre]))
        log = self._log
        if not log or t >= log[-1][0]:
            state = self._state
            self._state, ll = self._process(state, new)
            log.append((t, new, state, ll))
        elif t < log[0][0]:
            self.late += 1
            return
        else:  # rewind to the state before the first later line, replay in capture order
            i = bisect.bisect_right([e[0] for e in log], t)
            state = log[i][2]
            replay = [new] + [e[1] for e in log[i:]]
            del log[i:]
            for ln in replay:
                after, ll = self._process(state, ln)
                log.append((ln.t, ln, state, ll))
                state = after
            self._state = state
        cutoff = log[-1][0] - self.history
        k = 0
        while k < len(log) - 1 and log[k][0] < cutoff:
            k += 1
        if k:
            del log[:k]

    # ------------------------------------------------------------------------------------

    def _update(self, h: _Hypothesis, ln: _Line) -> tuple[float, float, _Hypothesis]:
        """``(d2, log det S, h')``: ``h`` predicted to the line's time and updated with it
        (:func:`~.line_kernels.line_step`)."""
        d2, logdet, xn, Pn = line_step(h.x, h.P, h.t, h.kicked_at, ln.row, self._model)
        return d2, logdet, _Hypothesis(xn, Pn, max(ln.t, h.t), ln.t, h.since_start + 1,
                                       h.kicked_at)

    def _phase(self, h: _Hypothesis) -> tuple[float, float]:
        """``(sliding deceleration, switch speed)`` of ``h``'s motion
        (:func:`~.line_kernels.phase`)."""
        return phase(h.x, h.t, h.kicked_at, self.sliding_deceleration, self.k_switch)

    def _predicted(self, h: _Hypothesis, t: float) -> _Hypothesis:
        dt = t - h.t
        if not dt > 0.0:
            return h
        x, P = drift_predict(h.x, h.P, dt, self.deceleration, *self._phase(h), *self._q)
        return h._replace(x=x, P=P, t=t)

    def _kicked(self, h: _Hypothesis, P: np.ndarray, at: float) -> _Hypothesis:
        """``h`` with the covariance ``P`` of a kick at ``at`` [s]."""
        return h._replace(P=P, kicked_at=at)

    def _start(self, ln: _Line, since: int = 0, old: _Hypothesis | None = None
               ) -> _Hypothesis | None:
        """A track started by the line (None for a bearing-only line): the ball unknown, at
        rest with ``init_speed_sigma``, the biases those of ``old`` (the priors without),
        then updated with the line."""
        if not math.isfinite(ln.row[4]):
            return None
        x, P = self._prior_x.copy(), self._prior_P.copy()
        if old is not None:
            x[BALL:], P[BALL:, BALL:] = old.x[BALL:], old.P[BALL:, BALL:]
        blank = _Hypothesis(x, P, ln.t, ln.t, since)
        return self._update(blank, ln)[2]

    def _open(self, track: _Hypothesis, ln: _Line, ll: float
              ) -> tuple[_Hypothesis | None, float]:
        """``(kick, L)``: the kick hypothesis the line opens from ``track`` (whose
        log-likelihood of it is ``ll``) and its starting log-likelihood ratio (see the module
        docstring: the kick time searched over the lines of the last ``kick_window``, by
        :func:`~.line_kernels.kick_search`)."""
        log = self._log
        first = len(log)
        while (first > 0 and log[first - 1][0] >= ln.t - self.kick_window
               and log[first - 1][2].track is not None):
            first -= 1
        kick_var = self.kick_sigma ** 2
        if first == len(log):  # nothing to search: kicked at the latest agreement
            pred = self._predicted(track, ln.t)
            at = min(track.fused_at, ln.t)
            pred = self._kicked(pred, kick_prior(pred.P, ln.t - at, kick_var), at)
            d2, _, kicked = self._update(pred, ln)
            if d2 <= self.gate:
                return kicked, 0.0
            return self._start(ln, track.since_start, track), 0.0
        window = log[first:]
        rest = [e[2].track for e in window] + [track]
        before = np.cumsum([0.0] + [e[3] for e in window])
        best, best_ll, x, P, t = kick_search(
            np.stack([h.x for h in rest]), np.stack([h.P for h in rest]),
            np.array([h.t for h in rest]), np.array([h.kicked_at for h in rest]), before,
            np.stack([e[1].row for e in window] + [ln.row]), self._model, kick_var,
            2.0 * self.gate)
        kicked = _Hypothesis(x, P, t, ln.t, track.since_start + 1,
                             (window[best][0] if best < len(window) else ln.t))
        return kicked, best_ll - (before[-1] + ll) - math.log(len(rest))

    def _process(self, s: _State, ln: _Line) -> tuple[_State, float]:
        """The state after one line in capture order (``s`` is not changed), and the track's
        log-likelihood of the line (0 where the line starts the track)."""
        track = s.track
        if track is None or ln.t - track.fused_at > self.lost_after:
            started = self._start(ln, 0, track)
            if started is None:
                self.rejected += 1
                return s, 0.0
            if track is not None:
                self.resets += 1
            self.fused += 1
            return _State(track=started), 0.0
        cap = 2.0 * self.gate
        d2_t, ld_t, upd_t = self._update(track, ln)
        ll = -0.5 * (min(d2_t, cap) + ld_t)
        agree_t = d2_t <= self.gate
        if s.kick is None:
            if agree_t:
                self.fused += 1
            else:
                self.rejected += 1
            if d2_t <= self.suspect:
                return _State(track=upd_t), ll
            return self._opened(track, upd_t if agree_t else None, ln, ll), ll
        d2_k, ld_k, upd_k = self._update(s.kick, ln)
        agree_k = d2_k <= self.gate
        if not (agree_t or agree_k):
            self.rejected += 1
            return self._opened(track, None, ln, ll), ll
        self.fused += 1
        score = s.score + 0.5 * (min(d2_t, cap) + ld_t - min(d2_k, cap) - ld_k)
        track = upd_t if agree_t else self._predicted(track, ln.t)
        kick = upd_k if agree_k else self._predicted(s.kick, ln.t)
        seen_by = s.seen_by | (_bit(ln) if agree_k else 0)
        late = ln.t - s.opened_at > self.history
        trusted = s.own or _two(seen_by)
        if trusted and (score >= self.decide or (late and score > 0.0)):
            self.kicks += 1
            return _State(track=kick), ll
        if score <= -self.decide or late:
            return _State(track=track), ll
        return _State(track, kick, s.opened_at, s.own, score, seen_by), ll

    def _opened(self, track: _Hypothesis, updated: _Hypothesis | None, ln: _Line,
                ll: float) -> _State:
        """The state once ``ln`` opened a kick hypothesis from ``track`` (``updated``: the
        track with ``ln`` fused, when it agreed; ``ll``: the track's log-likelihood of
        ``ln``)."""
        kick, score = self._open(track, ln, ll)
        if kick is None:
            return _State(track=track)
        return _State(track=updated if updated is not None else self._predicted(track, ln.t),
                      kick=kick, opened_at=ln.t, own=ln.own, score=score, seen_by=_bit(ln))


def _bit(ln: _Line) -> int:
    """The bit of the line's observer (by its bias slot)."""
    return 1 << ((int(ln.row[5]) - BALL) // SLOT)


def _two(seen_by: int) -> bool:
    """Whether at least two observers' lines are in the bit set ``seen_by``."""
    return seen_by & (seen_by - 1) != 0


def _observer_ids(observers: int | Sequence[int]) -> list[int]:
    """The observers' integer names: ``0 .. n-1`` for a count ``n``; ``ValueError`` naming
    the argument unless 1 to 64 distinct integers."""
    def integer(j: object) -> bool:
        return isinstance(j, (int, np.integer)) and not isinstance(j, bool)

    if integer(observers):
        ids = list(range(int(observers)))  # type: ignore[arg-type]
    else:
        try:
            ids = list(observers)  # type: ignore[arg-type]
        except TypeError:
            ids = []
        ids = [int(j) for j in ids] if all(integer(j) for j in ids) else []
    if not 1 <= len(ids) <= 64 or len(set(ids)) != len(ids):
        raise ValueError(f"observers must be a count 1..64 or 1 to 64 distinct integers, got "
                         f"{observers!r}")
    return ids
