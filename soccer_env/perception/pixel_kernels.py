"""The overhead pixels detector's heading match as compiled kernels (:func:`dot_pixels`,
:func:`best_heading`), which
:class:`~soccer_env.perception.pixels.OverheadPixelDetector` runs for every robot it finds in
every frame.

A robot's heading is the candidate ``phi_h`` (5-degree steps) whose rotated dot layout falls
on the most probability of the dots' colours: dot ``k`` at ``(l_x, l_y)`` [m] in the body frame
lies at the pixel ``(round(u + (cos phi l_x - sin phi l_y) / m), round(v - (sin phi l_x +
cos phi l_y) / m))`` (``m`` metres per pixel; field +y is image -v; rounded half to even and
clipped to the image), and the score of ``phi_h`` is the sum over the dots of their colour's
probability there. Bit for bit with the numpy it replaces (the same expressions, the scores
summed over the dots in their order, the first best heading on a tie); one pass instead of
a dozen array operations per robot.
"""

from __future__ import annotations

import numpy as np

from estimators.compiled import kernel

__all__ = ["dot_pixels", "best_heading"]


@kernel
def dot_pixels(u: float, v: float, layout: np.ndarray, cos: np.ndarray, sin: np.ndarray,
               m: float, width: int, height: int, cols: np.ndarray, rows: np.ndarray
               ) -> tuple[int, int, int, int]:
    """The pixels of the dots (``layout`` ``(K, 2)`` [m], body frame) of a robot at the pixel
    ``(u, v)`` for every candidate heading (``cos``, ``sin`` ``(P,)``), ``m`` metres per
    pixel, clipped to a ``width`` x ``height`` image: columns into ``cols`` and rows into
    ``rows`` (``(P, K)`` int64); returns the box ``(x0, y0, x1, y1)`` that holds them all
    (``x1``, ``y1`` exclusive)."""
    x0, y0, x1, y1 = width, height, -1, -1
    for h in range(cos.shape[0]):
        c, s = cos[h], sin[h]
        for k in range(layout.shape[0]):
            lx, ly = layout[k, 0], layout[k, 1]
            du = (c * lx - s * ly) / m
            dv = -(s * lx + c * ly) / m
            col = min(max(int(np.rint(u + du)), 0), width - 1)
            row = min(max(int(np.rint(v + dv)), 0), height - 1)
            cols[h, k], rows[h, k] = col, row
            x0, y0, x1, y1 = min(x0, col), min(y0, row), max(x1, col), max(y1, row)
    return x0, y0, x1 + 1, y1 + 1


@kernel
def best_heading(first: np.ndarray, second: np.ndarray, uses_second: np.ndarray,
                 cols: np.ndarray, rows: np.ndarray) -> int:
    """The index of the candidate heading whose dots fall on the most probability (the
    first on a tie): dot ``k`` reads the image ``second`` where ``uses_second[k]``, else
    ``first`` (the dots' two colours' probabilities, ``(H, W)``), at ``(rows[h, k],
    cols[h, k])``; the scores are summed over the dots in their order, in float64."""
    best, top = 0, -np.inf
    for h in range(cols.shape[0]):
        score = 0.0
        for k in range(cols.shape[1]):
            image = second if uses_second[k] else first
            score += image[rows[h, k], cols[h, k]]
        if score > top:
            best, top = h, score
    return best
