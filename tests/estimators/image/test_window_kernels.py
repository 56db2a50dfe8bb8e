"""The global search's window masses (estimators.image.window_kernels) against the numpy
summed-area table they replace, to the bit."""

import numpy as np
import pytest

from estimators.image.window_kernels import window_mass_scores


def _reference(image, w, h, area, tolerance):
    s = np.zeros((image.shape[0] + 1, image.shape[1] + 1))
    np.cumsum(image, axis=0, out=s[1:, 1:])
    np.cumsum(s[1:, 1:], axis=1, out=s[1:, 1:])
    box = s[h:, w:] - s[:-h, w:] - s[h:, :-w] + s[:-h, :-w]
    ok = np.abs(box - area) <= tolerance
    return ok.any(), np.where(ok, box, -np.inf)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_window_masses_equal_numpy(dtype):
    rng = np.random.default_rng(5)
    for _ in range(20):
        rows, cols = rng.integers(8, 60, 2)
        w, h = int(rng.integers(1, 8)), int(rng.integers(1, 8))
        image = (rng.random((rows, cols)) ** 3).astype(dtype)
        area = float(rng.uniform(0.0, 0.5 * w * h))
        tolerance = float(rng.uniform(0.0, 0.5)) * area
        score = np.empty((rows - h + 1, cols - w + 1))
        found = window_mass_scores(image, w, h, area, tolerance, score)
        want_found, want = _reference(image, w, h, area, tolerance)
        assert found == want_found
        assert np.array_equal(score, want)
