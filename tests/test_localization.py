"""KLD-sampling particle-filter localization (paper 001): global localization, tracking with
few particles, recovery after kidnapping, the KLD bound, reproducibility, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators.localization import KLDConfig, KLDLocalizer, _normal_quantile, kld_sample_size

# Goal posts, corners and the centre-line ends of a 6 m x 4 m field.
LANDMARKS = np.array([[3, 0.7], [3, -0.7], [-3, 0.7], [-3, -0.7], [3, 2], [3, -2], [-3, 2],
                      [-3, -2], [0, 2], [0, -2]], dtype=float)
BOUNDS = (-3.0, 3.0, -2.0, 2.0)


def _sight(pose, rng, max_range=4.0, noise=0.03):
    dist = np.hypot(*(LANDMARKS - pose[:2]).T)
    vis = dist < max_range
    rel = LANDMARKS[vis] - pose[:2]
    ranges = dist[vis] * (1.0 + rng.normal(0, noise, vis.sum()))
    bearings = np.arctan2(rel[:, 1], rel[:, 0]) - pose[2] + rng.normal(0, noise, vis.sum())
    return LANDMARKS[vis], ranges, bearings


def _walk(loc, pose, steps, rng):
    """Walk at 0.2 m/s (10 Hz), turning near the edges; returns errors and particle counts."""
    errors, counts = [], []
    for k in range(steps):
        v, w = 0.02, (0.03 if (k // 50) % 2 else 0.0)
        if abs(pose[0]) > 2.0 or abs(pose[1]) > 1.2:
            w = 0.05
        c, s = math.cos(pose[2] + w / 2), math.sin(pose[2] + w / 2)
        pose = pose + np.array([c * v, s * v, w])
        loc.predict(np.array([v, 0.0, w]) + rng.normal(0, 1, 3) * [0.005, 0.005, 0.01])
        loc.update(*_sight(pose, rng))
        errors.append(np.hypot(*(loc.estimate()[:2] - pose[:2])))
        counts.append(loc.n)
    return pose, np.array(errors), np.array(counts)


def test_kld_bound_and_quantile():
    for p, z in ((0.5, 0.0), (0.975, 1.959963985), (0.99, 2.326347874), (0.001, -3.090232306)):
        assert _normal_quantile(p) == pytest.approx(z, abs=1e-8)
    n = kld_sample_size(np.array([1, 2, 10, 100]), 0.05, 0.01)
    assert n[0] == 1
    k, z = 100, 2.326347874
    expected = (k - 1) / 0.1 * (1 - 2 / (9 * (k - 1)) + math.sqrt(2 / (9 * (k - 1))) * z) ** 3
    assert n[3] == math.ceil(expected)
    assert np.all(np.diff(n) > 0)


def test_global_localization_then_tracking_with_few_particles():
    rng = np.random.default_rng(0)
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(1))
    global_count = loc.n
    assert global_count == KLDConfig().max_particles
    _, errors, counts = _walk(loc, np.array([-1.0, 0.5, 0.3]), 200, rng)
    assert np.median(errors[20:]) < 0.15  # issue aim while walking
    assert np.max(counts[20:]) * 3 <= global_count  # at least 3x fewer while tracking


def test_recovers_after_being_picked_up():
    rng = np.random.default_rng(2)
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(3), pose=np.array([-1.0, 0.5, 0.3]))
    pose, _, _ = _walk(loc, np.array([-1.0, 0.5, 0.3]), 30, rng)
    kidnapped = np.array([2.0, -1.0, 2.0])
    assert np.hypot(*(loc.estimate()[:2] - kidnapped[:2])) > 1.0
    for _ in range(60):
        loc.predict(np.zeros(3))
        loc.update(*_sight(kidnapped, rng))
    assert np.hypot(*(loc.estimate()[:2] - kidnapped[:2])) < 0.15


def test_same_seed_same_run():
    runs = []
    for _ in range(2):
        loc = KLDLocalizer(BOUNDS, np.random.default_rng(5))
        _, errors, counts = _walk(loc, np.array([0.0, 0.0, 0.0]), 20, np.random.default_rng(6))
        runs.append((errors.tolist(), counts.tolist()))
    assert runs[0] == runs[1]


def test_bad_input():
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="bounds"):
        KLDLocalizer((1.0, 0.0, 0.0, 1.0), rng)
    with pytest.raises(TypeError, match="Generator"):
        KLDLocalizer(BOUNDS, 3)
    with pytest.raises(ValueError, match="min_particles"):
        KLDConfig(min_particles=10, max_particles=5)
    with pytest.raises(ValueError, match="epsilon"):
        KLDConfig(epsilon=0.0)
    with pytest.raises(ValueError, match="alpha"):
        KLDConfig(alpha_slow=0.5, alpha_fast=0.1)
    loc = KLDLocalizer(BOUNDS, rng)
    with pytest.raises(ValueError, match="odometry"):
        loc.predict([0.1, np.nan, 0.0])
    with pytest.raises(ValueError, match="match"):
        loc.update(LANDMARKS[:2], [1.0])
    loc.update(np.zeros((0, 2)), [])  # nothing seen: nothing changes
    assert loc.n == KLDConfig().max_particles
