"""Mean shift against OpenCV (``cv2.meanShift``) on synthetic weight images: the same windows
in the OpenCV-compatible mode, within a pixel or two otherwise and closer to the blobs, either
kernel; bad arguments. OpenCV is only an oracle here; ``estimators`` never imports it."""

from __future__ import annotations

import numpy as np
import pytest
from weight_images import H, W, blob, weight_image

from estimators import (
    mean_shift,
)

cv2 = pytest.importorskip("cv2")

IMG = np.zeros((H, W), np.float32)


def _blob_scenes(seed, n):
    """Random images with four well-separated blobs and a window near one of them."""
    rng = np.random.default_rng(seed)
    grid = [(60, 60), (220, 60), (60, 170), (220, 170)]
    for _ in range(n):
        img = (rng.random((H, W)) * 0.1).astype(np.float32)
        truth = []
        for gx, gy in grid:
            c = (gx + rng.uniform(-8, 8), gy + rng.uniform(-8, 8))
            truth.append(c)
            blob(img, c, rng.uniform(3, 6), rng.uniform(0.6, 1.0))
        img = np.clip(img, 0, 1)
        w, h = (int(v) for v in rng.integers(9, 25, 2))
        k = int(rng.integers(4))
        x = int(truth[k][0] + rng.integers(-10, 11) - w // 2)
        y = int(truth[k][1] + rng.integers(-10, 11) - h // 2)
        yield img, (x, y, w, h), np.array(truth[k])


def test_mean_shift_reproduces_cv2_windows_exactly_in_opencv_mode():
    crit = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 20, 1)
    for img, win, _ in _blob_scenes(0, 60):
        _, ours, _, mass = mean_shift(img, win, max_iter=20, eps=1.0, opencv_compatible=True)
        _, theirs = cv2.meanShift(img, win, crit)
        assert ours == tuple(theirs)
        x, y, w, h = ours
        assert mass == pytest.approx(float(img[y:y + h, x:x + w].sum()), rel=1e-5)


def test_mean_shift_matches_cv2_within_a_pixel_or_two_and_is_closer_to_the_blob():
    crit = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 20, 1)
    diffs, ours_err, cv_err = [], [], []
    for img, win, truth in _blob_scenes(1, 100):
        centre, ours, _, _ = mean_shift(img, win, max_iter=20, eps=1.0)
        _, theirs = cv2.meanShift(img, win, crit)
        diffs.append(max(abs(ours[0] - theirs[0]), abs(ours[1] - theirs[1])))
        x, y, w, h = theirs
        p = img[y:y + h, x:x + w].astype(np.float64)
        cv_centre = (x + p.sum(0) @ np.arange(w) / p.sum(), y + p.sum(1) @ np.arange(h) / p.sum())
        ours_err.append(np.hypot(*(centre - truth)))
        cv_err.append(np.hypot(*(np.array(cv_centre) - truth)))
    diffs = np.array(diffs)
    # OpenCV compares the centroid with w/2 instead of (w-1)/2: the windows stall at most a
    # pixel or two apart, and ours end nearer the blobs' centres.
    assert np.mean(diffs <= 1) > 0.6 and np.mean(diffs <= 2) > 0.9
    assert np.median(ours_err) < np.median(cv_err)
    assert np.median(ours_err) < 1.0


def test_mean_shift_climbs_to_the_blob_with_either_kernel():
    img = weight_image(np.random.default_rng(2), targets=[(100.3, 80.6)], sigma=5.0)
    for kernel in ("flat", "epanechnikov"):
        centre, win, iters, mass = mean_shift(img, (80, 65, 21, 21), kernel=kernel)
        assert np.hypot(centre[0] - 100.3, centre[1] - 80.6) < 1.0, kernel
        assert 1 <= iters <= 10 and mass > 100.0


@pytest.mark.parametrize("call, name", [
    (lambda: mean_shift(np.zeros((4, 4, 3)), (0, 0, 2, 2)), "weight_image"),
    (lambda: mean_shift(-IMG - 1, (0, 0, 2, 2)), "weight_image"),
    (lambda: mean_shift(IMG, (0, 0, 0, 2)), "window w"),
    (lambda: mean_shift(IMG, (0, 0, 2.5, 2)), "window"),
    (lambda: mean_shift(IMG, (0, 0, 400, 2)), "window size"),
    (lambda: mean_shift(IMG, (0, 0, 2, 2), max_iter=0), "max_iter"),
    (lambda: mean_shift(IMG, (0, 0, 2, 2), eps=-1), "eps"),
    (lambda: mean_shift(IMG, (0, 0, 2, 2), kernel="gauss"), "kernel"),
])
def test_bad_arguments_raise_value_error_naming_them(call, name):
    with pytest.raises(ValueError, match=name):
        call()
