"""Argument checks shared by the estimators (numpy only): each raises ``ValueError`` naming
the argument and the allowed range, so that bad input never turns into NaN inside a filter
or into an allocation the machine cannot hold."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["MAX_PARTICLES", "MAX_COORDINATE", "check_count", "check_real", "check_positive",
           "check_sigma", "check_points"]

#: The most particles a filter takes: a million 4-D particles are 32 MB, and each update
#: touches every one (10^10 asked for 298 GiB before failing).
MAX_PARTICLES = 1_000_000


#: The farthest a measured point may lie from the origin [m]: fields are tens of metres; a
#: detection a thousand kilometres away is corrupt data (and its squares near overflow).
MAX_COORDINATE = 1e6


def check_count(name: str, value: Any, low: int, high: int) -> int:
    """``value`` as an int; ``ValueError`` unless an integer (not a bool) in
    ``[low, high]``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) \
            or not low <= value <= high:
        raise ValueError(f"{name} must be an integer in [{low}, {high:,}], got {value!r}")
    return int(value)


def check_real(name: str, value: Any, low: float = -math.inf, high: float = math.inf, *,
               low_open: bool = False, unit: str = "") -> float:
    """``value`` as a float; ``ValueError`` unless a finite real number (not a bool) in
    ``[low, high]`` (``(low, high]`` with ``low_open``)."""
    ok = isinstance(value, (int, float, np.integer, np.floating)) and \
        not isinstance(value, (bool, np.bool_))
    v = float(value) if ok else math.nan
    if not (math.isfinite(v) and (v > low if low_open else v >= low) and v <= high):
        bracket = "(" if low_open else "["
        raise ValueError(f"{name} must be a finite number in {bracket}{low:g}, {high:g}]"
                         f"{unit}, got {value!r}")
    return v


def check_positive(name: str, value: Any, allow_zero: bool = False) -> float:
    """``value`` as a float; ``ValueError`` naming ``name`` unless a finite number > 0
    (>= 0 with ``allow_zero``)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < 0.0 or (v == 0.0 and not allow_zero):
        raise ValueError(f"{name} must be finite and {'>=' if allow_zero else '>'} 0, "
                         f"got {value!r}")
    return v


def check_sigma(name: str, value: float) -> float:
    """``value`` as a float if it is finite and >= 0 (a standard deviation that may be zero),
    else ``ValueError`` naming ``name``."""
    v = float(value)
    if not (math.isfinite(v) and v >= 0.0):
        raise ValueError(f"{name} must be finite and >= 0, got {value!r}")
    return v


def check_points(name: str, value: Any, exact: bool = True) -> list:
    """``value`` (``k`` points, k may be 0: an array ``(k, 2)`` or a sequence of ``(x, y)``
    sequences; with ``exact=False`` longer rows whose first two entries are ``x, y``, such as
    poses) as a list of rows; ``ValueError`` for other shapes or non-finite values,
    ``TypeError`` for what is neither an array nor a sequence."""
    if isinstance(value, np.ndarray):
        if value.size == 0:
            return []
        if value.ndim != 2 or value.shape[1] < 2 or (exact and value.shape[1] != 2):
            raise ValueError(f"{name} must have shape (k, 2), got {value.shape}")
        rows = value.tolist()
    elif isinstance(value, (list, tuple)):
        rows = value
    else:
        raise TypeError(f"{name} must be an array or a sequence of points, got "
                        f"{type(value).__name__}")
    total = 0.0
    for p in rows:
        n = len(p)
        if n < 2 or (exact and n != 2):
            raise ValueError(f"{name} must have shape (k, 2); got a point of length {n}")
        total += abs(p[0]) + abs(p[1])
    if not math.isfinite(total):
        raise ValueError(f"{name} must be finite (NaN measurements are refused)")
    if total > MAX_COORDINATE:
        raise ValueError(f"{name} must lie within {MAX_COORDINATE:g} m of the origin, got "
                         f"{rows!r}"[:300])
    return rows
