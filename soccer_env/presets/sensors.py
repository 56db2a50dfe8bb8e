"""Sensor presets: overhead vision (SSL), head cameras (humanoids) and team radio links."""

from __future__ import annotations

import math
from dataclasses import dataclass

from estimators import HeadCamera
from estimators.registry import Registry
from soccer_env.validation import (
    check_flag,
    check_integer,
    check_number,
    preset_table,
    resolve_preset,
)

__all__ = ["HeadCameraSpec", "HEAD_CAMERAS", "head_camera", "RadioSpec", "RADIO_PRESETS", "radio",
           "VisionSpec", "VISION", "vision", "SENSOR_PRESETS"]


@dataclass(frozen=True)
class VisionSpec:
    """Sensor and actuation characteristics of an SSL setup (see the module docstring).

    Attributes:
        frame_rate: frames per second per camera; None captures once per environment step.
        latency: capture-to-delivery delay of a frame [s].
        latency_jitter: extra delay, uniform in ``[0, latency_jitter]`` [s].
        actuation_latency: delay between the policy's command and the robot executing it [s].
        command_loss: probability that a robot misses a command (it keeps the previous one).
        ball_sigma: ball position noise [m]. robot_sigma: robot position noise [m].
        robot_sigma_theta: robot heading noise [rad].
        ball_detection, robot_detection: detection probabilities of visible objects.
        dribbler_false_rate: spurious balls at robot fronts [1/s per robot in view].
        random_false_rate: spurious balls anywhere in view [1/s per camera].
        occlusion_threshold: fraction of the ball that must be covered to hide it; above 1
            never hides it.
        camera_height: height of the cameras [m].
        camera_overlap: how far a camera sees beyond its own area [m].
        source: where the numbers come from.
    """

    name: str
    frame_rate: float | None
    latency: float
    latency_jitter: float
    actuation_latency: float
    command_loss: float
    ball_sigma: float
    robot_sigma: float
    robot_sigma_theta: float
    ball_detection: float
    robot_detection: float
    dribbler_false_rate: float
    random_false_rate: float
    occlusion_threshold: float
    camera_height: float
    camera_overlap: float
    source: str

    def __post_init__(self) -> None:
        def check(name: str, low: float, high: float) -> None:
            check_number(f"vision.{name}", getattr(self, name), low, high)

        if self.frame_rate is not None:
            check("frame_rate", 1.0, 1000.0)
        for name in ("latency", "latency_jitter", "actuation_latency"):
            check(name, 0.0, 2.0)
        for name in ("command_loss", "ball_detection", "robot_detection"):
            check(name, 0.0, 1.0)
        for name in ("ball_sigma", "robot_sigma"):
            check(name, 0.0, 1.0)
        check("robot_sigma_theta", 0.0, math.pi)
        for name in ("dribbler_false_rate", "random_false_rate"):
            check(name, 0.0, 1000.0)
        check("occlusion_threshold", 0.0, 2.0)
        check("camera_height", 0.5, 50.0)
        check("camera_overlap", 0.0, 10.0)


VISION: Registry[VisionSpec] = preset_table('vision', {
    # Perfect sensing: every step, no noise, no delay, nothing missed or hidden.
    "ideal": VisionSpec(
        name="ideal", frame_rate=None, latency=0.0, latency_jitter=0.0, actuation_latency=0.0,
        command_loss=0.0, ball_sigma=0.0, robot_sigma=0.0, robot_sigma_theta=0.0,
        ball_detection=1.0, robot_detection=1.0, dribbler_false_rate=0.0,
        random_false_rate=0.0, occlusion_threshold=2.0, camera_height=4.0,
        camera_overlap=0.3, source="no imperfection",
    ),
    # Zhao et al. (2012): 40 ms decision cycle (25 Hz vision), 120 ms from image capture to
    # actuation, ball position noise delta_xy = 25 mm. The paper does not split the 120 ms; we
    # take one 40 ms cycle for command transmission and execution and 80 ms for the vision pipeline,
    # so a measurement is three cycles old when the command it leads to takes effect (the
    # paper's N = 3). Robot noise as the ball's; heading noise 0.05 rad (not in the paper).
    "ssl-2012": VisionSpec(
        name="ssl-2012", frame_rate=25.0, latency=0.08, latency_jitter=0.0,
        actuation_latency=0.04, command_loss=0.0, ball_sigma=0.025, robot_sigma=0.025,
        robot_sigma_theta=0.05, ball_detection=1.0, robot_detection=1.0,
        dribbler_false_rate=0.0, random_false_rate=0.0, occlusion_threshold=0.4,
        camera_height=4.0, camera_overlap=0.3,
        source="Zhao et al. (2012) (25 Hz, 120 ms capture to actuation, 25 mm)",
    ),
    # ER-Force simulator, realism preset "Realistic": ball 1.4 mm, robots 1.3 mm and 0.01 rad,
    # 5 % missing ball and 2 % missing robot detections, 35 ms vision delay plus 10 ms
    # processing, ball hidden when 40 % covered, 1 m camera overlap, 0.05 spurious dribbler
    # detections per second per robot, 3 % lost robot commands. SSL-Vision runs at 60-75 Hz;
    # we take 60 Hz.
    "realistic": VisionSpec(
        name="realistic", frame_rate=60.0, latency=0.045, latency_jitter=0.0,
        actuation_latency=0.0, command_loss=0.03, ball_sigma=0.0014, robot_sigma=0.0013,
        robot_sigma_theta=0.01, ball_detection=0.95, robot_detection=0.98,
        dribbler_false_rate=0.05, random_false_rate=0.0, occlusion_threshold=0.4,
        camera_height=4.0, camera_overlap=1.0,
        source="ER-Force simulator realism preset 'Realistic'",
    ),
    # A poorly lit, badly calibrated setup (our choice, for robustness tests): 30 Hz, 100 ms
    # plus up to 20 ms of jitter, 40 ms actuation, centimetre noise, 20 % missing balls,
    # frequent spurious balls, easy occlusion, 10 % lost commands.
    "harsh": VisionSpec(
        name="harsh", frame_rate=30.0, latency=0.1, latency_jitter=0.02,
        actuation_latency=0.04, command_loss=0.1, ball_sigma=0.01, robot_sigma=0.01,
        robot_sigma_theta=0.05, ball_detection=0.8, robot_detection=0.9,
        dribbler_false_rate=0.3, random_false_rate=2.0, occlusion_threshold=0.25,
        camera_height=4.0, camera_overlap=0.5,
        source="our choice: larger noise, latency and loss than 'realistic'",
    ),
})


def vision(spec: str | VisionSpec = "realistic", **overrides) -> VisionSpec:
    """Return a vision preset (by name or spec) with optional validated overrides."""
    return resolve_preset("vision", VISION, spec, overrides)


@dataclass(frozen=True)
class HeadCameraSpec:
    """Characteristics of a head camera and its image processing (see the module docstring).

    Attributes:
        name: preset name.
        height: camera height above the ground [m].
        hfov: horizontal field of view [rad].
        width, height_px: image size [pixels].
        frame_rate: frames per second; None captures once per :meth:`HeadCameraSensor.step`.
        latency: capture-to-delivery delay [s]. latency_jitter: extra delay, uniform in
            ``[0, latency_jitter]`` [s].
        pixel_sigma: Gaussian noise on ``u`` and on ``v`` [pixels].
        ball_range, landmark_range, robot_range: farthest detection of each kind [m], ground
            distance from the observer.
        ball_detection, landmark_detection, robot_detection: probability of detecting an object
            that is in view, in range and not occluded.
        false_ball_rate: spurious balls [1/s] (at most one per frame), on the ground in view.
        occlusion: robots hide what is behind them.
        distinct_goals: the two goals can be told apart (coloured goals): posts are
            ``"post_blue"`` / ``"post_yellow"``, otherwise all are ``"post"``.
        source: where the numbers come from.
    """

    name: str
    height: float
    hfov: float
    width: int
    height_px: int
    frame_rate: float | None
    latency: float
    latency_jitter: float
    pixel_sigma: float
    ball_range: float
    landmark_range: float
    robot_range: float
    ball_detection: float
    landmark_detection: float
    robot_detection: float
    false_ball_rate: float
    occlusion: bool
    distinct_goals: bool
    source: str

    def __post_init__(self) -> None:
        def check(name: str, low: float, high: float, *, low_open: bool = False,
                  high_open: bool = False) -> None:
            check_number(f"head_camera.{name}", getattr(self, name), low, high,
                         low_open=low_open, high_open=high_open)

        check("height", 0.05, 5.0)
        check("hfov", 0.0, math.pi, low_open=True, high_open=True)
        for name in ("width", "height_px"):
            check_integer(f"head_camera.{name}", getattr(self, name), 2, 100_000, " pixels")
        if self.frame_rate is not None:
            check("frame_rate", 1.0, 1000.0)
        for name in ("latency", "latency_jitter"):
            check(name, 0.0, 2.0)
        check("pixel_sigma", 0.0, 100.0)
        for name in ("ball_range", "landmark_range", "robot_range"):
            check(name, 0.0, 100.0, low_open=True)
        for name in ("ball_detection", "landmark_detection", "robot_detection"):
            check(name, 0.0, 1.0)
        check("false_ball_rate", 0.0, 1000.0)
        for name in ("occlusion", "distinct_goals"):
            check_flag(f"head_camera.{name}", getattr(self, name))

    @property
    def camera(self) -> HeadCamera:
        """The pinhole model (:class:`estimators.HeadCamera`) with this geometry: the
        filters' measurement model of this sensor."""
        return HeadCamera(height=self.height, hfov=self.hfov, width=self.width,
                          height_px=self.height_px)


HEAD_CAMERAS: Registry[HeadCameraSpec] = preset_table('head_camera', {
    # Perfect sensing: Xu et al.'s (2012) camera geometry, a frame at every step call
    # (frame_rate=None), no delay, no noise, every object in view and range detected, no
    # spurious balls. Occlusion stays on: it is geometry, not an imperfection. Ranges of
    # 100 m: everything on any field.
    "ideal": HeadCameraSpec(
        name="ideal", height=0.56, hfov=math.radians(51.0), width=720, height_px=625,
        frame_rate=None, latency=0.0, latency_jitter=0.0, pixel_sigma=0.0,
        ball_range=100.0, landmark_range=100.0, robot_range=100.0,
        ball_detection=1.0, landmark_detection=1.0, robot_detection=1.0,
        false_ball_rate=0.0, occlusion=True, distinct_goals=True,
        source="no imperfection; Xu et al.'s (2012) camera geometry",
    ),
    # Xu et al.'s (2012) robot of 2012: CCD camera 0.56 m high, 51 degrees horizontal field of view,
    # 720 x 625 pixels at 25 frames/s (all from the paper). Assumptions (ours): 0.04 s from
    # capture to delivery (one frame period of embedded DSP processing), no jitter (a fixed
    # pipeline); 2 px noise on a colour blob's centroid; an orange ball found up to 5 m
    # (a 66 mm ball is then about 10 px wide); landmarks and robots' feet up to 4 m (Guo
    # and Li 2013 ignore obstacle-ground corners beyond 4 m, where their depth error grows);
    # detection 0.95 (ball), 0.9 (landmarks, robots); 0.2 spurious orange blobs per second
    # (clutter beyond the field); coloured goals (blue and yellow in 2012) tell the two goals
    # apart.
    "kidsize-2012": HeadCameraSpec(
        name="kidsize-2012", height=0.56, hfov=math.radians(51.0), width=720, height_px=625,
        frame_rate=25.0, latency=0.04, latency_jitter=0.0, pixel_sigma=2.0,
        ball_range=5.0, landmark_range=4.0, robot_range=4.0,
        ball_detection=0.95, landmark_detection=0.9, robot_detection=0.9,
        false_ball_rate=0.2, occlusion=True, distinct_goals=True,
        source="Xu et al. (2012) (0.56 m, 51 deg, 720 x 625, 25 Hz); Guo and Li (2013) (4 m "
               "landmark range); latency, noise, detection and false rates assumed",
    ),
    # A current KidSize robot (assumptions of ours, of the order of published KidSize
    # platforms): the same camera geometry as Xu et al.'s (2012), so that presets differ in their
    # processing only (real robots now often use wider lenses: override hfov); 30 frames/s;
    # 0.05 s from capture to delivery with up to 0.01 s of jitter (a neural detector on a
    # shared CPU/GPU); 1.5 px noise (a detector's box centre); a size-1 ball found up to 6 m;
    # landmarks and robots ignored beyond 4 m, as Guo and Li (2013) does (their ground projections
    # are poor farther away); detection 0.95 / 0.9 / 0.9; 0.1 spurious balls per second.
    # Both goals are white under the current rules: posts cannot be told apart.
    "kidsize": HeadCameraSpec(
        name="kidsize", height=0.56, hfov=math.radians(51.0), width=720, height_px=625,
        frame_rate=30.0, latency=0.05, latency_jitter=0.01, pixel_sigma=1.5,
        ball_range=6.0, landmark_range=4.0, robot_range=4.0,
        ball_detection=0.95, landmark_detection=0.9, robot_detection=0.9,
        false_ball_rate=0.1, occlusion=True, distinct_goals=False,
        source="current Humanoid KidSize rules (white goals); camera as Xu et al. (2012); timing, "
               "noise, ranges, detection and false rates assumed",
    ),
})


def head_camera(spec: str | HeadCameraSpec = "kidsize", **overrides: object) -> HeadCameraSpec:
    """Return a head-camera preset (by name or spec) with optional validated overrides."""
    return resolve_preset("head_camera", HEAD_CAMERAS, spec, overrides)


@dataclass(frozen=True)
class RadioSpec:
    """The link: ``latency`` [s] plus a uniform ``jitter`` [s], ``loss`` probability per
    packet and receiver."""

    latency: float = 0.03
    jitter: float = 0.02
    loss: float = 0.1
    name: str = "custom"
    source: str = ""

    def __post_init__(self) -> None:
        check_number("latency", self.latency, 0, 10, unit=" s")
        check_number("jitter", self.jitter, 0, 10, unit=" s")
        check_number("loss", self.loss, 0, 1)


#: Named links.
RADIO_PRESETS: Registry[RadioSpec] = preset_table("radio", {
    "ideal": RadioSpec(0.0, 0.0, 0.0, name="ideal", source="instant and lossless"),
    # Xu et al.'s (2012) robots talk over a self-organising ZigBee network; it gives no figures.
    "zigbee": RadioSpec(0.03, 0.02, 0.1, name="zigbee",
                        source="our reading of a crowded 2.4 GHz ZigBee network at a RoboCup "
                               "venue: tens of milliseconds, one packet in ten lost"),
})


#: The sensor presets that ``perception="NAME"`` selects, per robot kind: the overhead vision
#: of SSL robots and the head cameras of humanoids.
SENSOR_PRESETS: dict[str, Registry] = {"ssl": VISION, "humanoid": HEAD_CAMERAS}


def radio(spec: str | RadioSpec = "zigbee", **overrides: object) -> RadioSpec:
    """Return a radio preset (by name or spec) with optional validated overrides."""
    return resolve_preset("radio", RADIO_PRESETS, spec, overrides)
