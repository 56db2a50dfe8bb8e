"""The compiled Kalman blocks are the full Kalman equations."""

from __future__ import annotations

import numpy as np

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


def test_the_blocks_match_the_full_kalman_equations():
    rng = np.random.default_rng(4)
    P = blocks.blocks_from_row(random_blocks(rng, 1)[0])
    A, B, q = (0.02, 0.001, -0.002, 0.03), (0.9, 0.01, 0.02, 0.95), 0.3
    F = np.block([[np.eye(2), np.reshape(A, (2, 2))], [np.zeros((2, 2)), np.reshape(B, (2, 2))]])
    full = F @ blocks.full_covariance(P) @ F.T + np.diag([0.0, 0.0, q, q])
    np.testing.assert_allclose(blocks.full_covariance(blocks.predict_covariance(P, A, B, q)),
                               full, rtol=1e-12, atol=1e-12)
