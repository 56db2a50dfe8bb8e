"""The filter arithmetic of the :class:`~estimators.IMMBall` tracker as compiled kernels:
steps 1-3 of its docstring, the predicted mode probabilities, the mixing of the three
mode-matched filters and their predictions (:func:`imm_predict`), the combined mean ahead of
the latest frame (:func:`imm_predicted_mean`), the combined prediction's gate
(:func:`imm_combined_gate`), and steps 5-7 for a frame's detection, the gating, the
mode-matched updates and the new mode probabilities (:func:`imm_fuse`).

The filters are the tracker's plain-float tuples: ``rest = (x, y, P11)``,
``roll = (x, P)`` and ``man = (x, P)`` with ``x`` the state ``(x, y, vx, vy)`` [m, m/s] and
``P`` the covariance blocks of :mod:`estimators.kalman.blocks`; ``mu`` the three mode
probabilities. The tracker's figures are one float64 array (:func:`imm_parameters`). The
arithmetic is the order of the Python it replaced (the friction step by
:func:`~estimators.models.motion.friction_step`, ``math.hypot`` by
:func:`~estimators.exact.hypot_exact`, the mode chain by
:func:`~estimators.kalman.modes.mode_products`), so results are bit for bit the same. The
squared Mahalanobis distance of one detection from the combined prediction is written here as
:meth:`~estimators.tracking.Gate.nearest` computes it for a sequence of detections (the same
expression in a kernel).
"""

from __future__ import annotations

import math

import numpy as np

from ..compiled import kernel
from ..exact import hypot_exact
from ..models.motion import friction_step
from .blocks import innovation, predict_covariance, predict_jump, update_closed_form
from .modes import MIN_PROBABILITY, mode_products

__all__ = ["imm_parameters", "imm_deceleration", "imm_predict", "imm_predicted_mean",
           "imm_combined_gate", "imm_fuse"]

# Entries of the parameter array (imm_parameters).
(_REST_VAR_V, _REST_Q, _ROLL_Q, _MAN_Q, _ROLLING, _SLIDING, _K_SWITCH, _R, _LIMIT, _GATE_KICK,
 _SIGMA_XY, _MAX_JUMP) = range(12)


def imm_parameters(rest_var_v: float, rest_q: float, roll_q: float, man_q: float,
                   rolling: float, sliding: float | None, k_switch: float, r: float,
                   limit: float, gate_kick: float, sigma_xy: float, max_jump: float
                   ) -> np.ndarray:
    """The parameter array of the kernels for an :class:`~estimators.IMMBall`: the rest
    mode's velocity variance [m^2/s^2] and position variance per second [m^2/s], the rolling
    mode's velocity variance per second [m^2/s^3], the maneuver's velocity jump variance
    [m^2/s^2], the rolling and sliding decelerations [m/s^2] (None: one phase),
    ``k_switch``, the detections' noise variance ``r`` [m^2], the gate's squared Mahalanobis
    limit and kick speed [m/s] (:class:`~estimators.tracking.Gate`), the detections' noise
    ``sigma_xy`` [m] and ``max_jump`` [m]."""
    return np.array([rest_var_v, rest_q, roll_q, man_q, rolling,
                     0.0 if sliding is None else sliding, k_switch, r, limit, gate_kick,
                     sigma_xy, max_jump], dtype=np.float64)


@kernel
def imm_deceleration(x, kicked: bool, t_kick: float, t: float, p: np.ndarray) -> float:
    """The rolling mode's deceleration [m/s^2] from state ``x`` at time ``t`` [s]: sliding
    while a ball kicked at ``t_kick`` (``kicked``) is faster than ``k_switch`` times its kick
    speed, ``(1 - k) |v| > k a_s (t - t_kick)``, else rolling."""
    k = p[_K_SWITCH]
    if kicked and (1.0 - k) * hypot_exact(x[2], x[3]) > k * p[_SLIDING] * (t - t_kick):
        return p[_SLIDING]
    return p[_ROLLING]


@kernel
def _mixed(a: float, b: float, e: float, own: int, ax: float, ay: float, au: float,
           av: float, ex: float, ey: float, eu: float, ev: float, R, F, M, xF):
    """The mixture of the three modes into the rolling (``own == 1``) or maneuver (2) mode
    with unnormalised weights ``a, b, e`` (rest, rolling, maneuver): ``(c, (x0, P0))``, about
    the rolling mean ``xF`` with the rest and maneuver offsets ``(ax ..)``, ``(ex ..)`` and
    second moments ``R``, ``M``, the rolling covariance ``F``."""
    c = a + b + e
    if c > 0.0:
        a, b, e = a / c, b / c, e / c
    elif own == 1:  # no probability flows into the mode: it keeps its own estimate
        a, b, e = 0.0, 1.0, 0.0
    else:
        a, b, e = 0.0, 0.0, 1.0
    fx, fy, fu, fv = xF
    R0, R1, R3, R4, R5, R6, R7, R8, R9, R11 = R
    M0, M1, M3, M4, M5, M6, M7, M8, M9, M11 = M
    (f0, f1, _, f3), (g0, g1, g2, g3), (h0, h1, _, h3) = F
    mx, my, mu_, mv = a * ax + e * ex, a * ay + e * ey, a * au + e * eu, a * av + e * ev
    c01 = a * R1 + b * f1 + e * M1 - mx * my
    c23 = a * R9 + b * h1 + e * M9 - mu_ * mv
    return c, ((fx + mx, fy + my, fu + mu_, fv + mv),
               ((a * R0 + b * f0 + e * M0 - mx * mx, c01, c01,
                 a * R3 + b * f3 + e * M3 - my * my),
                (a * R4 + b * g0 + e * M4 - mx * mu_, a * R5 + b * g1 + e * M5 - mx * mv,
                 a * R6 + b * g2 + e * M6 - my * mu_, a * R7 + b * g3 + e * M7 - my * mv),
                (a * R8 + b * h0 + e * M8 - mu_ * mu_, c23, c23,
                 a * R11 + b * h3 + e * M11 - mv * mv)))


@kernel
def imm_predict(rest, roll, man, mu, dt: float, kicked: bool, t_kick: float, t: float,
                leave, jump, p: np.ndarray):
    """Steps 1-3 over ``dt`` > 0 seconds from the filters after a frame at ``t`` [s]:
    ``(rest, roll, man, c)`` predicted, ``c`` the predicted mode probabilities (``leave``,
    ``jump``: the :class:`~estimators.kalman.modes.ModeChain`'s rates).

    The mixtures are taken about the rolling mode's mean: with ``e_i = x_i - x_F``
    (``e_F = 0``) and ``S_i = P_i + e_i e_i^T``, ``x0_j = x_F + m_j`` and
    ``P0_j = sum_i mu_{i|j} S_i - m_j m_j^T``, ``m_j = sum_i mu_{i|j} e_i``."""
    aR, aF, aM, bR, bF, bM, eR, eF, eM = mode_products(mu, dt, leave, jump)
    px, py, (r0, r1, _, r3) = rest
    xF, PF = roll
    xM, PM = man
    fx, fy, fu, fv = xF
    # Second moments about the rolling mean: rest (velocity zero with variance vr,
    # uncorrelated: ``R``) and maneuver (``M``); the rolling mode's are its covariance.
    vr = p[_REST_VAR_V]
    ax, ay, au, av = px - fx, py - fy, -fu, -fv
    R = (r0 + ax * ax, r1 + ax * ay, r3 + ay * ay, ax * au, ax * av, ay * au, ay * av,
         vr + au * au, au * av, vr + av * av)
    ex, ey, eu, ev = xM[0] - fx, xM[1] - fy, xM[2] - fu, xM[3] - fv
    (k0, k1, _, k3), (l0, l1, l2, l3), (n0, n1, _, n3) = PM
    M = (k0 + ex * ex, k1 + ex * ey, k3 + ey * ey, l0 + ex * eu, l1 + ex * ev, l2 + ey * eu,
         l3 + ey * ev, n0 + eu * eu, n1 + eu * ev, n3 + ev * ev)
    (f0, f1, _, f3) = PF[0]
    # Rest: position only (its prediction drops the velocity).
    cR = aR + aF + aM
    if cR > 0.0:
        a, b, e = aR / cR, aF / cR, aM / cR
    else:
        a, b, e = 1.0, 0.0, 0.0
    mx, my = a * ax + e * ex, a * ay + e * ey
    q = p[_REST_Q] * dt
    c01 = a * R[1] + b * f1 + e * M[1] - mx * my
    rest_n = (fx + mx, fy + my, (a * R[0] + b * f0 + e * M[0] - mx * mx + q, c01, c01,
                                 a * R[2] + b * f3 + e * M[2] - my * my + q))
    cF, (x, P) = _mixed(bR, bF, bM, 1, ax, ay, au, av, ex, ey, eu, ev, R, PF, M, xF)
    cM, (xm, Pm) = _mixed(eR, eF, eM, 2, ax, ay, au, av, ex, ey, eu, ev, R, PF, M, xF)
    # Rolling: the friction model (analytic Jacobian), velocity random walk.
    xn, A, B = friction_step(x[0], x[1], x[2], x[3], dt,
                             imm_deceleration(x, kicked, t_kick, t, p), False)
    roll_n = (xn, predict_covariance(P, A, B, p[_ROLL_Q] * dt))
    # Maneuver: constant velocity, a velocity jump within the step.
    man_n = predict_jump(xm, Pm, dt, p[_MAN_Q])
    return rest_n, roll_n, man_n, (cR, cF, cM)


@kernel
def imm_predicted_mean(rest, roll, man, mu, dt: float, kicked: bool, t_kick: float, t: float,
                       leave, jump, p: np.ndarray) -> tuple[float, float, float, float]:
    """The combined mean predicted ``dt`` > 0 seconds ahead (steps 1-4, means only):
    ``c_j x0_j = sum_i mu_i Pi_ij x_i`` needs no division for the linear modes."""
    aR, aF, aM, bR, bF, bM, eR, eF, eM = mode_products(mu, dt, leave, jump)
    px, py = rest[0], rest[1]
    xF, xM = roll[0], man[0]
    fx, fy, fu, fv = xF
    mx, my, mu_, mv = xM
    cF = bR + bF + bM
    if cF > 0.0:
        f = ((bR * px + bF * fx + bM * mx) / cF, (bR * py + bF * fy + bM * my) / cF,
             (bF * fu + bM * mu_) / cF, (bF * fv + bM * mv) / cF)
    else:
        f = xF
    f = friction_step(f[0], f[1], f[2], f[3], dt, imm_deceleration(f, kicked, t_kick, t, p),
                      False)[0]
    # Maneuver: c_M (p + v dt) with c_M p and c_M v the unnormalised mixtures.
    u, v = eF * fu + eM * mu_, eF * fv + eM * mv
    return (aR * px + aF * fx + aM * mx + cF * f[0] + eR * px + eF * fx + eM * mx + u * dt,
            aR * py + aF * fy + aM * my + cF * f[1] + eR * py + eF * fy + eM * my + v * dt,
            cF * f[2] + u, cF * f[3] + v)


@kernel
def imm_combined_gate(rest, roll, man, c, r: float
                      ) -> tuple[float, float, float, float, float]:
    """Steps 4-5's combined prediction of the position: ``(gx, gy, s00, s01, s11)``, its mean
    [m] and the innovation covariance ``S = P11- + r I`` [m^2] of the mixture of the three
    filters with the predicted mode probabilities ``c``."""
    cR, cF, cM = c
    px, py, (r0, r1, _, r3) = rest
    xF, xM = roll[0], man[0]
    f0, f1, _, f3 = roll[1][0]
    k0, k1, _, k3 = man[1][0]
    gx, gy = cR * px + cF * xF[0] + cM * xM[0], cR * py + cF * xF[1] + cM * xM[1]
    ax, ay = px - gx, py - gy
    bx, by = xF[0] - gx, xF[1] - gy
    ex, ey = xM[0] - gx, xM[1] - gy
    s0 = cR * (r0 + ax * ax) + cF * (f0 + bx * bx) + cM * (k0 + ex * ex) + r
    s1 = cR * (r1 + ax * ay) + cF * (f1 + bx * by) + cM * (k1 + ex * ey)
    s3 = cR * (r3 + ay * ay) + cF * (f3 + by * by) + cM * (k3 + ey * ey) + r
    return gx, gy, s0, s1, s3


@kernel
def _combined_d2(rest, roll, man, c, zx: float, zy: float, r: float) -> float:
    """The squared Mahalanobis distance of ``(zx, zy)`` from the combined prediction
    (:meth:`~estimators.tracking.Gate.nearest` of one detection: ``inf`` unless finite)."""
    gx, gy, s0, s1, s3 = imm_combined_gate(rest, roll, man, c, r)
    det = s0 * s3 - s1 * s1
    i0, i1, i3 = s3 / det, -s1 / det, s0 / det
    y0, y1 = zx - gx, zy - gy
    d = y0 * (i0 * y0 + i1 * y1) + y1 * (i1 * y0 + i3 * y1)
    return d if d < math.inf else math.inf


@kernel
def imm_fuse(rest, roll, man, c, zx: float, zy: float, known: bool, d2: float, dt: float,
             p: np.ndarray):
    """Steps 5-7 for the detection ``(zx, zy)`` [m] of a frame ``dt`` seconds after the
    previous one, with the predicted filters and mode probabilities ``c``:
    ``(fused, rest, roll, man, mu)``, the filters updated and the new mode probabilities when
    the detection is fused, the predicted ones unchanged when it is gated out. ``d2``: its
    squared Mahalanobis distance from the combined prediction when ``known`` (computed here
    when needed otherwise)."""
    r = p[_R]
    px, py, (r0, r1, _, r3) = rest
    xF, PF = roll
    xM, PM = man
    z = (zx, zy)
    # Step 6: the innovations; the rest mode's in closed form (no velocity).
    s0, s3 = r0 + r, r3 + r
    det = s0 * s3 - r1 * r1
    j0, j1, j3 = s3 / det, -r1 / det, s0 / det
    y0, y1 = zx - px, zy - py
    dR = y0 * (j0 * y0 + j1 * y1) + y1 * (j1 * y0 + j3 * y1)
    yF, SF, dF = innovation(xF, PF, z, r)
    yM, SM, dM = innovation(xM, PM, z, r)
    low = dR
    if dF < low:
        low = dF
    if dM < low:
        low = dM
    # Step 5: within max_jump of the combined prediction, and inside its gate or inside a
    # mode's and near enough for a kick where the ball is.
    cR, cF, cM = c
    jump = hypot_exact(zx - cR * px - cF * xF[0] - cM * xM[0],
                       zy - cR * py - cF * xF[1] - cM * xM[1])
    kick = (low <= p[_LIMIT]
            and jump <= p[_GATE_KICK] * (0.0 if 0.0 > dt else dt) + 3.0 * p[_SIGMA_XY])
    if not kick and not known and jump <= p[_MAX_JUMP]:
        d2, known = _combined_d2(rest, roll, man, c, zx, zy, r), True
    if jump > p[_MAX_JUMP] or not (kick or d2 <= p[_LIMIT]):
        return False, rest, roll, man, c
    # Step 7: L_j ~ sqrt(det S_j^-1) exp(-d_j^2 / 2) (2 pi cancels), shifted by the
    # smallest d^2 so that the best mode's exponential is 1.
    lR = cR * math.sqrt(j0 * j3 - j1 * j1) * math.exp(0.5 * (low - dR))
    lF = cF * math.sqrt(SF[0] * SF[3] - SF[1] * SF[1]) * math.exp(0.5 * (low - dF))
    lM = cM * math.sqrt(SM[0] * SM[3] - SM[1] * SM[1]) * math.exp(0.5 * (low - dM))
    total = lR + lF + lM
    mu = (lR / total, lF / total, lM / total)
    if mu[0] < MIN_PROBABILITY or mu[1] < MIN_PROBABILITY or mu[2] < MIN_PROBABILITY:
        m0, m1, m2 = mu
        m0 = MIN_PROBABILITY if MIN_PROBABILITY > m0 else m0
        m1 = MIN_PROBABILITY if MIN_PROBABILITY > m1 else m1
        m2 = MIN_PROBABILITY if MIN_PROBABILITY > m2 else m2
        total = m0 + m1 + m2
        mu = (m0 / total, m1 / total, m2 / total)
    # Step 6: the updates. Rest: K = P11 S^-1 = I - r S^-1, so x = z - r S^-1 y and
    # P11 = (I - K) P11 = r (I - r S^-1) (P11 and S commute).
    rr = r * r
    rest_n = (zx - r * (j0 * y0 + j1 * y1), zy - r * (j1 * y0 + j3 * y1),
              (r - rr * j0, -rr * j1, -rr * j1, r - rr * j3))
    roll_n = update_closed_form(xF, PF, z, yF, SF, r)
    man_n = update_closed_form(xM, PM, z, yM, SM, r)
    return True, rest_n, roll_n, man_n, mu
