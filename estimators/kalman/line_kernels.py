"""Compiled steps of the sighting-line ball tracker (:mod:`estimators.kalman.lines`) on one
track: the state ``x = (px, py, vx, vy, b_0x, b_0y, beta_0, b_1x, ...)`` (the ball [m, m/s]
and each observer's position bias [m] and heading bias [rad]) with its covariance ``P``.

Each step is one call where numpy would pay a call per matrix operation (the tracker runs for
every sighting of every robot of a team, about a hundred a second per robot). The maths is
stated in :mod:`estimators.kalman.lines`; each kernel says which part it is.
"""

from __future__ import annotations

import math

import numpy as np

from ..compiled import kernel
from ..particle.filter_kernels import roll

__all__ = ["rolled", "drift_predict", "kick_prior", "update_point", "update_bearing", "phase",
           "line_step", "kick_search", "BALL", "SLOT", "LINE", "MODEL"]

#: Entries of the ball's state ``(px, py, vx, vy)``, first in the state.
BALL = 4
#: Entries of an observer's bias ``(bx, by, beta)``.
SLOT = 3


@kernel
def rolled(x: np.ndarray, dt: float, deceleration: float, sliding: float,
           switch: float) -> np.ndarray:
    """The ball ``x[0:4] = (px, py, vx, vy)`` ``dt >= 0`` [s] later (a new ``(4,)`` array),
    decelerating uniformly along its motion: by ``sliding`` [m/s^2] while its speed exceeds
    ``switch`` [m/s] (a kicked ball slides; ``inf``: never), then by ``deceleration`` until
    it stops. Over a phase of ``tau`` seconds at deceleration ``a`` from speed ``s`` along
    ``u``: ``p' = p + u (s tau - a tau^2 / 2)``, ``v' = u (s - a tau)``; rolling lasts
    ``tau = min(dt, s / a)`` (constant velocity for ``a = 0``)."""
    px, py, vx, vy = x[0], x[1], x[2], x[3]
    out = np.empty(4)
    speed = math.sqrt(vx * vx + vy * vy)
    if sliding > 0.0 and speed > switch:
        t1 = (speed - switch) / sliding
        tau = min(dt, t1)
        k = tau - 0.5 * sliding * tau * tau / speed
        f = 1.0 - sliding * tau / speed
        px, py, vx, vy = px + k * vx, py + k * vy, f * vx, f * vy
        dt -= tau
        speed = speed * f
    out[0], out[1], out[2], out[3] = roll(px, py, vx, vy, speed, dt, deceleration)
    return out


@kernel
def drift_predict(x: np.ndarray, P: np.ndarray, dt: float, deceleration: float,
                  sliding: float, switch: float, q: float, q_xy: float, q_theta: float,
                  s2_xy: float, s2_theta: float) -> tuple[np.ndarray, np.ndarray]:
    """The time update over ``dt >= 0`` [s] (new arrays).

    The ball's mean by :func:`rolled`; its covariance by the constant-velocity model with white
    acceleration noise of variance ``q`` [m^2/s^4]: ``A P A^T + q B B^T``,
    ``A = [[I, dt I], [0, I]]``, ``B = [dt^2/2 I; dt I]`` on the ball's block (and its rows
    of the cross-covariances). The biases are mean-reverting (Ornstein-Uhlenbeck) with
    stationary variance ``s2`` and, over short times, the walk ``q dt``: each decays by
    ``phi = exp(-dt / tau)``, ``tau = 2 s2 / q``, so ``b' = phi b`` and its rows and columns
    of ``P`` scale by ``phi``, its variance gaining ``s2 (1 - phi^2)`` (``q_xy``, ``s2_xy``
    [m^2/s, m^2] per position axis, ``q_theta``, ``s2_theta`` [rad^2/s, rad^2] per heading;
    none where either is 0)."""
    n = x.shape[0]
    xn = x.copy()
    ball = rolled(x, dt, deceleration, sliding, switch)
    for i in range(4):
        xn[i] = ball[i]
    Pn = P.copy()
    for j in range(n):  # rows: A P
        Pn[0, j] = P[0, j] + dt * P[2, j]
        Pn[1, j] = P[1, j] + dt * P[3, j]
    for i in range(n):  # columns: (A P) A^T
        Pn[i, 0] = Pn[i, 0] + dt * Pn[i, 2]
        Pn[i, 1] = Pn[i, 1] + dt * Pn[i, 3]
    h = 0.5 * dt * dt
    for a in range(2):
        Pn[a, a] += q * h * h
        Pn[a, a + 2] += q * h * dt
        Pn[a + 2, a] += q * h * dt
        Pn[a + 2, a + 2] += q * dt * dt
    if n > BALL and ((q_xy > 0.0 and s2_xy > 0.0) or (q_theta > 0.0 and s2_theta > 0.0)):
        phi_xy = math.exp(-dt * q_xy / (2.0 * s2_xy)) if s2_xy > 0.0 else 1.0
        phi_th = math.exp(-dt * q_theta / (2.0 * s2_theta)) if s2_theta > 0.0 else 1.0
        f = np.ones(n)
        for s in range(BALL, n, SLOT):
            f[s] = f[s + 1] = phi_xy
            f[s + 2] = phi_th
        for i in range(BALL, n):
            xn[i] *= f[i]
        for i in range(n):
            for j in range(n):
                if f[i] != 1.0 or f[j] != 1.0:
                    Pn[i, j] *= f[i] * f[j]
        for s in range(BALL, n, SLOT):
            Pn[s, s] += s2_xy * (1.0 - phi_xy * phi_xy)
            Pn[s + 1, s + 1] += s2_xy * (1.0 - phi_xy * phi_xy)
            Pn[s + 2, s + 2] += s2_theta * (1.0 - phi_th * phi_th)
    return xn, Pn


@kernel
def kick_prior(P: np.ndarray, elapsed: float, kick_var: float) -> np.ndarray:
    """The covariance of a track kicked ``elapsed`` [s] ago (a new array): a velocity jump
    ``dv ~ N(0, kick_var I)`` [m^2/s^2] at the kick moves the position by ``elapsed dv`` since,
    so the ball's block gains ``[[e^2 J I, e J I], [e J I, J I]]`` with ``e = elapsed``,
    ``J = kick_var``."""
    Pn = P.copy()
    for a in range(2):
        Pn[a, a] += elapsed * elapsed * kick_var
        Pn[a, a + 2] += elapsed * kick_var
        Pn[a + 2, a] += elapsed * kick_var
        Pn[a + 2, a + 2] += kick_var
    return Pn


@kernel
def update_point(x: np.ndarray, P: np.ndarray, zx: float, zy: float, r00: float, r01: float,
                 r11: float, slot: int, r: float, nx: float, ny: float
                 ) -> tuple[float, float, np.ndarray, np.ndarray]:
    """The update with a sighted position ``z`` [m] of white-noise covariance
    ``R = [[r00, r01], [r01, r11]]`` [m^2] by the observer whose bias starts at entry ``slot``
    of the state, at range ``r`` [m] along a line of unit normal ``n``:
    ``h(x) = p + b + r beta n`` (``H`` the ball's position, the observer's position bias and
    ``r n`` on its heading bias). Returns ``(d2, log det S, x', P')`` with ``y = z - h(x)``,
    ``S = H P H^T + R``, ``d2 = y^T S^-1 y``, ``K = P H^T S^-1``, ``x' = x + K y``,
    ``P' = P - K (P H^T)^T`` (symmetrised; new arrays)."""
    m = x.shape[0]
    bx, by, bt = slot, slot + 1, slot + 2
    PH = np.empty((m, 2))  # P H^T
    for i in range(m):
        PH[i, 0] = P[i, 0] + P[i, bx] + r * nx * P[i, bt]
        PH[i, 1] = P[i, 1] + P[i, by] + r * ny * P[i, bt]
    # S = H (P H^T) + R
    s0 = PH[0, 0] + PH[bx, 0] + r * nx * PH[bt, 0] + r00
    s1 = PH[1, 0] + PH[by, 0] + r * ny * PH[bt, 0] + r01
    s3 = PH[1, 1] + PH[by, 1] + r * ny * PH[bt, 1] + r11
    det = s0 * s3 - s1 * s1
    i0, i1, i3 = s3 / det, -s1 / det, s0 / det
    y0 = zx - (x[0] + x[bx] + r * nx * x[bt])
    y1 = zy - (x[1] + x[by] + r * ny * x[bt])
    d2 = y0 * (i0 * y0 + i1 * y1) + y1 * (i1 * y0 + i3 * y1)
    xn = np.empty(m)
    K = np.empty((m, 2))
    for i in range(m):
        K[i, 0] = PH[i, 0] * i0 + PH[i, 1] * i1
        K[i, 1] = PH[i, 0] * i1 + PH[i, 1] * i3
        xn[i] = x[i] + K[i, 0] * y0 + K[i, 1] * y1
    Pn = np.empty((m, m))
    for i in range(m):
        for j in range(i, m):
            v = P[i, j] - (K[i, 0] * PH[j, 0] + K[i, 1] * PH[j, 1])
            Pn[i, j] = v
            Pn[j, i] = v
    return d2, math.log(det), xn, Pn


@kernel
def update_bearing(x: np.ndarray, P: np.ndarray, ox: float, oy: float, nx: float, ny: float,
                   var: float, slot: int, d: float) -> tuple[float, float, np.ndarray, np.ndarray]:
    """The update with a bearing-only sighting from ``o`` [m] along a line of unit normal
    ``n``, by the observer whose bias starts at ``slot``, the ball about ``d`` [m] away:
    ``h(x) = n . (p + b - o) + d beta``, measured as 0 with white variance ``var`` [m^2].
    Returns ``(d2, log S, x', P')`` with ``y = -h(x)``, ``S = H P H^T + var``,
    ``d2 = y^2 / S``, ``K = P H^T / S``, ``x' = x + K y``, ``P' = P - K (P H^T)^T``
    (symmetrised; new arrays)."""
    m = x.shape[0]
    bx, by, bt = slot, slot + 1, slot + 2
    y = -(nx * (x[0] + x[bx] - ox) + ny * (x[1] + x[by] - oy) + d * x[bt])
    PH = np.empty(m)
    for i in range(m):
        PH[i] = nx * (P[i, 0] + P[i, bx]) + ny * (P[i, 1] + P[i, by]) + d * P[i, bt]
    S = nx * (PH[0] + PH[bx]) + ny * (PH[1] + PH[by]) + d * PH[bt] + var
    xn = np.empty(m)
    for i in range(m):
        xn[i] = x[i] + PH[i] / S * y
    Pn = np.empty((m, m))
    for i in range(m):
        for j in range(i, m):
            v = P[i, j] - PH[i] * PH[j] / S
            Pn[i, j] = v
            Pn[j, i] = v
    return y * y / S, math.log(S), xn, Pn


#: A line row's entries: capture time [s], origin x, y [m], angle [rad], range [m] (NaN: the
#: bearing only), the observer's bias slot (its first entry in the state), bearing sigma
#: [rad], range error per metre [1/m].
LINE = 8
#: The model row's entries: rolling and sliding deceleration [m/s^2], ``k_switch``, the
#: acceleration noise [m^2/s^4], the biases' walks [m^2/s, rad^2/s], the least relative range
#: error, the white floor [m], the observers' pose errors taken as white noise instead of
#: biases, position [m^2] and heading [rad^2] (0 when the state holds them), and the biases'
#: stationary variances [m^2, rad^2].
MODEL = 12


@kernel
def phase(x: np.ndarray, t: float, kicked_at: float, sliding: float,
          k_switch: float) -> tuple[float, float]:
    """``(sliding deceleration, switch speed)`` of a ball ``x`` at ``t`` [s] kicked at
    ``kicked_at`` (NaN: not known to be kicked, so it rolls: ``(0, inf)``) for :func:`rolled`:
    it slides until ``k_switch`` of its speed after the kick, which, if it still slides, is
    ``s + a_s (t - t_k)`` for its speed ``s``."""
    if sliding == 0.0 or not kicked_at <= t:
        return 0.0, np.inf
    speed = math.sqrt(x[2] * x[2] + x[3] * x[3])
    return sliding, k_switch * (speed + sliding * (t - kicked_at))


@kernel
def line_step(x: np.ndarray, P: np.ndarray, t: float, kicked_at: float, line: np.ndarray,
              model: np.ndarray) -> tuple[float, float, np.ndarray, np.ndarray]:
    """A track ``(x, P)`` at ``t`` [s] (kicked at ``kicked_at``) predicted to the capture time
    of ``line`` (a :data:`LINE` row) when that is later, and updated with it under ``model``
    (a :data:`MODEL` row): ``(d2, log det S, x', P')``. The line's white noise: with a range
    ``r``, ``R = s_r^2 u u^T + r^2 (s_b^2 + w_theta) n n^T + (f^2 + w_p) I`` with
    ``s_r = max(k_0, k r) r`` (:func:`update_point`); bearing only,
    ``d^2 (s_b^2 + w_theta) + f^2 + w_p`` at the predicted distance ``d`` (at least 0.1 m;
    :func:`update_bearing`); ``w_p``, ``w_theta`` the pose errors taken as white noise."""
    lt = line[0]
    if lt > t:
        a_s, switch = phase(x, t, kicked_at, model[1], model[2])
        x, P = drift_predict(x, P, lt - t, model[0], a_s, switch, model[3], model[4], model[5],
                             model[10], model[11])
    ox, oy, angle, r = line[1], line[2], line[3], line[4]
    slot, sb, k = int(line[5]), line[6], line[7]
    c, s = math.cos(angle), math.sin(angle)
    nx, ny = -s, c
    floor2 = model[7] * model[7] + model[8]
    cross = sb * sb + model[9]
    if math.isfinite(r):
        sa = max(model[6], k * r) * r
        along, across = sa * sa, r * r * cross
        return update_point(x, P, ox + r * c, oy + r * s, along * c * c + across * s * s + floor2,
                            (along - across) * c * s, along * s * s + across * c * c + floor2,
                            slot, r, nx, ny)
    d2 = (x[0] - ox) * (x[0] - ox) + (x[1] - oy) * (x[1] - oy)
    var = max(d2, 0.01) * cross + floor2
    return update_bearing(x, P, ox, oy, nx, ny, var, slot, math.sqrt(d2))


@kernel
def kick_search(X: np.ndarray, Ps: np.ndarray, T: np.ndarray, K: np.ndarray,
                before: np.ndarray, lines: np.ndarray, model: np.ndarray, kick_var: float,
                cap: float) -> tuple[int, float, np.ndarray, np.ndarray, float]:
    """The kick time searched over the lines ``lines`` (``(n, LINE)``, capture order): for
    each candidate ``c``, the track before line ``c`` (``X[c]``, ``Ps[c]`` at ``T[c]``,
    kicked at ``K[c]``) predicted to its time, kicked there (:func:`kick_prior` with no
    elapsed time) and updated with lines ``c .. n-1``; its log-likelihood is ``before[c]``
    (the lines before ``c`` under the track without a kick) less half of each later line's
    ``min(d2, cap) + log det S``. Returns ``(c, log-likelihood, x, P, t)`` of the most
    likely candidate."""
    n = lines.shape[0]
    best, best_ll = -1, -np.inf
    bx, bP, bt = X[0].copy(), Ps[0].copy(), 0.0
    for c in range(n):
        x, P, t = X[c], Ps[c], T[c]
        lt = lines[c, 0]
        if lt > t:
            a_s, switch = phase(x, t, K[c], model[1], model[2])
            x, P = drift_predict(x, P, lt - t, model[0], a_s, switch, model[3], model[4],
                                 model[5], model[10], model[11])
            t = lt
        P = kick_prior(P, 0.0, kick_var)
        ll = before[c]
        for i in range(c, n):
            d2, ld, x, P = line_step(x, P, t, lt, lines[i], model)
            t = max(t, lines[i, 0])
            ll -= 0.5 * (min(d2, cap) + ld)
        if ll > best_ll:
            best, best_ll, bx, bP, bt = c, ll, x, P, t
    return best, best_ll, bx, bP, bt
