"""The localization's compiled kernels against the same maths written as numpy arrays."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators.exact import floor_remainder
from estimators.particle.localization_kernels import (
    best_log_likelihood,
    kld_sample_count,
    move_particles,
    weigh,
    weighted_pose,
    weighted_spread,
)

SIGMAS = (0.05, 0.05, 0.02)


def _numpy_best(P, Lx, Ly, counts, r, b, sigma_b):
    """Every (sighting, candidate) pair as a column, the best candidate per sighting, the
    sum over the sightings."""
    rr = np.repeat(r, counts)
    dx = Lx - P[:, 0, None]
    dy = Ly - P[:, 1, None]
    sigma = SIGMAS[0] + (SIGMAS[1] + SIGMAS[2] * rr) * rr
    log = -0.5 * ((np.hypot(dx, dy) - rr) / sigma) ** 2
    if sigma_b > 0.0:
        err = np.remainder(np.arctan2(dy, dx) - P[:, 2, None] - np.repeat(b, counts)
                           + math.pi, 2.0 * math.pi) - math.pi
        log += -0.5 * (err / sigma_b) ** 2
    starts = np.cumsum(counts) - counts
    return sum(log[:, s:s + c].max(axis=1) for s, c in zip(starts, counts))


@pytest.mark.parametrize("sigma_b", [0.0, math.radians(5.0)])
def test_best_log_likelihood_is_the_best_candidate_summed_over_sightings(sigma_b):
    rng = np.random.default_rng(1)
    P = np.column_stack([rng.uniform(-4, 4, 300), rng.uniform(-3, 3, 300),
                         rng.uniform(-math.pi, math.pi, 300)])
    counts = np.array([1, 4, 2, 3])
    Lx, Ly = rng.uniform(-4.5, 4.5, counts.sum()), rng.uniform(-3, 3, counts.sum())
    r, b = rng.uniform(0.5, 5.0, 4), rng.uniform(-1.0, 1.0, 4)
    got = best_log_likelihood(P, Lx, Ly, counts, r, b, SIGMAS, sigma_b)
    np.testing.assert_allclose(got, _numpy_best(P, Lx, Ly, counts, r, b, sigma_b),
                               rtol=1e-9, atol=1e-9)


def test_floor_remainder_is_numpy_s_remainder_bit_for_bit():
    rng = np.random.default_rng(2)
    a = np.concatenate([rng.normal(0.0, 10.0, 2000), [0.0, -0.0, 2 * math.pi, -2 * math.pi,
                                                     math.pi, -math.pi, 1e300, -1e-300]])
    for b in (2.0 * math.pi, -3.0, 0.5):
        expected = np.remainder(a, b)
        got = np.array([floor_remainder(float(x), b) for x in a])
        np.testing.assert_array_equal(got, expected)
        assert (np.signbit(got) == np.signbit(expected)).all()


def test_weigh_normalises_and_averages_as_the_formulas_say():
    rng = np.random.default_rng(3)
    w = rng.random(50)
    w /= w.sum()
    log = rng.normal(-20.0, 5.0, 50)
    new, total, mean = weigh(w, log, 3)
    expected = w * np.exp(log - log.max())
    np.testing.assert_allclose(total, expected.sum(), rtol=1e-13)
    np.testing.assert_allclose(new, expected / expected.sum(), rtol=1e-13)
    np.testing.assert_allclose(mean, w @ np.exp(log / 3), rtol=1e-13)


def test_weigh_falls_back_to_uniform_weights_when_nothing_is_likely():
    new, total, _ = weigh(np.full(4, 0.25), np.full(4, -np.inf), 2)
    assert not math.isfinite(total)
    np.testing.assert_array_equal(new, np.full(4, 0.25))


def test_move_particles_applies_the_displacement_in_each_particle_s_frame():
    p = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, math.pi / 2], [0.0, 0.0, math.pi - 0.01]])
    move_particles(p, (0.1, 0.0, 0.02), np.zeros((3, 3)), (0.1, 0.02, 0.2, 0.05))
    np.testing.assert_allclose(p[0], [0.1 * math.cos(0.01), 0.1 * math.sin(0.01), 0.02],
                               atol=1e-15)
    np.testing.assert_allclose(p[1], [1.0 - 0.1 * math.sin(0.01), 2.0 + 0.1 * math.cos(0.01),
                                      math.pi / 2 + 0.02], atol=1e-15)
    assert p[2, 2] == pytest.approx(-math.pi + 0.01)  # wrapped into [-pi, pi)


def test_move_particles_spreads_with_the_motion():
    noise = np.random.default_rng(4).standard_normal((20000, 3))
    p = np.zeros((20000, 3))
    move_particles(p, (0.5, 0.0, 0.0), noise, (0.1, 0.02, 0.2, 0.05))
    assert np.std(p[:, 1]) == pytest.approx(0.1 * 0.5, rel=0.03)
    assert np.std(p[:, 2]) == pytest.approx(0.05 * 0.5, rel=0.03)


def test_kld_sample_count_stops_at_the_first_prefix_the_bound_allows():
    rows = np.array([[0.05, 0.05, 0.0], [0.1, 0.1, 0.0], [0.5, 0.0, 0.0], [0.9, 0.0, 0.0]])
    size = (0.2, 0.2, 0.3)
    bound = np.array([1.0, 1.0, 3.0, 4.0, 99.0])  # by the number of occupied bins
    assert kld_sample_count(rows, size, bound, 1) == 1  # one bin, one draw
    assert kld_sample_count(rows, size, bound, 2) == 2  # still one bin: 2 >= bound[1]
    assert kld_sample_count(rows, size, bound, 3) == 3  # two bins: 3 >= bound[2]
    assert kld_sample_count(rows, size, np.array([1.0, 1.0, 9.0, 9.0, 9.0]), 3) == 0


def test_weighted_pose_and_spread():
    p = np.array([[1.0, 0.0, math.pi - 0.1], [3.0, 2.0, -math.pi + 0.1]])
    w = np.array([0.5, 0.5])
    x, y, theta, r = weighted_pose(w, p)
    assert (x, y) == (2.0, 1.0)
    assert abs(abs(theta) - math.pi) < 1e-12  # the circular mean across the seam
    assert r == pytest.approx(math.cos(0.1))
    assert weighted_spread(w, p, x, y) == pytest.approx(math.sqrt(2.0))


@pytest.mark.parametrize("seed", range(5))
def test_kld_sample_count_counts_distinct_bins_as_a_set_does(seed):
    rng = np.random.default_rng(seed)
    size = (0.1, 0.1, 0.2)
    cells = rng.integers(-2, 2, size=(400, 3)) * rng.choice([1, 10**6], size=(400, 1))
    rows = (cells + rng.uniform(0.01, 0.99, size=(400, 3))) * size  # negative and huge bins
    bound = 1.5 * np.arange(402.0)
    bins, expected = set(), 0
    for i, row in enumerate(rows):
        bins.add(tuple(np.floor(row / size).astype(np.int64)))
        if i + 1 >= 10 and i + 1 >= bound[len(bins)]:
            expected = i + 1
            break
    assert expected > 0
    assert kld_sample_count(rows, size, bound, 10) == expected
