"""Synthetic weight images for the tests of the image trackers (tests/estimators/image/):
Gaussian blobs on a noisy background, distractors of a similar colour, manoeuvring targets."""

from __future__ import annotations

import math

import numpy as np

H, W = 240, 320
YY, XX = np.mgrid[0:H, 0:W].astype(np.float32)


def blob(img: np.ndarray, centre, sigma: float, amp: float) -> None:
    """Add a Gaussian blob (in place), evaluated within 4 sigma."""
    x, y = centre
    r = int(4 * sigma) + 1
    x0, x1 = max(int(x) - r, 0), min(int(x) + r + 1, img.shape[1])
    y0, y1 = max(int(y) - r, 0), min(int(y) + r + 1, img.shape[0])
    if x1 > x0 and y1 > y0:
        d2 = (XX[y0:y1, x0:x1] - x) ** 2 + (YY[y0:y1, x0:x1] - y) ** 2
        img[y0:y1, x0:x1] += amp * np.exp(-d2 / (2.0 * sigma * sigma))


def weight_image(rng, targets=(), distractors=(), sigma=4.0, noise=0.1) -> np.ndarray:
    """Colour probability image: uniform noise in [0, noise), target blobs of amplitude 0.9,
    distractors (a similar colour) of amplitude 0.5, clipped to [0, 1]."""
    img = (rng.random((H, W)) * noise).astype(np.float32)
    for p in targets:
        blob(img, p, sigma, 0.9)
    for p in distractors:
        blob(img, p, sigma, 0.5)
    return np.clip(img, 0.0, 1.0)


def frame_differences(frames):
    return [np.zeros_like(frames[0])] + [np.abs(b - a) for a, b in zip(frames, frames[1:])]


def manoeuvre(rng, steps=60, speed=10.0, every=6, start=(160.0, 120.0)) -> np.ndarray:
    """A target at ``speed`` px/frame that turns sharply (60-108 degrees) every ``every``
    frames and bounces off a 20 px margin."""
    p, heading, out = np.array(start), rng.uniform(0, 2 * math.pi), []
    for k in range(steps):
        if k and k % every == 0:
            heading += rng.choice([-1, 1]) * rng.uniform(math.pi / 3, 0.6 * math.pi)
        q = p + speed * np.array([math.cos(heading), math.sin(heading)])
        if not 20 < q[0] < W - 20:
            heading = math.pi - heading
        if not 20 < q[1] < H - 20:
            heading = -heading
        p = p + speed * np.array([math.cos(heading), math.sin(heading)])
        out.append(p.copy())
    return np.array(out)


def rmse(est, truth) -> float:
    return float(np.sqrt(np.mean(np.sum((np.asarray(est)[:, :2] - truth) ** 2, axis=1))))
