"""Li et al.'s (2010) feature-restricted mean-shift particle filter and the plain particle filter on
synthetic weight images: a manoeuvring target, a distractor of a similar colour, a target that
disappears and reappears, a ball occluded by a robot, reproducibility, the feature-check hook,
bad arguments."""

from __future__ import annotations

import numpy as np
import pytest
from weight_images import H, W, frame_differences, manoeuvre, rmse, weight_image

from estimators import (
    MeanShiftParticleFilter,
    ParticleFilterTracker,
)
from estimators.image import EmptyWindowError

GEN = np.random.default_rng(0)
IMG = np.zeros((H, W), np.float32)


def test_mean_shift_pf_with_20_particles_beats_plain_pf_on_a_manoeuvring_target():
    ms20, pf20, pf200 = [], [], []
    for seed in range(3):
        rng = np.random.default_rng(seed)
        truth = manoeuvre(rng)
        frames = [weight_image(rng, [p], [(60.0, 60.0), (260.0, 180.0)]) for p in truth]
        motion = frame_differences(frames)
        for out, cls, n in ((ms20, MeanShiftParticleFilter, 20),
                            (pf20, ParticleFilterTracker, 20),
                            (pf200, ParticleFilterTracker, 200)):
            f = cls(truth[0], (17, 17), np.random.default_rng(100 + seed), n_particles=n,
                    process_sigma=6.0, velocity=truth[1] - truth[0])
            est = [f.update(c, m) for c, m in zip(frames, motion)]
            out.append(rmse(est, truth))
            if cls is MeanShiftParticleFilter:
                assert f.lost_frames == 0
    ms20, pf20, pf200 = np.mean(ms20), np.mean(pf20), np.mean(pf200)
    assert ms20 < 1.5, ms20  # well within the blob (sigma 4 px) through every turn
    assert ms20 < 0.5 * pf20, (ms20, pf20)
    assert ms20 <= pf200 + 0.5, (ms20, pf200)  # as good as ten times the particles


def test_step_four_as_printed_tracks_with_the_unweighted_mean_of_the_restricted_set():
    """Li et al.'s (2010) step 4 as printed: the estimate is the plain mean of the particles, every
    particle is inside the feature restriction after the update (rejected ones replaced by
    allowed ones), no resampling by weight; and it tracks the manoeuvring target as well as
    the weighted mean with resampling does."""
    errors = {"weighted": [], "paper": []}
    for seed in range(3):
        rng = np.random.default_rng(seed)
        truth = manoeuvre(rng)
        frames = [weight_image(rng, [p], [(60.0, 60.0), (260.0, 180.0)]) for p in truth]
        motion = frame_differences(frames)
        for mean in errors:
            f = MeanShiftParticleFilter(truth[0], (17, 17), np.random.default_rng(100 + seed),
                                        process_sigma=6.0, velocity=truth[1] - truth[0],
                                        mean=mean)
            est = []
            for c, m in zip(frames, motion):
                est.append(f.update(c, m))
                if mean == "paper" and not f.lost:
                    np.testing.assert_allclose(est[-1], f.particles.mean(axis=0))
                    x0, y0 = f.windows()[:, 0], f.windows()[:, 1]
                    mass = np.array([c[y:y + 17, x:x + 17].sum() for x, y in zip(x0, y0)])
                    # every particle's window within the colour-mass band (up to the pixel
                    # rounding of the window corner at the particle's moved centre)
                    assert np.all(np.abs(mass - f.area) <= 0.35 * f.area)
            errors[mean].append(rmse(est, truth))
    assert np.mean(errors["paper"]) < 1.5, errors
    assert np.mean(errors["paper"]) <= np.mean(errors["weighted"]) + 0.5, errors


def test_lost_track_and_global_reacquisition():
    rng = np.random.default_rng(5)
    first = np.array([[60.0 + 4 * k, 60.0 + 2 * k] for k in range(15)])
    second = np.array([[250.0 - 3 * k, 190.0 - 2 * k] for k in range(10)])
    distractor = [(160.0, 200.0)]  # similar colour, too little of it: never taken
    frames = ([weight_image(rng, [p], distractor) for p in first]
              + [weight_image(rng, [], distractor) for _ in range(4)]
              + [weight_image(rng, [p], distractor) for p in second])
    f = MeanShiftParticleFilter(first[0], (17, 17), np.random.default_rng(0), velocity=(4, 2))
    lost, est = [], []
    for c in frames:
        est.append(f.update(c))
        lost.append(f.lost)
    assert not any(lost[:15])
    assert all(lost[15:19])  # lost while invisible, keeping the last estimate
    for e in est[15:19]:
        np.testing.assert_allclose(e[:2], est[14][:2])
        assert np.all(e[2:] == 0.0)
    assert f.lost_frames == 4
    assert not any(lost[19:])  # the global search finds it in the frame it reappears
    err = np.hypot(*(np.array(est[19:])[:, :2] - second).T)
    assert err.max() < 2.0, err


def test_ball_occluded_by_a_robot_is_placed_at_the_robot():
    ball = np.array([[50.0 + 6 * k, 100.0] for k in range(12)])
    robot = np.array([122.0, 101.0])  # the ball rolls under it at frame 12
    robots = np.array([[250.0, 40.0], robot])
    rng = np.random.default_rng(3)
    frames = ([weight_image(rng, [p], sigma=2.5) for p in ball]
              + [weight_image(rng, [], sigma=2.5)] * 3)
    results = {}
    for with_robots in (True, False):
        f = MeanShiftParticleFilter(ball[0], (11, 11), np.random.default_rng(1),
                                    velocity=(6, 0))
        for c in frames[:12]:
            f.update(c)
        assert f.occluded_by(robots, 8.0) == 1  # the predicted position is at the robot
        assert f.occluded_by(robots[:1], 8.0) is None
        e = f.update(frames[12], robots=robots if with_robots else None, robot_radius_px=8.0)
        results[with_robots] = (e, f.lost, f.occluded, f.occluder)
    e, lost, occluded, occluder = results[True]
    np.testing.assert_allclose(e, [robot[0], robot[1], 0.0, 0.0])
    assert occluded and occluder == 1 and not lost
    e, lost, occluded, _ = results[False]
    assert lost and not occluded
    assert abs(e[0] - ball[-1, 0]) < 2.0  # fell back to the last estimate


def test_same_seed_same_track_and_a_different_seed_differs():
    rng = np.random.default_rng(7)
    truth = manoeuvre(rng, steps=15)
    frames = [weight_image(rng, [p]) for p in truth]
    motion = frame_differences(frames)

    def run(seed, cls):
        f = cls(truth[0], (17, 17), np.random.default_rng(seed))
        est = [f.update(c, m) for c, m in zip(frames, motion)]
        return np.array(est), f.particles.copy()

    for cls in (MeanShiftParticleFilter, ParticleFilterTracker):
        a, pa = run(11, cls)
        b, pb = run(11, cls)
        c, pc = run(12, cls)
        np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(pa, pb)
        assert not np.array_equal(pa, pc)


def test_feature_check_hook_vetoes_windows():
    rng = np.random.default_rng(4)
    img = weight_image(rng, [(100.0, 100.0)], [(200.0, 100.0)])
    calls = []

    def left_half_only(windows, colour):
        calls.append(windows.shape)
        assert colour.shape == (H, W)
        return windows[:, 0] < 150

    f = MeanShiftParticleFilter((100.0, 100.0), (17, 17), np.random.default_rng(0),
                                feature_check=left_half_only)
    f.update(img)
    assert calls and calls[0][1] == 4 and not f.lost
    f = MeanShiftParticleFilter((100.0, 100.0), (17, 17), np.random.default_rng(0),
                                feature_check=lambda w, c: np.zeros(len(w), bool))
    f.update(img)
    assert f.lost


@pytest.mark.parametrize("call, name", [
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), GEN, n_particles=1), "n_particles"),
    (lambda: MeanShiftParticleFilter((1, 1), (0, 5), GEN), "window_size"),
    (lambda: MeanShiftParticleFilter((1, np.nan), (5, 5), GEN), "position"),
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), None), "rng"),
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), GEN, likelihood_sigma=0), "likelihood_sigma"),
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), GEN, area_tolerance=-1), "area_tolerance"),
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), GEN, max_motion_weight=2),
     "max_motion_weight"),
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), GEN, feature_check=3), "feature_check"),
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), GEN, area=1.0).update(IMG, IMG[:5]),
     "motion_image"),
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), GEN, area=1.0).update(IMG, robots=[]),
     "robot_radius_px"),
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), GEN).update(IMG), "area"),
    (lambda: ParticleFilterTracker((1, 1), (5, 5), GEN, process_sigma=-1), "process_sigma"),
    (lambda: MeanShiftParticleFilter((1, 1), (5, 5), GEN, mean="median"), "mean"),
])
def test_bad_arguments_raise_value_error_naming_them(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_a_first_image_with_nothing_to_calibrate_on_leaves_the_filter_as_it_was():
    """Without ``area``, a first image with no weight where the filter starts raises
    :class:`EmptyWindowError` (a ``ValueError``) and changes nothing: the same filter then
    calibrates on an image that shows the target, as a new one would."""
    img = np.zeros((60, 80))
    f = MeanShiftParticleFilter((30.0, 20.0), (9, 9), np.random.default_rng(4))
    g = MeanShiftParticleFilter((30.0, 20.0), (9, 9), np.random.default_rng(4))
    particles = f.particles.copy()
    with pytest.raises(EmptyWindowError, match="area"):
        f.update(img)
    assert issubclass(EmptyWindowError, ValueError)
    assert f.area is None and f.frame == 0 and not f.lost
    np.testing.assert_array_equal(f.particles, particles)
    img[17:24, 27:34] = 1.0
    np.testing.assert_array_equal(f.update(img), g.update(img))
    assert f.area == g.area > 0


@pytest.mark.parametrize("cls", [MeanShiftParticleFilter, ParticleFilterTracker])
def test_region_images_give_the_whole_images_results_bit_for_bit(cls):
    """Region images of the colour and the motion, computed only where the tracker asks (its
    windows widened by the longest way mean shift can take them; everything for a global
    search), give the tracks of the whole images exactly, through manoeuvres, a lost track
    and its global search; the mean-shift filter computes a small part of each image."""
    from estimators.image.meanshift import RegionImage

    rng = np.random.default_rng(4)
    truth = np.concatenate([manoeuvre(rng)[:30], np.array([[250.0 - 3 * k, 190.0 - 2 * k]
                                                          for k in range(10)])])
    frames = ([weight_image(rng, [p], [(60.0, 60.0)]) for p in truth[:30]]
              + [weight_image(rng, [], [(60.0, 60.0)]) for _ in range(3)]
              + [weight_image(rng, [p], [(60.0, 60.0)]) for p in truth[30:]])
    motion = frame_differences(frames)
    computed = []

    def run(lazy: bool) -> list:
        f = cls(truth[0], (17, 17), np.random.default_rng(8), n_particles=20,
                process_sigma=6.0, velocity=truth[1] - truth[0])
        out = []
        for c, m in zip(frames, motion):
            if lazy:
                img = RegionImage(c.shape, lambda x0, y0, x1, y1, c=c: c[y0:y1, x0:x1])
                lazy_m = None if m is None else RegionImage(
                    m.shape, lambda x0, y0, x1, y1, m=m: m[y0:y1, x0:x1])
                out.append(f.update(img, lazy_m).tolist())
                computed.append(sum((x1 - x0) * (y1 - y0)
                                    for x0, y0, x1, y1 in img._boxes) / c.size)
            else:
                out.append(f.update(c, m).tolist())
        return out

    assert run(True) == run(False)
    if cls is MeanShiftParticleFilter:  # (the plain filter's particles scatter when lost)
        assert np.median(computed) < 0.3  # (a 320 x 240 test image; 17 px windows)


def test_region_image_computes_each_box_once_and_clips_it():
    from estimators.image.meanshift import RegionImage

    calls = []
    base = np.arange(12.0, dtype=np.float32).reshape(3, 4)

    def fill(x0, y0, x1, y1):
        calls.append((x0, y0, x1, y1))
        return base[y0:y1, x0:x1]

    img = RegionImage((3, 4), fill)
    img.ensure(-2.5, 1, 2.2, 9)  # clipped to x 0..3, y 1..3
    img.ensure(0, 1, 2, 2)  # inside the first box: not computed again
    assert calls == [(0, 1, 3, 3)]
    assert img.array.tolist() == [[0, 0, 0, 0], [4, 5, 6, 0], [8, 9, 10, 0]]
    np.testing.assert_array_equal(img.full(), base)
