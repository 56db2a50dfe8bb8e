"""KLD-sampling's sample size (Fox 2003): how many particles keep the Kullback-Leibler
distance between the sample-based and the true (binned) posterior small, from the number of
histogram bins the drawn particles occupy (:func:`kld_sample_size`), and the packing of a
particle's bin into one integer key (:data:`BIN_PACK`), what :class:`~estimators.KLDLocalizer`
counts while it resamples."""

from __future__ import annotations

import functools
import math

import numpy as np

__all__ = ["normal_quantile", "kld_sample_size", "kld_table", "BIN_PACK"]


def normal_quantile(p: float) -> float:
    """The standard normal quantile (Acklam's rational approximation, |error| < 1.2e-9),
    to keep the module numpy-only."""
    if not 0.0 < p < 1.0:
        raise ValueError(f"p must be in (0, 1), got {p!r}")
    a = (-3.969683028665376e01, 2.209460984245205e02, -2.759285104469687e02,
         1.383577518672690e02, -3.066479806614716e01, 2.506628277459239e00)
    b = (-5.447609879822406e01, 1.615858368580409e02, -1.556989798598866e02,
         6.680131188771972e01, -1.328068155288572e01)
    c = (-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e00,
         -2.549732539343734e00, 4.374664141464968e00, 2.938163982698783e00)
    d = (7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e00,
         3.754408661907416e00)
    if p < 0.02425:
        q = math.sqrt(-2.0 * math.log(p))
        return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / \
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0)
    if p > 1.0 - 0.02425:
        return -normal_quantile(1.0 - p)
    q = p - 0.5
    r = q * q
    return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q / \
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0)


def kld_sample_size(k: int | np.ndarray, epsilon: float, delta: float) -> np.ndarray:
    """Fox's KLD bound: the number of particles that keeps the Kullback-Leibler distance
    between the sample-based and the true (binned) posterior below ``epsilon`` with
    probability ``1 - delta``, for ``k`` occupied bins (1 for ``k <= 1``)."""
    k = np.asarray(k, dtype=np.float64)
    z = normal_quantile(1.0 - delta)
    km1 = np.maximum(k - 1.0, 1.0)
    a = 2.0 / (9.0 * km1)
    n = km1 / (2.0 * epsilon) * (1.0 - a + np.sqrt(a) * z) ** 3
    return np.where(k <= 1.0, 1.0, np.ceil(n))


@functools.lru_cache(maxsize=16)
def kld_table(epsilon: float, delta: float, max_particles: int) -> list[float]:
    """:func:`kld_sample_size` for ``k = 0 .. max_particles``, as a list (looked up draw by
    draw while resampling)."""
    return kld_sample_size(np.arange(max_particles + 1), epsilon, delta).tolist()


#: Bin keys are packed into one integer, ``ix * 2^42 + iy * 2^21 + itheta``: distinct for
#: bin indices within +-2^20 (200 km at 0.2 m bins), far beyond any field.
BIN_PACK = np.array([1 << 42, 1 << 21, 1], dtype=np.int64)
