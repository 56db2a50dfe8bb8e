"""Image presets: the nominal colours of what cameras see and the appearance of rendered
overhead and head-camera frames (lighting, noise, blur), used by :mod:`soccer_env.sensors.images`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from estimators.registry import Registry
from soccer_env.validation import (
    check_flag,
    check_integer,
    check_number,
    check_rgb,
    preset_table,
    resolve_preset,
)

__all__ = ["RGB", "COLOURS", "OVERHEAD_CLASSES", "CLASS_ALIASES", "OverheadFrameSpec",
           "OVERHEAD_FRAMES", "overhead_frame",
           "HeadFrameSpec", "HEAD_FRAMES", "head_frame"]

RGB = tuple[int, int, int]


#: Nominal colours [RGB] of what the cameras see. Ball, team colours and carpet as the
#: top-down renderer (:mod:`soccer_env.render.renderer`); pink and a light green for the player dots
#: (SSL-Vision's pink and green), lighter than the carpet so the two greens stay apart.
COLOURS: dict[str, RGB] = {
    "orange": (255, 120, 0),
    "blue": (40, 100, 255),
    "yellow": (245, 215, 0),
    "pink": (255, 60, 200),
    "green": (120, 255, 120),
    "carpet": (24, 120, 48),
    "white": (235, 235, 235),
    "body": (25, 25, 25),
    "goal": (60, 60, 60),
    "wall": (90, 60, 30),
    "floor": (70, 70, 70),
}

#: The colour classes an overhead camera's look-up table tells apart (Li et al.'s 2010, built
#: offline from the nominal colours): the ball, the two team patches, the two player-dot
#: colours and the carpet.
OVERHEAD_CLASSES: dict[str, RGB] = {
    c: COLOURS[c] for c in ("orange", "blue", "yellow", "pink", "green", "carpet")}
#: Other names of those classes.
CLASS_ALIASES = {"ball": "orange"}


@dataclass(frozen=True)
class OverheadFrameSpec:
    """An overhead camera's image (module docstring).

    Attributes:
        name: preset name.
        width, height: image size [pixels].
        region: ``(x_min, x_max, y_min, y_max)`` [m, field frame] that the image must show
            (scaled to fit with square pixels and centred; the image may show more along one
            axis); None: the whole walled area. A
            :class:`~soccer_env.sensors.overhead.Camera` given to the renderer overrides it.
        frame_rate: frames per second (for the trackers' time step; the caller decides when to
            render) [Hz].
        exposure: exposure time [s], centred on the frame's time; 0 disables motion blur.
        blur_samples: most poses averaged for a moving object (>= 2).
        gain_sigma: standard deviation of the global brightness gain.
        gradient: largest amplitude of the linear brightness ramp (fraction, image centre to
            edge).
        noise_sigma: Gaussian pixel noise [grey levels].
        camera_height: height of the camera above the region's centre [m], for the parallax of
            a ball in the air.
        chip_parallax: draw a ball in the air where the camera sees it (offset and enlarged).
        antialias: anti-aliased drawing (``cv2.LINE_AA``).
        carpet, line: colours [RGB] of the carpet and of the field lines.
        source: where the numbers come from.
    """

    name: str
    width: int = 640
    height: int = 480
    region: tuple[float, float, float, float] | None = None
    frame_rate: float = 60.0
    exposure: float = 0.0
    blur_samples: int = 8
    gain_sigma: float = 0.0
    gradient: float = 0.0
    noise_sigma: float = 0.0
    camera_height: float = 4.0
    chip_parallax: bool = True
    antialias: bool = True
    carpet: RGB = COLOURS["carpet"]
    line: RGB = COLOURS["white"]
    source: str = ""

    def __post_init__(self) -> None:
        p = "overhead_frame"
        check_integer(f"{p}.width", self.width, 16, 8192)
        check_integer(f"{p}.height", self.height, 16, 8192)
        if self.region is not None:
            r = self.region
            ok = (isinstance(r, tuple) and len(r) == 4
                  and all(isinstance(c, (int, float)) and math.isfinite(c) for c in r)
                  and r[0] < r[1] and r[2] < r[3])
            if not ok:
                raise ValueError(f"{p}.region must be None or (x_min, x_max, y_min, y_max) with "
                                 f"x_min < x_max and y_min < y_max [m], got {r!r}")
        check_number(f"{p}.frame_rate", self.frame_rate, 1.0, 1000.0)
        check_number(f"{p}.exposure", self.exposure, 0.0, 0.1)
        check_integer(f"{p}.blur_samples", self.blur_samples, 2, 64)
        check_number(f"{p}.gain_sigma", self.gain_sigma, 0.0, 0.5)
        check_number(f"{p}.gradient", self.gradient, 0.0, 0.9)
        check_number(f"{p}.noise_sigma", self.noise_sigma, 0.0, 64.0)
        check_number(f"{p}.camera_height", self.camera_height, 0.5, 50.0)
        check_flag(f"{p}.chip_parallax", self.chip_parallax)
        check_flag(f"{p}.antialias", self.antialias)
        check_rgb(f"{p}.carpet", self.carpet)
        check_rgb(f"{p}.line", self.line)


OVERHEAD_FRAMES: Registry[OverheadFrameSpec] = preset_table('overhead_frame', {
    # No imperfection: no blur, no lighting change, no noise. 640 x 480 (Li et al.'s 2010 image)
    # at 60 Hz (SSL-Vision's 60-75 Hz, as VISION["realistic"]).
    "clean": OverheadFrameSpec(
        name="clean", source="no imperfection; 640 x 480 (Li et al. 2010), 60 Hz (SSL-Vision)"),
    # An SSL-Vision-like camera: 60 Hz, 4 m high (VISION). Assumptions (ours): 5 ms
    # exposure (teams shorten it to limit blur), 3 % flicker of the hall lighting, up to 15 %
    # brightness ramp across the image (uneven lighting), 3 grey levels of sensor noise.
    "realistic": OverheadFrameSpec(
        name="realistic", frame_rate=60.0, exposure=0.005, gain_sigma=0.03, gradient=0.15,
        noise_sigma=3.0, camera_height=4.0,
        source="SSL-Vision rate and height (VISION); exposure, lighting and noise "
               "assumed",
    ),
    # Li et al.'s (2010) MiroSot camera: 640 x 480, about 33 ms per cycle (30 Hz). Assumptions
    # (ours): an analog camera of the era integrating a 1/60 s field, 2.5 m above the field,
    # 5 % flicker, 20 % ramp, 5 grey levels of noise.
    "mirosot": OverheadFrameSpec(
        name="mirosot", frame_rate=30.0, exposure=1.0 / 60.0, blur_samples=12,
        gain_sigma=0.05, gradient=0.2, noise_sigma=5.0, camera_height=2.5,
        source="Li et al. (2010) (640 x 480, 33 ms cycle); exposure, height, lighting and noise "
               "assumed",
    ),
})


def overhead_frame(spec: str | OverheadFrameSpec = "realistic", **overrides: object
                   ) -> OverheadFrameSpec:
    """Return an overhead-frame preset (by name or spec) with optional validated overrides."""
    return resolve_preset("overhead_frame", OVERHEAD_FRAMES, spec, overrides)


@dataclass(frozen=True)
class HeadFrameSpec:
    """A head camera's image appearance (module docstring); the geometry comes from the
    :class:`~soccer_env.presets.HeadCameraSpec`.

    Attributes:
        name: preset name.
        gain_sigma, gradient, noise_sigma: lighting and noise, as
            :class:`OverheadFrameSpec`.
        antialias: anti-aliased drawing.
        sky: colour above the horizon (the hall). floor: the ground beyond the walled area.
        carpet, line: carpet and field lines. body: the robots' bodies. [RGB]
        source: where the numbers come from.
    """

    name: str
    gain_sigma: float = 0.0
    gradient: float = 0.0
    noise_sigma: float = 0.0
    antialias: bool = True
    sky: RGB = (175, 185, 200)
    floor: RGB = COLOURS["floor"]
    carpet: RGB = COLOURS["carpet"]
    line: RGB = COLOURS["white"]
    body: RGB = (35, 35, 35)
    source: str = ""

    def __post_init__(self) -> None:
        p = "head_frame"
        check_number(f"{p}.gain_sigma", self.gain_sigma, 0.0, 0.5)
        check_number(f"{p}.gradient", self.gradient, 0.0, 0.9)
        check_number(f"{p}.noise_sigma", self.noise_sigma, 0.0, 64.0)
        check_flag(f"{p}.antialias", self.antialias)
        for name in ("sky", "floor", "carpet", "line", "body"):
            check_rgb(f"{p}.{name}", getattr(self, name))


HEAD_FRAMES: Registry[HeadFrameSpec] = preset_table('head_frame', {
    "clean": HeadFrameSpec(name="clean", source="no imperfection"),
    # Xu et al.'s (2012) CCD camera of 2012 under hall lighting. Assumptions (ours): 5 % gain
    # changes (auto exposure, flicker), up to 20 % ramp, 4 grey levels of noise.
    "realistic": HeadFrameSpec(
        name="realistic", gain_sigma=0.05, gradient=0.2, noise_sigma=4.0,
        source="lighting and noise assumed (CCD head camera of Xu et al.'s (2012) era)",
    ),
})


def head_frame(spec: str | HeadFrameSpec = "realistic", **overrides: object) -> HeadFrameSpec:
    """Return a head-frame preset (by name or spec) with optional validated overrides."""
    return resolve_preset("head_frame", HEAD_FRAMES, spec, overrides)
