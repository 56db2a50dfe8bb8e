"""Argument checks shared by the estimators (numpy only): each raises ``ValueError`` naming
the argument and the allowed range, so that bad input never turns into NaN inside a filter
or into an allocation the machine cannot hold."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["MAX_PARTICLES", "check_count", "check_real"]

#: The most particles a filter takes: a million 4-D particles are 32 MB, and each update
#: touches every one (10^10 asked for 298 GiB before failing).
MAX_PARTICLES = 1_000_000


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
