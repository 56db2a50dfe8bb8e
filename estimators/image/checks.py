"""Argument checks of the image trackers (numpy only): each raises ``ValueError`` naming the
argument and what is allowed. Images are scanned for non-finite or negative weights only when
asked (``scan``): a per-frame scan of a camera image would cost as much as the tracking."""

from __future__ import annotations

import math

import numpy as np

from ..checks import MAX_PIXELS, check_reals, real_value

__all__ = ["MIN_SIGMA_PX", "check_number", "check_int", "check_image", "check_window_size",
           "check_point", "check_fits"]

#: The smallest standard deviation [px] a tracker's filter starts from: its square stays a
#: normal float (the square of 1e-300 is 0, a singular covariance).
MIN_SIGMA_PX = 1e-6


def check_number(name: str, value, low: float = 0.0, allow_low: bool = False,
                 high: float | None = None) -> float:
    """``value`` as a float; ``ValueError`` naming ``name`` unless a finite real number (not
    a bool or a string, see :func:`~estimators.checks.real_value`) ``> low`` (``>= low``
    with ``allow_low``; ``low = -inf``: no lower bound) and ``<= high`` when given."""
    v = real_value(value)
    if v is None or not math.isfinite(v) or v < low or (v == low and not allow_low) or (
            high is not None and v > high):
        bounds = ([] if low == -math.inf else [f"{'>=' if allow_low else '>'} {low}"]) + (
            [] if high is None else [f"<= {high}"])
        rng = " and " + ", ".join(bounds) if bounds else ""
        raise ValueError(f"{name} must be finite{rng}, got {value!r}"[:300])
    return v


def check_int(name: str, value, low: int = 1, high: int | None = None) -> int:
    """``value`` as an int; ``ValueError`` naming ``name`` unless an integer (not a bool)
    ``>= low`` and ``<= high`` when given."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low or (
            high is not None and value > high):
        top = "" if high is None else f" and <= {high:,}"
        raise ValueError(f"{name} must be an integer >= {low}{top}, got {value!r}"[:300])
    return int(value)


def check_image(name: str, image, shape: tuple[int, int] | None = None,
                scan: bool = False, window: tuple[int, int] | None = None) -> np.ndarray:
    """``image`` as a C-contiguous float32/float64 2-D array (a copy only if needed), of
    ``shape`` ``(H, W)`` when given and large enough to hold a ``window`` ``(w, h)`` [px]
    when given (:func:`check_fits`); ``ValueError`` naming ``name`` otherwise. Values
    are scanned (finite, non-negative) only when ``scan``: a per-frame scan of a 640 x 480
    image would cost as much as the tracking."""
    try:
        arr = np.asarray(image)
    except (TypeError, ValueError):
        arr = np.asarray(None)
    if arr.ndim != 2 or arr.shape[0] < 1 or arr.shape[1] < 1:
        raise ValueError(f"{name} must be a 2-D image, got shape {arr.shape}")
    if arr.dtype not in (np.float32, np.float64):
        if not (np.issubdtype(arr.dtype, np.number) and not np.iscomplexobj(arr)):
            raise ValueError(f"{name} must be a real-valued image, got dtype {arr.dtype}")
        arr = arr.astype(np.float32)
    if shape is not None and arr.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {arr.shape}")
    if window is not None:
        check_fits(name, window, arr.shape)
    if scan and not (np.all(np.isfinite(arr)) and arr.min() >= 0.0):
        raise ValueError(f"{name} must be finite and non-negative")
    return np.ascontiguousarray(arr)


def check_fits(name: str, window: tuple[int, int], shape: tuple[int, ...],
               window_name: str = "the window") -> None:
    """``ValueError`` naming the image ``name`` (and ``window_name``, where the window's size
    comes from) unless a window ``(w, h)`` [px] fits in an image of shape ``(H, W)``."""
    w, h = window
    if len(shape) != 2 or w > shape[1] or h > shape[0]:
        raise ValueError(f"{name} must be at least {w} x {h} pixels (w x h) to hold "
                         f"{window_name}, got shape {tuple(shape)} (H, W)")


def check_window_size(name: str, value) -> tuple[int, int]:
    """``value`` as a window size ``(w, h)`` [px] of two integers in ``[1, MAX_PIXELS]``
    (:data:`~estimators.checks.MAX_PIXELS`); ``ValueError`` naming ``name`` otherwise."""
    try:
        w, h = value
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be (w, h) in pixels, got {value!r}") from None
    return (check_int(f"{name}[0] (w)", w, high=MAX_PIXELS),
            check_int(f"{name}[1] (h)", h, high=MAX_PIXELS))


def check_point(name: str, value) -> np.ndarray:
    """``value`` as a finite ``(x, y)`` float array [px]; ``ValueError`` naming ``name``
    otherwise (:func:`~estimators.checks.check_reals`)."""
    return check_reals(name, value, 2, what="(x, y) [px]")
