"""Hough-space fusion (paper 000): exact on consistent lines, the least-squares point of
inconsistent ones, invariant to the frame, better weighted when bearings are noisy."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators.hough import fusion_weights, hough_fuse, hough_lines

# Paper 000, Table 1 (millimetres): the five robots and the ball's start.
ROBOTS = np.array([[1000, 3500], [250, 2000], [1750, 350], [4250, 2400], [5600, 3900]],
                  dtype=float)
BALL = np.array([3000.0, 3200.0])


def test_consistent_lines_meet_at_the_target():
    rng = np.random.default_rng(0)
    for n in (2, 3, 5, 9):
        origins = rng.uniform(-5, 5, (n, 2))
        target = rng.uniform(-3, 3, 2)
        np.testing.assert_allclose(hough_fuse(origins, target - origins), target, atol=1e-9)


def test_paper_geometry_distances_and_exact_fusion():
    dist = np.hypot(*(BALL - ROBOTS).T)
    np.testing.assert_allclose(dist, [2022.4, 3000.4, 3112.1, 1484.1, 2692.6], atol=0.1)
    for weighting in ("equal", "inverse", "inverse_square"):
        fused = hough_fuse(ROBOTS, BALL - ROBOTS, weights=fusion_weights(dist, weighting))
        np.testing.assert_allclose(fused, BALL, atol=1e-6)


def test_is_the_weighted_least_squares_point_of_perpendicular_distances():
    rng = np.random.default_rng(1)
    origins = rng.uniform(-4, 4, (6, 2))
    angles = rng.uniform(-math.pi, math.pi, 6)
    k = rng.uniform(0.1, 2.0, 6)
    fused = hough_fuse(origins, angles=angles, weights=k)
    theta, rho = hough_lines(origins, angles=angles)
    A = np.stack([np.cos(theta), np.sin(theta)], axis=1) * np.sqrt(k)[:, None]
    expected = np.linalg.lstsq(A, rho * np.sqrt(k), rcond=None)[0]
    np.testing.assert_allclose(fused, expected, atol=1e-9)

    def cost(p):
        normal = np.stack([np.cos(theta), np.sin(theta)], axis=1)
        return np.sum(k * (rho - normal @ p) ** 2)

    for _ in range(20):  # no nearby point does better
        assert cost(fused) <= cost(fused + rng.normal(0, 0.05, 2)) + 1e-12


def test_frame_invariance_and_equivalent_inputs():
    rng = np.random.default_rng(2)
    origins = rng.uniform(-4, 4, (5, 2))
    dirs = rng.normal(0, 1, (5, 2))
    k = rng.uniform(0.5, 1.5, 5)
    fused = hough_fuse(origins, dirs, weights=k)
    # Angles instead of vectors, reversed directions, scaled weights: the same point.
    np.testing.assert_allclose(hough_fuse(origins, angles=np.arctan2(dirs[:, 1], dirs[:, 0]),
                                          weights=k), fused, atol=1e-9)
    np.testing.assert_allclose(hough_fuse(origins, -3.0 * dirs, weights=k), fused, atol=1e-9)
    np.testing.assert_allclose(hough_fuse(origins, dirs, weights=7.0 * k), fused, atol=1e-9)
    # A rotated and shifted scene gives the rotated and shifted point.
    a, shift = 0.8, np.array([10.0, -3.0])
    R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    np.testing.assert_allclose(hough_fuse(origins @ R.T + shift, dirs @ R.T, weights=k),
                               R @ fused + shift, atol=1e-9)


def test_distance_weighting_helps_when_bearing_noise_grows_error_with_distance():
    """With bearing noise, a sighting's lateral error grows with its distance, so 1/L
    weights beat equal ones on the paper's geometry (the paper: 87 against 118 mm)."""
    rng = np.random.default_rng(3)
    path = np.linspace(BALL, [4500.0, 1200.0], 50)
    errors = {"equal": [], "inverse": [], "inverse_square": []}
    for ball in path:
        for _ in range(20):
            true_dirs = ball - ROBOTS
            dist = np.hypot(*true_dirs.T)
            angles = np.arctan2(true_dirs[:, 1], true_dirs[:, 0]) + rng.normal(0, 0.05, 5)
            for w in errors:
                fused = hough_fuse(ROBOTS, angles=angles, weights=fusion_weights(dist, w))
                errors[w].append(np.hypot(*(fused - ball)))
    mean = {w: float(np.mean(e)) for w, e in errors.items()}
    assert mean["inverse"] < mean["equal"]
    assert mean["inverse_square"] < mean["inverse"]


def test_degenerate_and_bad_input_is_reported():
    with pytest.raises(ValueError, match="parallel"):
        hough_fuse([[0, 0], [0, 1], [0, 2]], angles=[0.0, 0.0, 1e-12])
    with pytest.raises(ValueError, match="at least two lines"):
        hough_fuse([[0, 0]], angles=[0.3])
    with pytest.raises(ValueError, match="at least two lines"):
        hough_fuse([[0, 0], [1, 0]], angles=[0.3, 1.2], weights=[1.0, 0.0])
    with pytest.raises(ValueError, match="exactly one of"):
        hough_fuse([[0, 0], [1, 0]])
    with pytest.raises(ValueError, match="exactly one of"):
        hough_fuse([[0, 0], [1, 0]], [[1, 0], [0, 1]], angles=[0.0, 1.0])
    with pytest.raises(ValueError, match="origins must have shape"):
        hough_fuse([0, 0, 1], angles=[0.0])
    with pytest.raises(ValueError, match="directions must have shape"):
        hough_fuse([[0, 0], [1, 0]], [[1, 0]])
    with pytest.raises(ValueError, match="non-zero"):
        hough_fuse([[0, 0], [1, 0]], [[1, 0], [0, 0]])
    with pytest.raises(ValueError, match="finite"):
        hough_fuse([[0, np.nan], [1, 0]], angles=[0.0, 1.0])
    with pytest.raises(ValueError, match="non-negative"):
        hough_fuse([[0, 0], [1, 0]], angles=[0.0, 1.0], weights=[1.0, -1.0])
    with pytest.raises(ValueError, match="weighting must be one of"):
        fusion_weights([1.0, 2.0], "cubic")
    with pytest.raises(ValueError, match="positive"):
        fusion_weights([1.0, 0.0])
