"""Yu et al.'s (2010) Kalman-started mean shift with ego-motion compensation, plain mean shift and
depth from size on synthetic weight images: a camera that turns fast, a robot walking towards
its target, the ego-motion shift's signs, bad arguments."""

from __future__ import annotations

import math

import numpy as np
import pytest
from weight_images import H, W, rmse, weight_image

from estimators import (
    KalmanMeanShift,
    PlainMeanShift,
    apparent_height,
    depth_from_size,
    ego_motion_shift,
    focal_length_px,
)

IMG = np.zeros((H, W), np.float32)


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
    frames = [weight_image(rng, [p], [(40.0, 40.0)], sigma=5.0) for p in truth]
    kms = KalmanMeanShift(truth[0], (21, 21), image_size=(W, H), fov=(gamma_x, 0.75))
    plain = PlainMeanShift(truth[0], (21, 21))
    k_est, p_est = [], []
    for k in range(1, steps + 1):
        k_est.append(kms.update(frames[k], rotation=yaw[k] - yaw[k - 1]))
        p_est.append(plain.update(frames[k]))
    assert kms.lost_frames == 0
    assert rmse(k_est, truth[1:]) < 1.5
    assert plain.lost_frames >= 5
    assert rmse(p_est, truth[1:]) > 20.0
    # Without the rotation the Kalman prediction alone is not enough either.
    blind = KalmanMeanShift(truth[0], (21, 21), image_size=(W, H), fov=(gamma_x, 0.75))
    for k in range(1, steps + 1):
        blind.update(frames[k])
    assert blind.lost_frames > 0


@pytest.mark.parametrize("order", ["ours", "paper"])
def test_both_orders_keep_the_target_the_turning_camera_sweeps_across(order):
    rng = np.random.default_rng(8)
    steps = 40
    yaw = 0.35 * np.sin(2 * np.pi * np.arange(steps + 1) / 20)
    own = np.cumsum(rng.normal(0.0, 0.5, (steps + 1, 2)), axis=0)
    truth = np.stack([160.0 + yaw * W + own[:, 0], 120.0 + own[:, 1]], axis=1)
    frames = [weight_image(rng, [p], [(40.0, 40.0)], sigma=5.0) for p in truth]
    kms = KalmanMeanShift(truth[0], (21, 21), image_size=(W, H), fov=(1.0, 0.75), order=order)
    est = [kms.update(frames[k], rotation=yaw[k] - yaw[k - 1]) for k in range(1, steps + 1)]
    assert kms.lost_frames == 0
    assert rmse(est, truth[1:]) < 1.5


def test_paper_order_measures_the_region_centroid_then_shifts_from_the_posterior():
    """Yu et al.'s (2010) order: the measurement is the weights' centroid in the region R (twice
    the target) around the prediction; mean shift starts from the Kalman posterior and its
    result replaces the posterior's position. A target 14 px from the prediction (outside a
    21 px window centred there, inside the 42 px region): R sees part of it, the update pulls
    the posterior towards it, mean shift from there reaches its centre."""
    rng = np.random.default_rng(1)
    img = weight_image(rng, [(174.0, 120.0)], [], sigma=4.0)
    kms = KalmanMeanShift((160.0, 120.0), (21, 21), image_size=(W, H), fov=(1.0, 0.75),
                          order="paper", init_sigma=(20.0, 5.0))
    kms.update(img)
    assert not kms.lost
    assert abs(kms.state[0] - 174.0) < 1.0 and abs(kms.state[1] - 120.0) < 1.0
    # The Kalman filter's measurement was R's centroid, between the prediction and the
    # target (R holds only the target's near side), not mean shift's converged position.
    z = kms.kf.y + kms.prediction  # innovation plus the predicted position
    assert 160.0 < z[0] < 174.0
    # Nothing in R: lost, left at the prediction.
    kms = KalmanMeanShift((40.0, 200.0), (21, 21), image_size=(W, H), fov=(1.0, 0.75),
                          order="paper")
    kms.update(img)
    assert kms.lost
    np.testing.assert_allclose(kms.state[:2], (40.0, 200.0))


def test_kalman_mean_shift_standard_update_and_forward_motion():
    h, d0, s = 1.0, 3.0, 0.1
    fov = (1.0, 0.75)
    ds = d0 - s * np.arange(15)
    ys = 120.0 + np.arctan(h / ds) * H / fov[1] - np.arctan(h / d0) * H / fov[1] + 20.0
    truth = np.stack([np.full_like(ys, 160.0), ys], axis=1)
    rng = np.random.default_rng(9)
    frames = [weight_image(rng, [p], sigma=4.0) for p in truth]
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


def test_bad_order_arguments():
    with pytest.raises(ValueError, match="order must be one of"):
        KalmanMeanShift((1, 1), (5, 5), image_size=(W, H), fov=(1.0, 0.75), order="printed")
    with pytest.raises(ValueError, match="posterior must be 'replace' with order='paper'"):
        KalmanMeanShift((1, 1), (5, 5), image_size=(W, H), fov=(1.0, 0.75), order="paper",
                        posterior="update")
    with pytest.raises(ValueError, match="region_scale"):
        KalmanMeanShift((1, 1), (5, 5), image_size=(W, H), fov=(1.0, 0.75), region_scale=0)


@pytest.mark.parametrize("call, name", [
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
