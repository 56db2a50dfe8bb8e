"""The window kernels (estimators.image.window_kernels) against the numpy they replace, to
the bit: the global search's summed-area table, and the mean-shift windows' gathering and
steps."""

import numpy as np
import pytest

from estimators.image.meanshift import MeanShiftWindows
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


def _numpy_shift(win, flats, x0, y0, max_iter, eps):
    """Mean shift of the windows in numpy (the array version the kernels replace)."""
    def moments(xs, ys):
        patch = None
        for flat, c in flats:
            p = flat[(ys * win.width + xs)[:, None] + win.offsets]
            part = p if c == 1.0 else c * p
            patch = part if patch is None else patch + part
        return patch.astype(np.float64, copy=False) @ win.moments

    x0, y0 = x0.copy(), y0.copy()
    iters = np.zeros(len(x0), dtype=np.intp)
    active = np.arange(len(x0))
    for _ in range(max_iter):
        mom = moments(x0[active], y0[active])
        m00 = mom[:, 0]
        has_mass = m00 > 1e-12
        safe = np.where(has_mass, m00, 1.0)
        dx = np.where(has_mass, np.rint(mom[:, 1] / safe - win.ox), 0.0).astype(np.intp)
        dy = np.where(has_mass, np.rint(mom[:, 2] / safe - win.oy), 0.0).astype(np.intp)
        nx = np.minimum(np.maximum(x0[active] + dx, 0), win.width - win.w)
        ny = np.minimum(np.maximum(y0[active] + dy, 0), win.height - win.h)
        mx, my = nx - x0[active], ny - y0[active]
        iters[active[has_mass]] += 1
        x0[active], y0[active] = nx, ny
        active = active[has_mass & ((mx != 0) | (my != 0)) & (mx * mx + my * my >= eps * eps)]
        if active.size == 0:
            break
    return x0, y0, iters, moments(x0, y0)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("kernel", ["flat", "epanechnikov"])
def test_mean_shift_windows_equal_numpy(dtype, kernel):
    rng = np.random.default_rng(9)
    for trial in range(30):
        rows, cols = (int(v) for v in rng.integers(20, 70, 2))
        w, h = int(rng.integers(3, 15)), int(rng.integers(3, 15))
        win = MeanShiftWindows(w, h, (rows, cols), kernel, bool(trial % 4 == 0))
        a = (rng.random((rows, cols)) ** 6).astype(dtype)
        b = (rng.random((rows, cols)) ** 2).astype(dtype)
        weight = float(rng.uniform(0.0, 0.5))
        flats = [(a.ravel(), 1.0)] if trial % 2 else [(a.ravel(), 1.0 - weight),
                                                      (b.ravel(), weight)]
        n = int(rng.integers(1, 25))
        x0 = rng.integers(0, cols - w + 1, n).astype(np.intp)
        y0 = rng.integers(0, rows - h + 1, n).astype(np.intp)
        max_iter = int(rng.integers(1, 10))
        got = win.shift(flats, x0, y0, max_iter, 0.5)
        want = _numpy_shift(win, flats, x0, y0, max_iter, 0.5)
        for g, e in zip(got, want):
            assert g.dtype == e.dtype and np.array_equal(g, e)
