"""The compiled Kalman blocks: a row of the batched kernels is the single filter's block to the
bit, the blocks are the full Kalman equations, and bad shapes are refused by name."""

from __future__ import annotations

import numpy as np
import pytest

from estimators.kalman import blocks


def random_blocks(rng: np.random.Generator, d: int) -> np.ndarray:
    """``(d, 12)`` covariances: symmetric positive definite 4 x 4 matrices in block rows."""
    rows = np.empty((d, 12))
    for i in range(d):
        m = rng.normal(size=(4, 4))
        c = m @ m.T + 0.1 * np.eye(4)
        rows[i] = np.concatenate([c[0:2, 0:2].ravel(), c[0:2, 2:4].ravel(),
                                  c[2:4, 2:4].ravel()])
    return rows


def test_rows_are_the_single_blocks_to_the_bit():
    rng = np.random.default_rng(3)
    d, k, r = 7, 3, 2.5e-5
    P = random_blocks(rng, d)
    A, B = rng.normal(size=(d, 4)), rng.normal(size=(d, 4))
    q, x, z = rng.uniform(0, 1, d), rng.normal(size=(d, 4)), rng.normal(size=(d, k, 2))
    Pn = blocks.predict_covariance_rows(P, A, B, q)
    y0, y1, Si, d2 = blocks.innovation_rows(x, Pn, z, r)
    xn, Pu = blocks.update_rows(x, Pn, y0[:, 1], y1[:, 1], tuple(s[:, 0] for s in Si), r)
    for i in range(d):
        Pi = blocks.predict_covariance(blocks.blocks_from_row(P[i]), tuple(A[i]), tuple(B[i]),
                                       float(q[i]))
        assert Pi == blocks.blocks_from_row(Pn[i])
        xi = tuple(x[i].tolist())
        for j in range(k):
            y, S, dist2 = blocks.innovation(xi, Pi, (float(z[i, j, 0]), float(z[i, j, 1])), r)
            assert (y0[i, j], y1[i, j], d2[i, j]) == (y[0], y[1], dist2)
            assert (Si[0][i, 0], Si[1][i, 0], Si[2][i, 0]) == (S[0], S[1], S[3])
        y, S, _ = blocks.innovation(xi, Pi, (float(z[i, 1, 0]), float(z[i, 1, 1])), r)
        xs, Ps = blocks.update(xi, Pi, y, S, r)
        assert xs == tuple(xn[i].tolist()) and Ps == blocks.blocks_from_row(Pu[i])


def test_the_blocks_match_the_full_kalman_equations():
    rng = np.random.default_rng(4)
    P = blocks.blocks_from_row(random_blocks(rng, 1)[0])
    A, B, q = (0.02, 0.001, -0.002, 0.03), (0.9, 0.01, 0.02, 0.95), 0.3
    F = np.block([[np.eye(2), np.reshape(A, (2, 2))], [np.zeros((2, 2)), np.reshape(B, (2, 2))]])
    full = F @ blocks.full_covariance(P) @ F.T + np.diag([0.0, 0.0, q, q])
    np.testing.assert_allclose(blocks.full_covariance(blocks.predict_covariance(P, A, B, q)),
                               full, rtol=1e-12, atol=1e-12)


def test_innovation_rows_names_a_bad_shape():
    x, P = np.zeros((2, 4)), random_blocks(np.random.default_rng(5), 2)
    with pytest.raises(ValueError, match=r"z must have the shape \(d, k, 2\)"):
        blocks.innovation_rows(x, P, np.zeros((2, 2)), 1e-4)
    with pytest.raises(ValueError, match="d = 2 filters"):
        blocks.innovation_rows(x, P, np.zeros((3, 1, 2)), 1e-4)
