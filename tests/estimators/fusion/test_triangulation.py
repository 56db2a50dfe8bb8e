"""Three-landmark triangulation (paper 000): exact on exact bearings, error that grows
smoothly with bearing noise, and the degenerate configurations reported."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators.fusion import triangulate

# Two goal posts and the far corner of a 6 m x 4 m humanoid field (paper 000's), in metres.
LANDMARKS = np.array([[3.0, 0.7], [3.0, -0.7], [-3.0, 2.0]])


def _bearings(landmarks, pos, heading):
    d = landmarks - pos
    return np.arctan2(d[:, 1], d[:, 0]) - heading


def test_exact_bearings_give_the_exact_pose():
    rng = np.random.default_rng(0)
    done = 0
    for _ in range(300):
        landmarks = rng.uniform(-3, 3, (3, 2))
        pos, heading = rng.uniform(-3, 3, 2), rng.uniform(-math.pi, math.pi)
        phi = _bearings(landmarks, pos, heading) + 2 * math.pi * rng.integers(-1, 2, 3)
        fix = triangulate(landmarks, phi)
        if not fix.ok:  # near-degenerate draws are reported, never wrong
            assert fix.reason and np.all(np.isnan(fix.position))
            continue
        done += 1
        np.testing.assert_allclose(fix.position, pos, atol=1e-6)
        assert abs(math.remainder(fix.heading - heading, 2 * math.pi)) < 1e-6
    assert done > 280


def test_landmark_order_does_not_matter_and_noise_costs_little():
    pos, heading = np.array([0.5, 0.3]), 0.2
    phi = _bearings(LANDMARKS, pos, heading)
    for perm in ([0, 1, 2], [2, 0, 1], [1, 0, 2]):
        fix = triangulate(LANDMARKS[perm], phi[perm])
        np.testing.assert_allclose(fix.position, pos, atol=1e-9)
    rng = np.random.default_rng(1)
    errors = [np.hypot(*(triangulate(LANDMARKS, phi + rng.normal(0, 0.01, 3)).position - pos))
              for _ in range(200)]
    assert np.median(errors) < 0.1  # 0.6 degrees of bearing noise, landmarks 2.5-4 m away


def test_degenerate_configurations_are_reported():
    fix = triangulate(LANDMARKS[:2], [0.1, -0.1])
    assert not fix.ok and "three are needed" in fix.reason and math.isnan(fix.heading)
    # The robot on the line through two landmarks.
    pos = np.array([0.0, 0.7])
    phi = _bearings(np.array([[3.0, 0.7], [-2.0, 0.7], [3.0, -0.7]]), pos, 0.0)
    fix = triangulate([[3.0, 0.7], [-2.0, 0.7], [3.0, -0.7]], phi)
    assert not fix.ok and "line through two landmarks" in fix.reason
    # The robot on the circle through the three landmarks.
    centre, radius = np.array([0.0, 0.0]), 2.0
    on_circle = [centre + radius * np.array([math.cos(a), math.sin(a)])
                 for a in (0.3, 1.5, 2.9, -1.2)]
    landmarks, pos = np.array(on_circle[:3]), on_circle[3]
    fix = triangulate(landmarks, _bearings(landmarks, pos, 0.4))
    assert not fix.ok and "circle through the three landmarks" in fix.reason
    # Collinear landmarks with the robot off their line work.
    line = np.array([[3.0, -1.0], [3.0, 0.0], [3.0, 1.5]])
    fix = triangulate(line, _bearings(line, np.array([0.0, 0.4]), 0.1))
    assert fix.ok and np.allclose(fix.position, [0.0, 0.4])
    # ... and with the robot on it they do not.
    fix = triangulate(line, _bearings(line, np.array([3.0, -2.0]), 0.0))
    assert not fix.ok
    fix = triangulate([[0, 0], [0, 0], [1, 1]], [0.1, 0.2, 0.3])
    assert not fix.ok and "coincide" in fix.reason


def test_malformed_input_raises():
    with pytest.raises(ValueError, match="shape"):
        triangulate(LANDMARKS, [0.1, 0.2])
    with pytest.raises(ValueError, match="finite"):
        triangulate(LANDMARKS, [0.1, np.nan, 0.2])
    with pytest.raises(ValueError, match="exactly three"):
        triangulate(np.zeros((4, 2)), np.zeros(4))
