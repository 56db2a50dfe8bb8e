"""The prediction of the :class:`~estimators.IMMBall` tracker (steps 1-4 of its docstring) as
compiled kernels: the predicted mode probabilities, the mixing of the three mode-matched
filters and their predictions (:func:`imm_predict`), and the combined mean ahead of the
latest frame (:func:`imm_predicted_mean`).

The filters are the tracker's plain-float tuples: ``rest = (x, y, P11)``,
``roll = (x, P)`` and ``man = (x, P)`` with ``x`` the state ``(x, y, vx, vy)`` [m, m/s] and
``P`` the covariance blocks of :mod:`estimators.kalman.blocks`; ``mu`` the three mode
probabilities. The tracker's figures are one float64 array (:func:`imm_parameters`). The
arithmetic is the order of the Python it replaced (the friction step by
:func:`~estimators.models.motion.friction_step`, ``math.hypot`` by
:func:`~estimators.exact.hypot_exact`, the mode chain by
:func:`~estimators.kalman.modes.mode_products`), so results are bit for bit the same.
"""

from __future__ import annotations

import numpy as np

from ..compiled import kernel
from ..exact import hypot_exact
from ..models.motion import friction_step
from .blocks import predict_covariance, predict_jump
from .modes import mode_products

__all__ = ["imm_parameters", "imm_predict", "imm_predicted_mean"]

# Entries of the parameter array (imm_parameters).
_REST_VAR_V, _REST_Q, _ROLL_Q, _MAN_Q, _ROLLING, _SLIDING, _K_SWITCH = range(7)


def imm_parameters(rest_var_v: float, rest_q: float, roll_q: float, man_q: float,
                   rolling: float, sliding: float | None, k_switch: float) -> np.ndarray:
    """The parameter array of the kernels for an :class:`~estimators.IMMBall`: the rest
    mode's velocity variance [m^2/s^2] and position variance per second [m^2/s], the rolling
    mode's velocity variance per second [m^2/s^3], the maneuver's velocity jump variance
    [m^2/s^2], the rolling and sliding decelerations [m/s^2] (None: one phase) and
    ``k_switch``."""
    return np.array([rest_var_v, rest_q, roll_q, man_q, rolling,
                     0.0 if sliding is None else sliding, k_switch], dtype=np.float64)


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
