"""Argument checks of the image trackers (numpy only): each raises ``ValueError`` naming the
argument and what is allowed. Images are scanned for non-finite or negative weights only when
asked (``scan``): a per-frame scan of a camera image would cost as much as the tracking."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["check_number", "check_int", "check_image", "check_window_size", "check_point"]


def check_number(name: str, value, low: float = 0.0, allow_low: bool = False,
                 high: float | None = None) -> float:
    """``value`` as a float; ``ValueError`` naming ``name`` unless a finite number ``> low``
    (``>= low`` with ``allow_low``) and ``<= high`` when given."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < low or (v == low and not allow_low) or (
            high is not None and v > high):
        rng = f"{'>=' if allow_low else '>'} {low}" + ("" if high is None else f", <= {high}")
        raise ValueError(f"{name} must be finite and {rng}, got {value!r}")
    return v


def check_int(name: str, value, low: int = 1) -> int:
    """``value`` as an int; ``ValueError`` naming ``name`` unless an integer (not a bool)
    ``>= low``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    return int(value)


def check_image(name: str, image, shape: tuple[int, int] | None = None,
                scan: bool = False) -> np.ndarray:
    """``image`` as a C-contiguous float32/float64 2-D array (a copy only if needed). Values
    are scanned (finite, non-negative) only when ``scan``: a per-frame scan of a 640 x 480
    image would cost as much as the tracking."""
    arr = np.asarray(image)
    if arr.ndim != 2 or arr.shape[0] < 1 or arr.shape[1] < 1:
        raise ValueError(f"{name} must be a 2-D image, got shape {arr.shape}")
    if arr.dtype not in (np.float32, np.float64):
        if not (np.issubdtype(arr.dtype, np.number) and not np.iscomplexobj(arr)):
            raise ValueError(f"{name} must be a real-valued image, got dtype {arr.dtype}")
        arr = arr.astype(np.float32)
    if shape is not None and arr.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {arr.shape}")
    if scan and not (np.all(np.isfinite(arr)) and arr.min() >= 0.0):
        raise ValueError(f"{name} must be finite and non-negative")
    return np.ascontiguousarray(arr)


def check_window_size(name: str, value) -> tuple[int, int]:
    """``value`` as a window size ``(w, h)`` [px] of two integers >= 1; ``ValueError``
    otherwise."""
    try:
        w, h = value
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be (w, h) in pixels, got {value!r}") from None
    return check_int(f"{name}[0] (w)", w), check_int(f"{name}[1] (h)", h)


def check_point(name: str, value) -> np.ndarray:
    """``value`` as a finite ``(x, y)`` float array [px]; ``ValueError`` otherwise."""
    arr = np.asarray(value, dtype=np.float64)
    if arr.shape != (2,) or not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be a finite (x, y) pair, got {value!r}")
    return arr
