"""Argument checks shared by the estimators (numpy only): each raises ``ValueError`` naming
the argument and the allowed range, so that bad input never turns into NaN inside a filter
or into an allocation the machine cannot hold."""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

__all__ = ["MAX_PARTICLES", "MAX_COORDINATE", "MAX_SPEED", "MAX_ACCELERATION", "MAX_PIXELS",
           "real_value", "check_count", "check_real", "check_positive", "check_sigma",
           "check_reals", "check_flag", "check_points"]

#: The most particles a filter takes: a million 4-D particles are 32 MB, and each update
#: touches every one (10^10 asked for 298 GiB before failing).
MAX_PARTICLES = 1_000_000


#: The farthest a measured point may lie from the origin [m]: fields are tens of metres; a
#: detection a thousand kilometres away is corrupt data (and its squares near overflow).
MAX_COORDINATE = 1e6

#: The fastest a state's velocity component may be [m/s]: balls and robots move at metres per
#: second; ten kilometres per second is corrupt data (and far faster ones overflow squared).
MAX_SPEED = 1e4

#: The largest acceleration (or its noise) a model may assume [m/s^2]: a kick accelerates the
#: ball at about a thousand m/s^2 for milliseconds.
MAX_ACCELERATION = 1e4

#: The largest image side, window side or pixel spread [px].
MAX_PIXELS = 100_000


def check_count(name: str, value: Any, low: int, high: int) -> int:
    """``value`` as an int; ``ValueError`` unless an integer (not a bool) in
    ``[low, high]``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) \
            or not low <= value <= high:
        raise ValueError(f"{name} must be an integer in [{low}, {high:,}], got {value!r}")
    return int(value)


def real_value(value: Any) -> float | None:
    """``value`` as a float if it is a real number: a Python or numpy integer or float (or a
    0-d array of one), never a bool or a string; None otherwise. Integers too large for a
    float read as infinite. The one rule of what counts as a number in these checks."""
    if isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf":
        value = value[()]
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        return None
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf
    except (TypeError, ValueError):
        return None


def check_real(name: str, value: Any, low: float = -math.inf, high: float = math.inf, *,
               low_open: bool = False, high_open: bool = False, unit: str = "") -> float:
    """``value`` as a float; ``ValueError`` unless a finite real number (not a bool, see
    :func:`real_value`) in ``[low, high]`` (``low_open``, ``high_open``: the bound
    excluded)."""
    v = real_value(value)
    if v is None or not (math.isfinite(v) and (v > low if low_open else v >= low)
                         and (v < high if high_open else v <= high)):
        brackets = ("(" if low_open else "[") + ", " + (")" if high_open else "]")
        raise ValueError(f"{name} must be a finite number in {brackets[0]}{low:g}, "
                         f"{high:g}{brackets[-1]}{unit}, got {value!r}"[:300])
    return v


def check_positive(name: str, value: Any, allow_zero: bool = False, unit: str = "",
                   high: float = math.inf) -> float:
    """``value`` as a float; ``ValueError`` naming ``name`` (with ``unit`` after the bounds,
    e.g. ``" [m]"``) unless a finite real number (not a bool or a string, see
    :func:`real_value`) > 0 (>= 0 with ``allow_zero``) and <= ``high``."""
    v = real_value(value)
    if v is None or not math.isfinite(v) or v < 0.0 or (v == 0.0 and not allow_zero) \
            or v > high:
        top = "" if high == math.inf else f" and <= {high:g}"
        raise ValueError(f"{name} must be finite and {'>=' if allow_zero else '>'} 0{top}"
                         f"{unit}, got {value!r}"[:300])
    return v


def check_sigma(name: str, value: Any, unit: str = "", high: float = math.inf) -> float:
    """``value`` as a float if it is finite, >= 0 (a standard deviation that may be zero)
    and <= ``high``, else ``ValueError`` naming ``name``."""
    return check_positive(name, value, allow_zero=True, unit=unit, high=high)


def check_reals(name: str, value: Any, n: int, low: float = -math.inf,
                high: float = math.inf, what: str = "") -> np.ndarray:
    """``value`` (a list, tuple or 1-D array of ``n`` real numbers, not bools or strings, see
    :func:`real_value`) as a float array ``(n,)``; ``ValueError`` naming ``name`` (``what``:
    the entries' meaning and units, e.g. ``"(x, y) [px]"``) unless each entry is finite and
    in ``[low, high]``."""
    items = value.tolist() if isinstance(value, np.ndarray) and value.ndim == 1 else \
        list(value) if isinstance(value, (list, tuple)) else []
    reals = [real_value(v) for v in items]
    arr = np.array(reals, dtype=np.float64) if len(reals) == n and None not in reals else None
    if arr is None or not (np.isfinite(arr).all() and (arr >= low).all()
                           and (arr <= high).all()):
        rng = ("" if low == -math.inf and high == math.inf else f" >= {low:g}"
               if high == math.inf else f" <= {high:g}" if low == -math.inf
               else f" in [{low:g}, {high:g}]")
        count = {2: "two", 3: "three", 4: "four"}.get(n, str(n))
        raise ValueError(f"{name} must be {count} finite numbers{rng} {what}".rstrip()
                         + f", got {value!r}"[:300])
    return arr


def check_flag(name: str, value: Any, what: str = "") -> bool:
    """``value`` as a bool; ``ValueError`` naming ``name`` (``what``: what the flag switches
    on) unless it is ``True`` or ``False`` (numbers, strings and None are refused: ``"no"``
    would read as true)."""
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be True or False{what}, got {value!r}"[:300])
    return bool(value)


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
