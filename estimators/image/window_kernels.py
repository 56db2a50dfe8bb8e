"""The image trackers' window machinery as compiled kernels: the whole-image window search
(:func:`window_mass_scores`, which
:meth:`~estimators.image.mspf.MeanShiftParticleFilter.global_search` calls), and the
gathering of windows' pixels and the mean-shift step of
:meth:`~estimators.image.meanshift.MeanShiftWindows.shift` (:func:`gather_windows`,
:func:`mean_shift_step`).

The moments of the gathered windows stay one numpy matrix product (``(N, h w) @ (h w, 4)``):
the BLAS library sums in its own order, which a kernel would not reproduce to the bit.

Every window position's mass (the sum of its weights) from one summed-area table: with
``S[i, j] = sum_{r < i, c < j} I[r, c]`` (float64, summed down the columns first, then along
the rows, as two ``numpy.cumsum`` passes do), the window of size ``(w, h)`` at the top-left
pixel ``(x, y)`` holds ``S[y + h, x + w] - S[y, x + w] - S[y + h, x] + S[y, x]``. Bit for bit
with those numpy passes (the same running sums, the same four-term expression, left to right);
one pass instead of a table, two cumulative sums and five whole-image temporaries.
"""

from __future__ import annotations

import math

import numpy as np

from ..compiled import kernel

__all__ = ["window_mass_scores", "gather_windows", "mean_shift_step"]


@kernel
def window_mass_scores(image: np.ndarray, w: int, h: int, area: float, tolerance: float,
                       score: np.ndarray) -> bool:
    """Score every window position of ``image`` (``(H, W)`` non-negative weights) by its
    mass ``m`` when ``|m - area| <= tolerance`` (the colour-mass restriction), else
    ``-inf``, into ``score`` (``(H - h + 1, W - w + 1)`` float64, indexed by the windows'
    top-left pixel ``(y, x)``); True when any window passes.

    Args:
        image: the weights (float32 or float64).
        w: the windows' width [px].
        h: the windows' height [px].
        area: the target's mass.
        tolerance: the largest allowed ``|m - area|``.
        score: where the scores go.
    """
    rows, cols = image.shape
    s = np.zeros((rows + 1, cols + 1))
    down = np.empty(cols)  # the running sums down the columns, row by row
    for i in range(rows):
        for j in range(cols):
            down[j] = image[0, j] if i == 0 else down[j] + image[i, j]
        t = down[0]  # then along the row: S[i + 1, j + 1] = S[i + 1, j] + down[j]
        s[i + 1, 1] = t
        for j in range(1, cols):
            t = t + down[j]
            s[i + 1, j + 1] = t
    found = False
    for y in range(rows - h + 1):
        for x in range(cols - w + 1):
            m = s[y + h, x + w] - s[y, x + w] - s[y + h, x] + s[y, x]
            if abs(m - area) <= tolerance:
                score[y, x] = m
                found = True
            else:
                score[y, x] = -math.inf
    return found


@kernel
def gather_windows(first: np.ndarray, second: np.ndarray, scales: np.ndarray, both: bool,
                   x0: np.ndarray, y0: np.ndarray, active: np.ndarray, count: int,
                   width: int, offsets: np.ndarray, out: np.ndarray) -> None:
    """The pixels of the windows ``active[:count]`` (top-left pixels ``(x0, y0)``) of the
    image ``c_0 I_0 (+ c_1 I_1)`` into ``out`` (``(count, h w)`` float64): ``first`` and
    ``second`` the flat images ``I_0``, ``I_1`` (one dtype; ``second`` read only when
    ``both``), ``scales`` ``(c_0, c_1)`` in that dtype (a scale of 1 is not multiplied, as
    numpy's ``c * I`` is skipped for it), ``offsets`` ``(h w,)`` the window's flat pixel
    offsets in an image ``width`` pixels wide. The products and the sum are computed in the
    images' dtype, as numpy computes them, then widened to float64."""
    c0, c1 = scales[0], scales[1]
    for r in range(count):
        i = active[r]
        start = y0[i] * width + x0[i]
        for j in range(offsets.shape[0]):
            v = first[start + offsets[j]]
            if c0 != 1.0:
                v = c0 * v
            if both:
                u = second[start + offsets[j]]
                if c1 != 1.0:
                    u = c1 * u
                v = v + u
            out[r, j] = v


@kernel
def mean_shift_step(mom: np.ndarray, x0: np.ndarray, y0: np.ndarray, active: np.ndarray,
                    count: int, iters: np.ndarray, origin: tuple[float, float],
                    x_max: int, y_max: int, eps2: float) -> int:
    """One mean-shift step of the windows ``active[:count]`` from their moments ``mom``
    (``(count, 4)``: ``m00, m10, m01`` in window coordinates, and the mass): a window with
    ``m00 > 1e-12`` moves by ``round(m10 / m00 - origin_x, m01 / m00 - origin_y)`` (half to
    even), kept inside ``0 .. x_max``, ``0 .. y_max``, and counts an iteration in ``iters``;
    ``x0``, ``y0`` updated in place. The windows still moving (with mass, moved by at least
    one pixel and ``dx^2 + dy^2 >= eps2``) are compacted to the front of ``active``; returns
    their count."""
    ox, oy = origin
    kept = 0
    for r in range(count):
        i = active[r]
        m00 = mom[r, 0]
        has_mass = m00 > 1e-12
        dx = dy = 0
        if has_mass:
            dx = int(np.rint(mom[r, 1] / m00 - ox))
            dy = int(np.rint(mom[r, 2] / m00 - oy))
            iters[i] += 1
        nx = min(max(x0[i] + dx, 0), x_max)
        ny = min(max(y0[i] + dy, 0), y_max)
        mx, my = nx - x0[i], ny - y0[i]
        x0[i], y0[i] = nx, ny
        if has_mass and (mx != 0 or my != 0) and mx * mx + my * my >= eps2:
            active[kept] = i
            kept += 1
    return kept
