"""Cameras that deliver rendered images instead of geometric detections.

* :class:`OverheadImageCamera`: the overhead camera of a field (SSL / MiroSot vision) with the
  timing of :class:`~soccer_env.sensors.overhead.OverheadVision` (frame rate, phases, latency,
  jitter), each frame an image of the world interpolated to its capture time, drawn by
  :class:`~soccer_env.sensors.images.overhead.OverheadRenderer` with the frame preset's
  lighting, noise and motion blur. What is in the image is for the team's software to find
  (:class:`~soccer_env.perception.pixels.OverheadPixelDetector`).
* :class:`PixelHeadCamera`: humanoids' head cameras whose frames carry their rendered image
  (:class:`~soccer_env.sensors.images.head.HeadFrameRenderer`) instead of geometric ball
  detections; landmarks and robots stay the geometric sensor's.

Every overhead camera of the vision preset renders its own images (one over fields up to 7 m
long, one per quadrant on larger fields, overlapping as the geometric cameras do): each frame is
its camera's view at the frame preset's resolution.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.presets.sensors import HeadCameraSpec, VisionSpec
from soccer_env.sensors.headcam import HeadCameraSensor, HeadFrame
from soccer_env.sensors.images.head import HeadFrameRenderer
from soccer_env.sensors.images.overhead import OverheadRenderer
from soccer_env.sensors.overhead import OverheadVision
from soccer_env.state import HeadState, WorldState

__all__ = ["ImageFrame", "OverheadImageCamera", "PixelHeadCamera", "interpolate_state",
           "PIXEL_FRAME_PRESET", "HEAD_IMAGE_SIZE"]

#: The frame preset of the rendered overhead images (:data:`soccer_env.presets.OVERHEAD_FRAMES`).
PIXEL_FRAME_PRESET = "realistic"
#: Rendered head-camera images [px] (the camera's field of view at a quarter of Xu et al.'s (2012)
#: 720 x 625 pixels, for speed; detections are scaled back to the camera's pixels).
HEAD_IMAGE_SIZE = (320, 240)


class ImageFrame(NamedTuple):
    """One overhead camera image as the team's software receives it.

    Attributes:
        camera: camera index.
        t_capture: when the image was taken [s, episode time].
        t_delivered: when it reaches the team's software [s].
        image: ``(H, W, 3)`` uint8 RGB.
    """

    camera: int
    t_capture: float
    t_delivered: float
    image: np.ndarray


def interpolate_state(prev: WorldState, cur: WorldState, w: float, t: float) -> WorldState:
    """The world between two snapshots (robots and ball linearly, headings on the short
    arc), at fraction ``w`` of the way, stamped ``t``."""
    robots = prev.robots + w * (cur.robots - prev.robots)
    dth = np.remainder(cur.robots[:, 2] - prev.robots[:, 2] + math.pi, 2.0 * math.pi) - math.pi
    robots[:, 2] = prev.robots[:, 2] + w * dth
    robots[:, 3:6] = cur.robots[:, 3:6]
    ball = prev.ball + w * (cur.ball - prev.ball)
    ball[3:6] = cur.ball[3:6]
    return WorldState(t, ball, robots, cur.names, cur.teams)


class OverheadImageCamera(OverheadVision):
    """The overhead cameras of one field, delivering :class:`ImageFrame` s (module
    docstring): each camera of :func:`~soccer_env.sensors.overhead.default_cameras` renders
    its own area (:attr:`renderers`). :meth:`reset` and :meth:`step` return image frames where
    :class:`~soccer_env.sensors.overhead.OverheadVision` returns detection frames.

    Args:
        spec: the vision preset (timing; its detection and noise figures do not apply: what
            is found in the images is up to the software that reads them).
        field, ball: the world's field and ball.
        robots: every robot's spec, in robot order.
        teams: every robot's team (0 blue, 1 yellow).
        frames: the overhead frame preset (lighting, noise, blur, image size).
    """

    def __init__(self, spec: VisionSpec, field: FieldSpec, robots: Sequence[RobotSpec],
                 ball: BallSpec, teams: Sequence[int], frames: str = PIXEL_FRAME_PRESET
                 ) -> None:
        super().__init__(spec, field, robots[0], ball, len(robots))
        self.teams = [int(t) for t in teams]
        self.robot_specs = list(robots)
        #: One renderer per camera (its area is the camera's view), in camera order.
        self.renderers = [OverheadRenderer(frames, field, self.robot_specs, ball, self.teams,
                                           camera=cam) for cam in self.cameras]
        #: The first camera's renderer (the only one on fields up to 7 m long).
        self.renderer = self.renderers[0]

    def reset(self, state: WorldState, rng: np.random.Generator,
              image_rng: np.random.Generator | None = None) -> list[ImageFrame]:
        """As :meth:`OverheadVision.reset`; the images' lighting and noise draw from
        ``image_rng`` (default: a stream seeded from ``rng``)."""
        self._image_rng = (image_rng if image_rng is not None
                           else np.random.default_rng(rng.integers(2**63)))
        return super().reset(state, rng)

    def _capture(self, prev: WorldState, cur: WorldState, cams: list[int],
                 times: list[float], emit_empty: bool = False) -> list[ImageFrame]:
        """Images of cameras ``cams`` captured at ``times`` (between ``prev`` and ``cur``),
        each with its delivery delay."""
        frames = []
        span = cur.time - prev.time
        for cam, t in zip(cams, times):
            w = (t - prev.time) / span if span > 0 else 1.0
            image = self.renderers[cam].render(interpolate_state(prev, cur, w, t),
                                               self._image_rng)
            jitter = float(self._draws.uniforms(1)[0])
            delay = self.spec.latency + self.spec.latency_jitter * jitter
            frames.append(ImageFrame(cam, t, t + delay, image))
        return frames


class PixelHeadCamera(HeadCameraSensor):
    """Head cameras whose frames carry their rendered image (``HeadFrame.image``,
    :class:`~soccer_env.sensors.images.head.HeadFrameRenderer` at ``size``, the
    ``"realistic"`` head-frame preset: lighting and noise, the gait's sway in the true
    orientation) instead of geometric ball detections (``balls`` is empty): the robot's
    software finds the ball in the image
    (:class:`~soccer_env.perception.pixels.BallImageTracker`). Landmarks and robots stay the
    geometric sensor's.

    Args: as :class:`~soccer_env.sensors.headcam.HeadCameraSensor`, plus every robot's spec and
    the rendered image size ``(width, height)`` [px].
    """

    def __init__(self, spec: HeadCameraSpec, field: FieldSpec, ball: BallSpec,
                 robots: Sequence[RobotSpec], teams: Sequence[int], observers: Sequence[int],
                 size: tuple[int, int] = HEAD_IMAGE_SIZE) -> None:
        super().__init__(spec, field, ball, [s.radius for s in robots], teams, observers)
        self.renderer = HeadFrameRenderer(spec, field, list(robots), ball, list(teams),
                                          spec="realistic", size=size)

    def reset(self, state: WorldState, heads: HeadState, rng: np.random.Generator
              ) -> list[HeadFrame]:
        self._image_rng = np.random.default_rng(rng.integers(2**63))
        return super().reset(state, heads, rng)

    def _capture(self, state: WorldState, heads: HeadState, due: list[int],
                 interval: float | None) -> list[HeadFrame]:
        frames = super()._capture(state, heads, due, interval)
        return [f._replace(balls=(), image=self.renderer.render(state, heads, f.robot,
                                                                 self._image_rng))
                for f in frames]
