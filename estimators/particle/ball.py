"""Particle-filter ball tracking with the filters of Xu, Xie, Wang and Ni (2012).

The fused ball positions of a team (Hough fusion, :func:`~estimators.fusion.fuse_sightings`)
jitter around the truth; Xu et al. (2012) smooths and predicts them with a particle filter on the
ball's state ``X = (px, py, vx, vy)`` [m, m, m/s, m/s] in the field frame.

**Motion** (constant velocity, with the corrected ``B`` for this state order), over a
step of ``dT`` seconds taken from the time stamps:

    X_t = A X_{t-1} + B W_t,
    A = [[1, 0, dT, 0], [0, 1, 0, dT], [0, 0, 1, 0], [0, 0, 0, 1]],
    B = [[dT^2/2, 0], [0, dT^2/2], [dT, 0], [0, dT]],
    W_t ~ N(0, accel_sigma^2 I_2)   (white acceleration noise [m/s^2]).

With ``deceleration = a > 0`` (rolling friction, as in Zhao, Wang and Li 2012) the
deterministic part ``A X`` is replaced by uniform deceleration along the motion that stops the
ball instead of reversing it: with speed ``s = |v|``, unit direction ``u`` and
``tau = min(dT, s / a)``, ``p' = p + u (s tau - a tau^2 / 2)``, ``v' = u (s - a tau)``; the
noise ``B W`` is added as before. ``deceleration = 0`` is the paper's plain constant-velocity model.

**Measurement**: a position ``z`` [m] with covariance ``R`` (``sigma^2 I`` for a scalar
``sigma``, or a full 2 x 2 matrix, per measurement), ``p(z | X) = N(z; (px, py), R)``,
evaluated as ``exp(-d^2 / 2)`` with ``d^2 = (z - p)^T R^-1 (z - p)`` shifted by its minimum
over the particles (a constant factor, which no filter's weights depend on, against
underflow).

**Filters**: :class:`~estimators.particle.BootstrapPF`, :class:`~estimators.particle.FBPF` or
:class:`~estimators.particle.MFBPF` (the default, Xu et al.'s (2012)), with their own resampling and
SFN; the fission perturbation has one standard deviation per state component
(``fission_sigma`` [m, m, m/s, m/s]), because a single variance cannot suit metres and metres
per second alike.

**Track management**:

* The filter starts at the first measurement from ``N(x0, P0)``, ``x0 = (z, 0, 0)``,
  ``P0 = diag(R, init_speed_sigma^2 I)``. The velocity is unobservable from one position and
  weakly observable from a few close in time, and a hundred particles drawn from a broad
  velocity prior leave few near a fast ball's velocity, which resampling then loses (without
  a gate, the bootstrap filter and MFBPF ended far from the ball in about a quarter and a
  twentieth of our runs started that way: 0.1 m noise at 25 Hz, speeds up to 2.5 m/s). So
  the first ``kalman_start`` measurements go through the exact Kalman filter of the same
  (linear Gaussian) model, the particles redrawn from its ``N(x, P)`` after each; then the
  particle filter takes over. ``kalman_start=1``: the particles alone from the first
  measurement (the paper's start).
* A measurement is *implausible* when its squared Mahalanobis distance from the particles'
  weighted mean position, with the particles' weighted position covariance ``C`` plus ``R``,
  ``(z - m)^T (C + R)^-1 (z - m)``, exceeds ``gate``; ``reinit_after`` implausible
  measurements in a row (the ball was kicked or placed elsewhere) restart the filter at the
  last one; fewer are not fused (outliers). ``gate=None`` never restarts. During the Kalman
  start the same test uses the Kalman filter's innovation covariance ``H P H^T + R``.
* ``lost_after`` seconds without a fused measurement also restart the filter at the next one.
* A measurement *older* than the filter's time (stamps slightly out of order) is fused without
  predicting backwards: each particle is compared with its own position extrapolated back by
  the lag, ``p - lag v`` (the noise-free constant-velocity model; the deceleration is
  neglected over such a lag), and the filter's time stays where it is. Measurements older than
  ``max_lag`` are ignored (counted in ``late``).

The model's arithmetic over the particles in compiled kernels
(:mod:`estimators.particle.filter_kernels`); every random draw from the given generator.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..checks import (
    MAX_ACCELERATION,
    MAX_COORDINATE,
    MAX_PARTICLES,
    MAX_SPEED,
    check_count,
    check_positive,
    check_real,
    check_reals,
)
from ..kalman.core import KalmanFilter
from ..protocol import check_order, check_time
from ..tracking import TrackQualityMixin, TrackTimes, prior_gain
from .core import FBPF, PARTICLE_FILTERS, BootstrapPF
from .filter_kernels import drift, position_likelihood, position_moments, roll, transition

__all__ = ["ParticleBallTracker", "CHI2_2DOF_9999"]

#: 99.99 % quantile of the chi-square distribution with 2 degrees of freedom, ``-2 ln 1e-4``.
CHI2_2DOF_9999 = 18.420680743952367

#: The smallest ``init_speed_sigma`` [m/s]: its square stays a normal float (the Kalman
#: start's covariance must be positive definite).
MIN_SPEED_SIGMA = 1e-6

#: A re-initialisation takes its velocity from the measurement before it if that is at most
#: this old [s].
_MAX_DIFFERENCE_SPAN = 0.3


def _cv_matrix(dt: float) -> np.ndarray:
    """The constant-velocity model's ``A = [[I, dt I], [0, I]]`` over ``dt`` [s] for the state
    ``(px, py, vx, vy)``."""
    return np.array([[1.0, 0.0, dt, 0.0], [0.0, 1.0, 0.0, dt],
                     [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])


def _acceleration_noise(dt: float, s2: float) -> np.ndarray:
    """``s2 B B^T`` for the constant-velocity model's acceleration input
    ``B = [dt^2 / 2 I; dt I]`` over ``dt`` [s], written out: with ``h = dt^2 / 2``,
    ``B B^T = [[h^2 I, h dt I], [dt h I, dt^2 I]]`` (each entry one product, as the matrix
    product rounds it: its other term is an exact zero)."""
    h = 0.5 * dt * dt
    hh, hd, dh, dd = s2 * (h * h), s2 * (h * dt), s2 * (dt * h), s2 * (dt * dt)
    return np.array([[hh, 0.0, hd, 0.0], [0.0, hh, 0.0, hd],
                     [dh, 0.0, dd, 0.0], [0.0, dh, 0.0, dd]])


def _measurement_matrix(lag: float) -> np.ndarray:
    """The Kalman start's ``H = [I, -lag I]`` ((2, 4)), read-only."""
    H = np.zeros((2, 4))
    H[0, 0] = H[1, 1] = 1.0
    H[0, 2] = H[1, 3] = -lag
    H.flags.writeable = False
    return H


#: :func:`_measurement_matrix` at no lag (the usual case), built once.
_H_NO_LAG = _measurement_matrix(0.0)


def _start_measurement(lag: float) -> np.ndarray:
    """The Kalman start's ``H`` for a measurement ``lag`` [s] older than the filter."""
    return _H_NO_LAG if lag == 0.0 else _measurement_matrix(lag)


def _floats(value) -> np.ndarray | None:
    """``value`` as a float array, None when it is not numbers."""
    try:
        return np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        return None


class ParticleBallTracker(TrackQualityMixin):
    """Ball tracker on Xu et al.'s (2012) particle filters (see the module docstring).

    Its :meth:`covariance` at ``t`` is the Kalman start's ``P`` or the particles' weighted
    covariance at the filter's time, predicted to a later ``t`` by the constant-velocity model
    with the acceleration noise, ``P' = A P A^T + s^2 B B^T`` (``A = [[I, dt I], [0, I]]``,
    ``B = [dt^2/2 I; dt I]``); the deceleration, which :meth:`estimate` applies to the mean,
    is left out of the spread.

    Args:
        rng: the generator of every random draw.
        filter: a name in :data:`~estimators.particle.core.PARTICLE_FILTERS`:
            ``"bootstrap"``, ``"fbpf"`` or ``"mfbpf"`` (Xu et al.'s 2012, the default).
        n_particles: number of particles (Xu et al. 2012: 100).
        accel_sigma: standard deviation of the white acceleration noise ``W`` [m/s^2].
        deceleration: rolling deceleration ``a`` [m/s^2]; 0 is the plain constant-velocity
            model.
        threshold: ``N_th / N`` of the filter; None takes the filter's default (1.0 for the
            bootstrap filter, which then resamples every step; 0.5 for FBPF and MFBPF).
        fission_sigma: standard deviations of the fission offspring's perturbation,
            ``(px, py, vx, vy)`` [m, m, m/s, m/s] (FBPF and MFBPF; the filter gets their
            squares as its per-dimension ``fission_variance``).
        sfn_when: MFBPF's test, ``"above"`` (as printed in Xu et al. (2012)) or ``"below"``.
        resample: FBPF's resampling, ``"always"`` (as printed in Xu et al. (2012)) or
            ``"threshold"`` (only when ``N_eff < N_th``); see :class:`~estimators.FBPF`.
        init_speed_sigma: standard deviation of the velocity at (re-)initialisation [m/s].
        gate: squared Mahalanobis distance beyond which a measurement is implausible; None
            never re-initialises on a measurement.
        reinit_after: implausible measurements in a row that restart the filter (1: the first
            one; more: the earlier ones are dropped as outliers).
        lost_after: seconds without a fused measurement after which the next one restarts the
            filter; None: never.
        max_lag: measurements older than the filter's time by more than this [s] are ignored.
        max_speed: the fastest a ball moves [m/s]: a restart's finite-difference velocity
            above it is not believed.
        kalman_start: measurements fused by the Kalman start after each (re-)initialisation,
            the first included (1: none, the particles start from the first measurement).

    Attributes:
        fused, rejected, resets, late: counters of measurements fused (those that started
            the filter included), found implausible, re-initialisations (the first start not
            counted) and measurements ignored as too old.
    """

    def __init__(self, rng: np.random.Generator, *, filter: str = "mfbpf",
                 n_particles: int = 100, accel_sigma: float = 1.0, deceleration: float = 0.0,
                 threshold: float | None = None,
                 fission_sigma: Sequence[float] = (0.02, 0.02, 0.1, 0.1),
                 sfn_when: str = "above", resample: str = "always",
                 init_speed_sigma: float = 2.0,
                 gate: float | None = CHI2_2DOF_9999, reinit_after: int = 1,
                 lost_after: float | None = 1.0, max_lag: float = 0.1,
                 max_speed: float = 10.0,
                 kalman_start: int = 10) -> None:
        if not isinstance(rng, np.random.Generator):
            raise TypeError("rng must be a numpy.random.Generator")
        PARTICLE_FILTERS.check(filter, "filter")
        check_count("n_particles", n_particles, 2, MAX_PARTICLES)
        if threshold is not None:
            threshold = check_real("threshold", threshold, 0.0, 1.0, low_open=True,
                                   unit=" (N_th / N) or None")
        fs = check_reals("fission_sigma", fission_sigma, 4, 0.0, MAX_COORDINATE,
                         "(px, py, vx, vy) [m, m, m/s, m/s]")
        if sfn_when not in ("above", "below"):
            raise ValueError(f"sfn_when must be 'above' or 'below', got {sfn_when!r}")
        if resample not in FBPF.RESAMPLE:
            raise ValueError(f"resample must be one of {FBPF.RESAMPLE}, got {resample!r}")
        if gate is not None:
            gate = check_positive("gate", gate)
        if isinstance(reinit_after, bool) or not isinstance(reinit_after, (int, np.integer)) \
                or reinit_after < 1:
            raise ValueError(f"reinit_after must be an integer >= 1, got {reinit_after!r}")
        if lost_after is not None:
            lost_after = check_positive("lost_after", lost_after)
        if isinstance(kalman_start, bool) or not isinstance(kalman_start, (int, np.integer)) \
                or kalman_start < 1:
            raise ValueError(f"kalman_start must be an integer >= 1, got {kalman_start!r}")
        self.rng = rng
        self.filter = filter
        self.n_particles = int(n_particles)
        self.accel_sigma = check_positive("accel_sigma", accel_sigma, unit=" [m/s^2]",
                                          high=MAX_ACCELERATION)
        self.deceleration = check_positive("deceleration", deceleration, allow_zero=True,
                                           unit=" [m/s^2]", high=MAX_ACCELERATION)
        self.init_speed_sigma = check_real("init_speed_sigma", init_speed_sigma,
                                           MIN_SPEED_SIGMA, MAX_SPEED, unit=" m/s")
        self.max_lag = check_positive("max_lag", max_lag, allow_zero=True)
        self.max_speed = check_positive("max_speed", max_speed, unit=" [m/s]", high=MAX_SPEED)
        self.gate, self.reinit_after, self.lost_after = gate, int(reinit_after), lost_after
        self.kalman_start = int(kalman_start)
        kwargs: dict = {}
        if threshold is not None:
            kwargs["threshold"] = float(threshold)
        if filter != "bootstrap":
            kwargs["fission_variance"] = fs * fs
        if filter == "mfbpf":
            kwargs["sfn_when"] = sfn_when
        if filter == "fbpf":
            kwargs["resample"] = resample
        self._cls = PARTICLE_FILTERS[filter]
        self._kwargs = kwargs
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode)."""
        self._pf: BootstrapPF | None = None
        self._kf: KalmanFilter | None = None  # the Kalman start, while it runs
        self._t = -math.inf  # the filter's time [s]
        self._t_fused = -math.inf  # time of the latest fused measurement [s]
        self._x = np.zeros(4)  # the filter's estimate at its time
        self._misses = 0
        self._since_start = 0  # measurements fused since the last (re)start
        self._prev: tuple[float, np.ndarray, np.ndarray] | None = None  # last measurement
        # Set before each call into the filter: step length, lag and R^-1 entries.
        self._dt = 0.0
        self._lag = 0.0
        self._rinv = (1.0, 0.0, 1.0)
        self.fused = self.rejected = self.resets = self.late = 0
        # The latest estimate asked for: its time and value (a pipeline asks for the same
        # time several times per step); cleared whenever the filter changes.
        self._memo: tuple[float, np.ndarray | None] | None = None

    # ------------------------------------------------------------------------------------
    # The model, called by the filter

    def _transition(self, x: np.ndarray, k: int, rng: np.random.Generator) -> np.ndarray:
        """``X_t = A X_{t-1} + B W_t`` (or its decelerating variant) over ``self._dt``."""
        w = rng.normal(0.0, self.accel_sigma, (len(x), 2))  # W_t [m/s^2]
        return transition(x, self._dt, self.deceleration, w)

    def _likelihood(self, x: np.ndarray, z: np.ndarray) -> np.ndarray:
        """``N(z; p, R)`` up to a constant factor."""
        return position_likelihood(x, (float(z[0]), float(z[1])), self._lag, self._rinv)

    # ------------------------------------------------------------------------------------

    @property
    def _track(self) -> TrackTimes:
        """The track's times: the filter's time (its latest measurement's or prediction's),
        the latest fused measurement's, and the measurements fused since the latest
        (re)start."""
        return TrackTimes(self._t, self._t_fused, self._since_start)

    @property
    def particles(self) -> np.ndarray:
        """A copy of the ``(N, 4)`` particles at the filter's time (``(0, 4)`` before the
        first measurement)."""
        return np.zeros((0, 4)) if self._pf is None else self._pf.particles.copy()

    @property
    def weights(self) -> np.ndarray:
        """A copy of the particles' normalised weights ((N,))."""
        return np.zeros(0) if self._pf is None else self._pf.weights / self._pf.weights.sum()

    @property
    def spread(self) -> float | None:
        """Weighted RMS distance [m] of the particles' positions from their weighted mean
        (``sqrt(trace C)``, ``C`` the position covariance); None before the first
        measurement."""
        if self._pf is None:
            return None
        _, _, cxx, _, cyy = position_moments(self._pf.particles, self._pf.weights, 0.0)
        return math.sqrt(cxx + cyy)

    def _covariance(self, t: float) -> np.ndarray:
        """The Kalman start's ``P`` or the particles' weighted covariance at the filter's
        time, predicted to a later ``t`` (see the class docstring)."""
        if self._kf is not None:
            P = self._kf.P.copy()
        else:
            w = self.weights
            d = self._pf.particles - w @ self._pf.particles
            P = (d * w[:, None]).T @ d
        dt = float(t) - self._t
        if dt > 0.0:
            A = _cv_matrix(dt)
            P = A @ P @ A.T + _acceleration_noise(dt, self.accel_sigma**2)
        return P

    def _check(self, t: float, z, sigma) -> tuple[float, np.ndarray, np.ndarray]:
        t = check_time(t)
        zz = _floats(z)
        if zz is None or zz.shape != (2,) or not np.isfinite(zz).all():
            raise ValueError(f"z must be a finite (2,) position, got {z!r}")
        s = _floats(sigma)
        if s is None:
            raise ValueError(f"sigma must be a number > 0 or a 2 x 2 covariance, got "
                             f"{sigma!r}")
        if s.ndim == 0:
            sv = float(s)
            if not (math.isfinite(sv) and sv > 0.0):
                raise ValueError(f"sigma must be finite and > 0 or a 2 x 2 covariance, got "
                                 f"{sigma!r}")
            R = np.diag([sv * sv, sv * sv])
        else:
            R = s
            ok = (R.shape == (2, 2) and np.isfinite(R).all()
                  and abs(R[0, 1] - R[1, 0]) <= 1e-12 * max(1.0, abs(R[0, 1]))
                  and R[0, 0] > 0.0 and R[0, 0] * R[1, 1] - R[0, 1] * R[1, 0] > 0.0)
            if not ok:
                raise ValueError(f"sigma must be > 0 or a symmetric positive definite 2 x 2 "
                                 f"covariance, got {sigma!r}")
            R = 0.5 * (R + R.T)
        return t, zz, R

    def update(self, t: float, z: np.ndarray | Sequence[float],
               sigma: float | np.ndarray) -> None:
        """Fuse the position ``z`` [m] measured at time ``t`` [s] with standard deviation
        ``sigma`` [m] (or 2 x 2 covariance [m^2]): predict to ``t``, gate, weight, then the
        filter's own SFN and/or resampling (see the module docstring for the start,
        re-initialisation and late measurements)."""
        t, z, R = self._check(t, z, sigma)
        self.update_fused(t, z, R)

    def update_fused(self, t: float, z: np.ndarray, R: np.ndarray) -> None:
        """:meth:`update` without its argument checks, for callers with validated data (a
        pipeline's own fused points): ``t`` a finite time [s], ``z`` a finite ``(2,)``
        float array [m], ``R`` a symmetric positive definite ``2 x 2`` float array [m^2].
        Stamps are still checked to be in order."""
        if self._pf is not None:
            check_order(t, self._t)
        self._memo = None
        prev, self._prev = self._prev, (t, z, R)
        if self._pf is None or (self.lost_after is not None
                                and t - self._t_fused > self.lost_after):
            self._start(t, z, R)
            return
        lag = 0.0
        if t < self._t:
            lag = self._t - t
            if lag > self.max_lag:
                self.late += 1
                return
        else:
            self._advance(t)
        self._lag = lag
        kf = self._kf
        if kf is not None:
            # The Kalman start measures z with H = [I, -lag I] (the back-extrapolated
            # position); the filter gates and updates on one innovation.
            if not kf.update_unchecked(z, _start_measurement(lag), R, gate=self.gate):
                self._reject(t, z, R, prev)
                return
            self._misses = 0
            self._x = kf.x.copy()
        else:
            if self.gate is not None and self._mahalanobis2(z, R) > self.gate:
                self._reject(t, z, R, prev)
                return
            self._misses = 0
            det = R[0, 0] * R[1, 1] - R[0, 1] * R[1, 0]
            self._rinv = (R[1, 1] / det, -R[0, 1] / det, R[0, 0] / det)
            self._x = self._pf.correct(z)
        self._lag = 0.0
        self._t_fused = max(self._t_fused, t)
        self._since_start += 1
        self.fused += 1
        if kf is not None:
            self._redraw()
            if self._since_start >= self.kalman_start:
                self._kf = None  # the particles take over

    def _reject(self, t: float, z: np.ndarray, R: np.ndarray,
                prev: tuple[float, np.ndarray, np.ndarray] | None) -> None:
        """An implausible measurement: counted, and the filter restarted at it after
        ``reinit_after`` in a row (else, during the Kalman start, the particles redrawn)."""
        self.rejected += 1
        self._misses += 1
        if self._misses >= self.reinit_after:
            self._start(t, z, R, prev)
        elif self._kf is not None:
            self._redraw()

    def predict_to(self, t: float) -> None:
        """Time update only, to ``t`` [s] (a cycle without a measurement); nothing happens
        before the first measurement or for ``t`` at or before the filter's time."""
        t = check_time(t)
        if self._pf is not None and t > self._t:
            self._memo = None
            self._advance(t)
            if self._kf is not None:
                self._redraw()

    def estimate(self, t: float) -> np.ndarray | None:
        """The state ``(px, py, vx, vy)`` [m, m/s] at time ``t`` [s]: the filter's estimate
        moved by the deterministic motion (constant velocity, or the deceleration) when ``t``
        is later than the filter's time, unchanged otherwise; the filter is not changed.
        None before the first measurement. A new array each call; the value at the latest
        time asked for is kept until the filter changes (a pipeline asks for one time several
        times per step)."""
        t = check_time(t)
        memo = self._memo
        if memo is None or memo[0] != t:
            memo = self._memo = (t, self._drifted(t))
        est = memo[1]
        return None if est is None else est.copy()

    def _drifted(self, t: float) -> np.ndarray | None:
        """:meth:`estimate`'s value at the checked time ``t``."""
        if self._pf is None:
            return None
        dt = t - self._t
        if not dt > 0.0:
            return self._x.copy()
        # drift for one state (called every control step by a pipeline).
        px, py, vx, vy = self._x.tolist()
        return np.array(roll(px, py, vx, vy, math.hypot(vx, vy), dt, self.deceleration))

    # ------------------------------------------------------------------------------------

    def _advance(self, t: float) -> None:
        """Time update to ``t`` (later than the filter's time)."""
        dt = t - self._t
        if dt > 0.0:
            self._dt = dt
            kf = self._kf
            if kf is None:
                self._x = self._pf.predict()
            else:
                # x' = drift(x) (exactly A x without deceleration), P' = A P A^T + s^2 B B^T
                kf.predict_unchecked(_cv_matrix(dt),
                                     _acceleration_noise(dt, self.accel_sigma**2),
                                     drift(kf.x[None, :], dt, self.deceleration)[0])
                self._x = kf.x.copy()
            self._t = t

    def _redraw(self) -> None:
        """Kalman start: the particles drawn afresh from the filter's ``N(x, P)``, uniform
        weights."""
        kf, pf = self._kf, self._pf
        L = np.linalg.cholesky(kf.P)
        pf.particles = kf.x + self.rng.normal(0.0, 1.0, (pf.n, 4)) @ L.T
        pf.weights = np.full(pf.n, 1.0 / pf.n)

    def _mahalanobis2(self, z: np.ndarray, R: np.ndarray) -> float:
        """``(z - m)^T (C + R)^-1 (z - m)`` with the particles' weighted mean position ``m``
        and covariance ``C`` (at the measurement's time)."""
        mx, my, cxx, cxy, cyy = position_moments(self._pf.particles, self._pf.weights,
                                                 self._lag)
        y0, y1 = z[0] - mx, z[1] - my
        s00, s01, s11 = cxx + R[0, 0], cxy + R[0, 1], cyy + R[1, 1]  # C + R
        return float((s11 * y0 * y0 - 2.0 * s01 * y0 * y1 + s00 * y1 * y1)
                     / (s00 * s11 - s01 * s01))

    def _start(self, t: float, z: np.ndarray, R: np.ndarray,
               prev: tuple[float, np.ndarray, np.ndarray] | None = None) -> None:
        """(Re-)initialise at the measurement ``z`` taken at ``t``: ``N(x0, P0)`` with
        ``x0 = (z, v0)``, ``P0 = diag(R, s_v^2 I)``.

        The velocity's prior is ``N(0, init_speed_sigma^2)``. A re-initialisation on an
        implausible measurement (the ball was kicked or bounced) also knows the measurement
        ``prev = (t0, z0, R0)`` before it: the finite difference ``(z - z0) / (t - t0)`` has
        variance ``(tr R + tr R0) / 2 / (t - t0)^2`` per axis, and the two combine into
        ``v0 = g v_fd``, ``s_v^2 = g var_fd`` with ``g = s0^2 / (s0^2 + var_fd)``: the new
        motion is known at once rather than learnt over several measurements. A difference
        faster than ``max_speed`` joins no ball's two positions (one of them is an outlier):
        then the prior alone."""
        s0_2 = self.init_speed_sigma**2
        v0, var_v = (0.0, 0.0), s0_2
        if prev is not None and 0.0 < t - prev[0] <= _MAX_DIFFERENCE_SPAN:
            t0, z0, R0 = prev
            span = t - t0
            dx, dy = (z[0] - z0[0]) / span, (z[1] - z0[1]) / span
            if dx * dx + dy * dy <= self.max_speed**2:
                var_fd = 0.5 * float(np.trace(R) + np.trace(R0)) / span**2
                g = prior_gain(s0_2, var_fd)
                v0, var_v = (g * dx, g * dy), g * var_fd
        P0 = np.zeros((4, 4))
        P0[:2, :2] = R
        P0[2, 2] = P0[3, 3] = var_v
        x0 = np.array([z[0], z[1], v0[0], v0[1]])
        self._kf = KalmanFilter(x0, P0)
        n = self.n_particles
        if self._pf is not None:
            self.resets += 1
        self.fused += 1
        self._pf = self._cls(np.zeros((n, 4)), self._transition, self._likelihood, self.rng,
                             **self._kwargs)
        self._redraw()
        if self.kalman_start <= 1:
            self._kf = None
        self._t = self._t_fused = t
        self._x = x0
        self._misses = 0
        self._since_start = 1
        self._lag = 0.0
