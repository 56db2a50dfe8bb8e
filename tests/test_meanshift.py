"""Mean shift (against OpenCV), paper 003's feature-restricted mean-shift particle filter and
paper 004's Kalman-started mean shift, on synthetic images: Gaussian blobs on a noisy
background, a distractor of a similar colour, disappearing targets, occluding robots and a
camera that turns fast. OpenCV is only an oracle here; ``estimators`` never imports it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators import (
    KalmanMeanShift,
    MeanShiftParticleFilter,
    ParticleFilterTracker,
    PlainMeanShift,
    apparent_height,
    depth_from_size,
    ego_motion_shift,
    focal_length_px,
    mean_shift,
)

cv2 = pytest.importorskip("cv2")

H, W = 240, 320
YY, XX = np.mgrid[0:H, 0:W].astype(np.float32)


def _blob(img: np.ndarray, centre, sigma: float, amp: float) -> None:
    """Add a Gaussian blob (in place), evaluated within 4 sigma."""
    x, y = centre
    r = int(4 * sigma) + 1
    x0, x1 = max(int(x) - r, 0), min(int(x) + r + 1, img.shape[1])
    y0, y1 = max(int(y) - r, 0), min(int(y) + r + 1, img.shape[0])
    if x1 > x0 and y1 > y0:
        d2 = (XX[y0:y1, x0:x1] - x) ** 2 + (YY[y0:y1, x0:x1] - y) ** 2
        img[y0:y1, x0:x1] += amp * np.exp(-d2 / (2.0 * sigma * sigma))


def _frame(rng, targets=(), distractors=(), sigma=4.0, noise=0.1) -> np.ndarray:
    """Colour probability image: uniform noise in [0, noise), target blobs of amplitude 0.9,
    distractors (a similar colour) of amplitude 0.5, clipped to [0, 1]."""
    img = (rng.random((H, W)) * noise).astype(np.float32)
    for p in targets:
        _blob(img, p, sigma, 0.9)
    for p in distractors:
        _blob(img, p, sigma, 0.5)
    return np.clip(img, 0.0, 1.0)


def _motion(frames):
    return [np.zeros_like(frames[0])] + [np.abs(b - a) for a, b in zip(frames, frames[1:])]


def _manoeuvre(rng, steps=60, speed=10.0, every=6, start=(160.0, 120.0)) -> np.ndarray:
    """A target at ``speed`` px/frame that turns sharply (60-108 degrees) every ``every``
    frames and bounces off a 20 px margin."""
    p, heading, out = np.array(start), rng.uniform(0, 2 * math.pi), []
    for k in range(steps):
        if k and k % every == 0:
            heading += rng.choice([-1, 1]) * rng.uniform(math.pi / 3, 0.6 * math.pi)
        q = p + speed * np.array([math.cos(heading), math.sin(heading)])
        if not 20 < q[0] < W - 20:
            heading = math.pi - heading
        if not 20 < q[1] < H - 20:
            heading = -heading
        p = p + speed * np.array([math.cos(heading), math.sin(heading)])
        out.append(p.copy())
    return np.array(out)


def _rmse(est, truth) -> float:
    return float(np.sqrt(np.mean(np.sum((np.asarray(est)[:, :2] - truth) ** 2, axis=1))))


# ------------------------------------------------------------------------------------------
# mean_shift
# ------------------------------------------------------------------------------------------

def _blob_scenes(seed, n):
    """Random images with four well-separated blobs and a window near one of them."""
    rng = np.random.default_rng(seed)
    grid = [(60, 60), (220, 60), (60, 170), (220, 170)]
    for _ in range(n):
        img = (rng.random((H, W)) * 0.1).astype(np.float32)
        truth = []
        for gx, gy in grid:
            c = (gx + rng.uniform(-8, 8), gy + rng.uniform(-8, 8))
            truth.append(c)
            _blob(img, c, rng.uniform(3, 6), rng.uniform(0.6, 1.0))
        img = np.clip(img, 0, 1)
        w, h = (int(v) for v in rng.integers(9, 25, 2))
        k = int(rng.integers(4))
        x = int(truth[k][0] + rng.integers(-10, 11) - w // 2)
        y = int(truth[k][1] + rng.integers(-10, 11) - h // 2)
        yield img, (x, y, w, h), np.array(truth[k])


def test_mean_shift_reproduces_cv2_windows_exactly_in_opencv_mode():
    crit = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 20, 1)
    for img, win, _ in _blob_scenes(0, 60):
        _, ours, _, mass = mean_shift(img, win, max_iter=20, eps=1.0, opencv_compatible=True)
        _, theirs = cv2.meanShift(img, win, crit)
        assert ours == tuple(theirs)
        x, y, w, h = ours
        assert mass == pytest.approx(float(img[y:y + h, x:x + w].sum()), rel=1e-5)


def test_mean_shift_matches_cv2_within_a_pixel_or_two_and_is_closer_to_the_blob():
    crit = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 20, 1)
    diffs, ours_err, cv_err = [], [], []
    for img, win, truth in _blob_scenes(1, 100):
        centre, ours, _, _ = mean_shift(img, win, max_iter=20, eps=1.0)
        _, theirs = cv2.meanShift(img, win, crit)
        diffs.append(max(abs(ours[0] - theirs[0]), abs(ours[1] - theirs[1])))
        x, y, w, h = theirs
        p = img[y:y + h, x:x + w].astype(np.float64)
        cv_centre = (x + p.sum(0) @ np.arange(w) / p.sum(), y + p.sum(1) @ np.arange(h) / p.sum())
        ours_err.append(np.hypot(*(centre - truth)))
        cv_err.append(np.hypot(*(np.array(cv_centre) - truth)))
    diffs = np.array(diffs)
    # OpenCV compares the centroid with w/2 instead of (w-1)/2: the windows stall at most a
    # pixel or two apart, and ours end nearer the blobs' centres.
    assert np.mean(diffs <= 1) > 0.6 and np.mean(diffs <= 2) > 0.9
    assert np.median(ours_err) < np.median(cv_err)
    assert np.median(ours_err) < 1.0


def test_mean_shift_climbs_to_the_blob_with_either_kernel():
    img = _frame(np.random.default_rng(2), targets=[(100.3, 80.6)], sigma=5.0)
    for kernel in ("flat", "epanechnikov"):
        centre, win, iters, mass = mean_shift(img, (80, 65, 21, 21), kernel=kernel)
        assert np.hypot(centre[0] - 100.3, centre[1] - 80.6) < 1.0, kernel
        assert 1 <= iters <= 10 and mass > 100.0


# ------------------------------------------------------------------------------------------
# Paper 003: mean-shift particle filter
# ------------------------------------------------------------------------------------------

def test_mean_shift_pf_with_20_particles_beats_plain_pf_on_a_manoeuvring_target():
    ms20, pf20, pf200 = [], [], []
    for seed in range(3):
        rng = np.random.default_rng(seed)
        truth = _manoeuvre(rng)
        frames = [_frame(rng, [p], [(60.0, 60.0), (260.0, 180.0)]) for p in truth]
        motion = _motion(frames)
        for out, cls, n in ((ms20, MeanShiftParticleFilter, 20),
                            (pf20, ParticleFilterTracker, 20),
                            (pf200, ParticleFilterTracker, 200)):
            f = cls(truth[0], (17, 17), np.random.default_rng(100 + seed), n_particles=n,
                    process_sigma=6.0, velocity=truth[1] - truth[0])
            est = [f.update(c, m) for c, m in zip(frames, motion)]
            out.append(_rmse(est, truth))
            if cls is MeanShiftParticleFilter:
                assert f.lost_frames == 0
    ms20, pf20, pf200 = np.mean(ms20), np.mean(pf20), np.mean(pf200)
    assert ms20 < 1.5, ms20  # well within the blob (sigma 4 px) through every turn
    assert ms20 < 0.5 * pf20, (ms20, pf20)
    assert ms20 <= pf200 + 0.5, (ms20, pf200)  # as good as ten times the particles


def test_lost_track_and_global_reacquisition():
    rng = np.random.default_rng(5)
    first = np.array([[60.0 + 4 * k, 60.0 + 2 * k] for k in range(15)])
    second = np.array([[250.0 - 3 * k, 190.0 - 2 * k] for k in range(10)])
    distractor = [(160.0, 200.0)]  # similar colour, too little of it: never taken
    frames = ([_frame(rng, [p], distractor) for p in first]
              + [_frame(rng, [], distractor) for _ in range(4)]
              + [_frame(rng, [p], distractor) for p in second])
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
    frames = [_frame(rng, [p], sigma=2.5) for p in ball] + [_frame(rng, [], sigma=2.5)] * 3
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
    truth = _manoeuvre(rng, steps=15)
    frames = [_frame(rng, [p]) for p in truth]
    motion = _motion(frames)

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
    img = _frame(rng, [(100.0, 100.0)], [(200.0, 100.0)])
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


# ------------------------------------------------------------------------------------------
# Paper 004: Kalman-started mean shift with ego-motion compensation
# ------------------------------------------------------------------------------------------

def test_ego_motion_shift_signs_and_magnitudes():
    size, fov = (320, 240), (1.0, 0.75)
    dx, dy = ego_motion_shift(0.05, 0.0, size, fov)
    assert dx == pytest.approx(0.05 * 320 / 1.0) and dy == 0.0  # left turn: scene moves right
    dx, dy = ego_motion_shift(0.0, 0.5, size, fov, camera_height=1.0, distance=3.0)
    assert dx == 0.0
    assert dy == pytest.approx((math.atan(1 / 2.5) - math.atan(1 / 3.0)) * 240 / 0.75)
    assert dy > 0.0  # approaching a target below the camera moves it down the image
    assert ego_motion_shift(0.0, -0.5, size, fov, 1.0, 3.0)[1] < 0.0


def test_kalman_mean_shift_keeps_a_target_that_the_turning_camera_sweeps_across():
    rng = np.random.default_rng(8)
    gamma_x = 1.0
    steps = 40
    yaw = 0.35 * np.sin(2 * np.pi * np.arange(steps + 1) / 20)  # up to 35 px/frame
    own = np.cumsum(rng.normal(0.0, 0.5, (steps + 1, 2)), axis=0)  # the target's own drift
    truth = np.stack([160.0 + yaw * W / gamma_x + own[:, 0], 120.0 + own[:, 1]], axis=1)
    frames = [_frame(rng, [p], [(40.0, 40.0)], sigma=5.0) for p in truth]
    kms = KalmanMeanShift(truth[0], (21, 21), image_size=(W, H), fov=(gamma_x, 0.75))
    plain = PlainMeanShift(truth[0], (21, 21))
    k_est, p_est = [], []
    for k in range(1, steps + 1):
        k_est.append(kms.update(frames[k], rotation=yaw[k] - yaw[k - 1]))
        p_est.append(plain.update(frames[k]))
    assert kms.lost_frames == 0
    assert _rmse(k_est, truth[1:]) < 1.5
    assert plain.lost_frames >= 5
    assert _rmse(p_est, truth[1:]) > 20.0
    # Without the rotation the Kalman prediction alone is not enough either.
    blind = KalmanMeanShift(truth[0], (21, 21), image_size=(W, H), fov=(gamma_x, 0.75))
    for k in range(1, steps + 1):
        blind.update(frames[k])
    assert blind.lost_frames > 0


def test_kalman_mean_shift_standard_update_and_forward_motion():
    h, d0, s = 1.0, 3.0, 0.1
    fov = (1.0, 0.75)
    ds = d0 - s * np.arange(15)
    ys = 120.0 + np.arctan(h / ds) * H / fov[1] - np.arctan(h / d0) * H / fov[1] + 20.0
    truth = np.stack([np.full_like(ys, 160.0), ys], axis=1)
    rng = np.random.default_rng(9)
    frames = [_frame(rng, [p], sigma=4.0) for p in truth]
    for posterior in ("replace", "update"):
        kms = KalmanMeanShift(truth[0], (17, 17), image_size=(W, H), fov=fov,
                              camera_height=h, distance=d0, posterior=posterior)
        pred_err = []
        for k in range(1, len(ds)):
            kms.update(frames[k], advance=s)
            pred_err.append(abs(kms.prediction[1] - ys[k]))
        assert kms.lost_frames == 0 and kms.distance == pytest.approx(ds[-1])
        assert np.max(pred_err) < 3.0, (posterior, pred_err)
        np.testing.assert_allclose(kms.state[:2], truth[-1], atol=1.0)


def test_depth_from_apparent_size():
    f = focal_length_px(H, 0.75)
    assert f == pytest.approx(120 / math.tan(0.375))
    rng = np.random.default_rng(10)
    size_m = 0.4
    for d in (1.5, 3.0, 6.0):
        px = f * size_m / d
        img = (rng.random((H, W)) * 0.2).astype(np.float32)
        top = int(round(120 - px / 2))
        img[top:top + int(round(px)), 150:170] = 0.9  # the target's pixels
        region = (130, max(top - 20, 0), 60, int(px) + 40)
        est = depth_from_size(size_m, apparent_height(img, region), f)
        assert est == pytest.approx(d, rel=0.03)
    kms = KalmanMeanShift((160.0, 120.0), (21, 21), image_size=(W, H), fov=(1.0, 0.75),
                          target_height_m=size_m)
    img = (rng.random((H, W)) * 0.2).astype(np.float32)
    px = int(round(f * size_m / 10.0))  # 10 m away: about 27 px tall
    img[120 - px // 2:120 - px // 2 + px, 152:168] = 0.9
    kms.update(img)
    assert kms.distance == pytest.approx(f * size_m / px, rel=0.03)


# ------------------------------------------------------------------------------------------
# Bad arguments
# ------------------------------------------------------------------------------------------

GEN = np.random.default_rng(0)
IMG = np.zeros((H, W), np.float32)


@pytest.mark.parametrize("call, name", [
    (lambda: mean_shift(np.zeros((4, 4, 3)), (0, 0, 2, 2)), "weight_image"),
    (lambda: mean_shift(-IMG - 1, (0, 0, 2, 2)), "weight_image"),
    (lambda: mean_shift(IMG, (0, 0, 0, 2)), "window w"),
    (lambda: mean_shift(IMG, (0, 0, 2.5, 2)), "window"),
    (lambda: mean_shift(IMG, (0, 0, 400, 2)), "window size"),
    (lambda: mean_shift(IMG, (0, 0, 2, 2), max_iter=0), "max_iter"),
    (lambda: mean_shift(IMG, (0, 0, 2, 2), eps=-1), "eps"),
    (lambda: mean_shift(IMG, (0, 0, 2, 2), kernel="gauss"), "kernel"),
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
    (lambda: KalmanMeanShift((1, 1), (5, 5), image_size=(W, H), fov=(0, 1)), "fov"),
    (lambda: KalmanMeanShift((1, 1), (5, 5), image_size=(W, H), fov=(1, 1), posterior="x"),
     "posterior"),
    (lambda: KalmanMeanShift((1, 1), (5, 5), image_size=(W, H), fov=(1, 1)).update(
        IMG, advance=0.1), "distance"),
    (lambda: KalmanMeanShift((1, 1), (5, 5), image_size=(W, H), fov=(1, 1), min_fill=2),
     "min_fill"),
    (lambda: PlainMeanShift((1, 1), (5, 5), window_scale=0), "window_scale"),
    (lambda: depth_from_size(1.0, 0.0, 500.0), "apparent_size_px"),
    (lambda: focal_length_px(480, 4.0), "fov"),
    (lambda: ego_motion_shift(math.inf, 0.0, (W, H), (1, 1)), "rotation"),
])
def test_bad_arguments_raise_value_error_naming_them(call, name):
    with pytest.raises(ValueError, match=name):
        call()
