"""What a team perceives with: the configuration of its perception and the option families.

Three observation modes share one observation layout:

* ``"truth"``: the oracle, the true state itself;
* ``"raw"``: the latest delayed detections of the overhead vision, unfiltered (positions as
  last seen; velocities as the difference of the last two sightings);
* ``"perceived"``: the estimation stack's belief: the ball tracker chosen by
  ``ball_filter`` (Zhao et al.'s 2012 EKF by default) and batched robot pose filters, fed with the
  vision's frames by capture time and predicted to the present plus the actuation latency,
  so that the policy acts on where things will be when its command takes effect.

``perception=`` chooses the vision preset (:data:`soccer_env.presets.VISION`), which
also sets the actuation latency and command loss that apply in every mode, and the ball filter.
Its default is ``"ideal"`` for ``obs_mode="truth"`` and ``"realistic"`` otherwise.

Humanoid robots see through their head cameras instead (:mod:`soccer_env.perception.humanoid`):
``perception=`` then names a head-camera preset
(:data:`soccer_env.presets.HEAD_CAMERAS`, default the robot preset's camera) or gives
``camera``, ``radio``, ``localization``, ``fusion`` and ``ball_tracker``; their commands reach
the walk engine on board, without latency or loss.

Every pipeline returns two beliefs per step: the one the observation is built from (predicted
ahead by the actuation latency) and the one at the present time, reported in
``info["estimate"]`` with the keys of ``info["truth"]`` so that errors can be measured.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np

from soccer_env.perception import randomization
from soccer_env.perception.options import (
    BALL_FILTERS,
    BALL_TRACKERS,
    DETECTORS,
    FUSIONS,
    LOCALIZATIONS,
    ROBOT_PREDICTIONS,
)
from soccer_env.presets.sensors import (
    HEAD_CAMERAS,
    RADIO_PRESETS,
    VISION,
    HeadCameraSpec,
    RadioSpec,
    VisionSpec,
    head_camera,
    vision,
)
from soccer_env.state import WorldState
from soccer_env.validation import from_mapping

__all__ = ["OBS_MODES", "Perception", "PerceptionConfig", "BALL_FILTERS", "BALL_TRACKERS",
           "FUSIONS", "LOCALIZATIONS", "DETECTORS", "JUST_STARTED", "SSL_LOST_AFTER",
           "COAST_FRAMES", "ball_status", "sigmas", "expected_age"]

#: Observation modes.
OBS_MODES = ("truth", "raw", "perceived")

#: A ball track counts as just (re)started (status ``"reset"``) until it has fused this many
#: measurements: with fewer, its velocity rests on one or two differences of noisy positions.
JUST_STARTED = 3
#: An SSL ball not measured for this long [s] counts as lost (the SSL filters predict on
#: indefinitely; humanoid trackers restart after their own ``lost_after``).
SSL_LOST_AFTER = 1.0
#: A track counts as coasting once its latest measurement is older than the sensor's latency
#: (with its jitter) plus this many frame periods: a frame that should have seen it did not.
COAST_FRAMES = 1.5


def expected_age(frame_rate: float | None, latency: float, jitter: float,
                 control_dt: float = 1.0 / 60.0) -> float:
    """The oldest a measurement is while a sensor sees the ball in every frame [s]: latency,
    jitter and :data:`COAST_FRAMES` frame periods (a control step's for a sensor that
    captures every step)."""
    period = 1.0 / frame_rate if frame_rate else control_dt
    return latency + jitter + COAST_FRAMES * period


def ball_status(age: float, expected: float, since_start: int, lost_after: float) -> int:
    """The track's state, an index in :data:`~soccer_env.state.BALL_STATUSES`: lost when
    its latest measurement is older than ``lost_after`` [s] (or there is none), else reset
    while it has fused fewer than :data:`JUST_STARTED` measurements since its (re)start, else
    coasting when older than ``expected`` [s] (:func:`expected_age`), else tracking."""
    if not age <= lost_after:
        return 3
    if since_start < JUST_STARTED:
        return 2
    return 1 if age > expected else 0


def sigmas(P: np.ndarray | None) -> tuple[float, float]:
    """Position [m] and velocity [m/s] standard deviations per axis of a ``4 x 4``
    covariance of ``(x, y, vx, vy)``: ``sqrt`` of the mean of the two axes' variances;
    ``inf`` for None (nothing known)."""
    if P is None:
        return math.inf, math.inf
    return (math.sqrt(max(0.0, 0.5 * (P[0, 0] + P[1, 1]))),
            math.sqrt(max(0.0, 0.5 * (P[2, 2] + P[3, 3]))))


class Perception(Protocol):
    """One perception pipeline (shared by both teams of a match)."""

    vision_spec: VisionSpec

    def reset(self, state: WorldState, rng: np.random.Generator) -> tuple[Any, Any]:
        """Start an episode at ``state``; return ``(belief for the observation, belief now)``."""
        ...

    def update(self, state: WorldState) -> tuple[Any, Any]:
        """Advance to ``state``; return ``(belief for the observation, belief now)``."""
        ...


#: The options of humanoids' perception only.
_HUMANOID_ONLY = ("camera", "radio", "localization", "fusion", "ball_tracker")


@dataclass(frozen=True)
class PerceptionConfig:
    """What a team perceives with.

    SSL robots (overhead vision):

    Attributes:
        vision: a :class:`~soccer_env.presets.VisionSpec` (or preset name).
        ball_filter: one of :data:`~soccer_env.perception.options.BALL_FILTERS` (used by
            ``obs_mode="perceived"``).
        detector: ``"geometric"`` (the sensor model's detections) or ``"pixels"`` (rendered
            images tracked by Li et al.'s (2010) mean-shift particle filters,
            :mod:`soccer_env.perception.pixels`; needs the ``pixels`` extra).
        robot_prediction: one of :data:`~soccer_env.perception.options.ROBOT_PREDICTIONS`:
            ``"constant-velocity"`` (default) or ``"commands"``, the team's own robots
            predicted through the commands it sent (used by ``obs_mode="perceived"``; each
            team then runs its own filters, on shared camera frames).

    Humanoids (head cameras, :mod:`soccer_env.perception.humanoid`):

    Attributes:
        camera: a :class:`~soccer_env.presets.HeadCameraSpec`, a preset name, or None for the
            robot preset's camera.
        radio: the team radio, a :class:`~soccer_env.presets.RadioSpec` or preset name.
        localization: one of :data:`~soccer_env.perception.options.LOCALIZATIONS`.
        fusion: one of :data:`~soccer_env.perception.options.FUSIONS`.
        ball_tracker: one of :data:`~soccer_env.perception.options.BALL_TRACKERS`.

    Both:

    Attributes:
        randomize: sensor figures drawn afresh every episode, ``{figure: (low, high)}``,
            and ``"preset": [names]`` to draw a whole preset first (kept as a
            :class:`~soccer_env.perception.randomization.Randomization`; see
            :mod:`soccer_env.perception.randomization`).
    """

    vision: VisionSpec
    ball_filter: str = "ekf"
    detector: str = "geometric"
    robot_prediction: str = "constant-velocity"
    camera: HeadCameraSpec | str | None = None
    radio: RadioSpec | str = "zigbee"
    localization: str = "kld-triangulate"
    fusion: str = "inverse"
    ball_tracker: str = "mfbpf"
    randomize: Any = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "randomize", randomization.ranges(self.randomize))
        if isinstance(self.vision, str):
            object.__setattr__(self, "vision", vision(self.vision))
        elif not isinstance(self.vision, VisionSpec):
            raise TypeError(f"perception vision must be a preset name or a VisionSpec, got "
                            f"{type(self.vision).__name__}")
        BALL_FILTERS.check(self.ball_filter, "ball_filter")
        DETECTORS.check(self.detector, "detector")
        ROBOT_PREDICTIONS.check(self.robot_prediction, "robot_prediction")
        if isinstance(self.camera, str):
            object.__setattr__(self, "camera", head_camera(self.camera))
        elif self.camera is not None and not isinstance(self.camera, HeadCameraSpec):
            raise TypeError(f"perception camera must be a head-camera preset name, a "
                            f"HeadCameraSpec or None, got {type(self.camera).__name__}")
        if isinstance(self.radio, str):
            if self.radio not in RADIO_PRESETS:
                raise ValueError(f"radio must be one of {sorted(RADIO_PRESETS)} or a "
                                 f"RadioSpec, got {self.radio!r}")
            object.__setattr__(self, "radio", RADIO_PRESETS[self.radio])
        elif not isinstance(self.radio, RadioSpec):
            raise TypeError(f"perception radio must be a preset name or a RadioSpec, got "
                            f"{type(self.radio).__name__}")
        for name, family in (("localization", LOCALIZATIONS), ("fusion", FUSIONS),
                             ("ball_tracker", BALL_TRACKERS)):
            family.check(getattr(self, name), name)

    @classmethod
    def create(cls, value: Any, obs_mode: str, kind: str = "ssl") -> PerceptionConfig:
        """From ``perception=``: None (``"ideal"`` vision for truth, else ``"realistic"``),
        a vision preset name or :class:`VisionSpec` (for humanoids, ``kind="humanoid"``: a
        head-camera preset name or :class:`~soccer_env.presets.HeadCameraSpec`), a mapping of
        this class's fields, or an instance."""
        default_vision = "ideal" if obs_mode == "truth" else "realistic"
        if value is None:
            return cls(vision(default_vision))
        if isinstance(value, cls):
            return value
        if kind == "humanoid" and isinstance(value, (str, HeadCameraSpec)):
            if isinstance(value, str) and value not in HEAD_CAMERAS:
                raise ValueError(f"perception: unknown head-camera preset {value!r} for "
                                 f"humanoid perception; known: {sorted(HEAD_CAMERAS)}")
            return cls(vision(default_vision), camera=value)
        if isinstance(value, (str, VisionSpec)):
            if isinstance(value, str) and value not in VISION:
                raise ValueError(f"perception: unknown vision preset {value!r}; known: "
                                 f"{sorted(VISION)}")
            return cls(vision(value))
        if isinstance(value, Mapping):
            humanoid_only = [k for k in _HUMANOID_ONLY if k in value]
            if kind == "ssl" and humanoid_only:
                raise ValueError(f"perception {humanoid_only}: these are humanoids' head-camera "
                                 "options; SSL robots see through the overhead vision "
                                 "(vision, ball_filter, detector, robot_prediction, randomize)")
            return from_mapping(cls, value, "perception", defaults={
                "vision": default_vision if kind == "humanoid" else "realistic"})
        raise TypeError(f"perception must be a preset name, a VisionSpec or HeadCameraSpec, a "
                        f"mapping or a PerceptionConfig, got {type(value).__name__}")
