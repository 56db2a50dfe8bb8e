"""An interacting multiple model (IMM) ball tracker: rest, rolling and maneuver filters mixed.

A ball on carpet does one of three things between two camera frames: it lies still, it rolls
(or slides) under friction, or it is kicked or bounces off a robot. One Kalman filter must
pick one noise level for all three; :class:`IMMBall` runs a filter per behaviour on the same
state ``(x, y, vx, vy)`` [m, m/s] and weighs them by how well each predicted the detections
(Blom and Bar-Shalom 1988; Bar-Shalom, Li and Kirubarajan 2001, ch. 11.6). See
:class:`IMMBall` for the models and the equations.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from ..checks import check_points, check_real
from ..models.motion import PAPER_CYCLE, FrictionBallMotion
from ..protocol import check_order, check_time
from ..tracking import (
    CHI2_2DOF_999,
    MAX_SPEED_CHANGE,
    Candidates,
    Gate,
    ReplayBuffer,
    TrackInitiator,
    TrackQualityMixin,
    prior_gain,
)
from .imm_kernels import (
    imm_combined_gate,
    imm_deceleration,
    imm_fuse,
    imm_parameters,
    imm_predict,
    imm_predicted_mean,
)
from .modes import DEFAULT_RATES, MIN_PROBABILITY, ModeChain

__all__ = ["IMMBall", "DEFAULT_RATES"]

#: Speed [m/s] above which a maneuver counts as a kick (two-phase model).
KICK_SPEED = 1.0


_EQUAL = (1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0)


class _State(NamedTuple):
    """Everything a replay must restore (immutable, so snapshots need no copies), at capture
    time ``t``: the three mode-matched filters, the mode probabilities, gated-out detections
    that may restart the track, and the two-phase model's kick.

    ``rest`` is ``(x, y, P11)`` with ``P11`` the row-major 2 x 2 position covariance (the rest
    filter's velocity is zero with the fixed variance ``IMMBall._rest_var_v``, uncorrelated
    with the position); ``roll`` and ``man`` are ``(x, P)`` with ``x`` the 4-tuple state and
    ``P`` the three 2 x 2 blocks ``(P11, P12, P22)`` of :mod:`estimators.kalman.blocks`.
    """

    t: float = -math.inf
    rest: tuple | None = None
    roll: tuple | None = None
    man: tuple | None = None
    mu: tuple = _EQUAL
    candidates: Candidates = ()
    fused_at: float = -math.inf
    since_start: int = 0
    kicked: float | None = None  # two-phase model: when the sliding ball was kicked
    maneuver: tuple | None = None  # the current maneuver's start time and the speed before


class IMMBall(ReplayBuffer, TrackQualityMixin):
    r"""Interacting multiple model ball tracker for delayed overhead-camera detections.

    **Modes.** Three Kalman filters on the state ``x = (x, y, vx, vy)`` [m, m/s], each with the
    detection model ``z = H x + v``, ``H = [I 0]``, ``v ~ N(0, r I)``, ``r = sigma_xy^2``
    [m^2], and its own motion over a step of ``T`` seconds, ``x' = f_j(x) + w_j``,
    ``w_j ~ N(0, Q_j)``, with Jacobian ``F_j = [[I, A_j], [0, B_j]]`` (``T0`` = 0.04 s, the
    paper cycle of :data:`~estimators.models.motion.PAPER_CYCLE`):

    0. ``rest``: the ball lies still. ``f(x) = (x, y, 0, 0)`` (``A = B = 0``);
       ``Q = diag(q_p, q_p, v_r, v_r)`` with position noise ``q_p = rest_noise^2 T / T0``
       [m^2] and the velocity's spread ``v_r = (rest_noise / T0)^2`` [m^2/s^2].
    1. ``rolling``: the friction model of :class:`~estimators.models.FrictionBallMotion`
       (deceleration ``a`` [m/s^2] against the velocity until the ball stops; analytic
       Jacobian; the ball stops rather than reverses); ``a = rolling_deceleration``, or with
       ``sliding_deceleration`` the two-phase model after a kick (see below);
       ``Q = diag(0, 0, q_v, q_v)``, ``q_v = rolling_noise^2 T / T0`` [m^2/s^2] (a velocity
       random walk, as the EKF's ``sigma_r``, smaller: the maneuver mode takes the kicks).
    2. ``maneuver``: constant velocity (``A = T I``, ``B = I``) with a velocity change
       ``dv ~ N(0, maneuver_noise^2 I)`` at a time uniform in the step (a kick or a bounce is an
       impulse), so per axis ``Q = maneuver_noise^2 [[T^2 / 3, T / 2], [T / 2, 1]]``
       [m^2, m^2/s, m^2/s^2]: the kick moves the predicted position within the step it happens
       in, and the detection after a kick lies inside this mode's gate.

    **Mode switching.** A continuous-time Markov chain with rates ``lambda_ij`` [1/s]
    (``rates[i][j]``, ``i != j``) and ``lambda_i = sum_j lambda_ij``. Over a step ``T`` the
    transition probabilities are taken as ``Pi_ii = exp(-lambda_i T)`` and
    ``Pi_ij = (1 - exp(-lambda_i T)) lambda_ij / lambda_i``: the exact probability of leaving
    mode ``i`` within ``T``, sent where the first jump goes (this leaves out two or more jumps
    within one step, ``O((lambda T)^2)``, and costs three exponentials instead of a matrix
    exponential). Each row sums to 1 (:class:`~estimators.kalman.modes.ModeChain`).

    **One cycle** (a frame captured ``T`` seconds after the previous one; ``mu_i`` the mode
    probabilities and ``x_i``, ``P_i`` the mode-matched estimates after the previous frame):

    1. predicted mode probabilities ``c_j = sum_i Pi_ij mu_i``;
    2. mixing: ``mu_{i|j} = Pi_ij mu_i / c_j``, ``x0_j = sum_i mu_{i|j} x_i``,
       ``P0_j = sum_i mu_{i|j} (P_i + (x_i - x0_j)(x_i - x0_j)^T)``;
    3. mode-matched prediction: ``x_j- = f_j(x0_j)``, ``P_j- = F_j P0_j F_j^T + Q_j``;
    4. the combined prediction ``x- = sum_j c_j x_j-``,
       ``P- = sum_j c_j (P_j- + (x_j- - x-)(x_j- - x-)^T)``;
    5. gating: of the frame's detections, the one nearest the combined prediction (smallest
       ``d^2 = (z - H x-)^T (H P- H^T + r I)^-1 (z - H x-)``) is the ball if it lies within
       ``max_jump`` of ``H x-`` and either ``d^2 <= gate`` or it lies within ``gate`` of some
       mode's prediction (``y_j^T S_j^-1 y_j <= gate``, step 6) no farther from ``H x-``
       than a kicked ball could get since the previous frame (``max_kick_speed T +
       3 sigma_xy``, as :class:`~estimators.BallTracker`'s maneuvers): a kick where the
       ball is. The maneuver mode's gate is the widest, so a kick is fused in the frame that
       shows it, while the bounds keep a spurious ball near the real one (at a robot's
       dribbler, or in a second camera's frame a moment later) from being taken for a kick;
       after the ball has gone unseen for a while, when the gates span metres, a detection
       beyond ``max_jump`` needs a second one that agrees (the restart below);
    6. mode-matched update: innovation ``y_j = z - H x_j-`` [m], ``S_j = H P_j- H^T + r I``
       [m^2], ``K_j = P_j- H^T S_j^-1``, ``x_j = x_j- + K_j y_j``, ``P_j = (I - K_j H) P_j-``
       (in closed form: with ``R = r I``, ``S_j`` commutes with the position block, so the
       position gain is ``I - r S_j^-1`` and the position covariance ``r (I - r S_j^-1)``,
       symmetric and positive definite by construction);
    7. mode probabilities: likelihood
       ``L_j = exp(-y_j^T S_j^-1 y_j / 2) / (2 pi sqrt(det S_j))`` [1/m^2],
       ``mu_j = c_j L_j / sum_k c_k L_k`` (floored at
       :data:`~estimators.kalman.modes.MIN_PROBABILITY`);
    8. output: ``x = sum_j mu_j x_j``, ``P = sum_j mu_j (P_j + (x_j - x)(x_j - x)^T)``.

    A frame without a detection, or whose nearest detection is gated out, ends after step 3
    with ``mu_j = c_j``. :meth:`estimate` and :meth:`covariance` at a later time ``t`` are
    steps 1-4 over ``T = t - time`` without changing the tracker, :meth:`mode_probabilities`
    is ``c_j`` (step 1).

    **Outliers and restarts** (as :class:`~estimators.BallTracker`): a gated-out detection is
    kept; when the next gated-out detection agrees with it (a ball at most
    ``MAX_SPEED_CHANGE`` = 10 m/s fast could connect them, plus ``5 sigma_xy``), the ball is
    somewhere else and the track restarts there: every mode at the newer detection, velocity
    the finite difference of the two (shrunk towards zero for detections a moment apart), the
    rest mode's probability the posterior of "at rest" against "moving" given that
    finite-difference velocity (equal priors; per axis ``N(0, var_fd + v_r)`` against
    ``N(0, var_fd + (10/3 m/s)^2)``, ``var_fd = 2 sigma_xy^2 / span^2``), the other two
    sharing the remainder equally; with the two-phase model a restart faster than
    :data:`KICK_SPEED` counts as a kick at the first of the two detections. A single
    gated-out detection never moves the track. The first detection starts the track with
    velocity zero of standard deviation 10/3 m/s and equal mode probabilities.

    **Two-phase model.** With ``sliding_deceleration`` ``a_s`` set, a fused frame after which
    the maneuver mode is the most probable is a maneuver, and a kick at ``t_k`` (the middle of
    the interval before the maneuver's first frame) if the combined speed has risen by more
    than :data:`KICK_SPEED` over the speed before the maneuver (a bounce or a push keeps the
    phase the ball was in). A kicked ball slides until its speed has fallen to ``k_switch``
    times its kick speed, which is its current speed plus what it lost sliding since the kick,
    ``|v| + a_s (t - t_k)``: the rolling mode decelerates with ``a_s`` while
    ``(1 - k_switch) |v| > k_switch a_s (t - t_k)`` at the start of a step, then with the
    rolling deceleration for good. The kick speed is never estimated by itself, so a poor
    speed estimate in the frames right after the kick only delays or advances the switch, and
    the switch comes at the right time once the speed estimate has settled.

    **Latency compensation** (Zhao et al. 2012): ``update`` takes capture times; a detection
    corrects the state at its capture time and :meth:`estimate` predicts to any later time.
    Frames that arrive out of capture order (several cameras, jittering latency) are replayed
    (:class:`~estimators.tracking.ReplayBuffer`): the tracker keeps the frames of the last
    ``history`` seconds with the state after each, rewinds to the state before a late frame
    and processes the frames from there in capture-time order; a frame older than that window
    is dropped and counted in ``late``.

    ``obstacles`` (the robots seen in a frame) are accepted for the protocol's sake and not
    used: the maneuver mode covers collisions wherever they happen.

    **Parts.** The gate (:class:`~estimators.tracking.Gate`: the nearest detection, the
    reach of a kick), the restarts (:class:`~estimators.tracking.TrackInitiator`), the replay
    and the track quality (:class:`~estimators.tracking.TrackQualityMixin`) are the shared
    parts of :mod:`estimators.tracking`; what is this tracker's own is its three motion
    models, the mixing and the mode-matched updates above.

    Cost: plain-float arithmetic on 2 x 2 blocks, compiled: the prediction (steps 1-4) and
    the gating, mode-matched updates and mode probabilities (steps 5-7) are kernels of
    :mod:`~estimators.kalman.imm_kernels` on the filters' tuples; the choice among several
    detections (:class:`~estimators.tracking.Gate`), the restarts, the two-phase kick and the
    replay stay in Python. :meth:`covariance` costs about one frame.

    Args:
        rolling_deceleration: rolling friction [m/s^2], in [0, 100].
        sliding_deceleration: sliding friction after a kick [m/s^2], in [0, 100]; None: one
            phase (the rolling deceleration throughout).
        k_switch: the speed at which a kicked ball starts rolling, as a fraction of its kick
            speed, in (0, 1] (used with ``sliding_deceleration``; 1: it never slides).
        sigma_xy: the detections' noise per axis [m], in (0, 10].
        rest_noise: the rest mode's position noise per 0.04 s [m], in (0, 1].
        rolling_noise: the rolling mode's velocity noise per 0.04 s [m/s], in (0, 10].
        maneuver_noise: the maneuver mode's velocity change per step [m/s], in (0, 100].
        rates: ``3 x 3`` transition rates [1/s] between the modes ``MODES`` (row: from,
            column: to; the diagonal is ignored), each in [0, 1000].
        gate: squared Mahalanobis distance beyond which a detection is not the ball, > 0.
        max_jump: the farthest [m] from the combined predicted position a detection may lie
            and be fused, in (0, 10]; a farther one only moves the track with a second
            detection that agrees with it (a restart).
        max_kick_speed: the fastest a kick sends the ball [m/s] (SSL rules: 6.5), in
            (0, 10]: a detection outside the combined gate and farther from the combined
            prediction than a ball this fast could have got since the previous frame is no
            kick (a faster change, such as a moving ball sent back, restarts the track).
        history: seconds of frames kept to replay out-of-order arrivals, in [0, 10].

    Attributes:
        fused, rejected, resets, late: counters of detections fused, nearest detections gated
            out, track restarts and frames too old to replay.
    """

    #: The modes, in the order of :meth:`mode_probabilities`.
    MODES = ("rest", "rolling", "maneuver")

    def __init__(self, rolling_deceleration: float = 0.3,
                 sliding_deceleration: float | None = 3.0, k_switch: float = 0.64,
                 sigma_xy: float = 0.025, rest_noise: float = 0.0005,
                 rolling_noise: float = 0.03, maneuver_noise: float = 4.0,
                 rates: Sequence[Sequence[float]] = DEFAULT_RATES,
                 gate: float = CHI2_2DOF_999, max_jump: float = 0.3,
                 max_kick_speed: float = 6.5, history: float = 0.5) -> None:
        self.rolling = check_real("rolling_deceleration", rolling_deceleration, 0.0, 100.0,
                                  unit=" m/s^2")
        self.sliding = None if sliding_deceleration is None else check_real(
            "sliding_deceleration", sliding_deceleration, 0.0, 100.0, unit=" m/s^2")
        self.k_switch = check_real("k_switch", k_switch, 0.0, 1.0, low_open=True)
        self.sigma_xy = check_real("sigma_xy", sigma_xy, 0.0, 10.0, low_open=True, unit=" m")
        self.rest_noise = check_real("rest_noise", rest_noise, 0.0, 1.0, low_open=True,
                                     unit=" m")
        self.rolling_noise = check_real("rolling_noise", rolling_noise, 0.0, 10.0,
                                        low_open=True, unit=" m/s")
        self.maneuver_noise = check_real("maneuver_noise", maneuver_noise, 0.0, 100.0,
                                         low_open=True, unit=" m/s")
        chain = ModeChain(rates)
        self.rates = chain.rates
        self._products = chain.products  # mu_i Pi_ij(dt), see ModeChain.products
        self._chain = chain.leave, chain.jump
        self.gate = check_real("gate", gate, 0.0, low_open=True)
        self.max_jump = check_real("max_jump", max_jump, 0.0, 10.0, low_open=True, unit=" m")
        self.max_kick_speed = check_real("max_kick_speed", max_kick_speed, 0.0,
                                         MAX_SPEED_CHANGE, low_open=True, unit=" m/s")
        self.history = check_real("history", history, 0.0, 10.0, unit=" s")
        self.motion = FrictionBallMotion(self.rolling)
        self._r = self.sigma_xy ** 2
        self._rest_q = self.rest_noise ** 2 / PAPER_CYCLE  # position variance per second
        self._rest_var_v = (self.rest_noise / PAPER_CYCLE) ** 2
        self._roll_q = self.rolling_noise ** 2 / PAPER_CYCLE  # velocity variance per second
        self._man_q = self.maneuver_noise ** 2
        self._gate = Gate(self.gate, self.max_kick_speed)
        self._initiator = TrackInitiator(self.sigma_xy)
        self._params = imm_parameters(self._rest_var_v, self._rest_q, self._roll_q,
                                      self._man_q, self.rolling, self.sliding, self.k_switch,
                                      self._r, self._gate.limit, self._gate.kick_speed,
                                      self.sigma_xy, self.max_jump)
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode)."""
        self._track = _State()
        self.reset_replay()
        self.fused = self.rejected = self.resets = 0

    # ------------------------------------------------------------------------------------
    # Protocol

    def update(self, t: float, detections, obstacles=None) -> None:
        """Process one frame captured at ``t`` [s] with ball detections ``(k, 2)`` [m] (k may
        be 0); ``obstacles`` (the robots seen, ``(j, 2)`` or poses whose first two entries are
        the position) is checked and not used.

        Raises:
            ValueError: ``t`` not a finite time or more than
                :data:`~estimators.protocol.MAX_REWIND` before the latest frame; detections
                not of shape ``(k, 2)`` or not finite; obstacles not rows of at least two
                finite numbers.
        """
        t = check_time(t)
        check_order(t, self._track.t)
        dets = check_points("detections", detections)
        if obstacles is not None:
            check_points("obstacles", obstacles, exact=False)
        self.update_frame(t, dets, ())

    def estimate(self, t: float) -> np.ndarray | None:
        """The combined state ``(x, y, vx, vy)`` [m, m/s] predicted to time ``t`` [s] (None
        before the first detection): ``sum_j c_j f_j(x0_j)``, steps 1-4 of the class
        docstring over ``t - time`` (the latest estimate for ``t <= time``)."""
        t = check_time(t)
        s = self._track
        if s.rest is None:
            return None
        dt = t - s.t
        if dt <= 0.0:
            return np.array(self._combined_mean(s.rest, s.roll, s.man, s.mu))
        return np.array(self._predicted_mean(s, dt))

    def _covariance(self, t: float) -> np.ndarray:
        """The ``4 x 4`` covariance [m^2, m^2/s, m^2/s^2] of the combined estimate of
        ``(x, y, vx, vy)`` predicted to ``t`` [s] (see :meth:`covariance`)."""
        s = self._track
        dt = t - s.t
        if dt > 0.0:
            rest, roll, man, mu = self._predict(s, dt)
        else:
            rest, roll, man, mu = s.rest, s.roll, s.man, s.mu
        g0, g1, g2, g3 = self._combined_mean(rest, roll, man, mu)
        v = self._rest_var_v
        px, py, R = rest
        P = [0.0] * 10  # P11 (00, 01, 11), P12 (02, 03, 12, 13), P22 (22, 23, 33)
        for w, x, (P11, P12, P22) in ((mu[0], (px, py, 0.0, 0.0), (R, (0.0,) * 4,
                                                                   (v, 0.0, 0.0, v))),
                                      (mu[1], *roll), (mu[2], *man)):
            d0, d1, d2, d3 = x[0] - g0, x[1] - g1, x[2] - g2, x[3] - g3
            for k, (pk, dk) in enumerate(((P11[0], d0 * d0), (P11[1], d0 * d1),
                                          (P11[3], d1 * d1), (P12[0], d0 * d2),
                                          (P12[1], d0 * d3), (P12[2], d1 * d2),
                                          (P12[3], d1 * d3), (P22[0], d2 * d2),
                                          (P22[1], d2 * d3), (P22[3], d3 * d3))):
                P[k] += w * (pk + dk)
        a0, a1, a3, b0, b1, b2, b3, c0, c1, c3 = P
        return np.array([[a0, a1, b0, b1], [a1, a3, b2, b3], [b0, b2, c0, c1],
                         [b1, b3, c1, c3]])

    def mode_probabilities(self, t: float | None = None) -> np.ndarray:
        """The probabilities of the modes ``MODES`` (rest, rolling, maneuver), ``(3,)``: after
        the latest frame, or predicted to ``t`` [s] by the mode transitions
        (``c_j = sum_i Pi_ij(t - time) mu_i``; the latest for ``t <= time``). Before the
        first detection: equal."""
        s = self._track
        mu = s.mu
        if t is not None:
            t = check_time(t)
            if s.rest is not None and t > s.t:
                w = self._products(mu, t - s.t)
                mu = (w[0] + w[1] + w[2], w[3] + w[4] + w[5], w[6] + w[7] + w[8])
        return np.array(mu)

    # ------------------------------------------------------------------------------------
    # The filter

    def _decel(self, x: tuple, kicked: float | None, t: float) -> float:
        """The rolling mode's deceleration from state ``x`` at time ``t``: sliding while the
        speed exceeds ``k_switch`` times the kick speed (``(1 - k) |v| > k a_s (t - kicked)``),
        else rolling (:func:`~estimators.kalman.imm_kernels.imm_deceleration`)."""
        return imm_deceleration(x, kicked is not None, 0.0 if kicked is None else kicked, t,
                                self._params)

    def _kicked(self, kicked: float | None, x: tuple, t: float) -> float | None:
        """The kick time after a frame at ``t`` with the rolling mode at ``x``: None (rolling
        for good) once the ball has slowed to the switch speed."""
        if kicked is None or self._decel(x, kicked, t) == self.sliding:
            return kicked
        return None

    def _predicted_mean(self, s: _State, dt: float) -> tuple[float, float, float, float]:
        """The combined mean predicted ``dt`` > 0 seconds ahead (steps 1-4, means only;
        :func:`~estimators.kalman.imm_kernels.imm_predicted_mean`)."""
        return imm_predicted_mean(s.rest, s.roll, s.man, s.mu, dt, *self._kick(s), *self._chain,
                                  self._params)

    @staticmethod
    def _kick(s: _State) -> tuple[bool, float, float]:
        """The kernels' ``(kicked, t_kick, t)`` of state ``s``."""
        return s.kicked is not None, 0.0 if s.kicked is None else s.kicked, s.t

    @staticmethod
    def _combined_mean(rest, roll, man, mu) -> tuple[float, float, float, float]:
        mR, mF, mM = mu
        xF, xM = roll[0], man[0]
        return (mR * rest[0] + mF * xF[0] + mM * xM[0], mR * rest[1] + mF * xF[1] + mM * xM[1],
                mF * xF[2] + mM * xM[2], mF * xF[3] + mM * xM[3])

    def _predict(self, s: _State, dt: float):
        """Steps 1-3 over ``dt`` > 0 seconds: ``(rest, roll, man, c)`` predicted
        (:func:`~estimators.kalman.imm_kernels.imm_predict`)."""
        return imm_predict(s.rest, s.roll, s.man, s.mu, dt, *self._kick(s), *self._chain,
                           self._params)

    def process(self, s: _State, t: float, dets: Sequence, obstacles: Sequence = ()) -> _State:
        """The state after one frame captured at ``t`` (no earlier than ``s.t``): steps 1-7
        of the class docstring (``obstacles`` not used); what :meth:`update_frame`
        replays."""
        if s.rest is None:
            if not dets:
                return s
            z = dets[0]
            return self._start(t, float(z[0]), float(z[1]), 0.0, 0.0,
                               (MAX_SPEED_CHANGE / 3.0) ** 2)
        dt = t - s.t
        if dt > 0.0:
            rest, roll, man, c = self._predict(s, dt)
        else:  # another view of the same instant: nothing to predict
            rest, roll, man, c = s.rest, s.roll, s.man, s.mu
        if not dets:
            return _State(t, rest, roll, man, c, s.candidates, s.fused_at, s.since_start,
                          self._kicked(s.kicked, roll[0], t), s.maneuver)
        # The combined gate's distance is needed only when no mode's gate takes the
        # detection; with several detections the nearest one's comes with the choice.
        z, d2 = (dets[0], None) if len(dets) == 1 else self._nearest(rest, roll, man, c, dets)
        zx, zy = float(z[0]), float(z[1])
        fused, rest, roll, man, mu = imm_fuse(rest, roll, man, c, zx, zy, d2 is not None,
                                              0.0 if d2 is None else d2, t - s.t,
                                              self._params)
        if not fused:
            self.rejected += 1
            return self._outlier(_State(t, rest, roll, man, c, s.candidates, s.fused_at,
                                        s.since_start, self._kicked(s.kicked, roll[0], t),
                                        s.maneuver), t, zx, zy)
        self.fused += 1
        kicked, maneuver = self._kicked(s.kicked, roll[0], t), None
        if self.sliding is not None and mu[2] >= mu[0] and mu[2] >= mu[1]:
            # A maneuver: a kick if it made the ball faster by more than KICK_SPEED.
            maneuver = s.maneuver
            if maneuver is None:
                x = self._combined_mean(s.rest, s.roll, s.man, s.mu)
                maneuver = (0.5 * (s.t + t), math.hypot(x[2], x[3]))
            x = self._combined_mean(rest, roll, man, mu)
            if math.hypot(x[2], x[3]) > maneuver[1] + KICK_SPEED:
                kicked = maneuver[0]
        return _State(t, rest, roll, man, mu, (), t, s.since_start + 1, kicked, maneuver)

    def _nearest(self, rest, roll, man, c, dets) -> tuple[Sequence[float], float]:
        """Steps 4-5: the detection nearest the combined prediction and its squared
        Mahalanobis distance ``d^2`` from it."""
        gx, gy, s0, s1, s3 = imm_combined_gate(rest, roll, man, c, self._r)
        best, d2, _ = self._gate.nearest(gx, gy, (s0, s1, s3), dets)
        return best, d2

    def _start(self, t: float, zx: float, zy: float, vx: float, vy: float, var_v: float,
               mu: tuple = _EQUAL, since: float | None = None) -> _State:
        """A new track at ``(zx, zy)`` with velocity ``(vx, vy)`` of variance ``var_v`` per
        axis in the rolling and maneuver modes and mode probabilities ``mu``; with the
        two-phase model a ball faster than :data:`KICK_SPEED` is taken as kicked at ``since``
        (default ``t``)."""
        r = self._r
        P11 = (r, 0.0, 0.0, r)
        P = (P11, (0.0,) * 4, (var_v, 0.0, 0.0, var_v))
        x = (zx, zy, vx, vy)
        kicked = None
        if self.sliding is not None and math.hypot(vx, vy) > KICK_SPEED:
            kicked = t if since is None else since
        return _State(t, (zx, zy, P11), (x, P), (x, P), mu, (), t, 1, kicked, None)

    def _outlier(self, s: _State, t: float, zx: float, zy: float) -> _State:
        """Keep a gated-out detection; restart the track when two agree (the
        :class:`~estimators.tracking.TrackInitiator` of :class:`~estimators.BallTracker` with
        ``reset_after=2``)."""
        initiator = self._initiator
        candidates = initiator.offer(s.candidates, t, (float(zx), float(zy)))
        if not initiator.ready(candidates):
            return s._replace(candidates=candidates)
        t0, (x0, y0) = candidates[0]
        span = t - t0
        sigma = self.sigma_xy
        # The finite-difference velocity, combined with the prior that a ball moves at most
        # MAX_SPEED_CHANGE (v ~ N(0, s0^2), s0 a third of it): v = g v_fd, var = g var_fd.
        s0_2 = initiator.prior_var
        var_fd = 2.0 * sigma * sigma / (span * span)
        g = prior_gain(s0_2, var_fd)
        ux, uy = (zx - x0) / span, (zy - y0) / span
        # At rest or moving: the finite-difference velocity's likelihood under each, per axis
        # N(0, var_fd + v_r) and N(0, var_fd + s0^2), sets the rest mode's probability; the
        # rolling and maneuver modes share the rest.
        v2 = ux * ux + uy * uy
        still, moving = var_fd + self._rest_var_v, var_fd + s0_2
        log_odds = 0.5 * v2 * (1.0 / still - 1.0 / moving) + math.log(still / moving)
        p = MIN_PROBABILITY if log_odds > 700.0 else min(
            max(1.0 / (1.0 + math.exp(log_odds)), MIN_PROBABILITY), 1.0 - 2 * MIN_PROBABILITY)
        self.resets += 1
        return self._start(t, float(zx), float(zy), g * ux, g * uy,
                           g * var_fd + self.rolling_noise ** 2,
                           (p, 0.5 * (1.0 - p), 0.5 * (1.0 - p)), t0)
