"""Three-landmark triangulation (Xu et al. 2012): exact on exact bearings, error that grows
smoothly with bearing noise, and the degenerate configurations reported."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators.fusion import SEED_FAILURES, SightingMemory, triangulate, triangulate_sightings

# Two goal posts and the far corner of a 6 m x 4 m humanoid field (Xu et al.'s 2012), in metres.
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


# --------------------------------------------------------------------------------------------
# Landmarks known by kind only, sightings gathered over frames (the recovery seed's input)
# --------------------------------------------------------------------------------------------

#: A 6 m x 4 m field by kind: coloured posts, corners and the centre-line ends.
KINDS = {"post_a": np.array([[3.0, 0.7], [3.0, -0.7]]),
         "post_b": np.array([[-3.0, 0.7], [-3.0, -0.7]]),
         "L": np.array([[3.0, 2.0], [3.0, -2.0], [-3.0, 2.0], [-3.0, -2.0]]),
         "T": np.array([[0.0, 2.0], [0.0, -2.0]])}
FIELD = (-3.0, 3.0, -2.0, 2.0)


def _body_points(pose, kinds_and_landmarks):
    """Exact body-frame sightings from ``pose`` of ``[(kind, landmark index), ...]``."""
    c, s = math.cos(pose[2]), math.sin(pose[2])
    kinds, pts = [], []
    for kind, j in kinds_and_landmarks:
        d = KINDS[kind][j] - pose[:2]
        kinds.append(kind)
        pts.append([c * d[0] + s * d[1], -s * d[0] + c * d[1]])
    return kinds, np.array(pts)


def test_sightings_by_kind_give_the_pose_and_the_mirror_only_without_a_coloured_post():
    pose = np.array([0.8, -0.4, 0.5])
    seen = [("L", 0), ("T", 0), ("L", 1), ("post_a", 0)]
    kinds, pts = _body_points(pose, seen)
    hyp = triangulate_sightings(kinds, pts, KINDS, 0.05, 0.01, FIELD)
    assert hyp.ok and hyp.reason == "" and hyp.sightings == 4
    np.testing.assert_allclose(hyp.poses[0], pose, atol=1e-6)
    # Every kept pose explains the sightings; the best is the truth, nothing at the mirror.
    mirror = np.array([-pose[0], -pose[1], pose[2] - math.pi])
    assert not any(np.hypot(*(p[:2] - mirror[:2])) < 0.3 for p in hyp.poses)
    # Without the post, the field turned by half a turn explains the corners as well: both
    # poses are kept with the same score.
    kinds, pts = _body_points(pose, seen[:3])
    hyp = triangulate_sightings(kinds, pts, KINDS, 0.05, 0.01, FIELD)
    assert len(hyp.poses) == 2 and hyp.scores[0] == pytest.approx(hyp.scores[1], abs=1e-6)
    found = sorted(hyp.poses.tolist())
    np.testing.assert_allclose(found[0][:2], mirror[:2], atol=1e-6)
    np.testing.assert_allclose(found[1][:2], pose[:2], atol=1e-6)
    # Noisy sightings: close to the truth, with a spread from the bearing noise.
    rng = np.random.default_rng(3)
    kinds, pts = _body_points(pose, seen)
    r, b = np.hypot(*pts.T), np.arctan2(pts[:, 1], pts[:, 0])
    errors = []
    for _ in range(50):
        rn, bn = r * (1 + rng.normal(0, 0.03, 4)), b + rng.normal(0, 0.01, 4)
        hyp = triangulate_sightings(kinds, np.column_stack([rn * np.cos(bn), rn * np.sin(bn)]),
                                    KINDS, 0.05 + 0.03 * rn, 0.01, FIELD)
        errors.append(np.hypot(*(hyp.poses[0, :2] - pose[:2])))
        assert 0.0 < hyp.sigmas[0, 0] < 0.5
    assert np.median(errors) < 0.1


def test_degenerate_and_too_few_sightings_are_skipped():
    # Three landmarks on the goal line x = 3, the robot on that line: no pose, not garbage.
    line = {"a": np.array([[3.0, -2.0]]), "b": np.array([[3.0, 0.7]]),
            "c": np.array([[3.0, 2.0]])}
    pose = np.array([3.0, -3.0, 1.2])  # on the line, beyond the corner
    c, s = math.cos(pose[2]), math.sin(pose[2])
    pts = np.array([[c * (p[0][0] - 3.0) + s * (p[0][1] + 3.0),
                     -s * (p[0][0] - 3.0) + c * (p[0][1] + 3.0)] for p in line.values()])
    hyp = triangulate_sightings(["a", "b", "c"], pts, line, 0.05, 0.01)
    assert not hyp.ok and hyp.reason == "degenerate" and hyp.poses.shape == (0, 3)
    # The robot on the circle through the three landmarks.
    circle = {k: np.array([[2.0 * math.cos(a), 2.0 * math.sin(a)]])
              for k, a in zip("abc", (0.3, 1.5, 2.9))}
    pose = np.array([2.0 * math.cos(-1.2), 2.0 * math.sin(-1.2), 0.4])
    c, s = math.cos(pose[2]), math.sin(pose[2])
    pts = np.array([[c * (p[0][0] - pose[0]) + s * (p[0][1] - pose[1]),
                     -s * (p[0][0] - pose[0]) + c * (p[0][1] - pose[1])]
                    for p in circle.values()])
    hyp = triangulate_sightings(list("abc"), pts, circle, 0.05, 0.01)
    assert not hyp.ok and hyp.reason == "degenerate"
    # Off the circle the same landmarks work.
    pose = np.array([0.2, -0.5, 0.4])
    c, s = math.cos(pose[2]), math.sin(pose[2])
    pts = np.array([[c * (p[0][0] - pose[0]) + s * (p[0][1] - pose[1]),
                     -s * (p[0][0] - pose[0]) + c * (p[0][1] - pose[1])]
                    for p in circle.values()])
    hyp = triangulate_sightings(list("abc"), pts, circle, 0.05, 0.01)
    assert hyp.ok
    np.testing.assert_allclose(hyp.poses[0], pose, atol=1e-6)
    # Two landmarks, or one landmark seen three times: too few.
    kinds, pts = _body_points(np.zeros(3), [("L", 0), ("T", 0)])
    assert triangulate_sightings(kinds, pts, KINDS, 0.05, 0.01).reason == "too_few"
    kinds, pts = _body_points(np.zeros(3), [("L", 0)] * 3)
    hyp = triangulate_sightings(kinds, pts + [[0.0, 0.01], [0.01, 0.0], [0.0, 0.0]], KINDS,
                                0.05, 0.01)
    assert hyp.reason == "too_few" and hyp.sightings == 1
    # Sightings no assignment fits (distances no landmarks have).
    hyp = triangulate_sightings(["T", "T", "T"], [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]], KINDS,
                                0.01, 0.01)
    assert hyp.reason == "no_fit"
    assert set(SEED_FAILURES) == {"too_few", "degenerate", "no_fit"}


def test_the_memory_moves_old_sightings_with_the_odometry():
    # A robot walks a curve, seeing one landmark per frame; after the walk the remembered
    # sightings equal what it would see from where it now is (exact odometry).
    memory = SightingMemory(5)
    pose = np.array([-1.0, 0.3, 0.2])
    order = [("L", 0), ("T", 0), ("post_a", 1), ("L", 1), ("T", 1), ("L", 2)]
    for kind, j in order:
        d = np.array([0.05, 0.01, 0.04])  # body frame, applied at the mid-step heading
        th = pose[2] + 0.5 * d[2]
        pose = pose + [math.cos(th) * d[0] - math.sin(th) * d[1],
                       math.sin(th) * d[0] + math.cos(th) * d[1], d[2]]
        memory.move(d)
        _, pts = _body_points(pose, [(kind, j)])
        memory.add([kind], np.hypot(*pts.T), np.arctan2(pts[:, 1], pts[:, 0]))
    kinds, pts = memory.sightings()
    assert kinds == tuple(k for k, _ in order[1:])  # the oldest frame dropped
    np.testing.assert_allclose(pts, _body_points(pose, order[1:])[1], atol=1e-12)
    hyp = triangulate_sightings(kinds, pts, KINDS, 0.05, 0.01, FIELD)
    np.testing.assert_allclose(hyp.poses[0], [*pose[:2], math.remainder(pose[2], 2 * math.pi)],
                               atol=1e-6)
    assert len(memory) == 5
    memory.clear()
    assert len(memory) == 0 and memory.sightings()[1].shape == (0, 2)


def test_bad_sightings_raise():
    kinds, pts = _body_points(np.zeros(3), [("L", 0), ("T", 0), ("L", 1)])
    with pytest.raises(ValueError, match="points"):
        triangulate_sightings(kinds, pts[:2], KINDS, 0.05, 0.01)
    with pytest.raises(ValueError, match="unknown landmark kind 'Z'"):
        triangulate_sightings(["Z", "T", "L"], pts, KINDS, 0.05, 0.01)
    with pytest.raises(ValueError, match="range_sigma"):
        triangulate_sightings(kinds, pts, KINDS, 0.0, 0.01)
    with pytest.raises(ValueError, match="bearing_sigma"):
        triangulate_sightings(kinds, pts, KINDS, 0.05, math.nan)
    with pytest.raises(ValueError, match="max_sigma"):
        triangulate_sightings(kinds, pts, KINDS, 0.05, 0.01, max_sigma=0.0)
    for frames in (0, 1001, 2.5, True):
        with pytest.raises(ValueError, match=r"frames must be an integer in \[1, 1000\]"):
            SightingMemory(frames)
    with pytest.raises(ValueError, match="must match"):
        SightingMemory(2).add(["L"], [1.0, 2.0], [0.0, 0.1])
    memory = SightingMemory(1)
    memory.add(["L"], [1.0], [0.0])
    with pytest.raises(ValueError, match="must match and be finite"):
        memory.add(["T"], [math.nan], [0.0])
    assert memory.sightings()[0] == ("L",) and len(memory) == 1  # left as it was
