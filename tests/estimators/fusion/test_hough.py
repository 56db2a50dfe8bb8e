"""Hough-space fusion (Xu et al. 2012): exact on consistent lines, the least-squares point of
inconsistent ones, invariant to the frame, better weighted when bearings are noisy."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators.fusion import FusedSighting, fuse_sightings, fusion_weights, hough_fuse, hough_lines

# Xu et al. (2012), Table 1 (millimetres): the five robots and the ball's start.
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
    with pytest.raises(ValueError, match=r"distances must be a 1-d array of finite numbers in "
                                         r"\[1e-06, 1e\+06\] m"):
        fusion_weights([1.0, 0.0])


# --------------------------------------------------------------------------------------------
# fuse_sightings: a team's timestamped sightings
# --------------------------------------------------------------------------------------------

ROBOTS_M = ROBOTS / 1000.0
BALL_M = BALL / 1000.0


def _sightings(ball, robots=ROBOTS_M):
    d = ball - robots
    return np.arctan2(d[:, 1], d[:, 0]), np.hypot(d[:, 0], d[:, 1])


def test_fuse_sightings_exact_on_consistent_sightings():
    angles, ranges = _sightings(BALL_M)
    res = fuse_sightings(ROBOTS_M, angles, ranges)
    assert isinstance(res, FusedSighting) and res.fused and res.n_lines == 5
    np.testing.assert_allclose(res.point, BALL_M, atol=1e-9)
    assert res.sigma > 0.0 and res.cov.shape == (2, 2)
    # Bearing-only sightings (NaN ranges) still cross at the target.
    ranges[[1, 3]] = np.nan
    res = fuse_sightings(ROBOTS_M, angles, ranges)
    assert res.fused and res.n_lines == 5
    np.testing.assert_allclose(res.point, BALL_M, atol=1e-9)


def test_fuse_sightings_weights_bearing_only_lines_as_far_ones():
    """A NaN range weighs like twice the largest known range (the paper's 1/L weights)."""
    rng = np.random.default_rng(4)
    angles, ranges = _sightings(BALL_M)
    angles = angles + rng.normal(0, 0.05, 5)
    ranges[[0, 2]] = np.nan
    L = np.where(np.isfinite(ranges), ranges, 2.0 * np.nanmax(ranges))
    for weighting in ("equal", "inverse", "inverse_square"):
        expected = hough_fuse(ROBOTS_M, angles=angles, weights=fusion_weights(L, weighting))
        res = fuse_sightings(ROBOTS_M, angles, ranges, weighting=weighting)
        np.testing.assert_allclose(res.point, expected, atol=1e-12)


def test_fuse_sightings_moves_old_sightings_with_the_velocity():
    """The ball rolls at v; each robot saw it at its own stamp. Shifting every line by
    v (now - stamp) gives the ball's position now exactly; without the velocity the old
    sightings pull the point back."""
    v = np.array([1.5, -0.8])
    now = 10.0
    stamps = np.array([9.70, 9.84, 9.92, 9.96, 10.0])
    angles, ranges = np.empty(5), np.empty(5)
    for i, s in enumerate(stamps):
        a, r = _sightings(BALL_M + v * (s - now), ROBOTS_M[i:i + 1])
        angles[i], ranges[i] = a[0], r[0]
    res = fuse_sightings(ROBOTS_M, angles, ranges, stamps, now=now, velocity=v)
    np.testing.assert_allclose(res.point, BALL_M, atol=1e-9)
    # now defaults to the latest stamp.
    np.testing.assert_allclose(fuse_sightings(ROBOTS_M, angles, ranges, stamps, velocity=v).point,
                               BALL_M, atol=1e-9)
    stale = fuse_sightings(ROBOTS_M, angles, ranges, stamps, now=now)
    assert np.hypot(*(stale.point - BALL_M)) > 0.05


def test_fuse_sightings_falls_back_to_ranged_points():
    # One sighting with a range: its point estimate, with a range-based error scale.
    res = fuse_sightings([[0.0, 0.0]], [0.5], [2.0], bearing_sigma=0.05, range_sigma_rel=0.1)
    assert not res.fused and res.n_lines == 1
    np.testing.assert_allclose(res.point, [2 * math.cos(0.5), 2 * math.sin(0.5)], atol=1e-12)
    assert res.sigma == pytest.approx(2.0 * math.sqrt((0.1**2 + 0.05**2) / 2))
    u = np.array([math.cos(0.5), math.sin(0.5)])
    assert u @ res.cov @ u == pytest.approx((0.2) ** 2)  # along the line: the range error
    # Two robots in line with the ball: the lines (nearly) coincide, the ranged points fuse
    # as their 1/L-weighted mean; the bearing-only one is dropped.
    origins = np.array([[0.0, 0.0], [1.0, 0.001], [-1.0, 0.0]])
    res = fuse_sightings(origins, [0.0, 0.0, 0.0], [2.1, 0.9, np.nan])
    assert not res.fused and res.n_lines == 2
    k = np.array([1 / 2.1, 1 / 0.9])
    np.testing.assert_allclose(res.point, (k @ np.array([[2.1, 0.0], [1.9, 0.001]])) / k.sum(),
                               atol=1e-12)
    # Shallow crossing, nothing ranged: still fused, with a long error ellipse.
    res = fuse_sightings([[0.0, 0.0], [0.0, 0.1]], [0.0, -0.05], [np.nan, np.nan])
    assert res.fused
    np.testing.assert_allclose(res.point, [0.1 / math.tan(0.05), 0.0], atol=1e-9)
    assert np.sqrt(res.cov[0, 0]) > 10 * np.sqrt(res.cov[1, 1])


def test_fuse_sightings_error_scale_matches_the_scatter():
    """With bearing noise of bearing_sigma, two lines' covariance is the fused point's
    (within sampling error); with five it errs on the large side (the residual inflation)
    but not by much."""
    rng = np.random.default_rng(7)
    for idx, low, high in (([0, 3], 0.85, 1.15), ([0, 1, 2, 3, 4], 1.0, 2.0)):
        angles, ranges = _sightings(BALL_M, ROBOTS_M[idx])
        points, traces = [], []
        for _ in range(3000):
            a = angles + rng.normal(0, 0.05, len(idx))
            res = fuse_sightings(ROBOTS_M[idx], a, ranges, bearing_sigma=0.05)
            points.append(res.point)
            traces.append(np.trace(res.cov))
        scatter = np.mean(np.sum((np.array(points) - BALL_M) ** 2, axis=1))
        assert low < np.mean(traces) / scatter < high


def test_fuse_sightings_no_position_and_bad_input():
    with pytest.raises(ValueError, match="no position"):
        fuse_sightings([[0.0, 0.0]], [0.3], [np.nan])
    with pytest.raises(ValueError, match="no position"):
        fuse_sightings([[0.0, 0.0], [0.0, 1.0]], [0.0, 0.0], [np.nan, np.nan])
    with pytest.raises(ValueError, match="origins"):
        fuse_sightings(np.zeros((0, 2)), [], [])
    with pytest.raises(ValueError, match="angles"):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3], [1.0, 1.0])
    with pytest.raises(ValueError, match="ranges must have shape"):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3, 1.0], [1.0])
    with pytest.raises(ValueError, match="ranges must be > 0"):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3, 1.0], [1.0, -1.0])
    with pytest.raises(ValueError, match="weighting"):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3, 1.0], [1.0, 1.0], weighting="cubic")
    with pytest.raises(ValueError, match="stamps"):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3, 1.0], [1.0, 1.0], [0.0], velocity=[1, 0])
    with pytest.raises(ValueError, match="velocity"):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3, 1.0], [1.0, 1.0], [0.0, 0.1],
                       velocity=[1.0, np.nan])
    with pytest.raises(ValueError, match="bearing_sigma"):
        fuse_sightings([[0.0, 0.0]], [0.3], [1.0], bearing_sigma=0.0)
    with pytest.raises(ValueError, match="min_angle"):
        fuse_sightings([[0.0, 0.0]], [0.3], [1.0], min_angle=2.0)


def test_fuse_lines_is_fuse_sightings_without_the_checks():
    """The unchecked plain-list path gives fuse_sightings' results bit for bit: crossing
    lines, shallow crossings, bearing-only lines, one ranged line, lines moved to a common
    time."""
    from estimators.fusion import FUSION_WEIGHTINGS, fuse_lines

    rng = np.random.default_rng(3)
    for trial in range(300):
        n = int(rng.integers(1, 5))
        origins = rng.uniform(-4, 4, (n, 2))
        target = rng.uniform(-2, 2, 2)
        rel = target - origins
        angles = np.arctan2(rel[:, 1], rel[:, 0]) + rng.normal(0, 0.05, n)
        if trial % 7 == 0:
            angles[:] = angles[0] + rng.normal(0, 0.01, n)  # nearly parallel
        ranges = np.hypot(*rel.T) * rng.uniform(0.9, 1.1, n)
        ranges[rng.random(n) < 0.3] = np.nan
        stamps = rng.uniform(0.0, 0.1, n)
        velocity = rng.normal(0, 1, 2)
        weighting = ("equal", "inverse", "inverse_square")[trial % 3]
        try:
            ref = fuse_sightings(origins, angles, ranges, stamps, 0.1, velocity, weighting,
                                 bearing_sigma=0.02, range_sigma_rel=0.07)
        except ValueError:
            with pytest.raises(ValueError, match="no position"):
                moved = origins + np.outer(0.1 - stamps, velocity)
                fuse_lines(moved.tolist(), angles.tolist(), ranges.tolist(),
                           FUSION_WEIGHTINGS[weighting], 0.02, 0.07, math.radians(5.0))
            continue
        if trial % 2:  # moved by the caller, or by fuse_lines
            moved = origins + np.outer(0.1 - stamps, velocity)
            got = fuse_lines(moved.tolist(), angles.tolist(), ranges.tolist(),
                             FUSION_WEIGHTINGS[weighting], 0.02, 0.07, math.radians(5.0))
        else:
            got = fuse_lines(origins.tolist(), angles.tolist(), ranges.tolist(),
                             FUSION_WEIGHTINGS[weighting], 0.02, 0.07, math.radians(5.0),
                             stamps.tolist(), 0.1, tuple(velocity.tolist()))
        np.testing.assert_array_equal(got.point, ref.point)
        np.testing.assert_array_equal(got.cov, ref.cov)
        assert (got.n_lines, got.fused, got.sigma) == (ref.n_lines, ref.fused, ref.sigma)
