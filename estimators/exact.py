"""CPython's ``math.hypot`` and ``math.remainder``, and numpy's ``remainder``, stable
``argsort`` and ``searchsorted``, bit for bit in compiled kernels, with array forms of the
first two.

The batched paths of the estimators and the environments (many filters, sensors or scripted
robots stepped as arrays) must give the same numbers as their one-at-a-time versions, which run
in plain Python floats: ``+ - * /`` and ``sqrt`` round alike in both, but the C library's
``hypot`` and numpy's differ from ``math.hypot`` in the last bit for some inputs, and
``math.remainder`` has no numpy or numba counterpart. Each function is written once, as a
scalar kernel (:func:`hypot_exact`, :func:`wrap_angle`, :func:`floor_remainder`); the array
forms (:func:`hypots`, :func:`wrap_angles`) run it over every element.

numba compiles ``np.argsort(..., kind="mergesort")`` and ``np.searchsorted`` from generic
templates that take seconds to compile on a first run (about 2 s for the stable argsort
alone, against a tenth of that for a loop); :func:`stable_argsort` and
:func:`search_right` are those loops, with numpy's ordering of floats (NaN last).
"""

from __future__ import annotations

import math

import numpy as np

from .compiled import kernel

__all__ = ["hypots", "hypot_exact", "wrap_angles", "wrap_angle", "floor_remainder",
           "stable_argsort", "search_right"]

#: The full turn that :func:`wrap_angles` wraps by [rad].
_TWO_PI = 2.0 * math.pi
#: Veltkamp's splitting constant ``2**27 + 1``: splits a double into two 26-bit halves whose
#: products are exact (Dekker).
_SPLIT = 134217729.0
#: The smallest normal double, 2**-1022.
_DBL_MIN = float(np.finfo(np.float64).tiny)


def hypots(x: np.ndarray | float, y: np.ndarray | float) -> np.ndarray:
    """Elementwise ``math.hypot(x, y)``: the length ``sqrt(x^2 + y^2)`` of the vectors
    ``(x, y)`` (broadcast), float64, bit for bit (:func:`hypot_exact` on every pair;
    ``np.hypot``, the C library's, differs in the last bit for about one pair in 160)."""
    x, y = np.broadcast_arrays(np.asarray(x, dtype=np.float64),
                               np.asarray(y, dtype=np.float64))
    return _hypot_rows(x.ravel(), y.ravel()).reshape(x.shape)


def wrap_angles(angle: np.ndarray | float) -> np.ndarray:
    """Elementwise ``math.remainder(angle, 2 pi)``: ``angle`` [rad] wrapped into
    ``[-pi, pi]``, float64, bit for bit at every magnitude (:func:`wrap_angle` on every
    element)."""
    x = np.asarray(angle, dtype=np.float64)
    return _wrap_rows(x.ravel()).reshape(x.shape)


@kernel
def wrap_angle(x: float) -> float:
    """``math.remainder(x, 2 pi)`` for one angle ``x`` [rad] in compiled kernels, which have no
    ``math.remainder``, bit for bit at every magnitude.

    CPython's own algorithm (``m_remainder``): ``m = fmod(|x|, 2 pi)`` (exact), then ``m`` or
    ``m - 2 pi`` (exact by Sterbenz's lemma), whichever is smaller in magnitude, the half-way
    case to the even quotient; the sign of ``x``.
    """
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
    """``(x * x, error)``: the rounded square and its exact rounding error (Dekker's
    product)."""
    t = x * _SPLIT
    hi = t - (t - x)
    lo = x - hi
    sq = x * x
    return sq, ((hi * hi - sq) + 2.0 * hi * lo) + lo * lo


@kernel
def hypot_exact(x: float, y: float) -> float:
    """``math.hypot(x, y)`` for one pair in compiled kernels: the length ``sqrt(x^2 + y^2)``
    as CPython computes it (its ``vector_norm``: scaling by a power of two, exact squares,
    compensated summation and a differential correction of the square root), bit for bit on
    CPython 3.11 and later; numba's ``math.hypot`` and ``np.hypot`` are the C library's,
    which differs in the last bit for about one pair in 160."""
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


@kernel
def _hypot_rows(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """:func:`hypot_exact` of every pair ``(x[i], y[i])``."""
    out = np.empty(x.shape[0])
    for i in range(x.shape[0]):
        out[i] = hypot_exact(x[i], y[i])
    return out


@kernel
def _wrap_rows(x: np.ndarray) -> np.ndarray:
    """:func:`wrap_angle` of every ``x[i]``."""
    out = np.empty(x.shape[0])
    for i in range(x.shape[0]):
        out[i] = wrap_angle(x[i])
    return out


@kernel
def floor_remainder(a: float, b: float) -> float:
    """``numpy.remainder(a, b)`` on floats (the sign of ``b``): ``fmod(a, b)`` (exact), plus
    ``b`` when its sign differs from ``b``'s, a zero with ``b``'s sign; numpy's
    ``npy_divmod`` step by step, bit for bit (NaN for ``b = 0``), so that a kernel wraps an
    angle exactly as the array code does."""
    mod = np.fmod(a, b)
    if mod != 0.0:
        if (b < 0.0) != (mod < 0.0):
            mod += b
    else:
        mod = math.copysign(0.0, b)
    return mod


@kernel
def _less(a: float, b: float) -> bool:
    """numpy's order of floats: ``a < b``, NaN after every number."""
    return a < b or (b != b and a == a)


@kernel
def stable_argsort(keys: np.ndarray) -> np.ndarray:
    """``np.argsort(keys, kind="stable")`` of a float array ``(n,)``: the indices that sort
    ``keys`` ascending, equal keys in their original order, NaN last (a bottom-up merge
    sort; a stable order is unique, so the indices are numpy's)."""
    n = keys.shape[0]
    idx = np.empty(n, dtype=np.int64)
    for i in range(n):
        idx[i] = i
    tmp = np.empty(n, dtype=np.int64)
    width = 1
    while width < n:
        for lo in range(0, n, 2 * width):
            mid = min(lo + width, n)
            hi = min(lo + 2 * width, n)
            i, j, k = lo, mid, lo
            while i < mid and j < hi:
                if _less(keys[idx[j]], keys[idx[i]]):
                    tmp[k] = idx[j]
                    j += 1
                else:
                    tmp[k] = idx[i]
                    i += 1
                k += 1
            while i < mid:
                tmp[k] = idx[i]
                i += 1
                k += 1
            while j < hi:
                tmp[k] = idx[j]
                j += 1
                k += 1
        idx, tmp = tmp, idx
        width *= 2
    return idx


@kernel
def search_right(a: np.ndarray, v: float) -> int:
    """``np.searchsorted(a, v, side="right")`` for a sorted float array ``a`` ``(n,)``: the
    number of entries not after ``v`` in numpy's order (NaN last), by bisection."""
    lo, hi = 0, a.shape[0]
    while lo < hi:
        mid = (lo + hi) >> 1
        if _less(v, a[mid]):
            hi = mid
        else:
            lo = mid + 1
    return lo
