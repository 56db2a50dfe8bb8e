"""The particle filters' compiled kernels against the same maths written as numpy arrays."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators.particle.core import sfn, systematic_resample
from estimators.particle.filter_kernels import (
    drift,
    position_likelihood,
    position_moments,
    systematic_indices,
    transition,
    weighted_mean,
)


def _weights(n, seed):
    w = np.random.default_rng(seed).random(n) ** 4
    return w / w.sum()


@pytest.mark.parametrize("n", [2, 7, 100, 1000])
def test_systematic_indices_are_numpy_s_search_bit_for_bit(n):
    w = _weights(n, n)
    for offset in (0.0, 0.3, 0.999999):
        cumulative = np.cumsum(w)
        cumulative[-1] = 1.0
        expected = np.searchsorted(cumulative, (offset + np.arange(n)) / n,
                                   side="right").clip(0, n - 1)
        np.testing.assert_array_equal(systematic_indices(w, offset), expected)


def _numpy_sfn(particles, weights, noise, scale):
    """Sorting, fission and normalising written with numpy arrays."""
    n = len(weights)
    order = np.argsort(-weights, kind="stable")
    p, w = particles[order], weights[order]
    children = np.maximum(np.floor(n * w).astype(int) - 1, 0)
    k = int(children.sum())
    parents = np.repeat(np.arange(n), children)
    new_p, new_w = p.copy(), w / (children + 1)
    new_p[n - k:] = p[parents] + noise * scale
    new_w[n - k:] = new_w[parents]
    return new_p, new_w / new_w.sum(), k


def test_sfn_is_sorting_fission_and_normalising():
    rng = np.random.default_rng(1)
    particles = rng.normal(0.0, 1.0, (50, 4))
    weights = _weights(50, 2)
    variance = np.array([0.01, 0.01, 0.04, 0.04])
    p, w, born = sfn(particles, weights, np.random.default_rng(3), variance)
    expect_p, expect_w, k = _numpy_sfn(particles, weights, np.random.default_rng(3)
                                       .standard_normal((_children(weights), 4)),
                                       np.sqrt(variance))
    assert k > 0 and born.sum() == k and born[-k:].all()
    np.testing.assert_array_equal(p, expect_p)
    np.testing.assert_allclose(w, expect_w, rtol=1e-14)
    assert math.isclose(w.sum(), 1.0, rel_tol=1e-14)


def _children(weights):
    n = len(weights)
    return int(np.maximum(np.floor(n * weights).astype(int) - 1, 0).sum())


def test_sfn_without_heavy_particles_only_sorts():
    weights = np.array([0.2, 0.3, 0.25, 0.25])
    p, w, born = sfn(np.arange(8.0).reshape(4, 2), weights, np.random.default_rng(0), 1.0)
    np.testing.assert_array_equal(p, [[2.0, 3.0], [4.0, 5.0], [6.0, 7.0], [0.0, 1.0]])
    np.testing.assert_allclose(w, [0.3, 0.25, 0.25, 0.2])
    assert not born.any()


def test_systematic_resample_keeps_the_generator_s_stream():
    w = _weights(30, 4)
    a, b = np.random.default_rng(5), np.random.default_rng(5)
    idx = systematic_resample(w, a)
    assert a.random() == (b.random(), b.random())[1]  # one draw taken
    assert idx.dtype.kind == "i" and (np.diff(idx) >= 0).all()


@pytest.mark.parametrize("a", [0.0, 0.4])
def test_drift_is_the_closed_form_decelerating_motion(a):
    x = np.array([[0.0, 0.0, 1.0, 0.0], [1.0, 1.0, 0.0, -0.1], [2.0, 0.0, 0.0, 0.0]])
    out = drift(x, 0.5, a)
    if a == 0.0:
        np.testing.assert_array_equal(out, x + np.column_stack([0.5 * x[:, 2:], 0 * x[:, 2:]]))
        return
    # 1 m/s for 0.5 s at 0.4 m/s^2: s = 0.5 - 0.05, v = 0.8; 0.1 m/s stops after 0.25 s.
    np.testing.assert_allclose(out[0], [0.45, 0.0, 0.8, 0.0], atol=1e-15)
    np.testing.assert_allclose(out[1], [1.0, 1.0 - 0.1 * 0.25 / 2, 0.0, 0.0], atol=1e-15)
    np.testing.assert_array_equal(out[2], x[2])


def test_transition_adds_the_acceleration_through_b():
    x = np.zeros((2, 4))
    w = np.array([[1.0, 0.0], [0.0, -2.0]])
    out = transition(x, 0.1, 0.0, w)
    np.testing.assert_allclose(out, [[0.005, 0.0, 0.1, 0.0], [0.0, -0.01, 0.0, -0.2]])


def test_position_likelihood_and_moments():
    rng = np.random.default_rng(6)
    x = rng.normal(0.0, 1.0, (40, 4))
    R = np.array([[0.04, 0.01], [0.01, 0.09]])
    a, b, _, c = np.linalg.inv(R).ravel()
    z, lag = np.array([0.2, -0.1]), 0.05
    d = x[:, :2] - lag * x[:, 2:] - z
    m = np.einsum("ni,ij,nj->n", d, np.linalg.inv(R), d)
    np.testing.assert_allclose(position_likelihood(x, (0.2, -0.1), lag, (a, b, c)),
                               np.exp(-0.5 * (m - m.min())), rtol=1e-12)
    w = _weights(40, 7) * 3.0  # any positive total
    mx, my, cxx, cxy, cyy = position_moments(x, w, lag)
    p = x[:, :2] - lag * x[:, 2:]
    np.testing.assert_allclose([mx, my], (w / w.sum()) @ p, rtol=1e-12)
    np.testing.assert_allclose([[cxx, cxy], [cxy, cyy]],
                               np.cov(p.T, aweights=w, bias=True), rtol=1e-12)
    np.testing.assert_allclose(weighted_mean(w, x, 0.5), 0.5 * (w @ x), rtol=1e-12)
