"""The image trackers' whole-image window search as a compiled kernel
(:func:`window_mass_scores`), which
:meth:`~estimators.image.mspf.MeanShiftParticleFilter.global_search` calls.

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

__all__ = ["window_mass_scores"]


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
