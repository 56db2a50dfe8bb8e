"""Numpy versions of CPython's ``math`` functions that agree with them bit for bit.

The batched paths of the estimators and the environments (many filters, sensors or scripted
robots stepped as arrays) must give the same numbers as their one-at-a-time versions, which run
in plain Python floats: ``+ - * /`` and ``sqrt`` round alike in both, but the C library's
``hypot`` and numpy's differ from ``math.hypot`` in the last bit for some inputs, and
``math.remainder`` has no numpy counterpart.
"""

from __future__ import annotations

import math

import numpy as np

from .compiled import kernel

__all__ = ["hypots", "hypot_exact", "wrap_angles", "wrap_angle"]

#: The full turn that :func:`wrap_angles` wraps by [rad].
_TWO_PI = 2.0 * math.pi
#: Veltkamp's splitting constant ``2**27 + 1``: splits a double into two 26-bit halves whose
#: products are exact (Dekker).
_SPLIT = 134217729.0
#: The smallest normal double, 2**-1022.
_DBL_MIN = float(np.finfo(np.float64).tiny)


def _square(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(x * x, error)``: the rounded square and its exact rounding error (Dekker's product),
    elementwise."""
    t = x * _SPLIT
    hi = t - (t - x)
    lo = x - hi
    sq = x * x
    return sq, ((hi * hi - sq) + 2.0 * hi * lo) + lo * lo


def hypots(x: np.ndarray | float, y: np.ndarray | float) -> np.ndarray:
    """Elementwise ``math.hypot(x, y)``: the length ``sqrt(x^2 + y^2)`` of the vectors
    ``(x, y)`` (broadcast), float64.

    It computes what CPython's ``math.hypot`` computes (its ``vector_norm``: scaling by a power
    of two, exact squares, compensated summation and a differential correction of the square
    root), so the results equal it bit for bit on CPython 3.11 and later; ``np.hypot`` (the C
    library's) differs from it in the last bit for about one pair in 160.
    """
    x, y = np.broadcast_arrays(np.abs(np.asarray(x, dtype=np.float64)),
                               np.abs(np.asarray(y, dtype=np.float64)))
    big = np.maximum(x, y)
    with np.errstate(all="ignore"):  # zeros, infinities and NaN are set at the end
        exponent = np.frexp(big)[1]
        tiny = exponent < -1023
        if tiny.any():  # subnormal: make it normal first, as CPython does
            x, y = x / np.where(tiny, _DBL_MIN, 1.0), y / np.where(tiny, _DBL_MIN, 1.0)
            exponent = np.frexp(np.maximum(x, y))[1]
        scale = np.ldexp(1.0, -exponent)  # lossless scaling of the larger one into [0.5, 1)
        x2, x2_err = _square(x * scale)
        y2, y2_err = _square(y * scale)
        # Compensated sum 1 + x^2 + y^2 (CPython's csum, frac1, frac2).
        csum = 1.0 + x2
        frac2 = (1.0 - csum) + x2
        total = csum + y2
        frac2 += (csum - total) + y2
        csum = total
        frac1 = x2_err + y2_err
        h = np.sqrt((csum - 1.0) + (frac1 + frac2))
        # Differential correction: h += (x^2 + y^2 - h^2) / (2 h).
        h2, h2_err = _square(h)
        total = csum - h2
        frac1 -= h2_err
        frac2 += (csum - total) - h2
        h += ((total - 1.0) + (frac1 + frac2)) / (2.0 * h)
        h /= scale
        if tiny.any():
            h *= np.where(tiny, _DBL_MIN, 1.0)
    h = np.where(big == 0.0, 0.0, h)
    return np.where(np.isinf(x) | np.isinf(y), np.inf, h)


def wrap_angles(angle: np.ndarray | float) -> np.ndarray:
    """Elementwise ``math.remainder(angle, 2 pi)``: ``angle`` [rad] wrapped into
    ``[-pi, pi]``, float64, bit for bit at every magnitude.

    CPython's own algorithm (``m_remainder``) on arrays: ``m = fmod(|x|, 2 pi)`` (exact), then
    ``m`` or ``m - 2 pi`` (exact by Sterbenz's lemma), whichever is smaller in magnitude, the
    half-way case to the even quotient; the sign of ``x``.
    """
    x = np.asarray(angle, dtype=np.float64)
    ax = np.abs(x)
    m = np.fmod(ax, _TWO_PI)
    c = _TWO_PI - m
    half = m - 2.0 * np.fmod(0.5 * (ax - m), _TWO_PI)
    return np.copysign(1.0, x) * np.where(m < c, m, np.where(m > c, -c, half))


@kernel
def wrap_angle(x: float) -> float:
    """``math.remainder(x, 2 pi)`` for one angle ``x`` [rad] in compiled kernels, which have no
    ``math.remainder``: :func:`wrap_angles`' steps on a float, bit for bit."""
    ax = abs(x)
    m = np.fmod(ax, _TWO_PI)
    c = _TWO_PI - m
    if m < c:
        r = m
    elif m > c:
        r = -c
    else:
        r = m - 2.0 * np.fmod(0.5 * (ax - m), _TWO_PI)
    return math.copysign(1.0, x) * r


@kernel
def _square_exact(x: float) -> tuple[float, float]:
    """:func:`_square` on one float: ``(x * x, error)``, Dekker's exact product."""
    t = x * _SPLIT
    hi = t - (t - x)
    lo = x - hi
    sq = x * x
    return sq, ((hi * hi - sq) + 2.0 * hi * lo) + lo * lo


@kernel
def hypot_exact(x: float, y: float) -> float:
    """``math.hypot(x, y)`` for one pair in compiled kernels: the length ``sqrt(x^2 + y^2)``
    by :func:`hypots`' steps (CPython's algorithm) on floats, bit for bit; numba's
    ``math.hypot`` is the C library's, which differs in the last bit for about one pair in
    160."""
    x, y = abs(x), abs(y)
    if math.isinf(x) or math.isinf(y):
        return math.inf
    if math.isnan(x) or math.isnan(y):
        return math.nan
    big = max(x, y)
    if big == 0.0:
        return 0.0
    exponent = math.frexp(big)[1]
    tiny = exponent < -1023
    if tiny:  # subnormal: make it normal first, as CPython does
        x, y = x / _DBL_MIN, y / _DBL_MIN
        exponent = math.frexp(max(x, y))[1]
    scale = math.ldexp(1.0, -exponent)  # lossless scaling of the larger one into [0.5, 1)
    x2, x2_err = _square_exact(x * scale)
    y2, y2_err = _square_exact(y * scale)
    # Compensated sum 1 + x^2 + y^2 (CPython's csum, frac1, frac2).
    csum = 1.0 + x2
    frac2 = (1.0 - csum) + x2
    total = csum + y2
    frac2 += (csum - total) + y2
    csum = total
    frac1 = x2_err + y2_err
    h = math.sqrt((csum - 1.0) + (frac1 + frac2))
    # Differential correction: h += (x^2 + y^2 - h^2) / (2 h).
    h2, h2_err = _square_exact(h)
    total = csum - h2
    frac1 -= h2_err
    frac2 += (csum - total) - h2
    h += ((total - 1.0) + (frac1 + frac2)) / (2.0 * h)
    h /= scale
    if tiny:
        h *= _DBL_MIN
    return h
