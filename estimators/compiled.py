"""The compiled form of the package's kernels (:func:`kernel`).

Every hot path of the estimators and the environments is a ``numba`` kernel over rows
(filters, particles, detections, environments), written once and called by the single and the
batched classes alike. :func:`kernel` is the one decorator they share: ``numba.njit`` without
fastmath, so no fused multiply-adds and no reordered sums (a kernel rounds as the same
expressions do in Python floats), cached on disk so that a new process (a test worker, an
evaluation pool's worker) loads the machine code instead of compiling it again.

Where the cache lives is numba's rule: in ``__pycache__`` beside the source when that is
writable, else in the user-wide cache directory (``NUMBA_CACHE_DIR``, or the platform's user
cache folder). A read-only install with no writable user cache has no location; numba would
then refuse the decorator at import, so :func:`kernel` compiles without the disk cache there
instead: the package works, and each process pays the compile time (seconds on the first
step) again.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import numba

__all__ = ["kernel"]

F = TypeVar("F", bound=Callable)


def kernel(function: F) -> F:
    """``function`` compiled by ``numba.njit``, cached on disk where numba finds a writable
    cache location, else compiled in each process (see the module docstring)."""
    try:
        return numba.njit(cache=True)(function)
    except RuntimeError:  # "cannot cache function ...: no locator available"
        return numba.njit(function)
