"""The compiled ports of CPython's ``math`` functions and numpy's stable argsort and searchsorted
equal them bit for bit."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

from estimators.exact import hypot_exact, search_right, stable_argsort, wrap_angle


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


def _sort_cases():
    rng = np.random.default_rng(7)
    yield np.array([])
    yield np.array([1.0])
    yield rng.integers(0, 4, 37).astype(float)  # many ties
    yield np.array([0.0, -0.0, np.nan, 1.0, np.nan, -np.inf, np.inf, -0.0])
    for n in (2, 3, 20, 21, 64, 1000):
        yield rng.normal(size=n)


@pytest.mark.parametrize("keys", list(_sort_cases()), ids=lambda k: f"n{len(k)}")
def test_stable_argsort_is_numpys_stable_argsort(keys):
    assert np.array_equal(stable_argsort(keys), np.argsort(keys, kind="stable"))


@pytest.mark.parametrize("keys", list(_sort_cases()), ids=lambda k: f"n{len(k)}")
def test_search_right_is_numpys_searchsorted_right(keys):
    a = np.sort(keys)
    probes = np.concatenate([a, a + 1e-12, a - 1e-12, [np.nan, -np.inf, np.inf, 0.5]])
    for v in probes:
        assert search_right(a, float(v)) == np.searchsorted(a, v, side="right"), v
