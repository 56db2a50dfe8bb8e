"""The compiled scalar ports of CPython's ``math`` functions equal them bit for bit."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

from estimators.exact import hypot_exact, wrap_angle


@pytest.mark.skipif(sys.version_info < (3, 11), reason="math.hypot's algorithm since 3.11")
def test_hypot_exact_is_math_hypot_bit_for_bit():
    rng = np.random.default_rng(0)
    x = np.concatenate([rng.normal(0.0, 3.0, 100_000), rng.uniform(-1e-3, 1e-3, 20_000),
                        np.exp(rng.uniform(-700.0, 700.0, 20_000))
                        * rng.choice([-1.0, 1.0], 20_000)])
    y = np.concatenate([rng.normal(0.0, 3.0, 100_000), rng.uniform(-1e-3, 1e-3, 20_000),
                        np.exp(rng.uniform(-700.0, 700.0, 20_000))])
    edges = [0.0, -0.0, 5e-324, -5e-324, 2.2e-308, 1e-310, 1.0, 3.0, 4.0, 1e308, 1.7e308,
             math.inf, -math.inf, math.nan]
    pairs = list(zip(x.tolist(), y.tolist())) + [(a, b) for a in edges for b in edges]
    differ = [(a, b) for a, b in pairs
              if not (hypot_exact(a, b) == math.hypot(a, b)
                      or (math.isnan(hypot_exact(a, b)) and math.isnan(math.hypot(a, b))))]
    assert differ == []
    # The C library's hypot (numba's math.hypot) differs from math.hypot on some of these.
    assert np.any(np.hypot(x, y) != [math.hypot(a, b) for a, b in zip(x, y)])


def test_wrap_angle_is_math_remainder_bit_for_bit():
    rng = np.random.default_rng(1)
    angles = np.concatenate([rng.uniform(-20.0, 20.0, 20_000), [0.0, -0.0, math.pi, -math.pi,
                                                                 3.0 * math.pi, 1e300]])
    for a in angles.tolist():
        assert wrap_angle(a) == math.remainder(a, 2.0 * math.pi)
