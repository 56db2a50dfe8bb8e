"""KLD-sampling particle-filter localization (Guo and Li 2013): global localization, tracking with
few particles, recovery after kidnapping, the KLD bound, reproducibility, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators.particle.kld import kld_sample_size, kld_table, normal_quantile
from estimators.particle.landmarks import LandmarkTable
from estimators.particle.localization import RECOVERIES, KLDConfig, KLDLocalizer

# Goal posts, corners and the centre-line ends of a 6 m x 4 m field.
LANDMARKS = np.array([[3, 0.7], [3, -0.7], [-3, 0.7], [-3, -0.7], [3, 2], [3, -2], [-3, 2],
                      [-3, -2], [0, 2], [0, -2]], dtype=float)
BOUNDS = (-3.0, 3.0, -2.0, 2.0)


def _sight(pose, rng, max_range=4.0, noise=0.03):
    dist = np.hypot(*(LANDMARKS - pose[:2]).T)
    vis = dist < max_range
    rel = LANDMARKS[vis] - pose[:2]
    ranges = dist[vis] * (1.0 + rng.normal(0, noise, vis.sum()))
    bearings = np.arctan2(rel[:, 1], rel[:, 0]) - pose[2] + rng.normal(0, noise, vis.sum())
    return LANDMARKS[vis], ranges, bearings


def _walk(loc, pose, steps, rng):
    """Walk at 0.2 m/s (10 Hz), turning near the edges; returns errors and particle counts."""
    errors, counts = [], []
    for k in range(steps):
        v, w = 0.02, (0.03 if (k // 50) % 2 else 0.0)
        if abs(pose[0]) > 2.0 or abs(pose[1]) > 1.2:
            w = 0.05
        c, s = math.cos(pose[2] + w / 2), math.sin(pose[2] + w / 2)
        pose = pose + np.array([c * v, s * v, w])
        loc.predict(np.array([v, 0.0, w]) + rng.normal(0, 1, 3) * [0.005, 0.005, 0.01])
        loc.update(*_sight(pose, rng))
        errors.append(np.hypot(*(loc.estimate()[:2] - pose[:2])))
        counts.append(loc.n)
    return pose, np.array(errors), np.array(counts)


def test_kld_bound_and_quantile():
    for p, z in ((0.5, 0.0), (0.975, 1.959963985), (0.99, 2.326347874), (0.001, -3.090232306)):
        assert normal_quantile(p) == pytest.approx(z, abs=1e-8)
    n = kld_sample_size(np.array([1, 2, 10, 100]), 0.05, 0.01)
    assert n[0] == 1
    k, z = 100, 2.326347874
    expected = (k - 1) / 0.1 * (1 - 2 / (9 * (k - 1)) + math.sqrt(2 / (9 * (k - 1))) * z) ** 3
    assert n[3] == math.ceil(expected)
    assert np.all(np.diff(n) > 0)


def test_global_localization_then_tracking_with_few_particles():
    rng = np.random.default_rng(0)
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(1))
    global_count = loc.n
    assert global_count == KLDConfig().max_particles
    _, errors, counts = _walk(loc, np.array([-1.0, 0.5, 0.3]), 200, rng)
    assert np.median(errors[20:]) < 0.15  # issue aim while walking
    assert np.max(counts[20:]) * 3 <= global_count  # at least 3x fewer while tracking


def test_recovers_after_being_picked_up():
    rng = np.random.default_rng(2)
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(3), pose=np.array([-1.0, 0.5, 0.3]))
    pose, _, _ = _walk(loc, np.array([-1.0, 0.5, 0.3]), 30, rng)
    kidnapped = np.array([2.0, -1.0, 2.0])
    assert np.hypot(*(loc.estimate()[:2] - kidnapped[:2])) > 1.0
    for _ in range(60):
        loc.predict(np.zeros(3))
        loc.update(*_sight(kidnapped, rng))
    assert np.hypot(*(loc.estimate()[:2] - kidnapped[:2])) < 0.15


def test_same_seed_same_run():
    runs = []
    for _ in range(2):
        loc = KLDLocalizer(BOUNDS, np.random.default_rng(5))
        _, errors, counts = _walk(loc, np.array([0.0, 0.0, 0.0]), 20, np.random.default_rng(6))
        runs.append((errors.tolist(), counts.tolist()))
    assert runs[0] == runs[1]


def test_bad_input():
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="bounds"):
        KLDLocalizer((1.0, 0.0, 0.0, 1.0), rng)
    with pytest.raises(TypeError, match="Generator"):
        KLDLocalizer(BOUNDS, 3)
    with pytest.raises(ValueError, match="min_particles"):
        KLDConfig(min_particles=10, max_particles=5)
    with pytest.raises(ValueError, match="epsilon"):
        KLDConfig(epsilon=0.0)
    with pytest.raises(ValueError, match="alpha"):
        KLDConfig(alpha_slow=0.5, alpha_fast=0.1)
    loc = KLDLocalizer(BOUNDS, rng)
    with pytest.raises(ValueError, match="odometry"):
        loc.predict([0.1, np.nan, 0.0])
    with pytest.raises(ValueError, match="match"):
        loc.update(LANDMARKS[:2], [1.0])
    loc.update(np.zeros((0, 2)), [])  # nothing seen: nothing changes
    assert loc.n == KLDConfig().max_particles


# --------------------------------------------------------------------------------------------
# Ambiguous landmarks: a corner or a post, not which one
# --------------------------------------------------------------------------------------------

TABLE = {
    "corner": np.array([[3, 2], [3, -2], [-3, 2], [-3, -2]], dtype=float),
    "post": np.array([[3, 0.7], [3, -0.7], [-3, 0.7], [-3, -0.7]], dtype=float),
    "T": np.array([[0, 2], [0, -2]], dtype=float),
}


def _sight_kinds(pose, rng, max_range=4.0, noise=0.03, table=TABLE):
    kinds, ranges, bearings = [], [], []
    for kind, pos in table.items():
        rel = pos - pose[:2]
        dist = np.hypot(*rel.T)
        for j in np.flatnonzero(dist < max_range):
            kinds.append(kind)
            ranges.append(dist[j] * (1.0 + rng.normal(0, noise)))
            bearings.append(math.atan2(rel[j, 1], rel[j, 0]) - pose[2] + rng.normal(0, noise))
    return kinds, np.array(ranges), np.array(bearings)


def _walk_kinds(loc, pose, steps, rng):
    errors = []
    for k in range(steps):
        v, w = 0.02, (0.03 if (k // 50) % 2 else 0.0)
        if abs(pose[0]) > 2.0 or abs(pose[1]) > 1.2:
            w = 0.05
        c, s = math.cos(pose[2] + w / 2), math.sin(pose[2] + w / 2)
        pose = pose + np.array([c * v, s * v, w])
        loc.predict(np.array([v, 0.0, w]) + rng.normal(0, 1, 3) * [0.005, 0.005, 0.01])
        loc.update_kinds(*_sight_kinds(pose, rng), TABLE)
        errors.append(np.hypot(*(loc.estimate()[:2] - pose[:2])))
    return pose, np.array(errors)


def test_update_kinds_with_one_candidate_per_kind_is_update():
    """Unambiguous kinds (one landmark each) give exactly update()'s filter."""
    table = {f"L{i}": LANDMARKS[i:i + 1] for i in range(len(LANDMARKS))}
    runs = []
    for by_kind in (False, True):
        loc = KLDLocalizer(BOUNDS, np.random.default_rng(5), pose=np.array([-1.0, 0.5, 0.3]))
        rng = np.random.default_rng(6)
        for _ in range(10):
            loc.predict([0.02, 0.0, 0.01])
            L, r, b = _sight(np.array([-1.0, 0.5, 0.3]), rng)
            if by_kind:
                idx = [int(np.flatnonzero((LANDMARKS == p).all(axis=1))[0]) for p in L]
                loc.update_kinds([f"L{i}" for i in idx], r, b, table)
            else:
                loc.update(L, r, b)
        runs.append((loc.particles.copy(), loc.estimate()))
    np.testing.assert_allclose(runs[0][0], runs[1][0], atol=1e-12)


def test_tracks_from_a_known_start_with_ambiguous_landmarks():
    rng = np.random.default_rng(10)
    start = np.array([-1.0, 0.5, 0.3])
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(11), pose=start)
    _, errors = _walk_kinds(loc, start, 200, rng)
    assert np.median(errors) < 0.15 and np.max(errors) < 0.5


@pytest.mark.parametrize("seed", [0, 7, 12])  # 7 and 12 settle on the mirror
def test_global_localization_with_symmetric_landmarks_finds_the_pose_or_its_mirror(seed):
    """The landmark table is symmetric under a half turn of the field, so (x, y, theta) and
    (-x, -y, theta + pi) explain every observation alike: the filter must settle on one of
    the two."""
    rng = np.random.default_rng(20 + seed)
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(30 + seed))
    pose, _ = _walk_kinds(loc, np.array([-1.2, 0.6, 0.4]), 250, rng)
    est = loc.estimate()
    mirror = np.array([-pose[0], -pose[1], pose[2] + math.pi])
    errors = [np.hypot(*(est[:2] - p[:2])) for p in (pose, mirror)]
    heading = [abs(math.remainder(est[2] - p[2], 2 * math.pi)) for p in (pose, mirror)]
    best = int(np.argmin(errors))
    assert errors[best] < 0.2 and heading[best] < 0.2


def test_update_kinds_bad_input():
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(0))
    with pytest.raises(ValueError, match="'flag'"):
        loc.update_kinds(["corner", "flag"], [1.0, 2.0], [0.0, 0.1], TABLE)
    with pytest.raises(ValueError, match="match"):
        loc.update_kinds(["corner"], [1.0, 2.0], None, TABLE)
    with pytest.raises(ValueError, match="bearings"):
        loc.update_kinds(["corner", "post"], [1.0, 2.0], [0.0], TABLE)
    with pytest.raises(ValueError, match="table\\['empty'\\]"):
        loc.update_kinds(["empty"], [1.0], None, {"empty": np.zeros((0, 2))})
    loc.update_kinds([], [], [], TABLE)  # nothing seen: nothing changes
    assert loc.n == KLDConfig().max_particles


def _reference_kld_resample(loc: KLDLocalizer, rng: np.random.Generator,
                            d: np.ndarray | None = None) -> np.ndarray:
    """Fox's KLD-sampling written out plainly (one draw at a time, bins as tuples, no
    recovery): the particles it keeps. With the odometry ``d`` (Fox 2003, Table 1) every
    drawn particle is first moved by the motion model, and the bin of the *predicted* sample
    is counted."""
    c = loc.cfg
    bound = kld_table(c.epsilon, c.delta, c.max_particles)
    cumulative = np.cumsum(loc.weights)
    cumulative /= cumulative[-1]
    batch = min(c.max_particles, max(c.min_particles, 2 * loc.n))
    drawn, seen, kept = 0, set(), []
    while True:
        take = min(batch, c.max_particles - drawn)
        idx = np.searchsorted(cumulative, rng.random(take), side="right")
        rows = loc.particles[np.minimum(idx, loc.n - 1)]
        if d is not None:
            rows = [_reference_move(row, d, e, c) for row, e in
                    zip(rows, rng.normal(0.0, 1.0, (take, 3)))]
        for row in rows:
            kept.append(row)
            seen.add(tuple(int(v) for v in np.floor(row / np.asarray(c.bin_size))))
            drawn += 1
            if drawn >= c.min_particles and drawn >= bound[len(seen)]:
                return np.array(kept)
        if drawn >= c.max_particles:
            return np.array(kept)
        batch *= 2


def _reference_move(row: np.ndarray, d: np.ndarray, e: np.ndarray, c: KLDConfig
                    ) -> np.ndarray:
    """One particle moved by the odometry ``d`` with standard normal noise ``e``, written
    out plainly."""
    dist, turn = math.hypot(d[0], d[1]), abs(d[2])
    s_xy = c.a_trans * dist + c.a_rot_xy * turn
    s_th = c.a_rot * turn + c.a_trans_theta * dist
    th = row[2] + 0.5 * d[2]
    dx, dy = d[0] + s_xy * e[0], d[1] + s_xy * e[1]
    return np.array([row[0] + math.cos(th) * dx - math.sin(th) * dy,
                     row[1] + math.sin(th) * dx + math.cos(th) * dy,
                     math.remainder(row[2] + d[2] + s_th * e[2], 2.0 * math.pi)])


@pytest.mark.parametrize("spread", [0.01, 0.3, 3.0])
def test_resampling_keeps_as_many_particles_as_fox_bound_says(spread):
    """The resampler's packed bin keys and bulk start give exactly the sample of Fox's
    draw-by-draw rule, from a converged belief (few bins) to a spread one (many)."""
    for seed in range(5):
        config = KLDConfig(min_particles=20, max_particles=3000, alpha_fast=0.0)
        loc = KLDLocalizer(BOUNDS, np.random.default_rng(seed), config)
        loc.particles = np.random.default_rng(100 + seed).normal(
            [0.5, -0.2, 1.0], spread, (400, 3))
        loc.weights = np.random.default_rng(200 + seed).random(400)
        loc.weights /= loc.weights.sum()
        expected = _reference_kld_resample(loc, np.random.default_rng(300 + seed))
        loc.rng = np.random.default_rng(300 + seed)
        loc._resample()
        np.testing.assert_array_equal(loc.particles, expected)


def test_a_landmark_table_gives_the_mapping_s_results_bit_for_bit():
    """update_kinds with a LandmarkTable (validated once, layouts cached), and
    update_sightings (the unchecked path), give exactly the plain mapping's filter."""
    table = LandmarkTable(TABLE)
    runs = []
    for mode in ("mapping", "table", "sightings"):
        loc = KLDLocalizer(BOUNDS, np.random.default_rng(5), pose=np.array([-1.0, 0.5, 0.3]))
        rng = np.random.default_rng(6)
        pose = np.array([-1.0, 0.5, 0.3])
        for _ in range(30):
            loc.predict([0.02, 0.0, 0.01])
            kinds, r, b = _sight_kinds(pose, rng)
            if mode == "mapping":
                loc.update_kinds(kinds, r, b, TABLE)
            elif mode == "table":
                loc.update_kinds(kinds, r, b, table)
            elif len(kinds):
                loc.update_sightings(tuple(kinds), np.asarray(r, float), np.asarray(b, float),
                                     table)
        runs.append(loc.particles.copy())
    np.testing.assert_array_equal(runs[0], runs[1])
    np.testing.assert_array_equal(runs[0], runs[2])


def test_landmark_table_bad_input():
    with pytest.raises(ValueError, match="table\\['empty'\\]"):
        LandmarkTable({"empty": np.zeros((0, 2))})
    with pytest.raises(ValueError, match="table\\['nan'\\]"):
        LandmarkTable({"nan": [[0.0, math.nan]]})
    with pytest.raises(ValueError, match="unknown landmark kind 'flag'"):
        LandmarkTable(TABLE).layout(("flag",))
    table = LandmarkTable(TABLE)
    with pytest.raises(ValueError):  # read-only: the cached layouts cannot go stale
        table["corner"][0, 0] = 9.0


# --------------------------------------------------------------------------------------------
# Recovery seeded by triangulation (Xu et al.'s 2012 three-landmark self-localization)
# --------------------------------------------------------------------------------------------

#: Posts told apart by colour, corners and centre-line ends by kind only.
COLOURED = {"post_a": np.array([[3, 0.7], [3, -0.7]], dtype=float),
            "post_b": np.array([[-3, 0.7], [-3, -0.7]], dtype=float),
            "L": np.array([[3, 2], [3, -2], [-3, 2], [-3, -2]], dtype=float),
            "T": np.array([[0, 2], [0, -2]], dtype=float)}


def _frames_to_recover(recovery, seed, known=False, frames=60):
    """A fixed-size filter (300 particles) tracks a walking robot from a known start, which
    is then picked up and put down elsewhere: the frames until the estimate is within 0.2 m
    (None: not within ``frames``)."""
    sight_rng = np.random.default_rng(100 + seed)
    cfg = KLDConfig(min_particles=300, max_particles=300, bearing_sigma=0.05)
    pose = np.array([-1.0, 0.5, 0.3])
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(seed), cfg, pose=pose, recovery=recovery)
    table = LandmarkTable(COLOURED)

    def frame(pose):
        pose = pose + [0.02 * math.cos(pose[2]), 0.02 * math.sin(pose[2]), 0.0]
        loc.predict((0.02, 0.0, 0.0))
        kinds, ranges, bearings = _sight_kinds(pose, sight_rng, noise=0.02, table=COLOURED)
        if known:  # the landmarks' identities known: each sighting its nearest landmark
            pts = pose[:2] + np.column_stack([ranges * np.cos(bearings + pose[2]),
                                              ranges * np.sin(bearings + pose[2])])
            where = np.array([COLOURED[k][np.argmin(np.hypot(*(COLOURED[k] - p).T))]
                              for k, p in zip(kinds, pts)])
            loc.update(where, ranges, bearings)
        else:
            loc.update_kinds(kinds, ranges, bearings, table)
        return pose

    for _ in range(20):
        pose = frame(pose)
    assert np.hypot(*(loc.estimate()[:2] - pose[:2])) < 0.2
    pose = np.array([1.5, -0.8, 2.5])  # kidnapped
    for k in range(frames):
        pose = frame(pose)
        if np.hypot(*(loc.estimate()[:2] - pose[:2])) < 0.2:
            return k + 1
    return None


def test_triangulated_seed_recovers_a_kidnapped_robot_far_sooner_than_uniform_draws():
    seeds = range(4)
    tri = [_frames_to_recover("triangulate", s) for s in seeds]
    uni = [_frames_to_recover("uniform", s) for s in seeds]
    # The seed: once the likelihood averages call the filter lost (a few frames), the
    # triangulated pose is among the new particles at once.
    assert all(t is not None and t <= 15 for t in tri), tri
    # Uniform draws over 24 m^2 x 2 pi land near the pose by chance: far later, or never.
    later = [60 if u is None else u for u in uni]
    assert np.median(later) >= 2 * np.median(tri), (tri, uni)
    # Landmarks of known identity (update) feed the seed as well.
    assert _frames_to_recover("triangulate", 0, known=True) <= 15


def test_the_seed_is_skipped_when_the_geometry_gives_no_pose():
    # Only two landmarks in view: no hypothesis, every injected particle uniform (as
    # "uniform", but the filter keeps working).
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(0), recovery="triangulate")
    two = LANDMARKS[[0, 1]]
    pose = np.array([1.0, 0.0, 0.0])
    for _ in range(5):
        rel = two - pose[:2]
        loc.predict(np.zeros(3))
        loc.update(two, np.hypot(*rel.T), np.arctan2(rel[:, 1], rel[:, 0]))
    hyp = loc.seed_hypotheses()
    assert not hyp.ok and hyp.reason == "too_few"
    assert loc._recovery_draws(100).shape == (100, 3)
    # The robot on the line of three collinear landmarks: degenerate, skipped.
    line = np.array([[3.0, -2.0], [3.0, -0.7], [3.0, 0.7]])
    loc = KLDLocalizer((-3.0, 3.0, -4.0, 2.0), np.random.default_rng(0),
                       recovery="triangulate")
    pose = np.array([3.0, -3.5, 1.0])
    rel = line - pose[:2]
    loc.update(line, np.hypot(*rel.T), np.arctan2(rel[:, 1], rel[:, 0]) - pose[2])
    hyp = loc.seed_hypotheses()
    assert not hyp.ok and hyp.reason == "degenerate"
    draws = loc._recovery_draws(1000)
    assert (draws[:, 0] >= -3.0).all() and (draws[:, 0] <= 3.0).all()  # uniform, in bounds
    assert np.std(draws[:, 0]) > 1.0


def test_uniform_recovery_is_the_default_draw_for_draw():
    runs = []
    for kwargs in ({}, {"recovery": "uniform", "seed_fraction": 0.3, "seed_memory": 3}):
        loc = KLDLocalizer(BOUNDS, np.random.default_rng(5), **kwargs)
        _, errors, counts = _walk(loc, np.array([0.0, 0.0, 0.0]), 20, np.random.default_rng(6))
        runs.append((errors.tolist(), counts.tolist(), loc.particles.tolist()))
        assert loc.memory is None
    assert runs[0] == runs[1]


def test_recovery_option_bad_input():
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match=r"recovery must be one of \('uniform', "
                                         r"'triangulate'\), got 'kidnap'"):
        KLDLocalizer(BOUNDS, rng, recovery="kidnap")
    for bad in (-0.1, 1.5, math.nan, True, "half"):
        with pytest.raises(ValueError, match=r"seed_fraction must be in \[0, 1\]"):
            KLDLocalizer(BOUNDS, rng, recovery="triangulate", seed_fraction=bad)
    for bad in (0, 1001, 2.5, False):
        with pytest.raises(ValueError, match=r"seed_memory must be an integer in \[1, 1000\]"):
            KLDLocalizer(BOUNDS, rng, recovery="triangulate", seed_memory=bad)
    with pytest.raises(ValueError, match="recovery='triangulate'"):
        KLDLocalizer(BOUNDS, rng).seed_hypotheses()
    assert RECOVERIES == ("uniform", "triangulate")


def test_fox_binning_counts_the_predicted_samples():
    """binning="predicted": an update only weighs (no resampling); the next predict draws,
    moves and bins the predicted samples as Fox's listing does, so with the motion's spread
    added it keeps more particles than binning the resampled ones."""
    counts = {}
    for binning in KLDConfig.BINNINGS:
        config = KLDConfig(min_particles=20, max_particles=3000, alpha_fast=0.0,
                           binning=binning)
        loc = KLDLocalizer(BOUNDS, np.random.default_rng(3), config,
                           pose=np.array([0.5, -0.2, 1.0]), pose_sigma=(0.05, 0.05, 0.05))
        loc.update(*_sight(np.array([0.5, -0.2, 1.0]), np.random.default_rng(4)))
        if binning == "predicted":
            assert loc.n == 20 and np.ptp(loc.weights) > 0.0  # weighed, not resampled
            d = np.array([0.4, 0.0, 0.6])  # a large, turning step: a wide motion spread
            expected = _reference_kld_resample(loc, np.random.default_rng(9), d)
            loc.rng = np.random.default_rng(9)
            loc.predict(d)
            np.testing.assert_allclose(loc.particles, expected, atol=1e-12)
            np.testing.assert_array_equal(loc.weights, np.full(loc.n, 1.0 / loc.n))
        else:
            loc.predict(np.array([0.4, 0.0, 0.6]))
        counts[binning] = loc.n
    assert counts["predicted"] > counts["resampled"], counts


def test_fox_binning_tracks_and_adapts_as_ours_does():
    rng = np.random.default_rng(0)
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(1), KLDConfig(binning="predicted"))
    _, errors, counts = _walk(loc, np.array([-1.0, 0.5, 0.3]), 200, rng)
    assert np.median(errors[20:]) < 0.15
    assert np.max(counts[20:]) * 3 <= KLDConfig().max_particles
    with pytest.raises(ValueError, match="binning must be one of"):
        KLDConfig(binning="before")
