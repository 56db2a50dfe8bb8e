"""The inverse-variance weighting of the Hough fusion: each line weighted by the inverse of
its perpendicular offset's variance at the target, ``D^2 (sigma_b^2 + sigma_h^2) +
sigma_p^2`` (derivation in :mod:`estimators.fusion.hough`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators import (
    FUSION_WEIGHTINGS,
    INVERSE_VARIANCE,
    WEIGHTING_NAMES,
    fuse_lines,
    fuse_sightings,
    fusion_weights,
    hough_fuse,
    line_offset_variance,
)

# Xu et al. (2012), Table 1 [m]: the five robots and the ball's start.
ROBOTS = np.array([[1.0, 3.5], [0.25, 2.0], [1.75, 0.35], [4.25, 2.4], [5.6, 3.9]])
BALL = np.array([3.0, 3.2])


def _normals(psi: np.ndarray) -> np.ndarray:
    return np.column_stack([-np.sin(psi), np.cos(psi)])


def _covariance(n: np.ndarray, k: np.ndarray, var: np.ndarray) -> np.ndarray:
    """``M^-1 (sum K^2 s^2 n n^T) M^-1`` of the weighted line fit (first order)."""
    M = (k[:, None, None] * n[:, :, None] * n[:, None, :]).sum(axis=0)
    S = ((k * k * var)[:, None, None] * n[:, :, None] * n[:, None, :]).sum(axis=0)
    Mi = np.linalg.inv(M)
    return Mi @ S @ Mi


def test_the_offset_variance_formula_and_its_special_cases():
    D = np.array([0.5, 1.0, 2.0, 4.0])
    np.testing.assert_allclose(line_offset_variance(D, 0.03, 0.05, 0.02),
                               D**2 * (0.03**2 + 0.02**2) + 0.05**2)
    # Angles only (bearing and heading): proportional to 1/D^2, i.e. "inverse_square" -
    # not the paper's 1/D, which no error of a robot's pose or sighting gives.
    k = fusion_weights(D, INVERSE_VARIANCE, bearing_sigma=0.03, heading_sigma=0.02)
    ratio = k / fusion_weights(D, "inverse_square")
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-12)
    assert np.ptp(k / fusion_weights(D, "inverse")) > 0.1
    # Positions only (or isotropic noise on each estimate): equal weights.
    k = fusion_weights(D, INVERSE_VARIANCE, bearing_sigma=0.0, position_sigma=0.2)
    np.testing.assert_allclose(k, 1.0 / 0.2**2)
    assert INVERSE_VARIANCE in WEIGHTING_NAMES and INVERSE_VARIANCE not in FUSION_WEIGHTINGS


def test_the_formula_matches_the_simulated_offset_of_a_line():
    """A robot with position, heading and bearing errors draws a line whose offset at the
    target has the variance the formula gives (first order: within a few per cent)."""
    rng = np.random.default_rng(0)
    sb, sp, sh = 0.03, 0.1, 0.02
    target = np.array([0.0, 0.0])
    for robot in (np.array([-2.5, 0.7]), np.array([0.4, -0.9])):
        rel = target - robot
        D = float(np.hypot(*rel))
        m = 40_000
        pos = robot + rng.normal(0.0, sp, (m, 2))
        psi = math.atan2(rel[1], rel[0]) + rng.normal(0.0, sb, m) + rng.normal(0.0, sh, m)
        offset = np.einsum("ij,ij->i", _normals(psi), target - pos)
        expected = line_offset_variance([D], sb, sp, sh)[0]
        assert np.var(offset) == pytest.approx(expected, rel=0.03)


def test_inverse_variance_minimises_the_fused_covariance():
    """Gauss-Markov: no other weights give the fused point a smaller covariance (its trace,
    and in the positive semi-definite order)."""
    rng = np.random.default_rng(1)
    for _ in range(50):
        n_lines = int(rng.integers(2, 7))
        n = _normals(rng.uniform(-math.pi, math.pi, n_lines))
        D = rng.uniform(0.3, 6.0, n_lines)
        var = line_offset_variance(D, 0.03, 0.08, 0.01)
        best = _covariance(n, 1.0 / var, var)
        np.testing.assert_allclose(best, np.linalg.inv((n.T / var) @ n), rtol=1e-9)
        for k in (np.ones(n_lines), 1.0 / D, 1.0 / D**2, rng.uniform(0.1, 3.0, n_lines)):
            other = _covariance(n, k, var)
            assert np.trace(best) <= np.trace(other) * (1.0 + 1e-9)
            assert np.linalg.eigvalsh(other - best).min() >= -1e-9 * np.trace(other)


def test_inverse_variance_lowers_the_error_against_the_truth():
    """Robots near and far, with position and bearing errors of which neither dominates:
    the inverse-variance weights beat equal, 1/L and 1/L^2 weights on the same draws."""
    rng = np.random.default_rng(2)
    robots = np.array([[0.3, 0.2], [-0.2, 0.5], [4.0, 3.0], [-5.0, 1.0], [1.0, -6.0]])
    target = np.zeros(2)
    rel = target - robots
    D = np.hypot(rel[:, 0], rel[:, 1])
    sb, sp = 0.05, 0.15  # the two terms equal at D = 3 m
    weights = {w: fusion_weights(D, w) for w in FUSION_WEIGHTINGS}
    weights[INVERSE_VARIANCE] = fusion_weights(D, INVERSE_VARIANCE, bearing_sigma=sb,
                                               position_sigma=sp)
    errors = {w: [] for w in weights}
    for _ in range(3000):
        pos = robots + rng.normal(0.0, sp, robots.shape)
        psi = np.arctan2(rel[:, 1], rel[:, 0]) + rng.normal(0.0, sb, len(robots))
        for w, k in weights.items():
            errors[w].append(np.hypot(*(hough_fuse(pos, angles=psi, weights=k) - target)))
    mean = {w: float(np.mean(e)) for w, e in errors.items()}
    for w in FUSION_WEIGHTINGS:
        assert mean[INVERSE_VARIANCE] < 0.97 * mean[w], mean


def test_fuse_sightings_refuses_at_the_first_fused_point():
    """weighting="inverse_variance": the lines fused with 1/L weights, then again with the
    inverse variances at that point; exact on consistent lines; with two lines (no chi^2
    inflation) the covariance is (sum n n^T / s^2)^-1."""
    rng = np.random.default_rng(3)
    d = BALL - ROBOTS
    angles = np.arctan2(d[:, 1], d[:, 0])
    ranges = np.hypot(d[:, 0], d[:, 1])
    res = fuse_sightings(ROBOTS, angles, ranges, weighting=INVERSE_VARIANCE,
                         bearing_sigma=0.03, position_sigma=0.05, heading_sigma=0.01)
    np.testing.assert_allclose(res.point, BALL, atol=1e-9)
    assert res.fused and res.n_lines == 5
    for _ in range(20):
        noisy = angles + rng.normal(0.0, 0.03, 5)
        got = fuse_sightings(ROBOTS, noisy, ranges, weighting=INVERSE_VARIANCE,
                             bearing_sigma=0.03, position_sigma=0.05, heading_sigma=0.01)
        first = hough_fuse(ROBOTS, angles=noisy, weights=fusion_weights(ranges, "inverse"))
        D = np.hypot(*(first - ROBOTS).T)
        k = fusion_weights(D, INVERSE_VARIANCE, bearing_sigma=0.03, position_sigma=0.05,
                           heading_sigma=0.01)
        np.testing.assert_allclose(got.point, hough_fuse(ROBOTS, angles=noisy, weights=k),
                                   atol=1e-12)
    two = fuse_sightings(ROBOTS[:2], angles[:2] + [0.02, -0.01], ranges[:2],
                         weighting=INVERSE_VARIANCE, bearing_sigma=0.03, position_sigma=0.05)
    n = _normals(angles[:2] + [0.02, -0.01])
    var = line_offset_variance(np.hypot(*(two.point - ROBOTS[:2]).T), 0.03, 0.05)
    np.testing.assert_allclose(two.cov, np.linalg.inv((n.T / var) @ n), rtol=1e-9)


def test_fuse_lines_with_pose_sigmas_is_fuse_sightings_without_the_checks():
    rng = np.random.default_rng(4)
    for trial in range(100):
        n = int(rng.integers(1, 5))
        origins = rng.uniform(-4, 4, (n, 2))
        rel = rng.uniform(-2, 2, 2) - origins
        angles = np.arctan2(rel[:, 1], rel[:, 0]) + rng.normal(0, 0.05, n)
        if trial % 7 == 0:
            angles[:] = angles[0] + rng.normal(0, 0.01, n)  # nearly parallel
        ranges = np.hypot(*rel.T) * rng.uniform(0.9, 1.1, n)
        ranges[rng.random(n) < 0.3] = np.nan
        try:
            ref = fuse_sightings(origins, angles, ranges, weighting=INVERSE_VARIANCE,
                                 bearing_sigma=0.02, range_sigma_rel=0.07,
                                 position_sigma=0.04, heading_sigma=0.01)
        except ValueError:
            with pytest.raises(ValueError, match="no position"):
                fuse_lines(origins.tolist(), angles.tolist(), ranges.tolist(), 1, 0.02, 0.07,
                           math.radians(5.0), pose_sigmas=(0.04, 0.01))
            continue
        got = fuse_lines(origins.tolist(), angles.tolist(), ranges.tolist(), 1, 0.02, 0.07,
                         math.radians(5.0), pose_sigmas=(0.04, 0.01))
        np.testing.assert_array_equal(got.point, ref.point)
        np.testing.assert_array_equal(got.cov, ref.cov)


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match=r"position_sigma must be finite and >= 0"):
        line_offset_variance([1.0], 0.01, -0.1)
    with pytest.raises(ValueError, match=r"heading_sigma must be finite and >= 0"):
        line_offset_variance([1.0], 0.01, 0.0, math.nan)
    with pytest.raises(ValueError, match=r"bearing_sigma must be finite and >= 0"):
        line_offset_variance([1.0], -0.01)
    with pytest.raises(ValueError, match="at least one must be > 0"):
        line_offset_variance([1.0], 0.0)
    with pytest.raises(ValueError, match="distances must be"):
        line_offset_variance([1.0, 0.0], 0.01)
    with pytest.raises(ValueError, match="needs bearing_sigma"):
        fusion_weights([1.0, 2.0], INVERSE_VARIANCE)
    with pytest.raises(ValueError, match="apply to weighting 'inverse_variance' only"):
        fusion_weights([1.0, 2.0], "inverse", bearing_sigma=0.01)
    with pytest.raises(ValueError, match="apply to weighting 'inverse_variance' only"):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3, 1.0], [1.0, 1.0], position_sigma=0.1)
    with pytest.raises(ValueError, match="position_sigma must be finite and >= 0"):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3, 1.0], [1.0, 1.0],
                       weighting=INVERSE_VARIANCE, position_sigma=-0.1)
    with pytest.raises(ValueError, match=r"weighting must be one of \[.*'inverse_variance'\], "
                                         r"got 'cubic'"):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3, 1.0], [1.0, 1.0], weighting="cubic")
