"""Camera images drawn from the world state with OpenCV: the overhead camera of SSL / MiroSot
vision (SPEC 1.4) and a humanoid's head camera (SPEC 1.1, 1.5), plus the colour and motion
helpers that image trackers read (paper 003's colour-probability and frame-difference images,
paper 004's hue back-projection).

Images are ``(H, W, 3)`` ``uint8`` arrays in **RGB** order (as every other image of the
package, e.g. :class:`~soccer_env.render.Renderer`); convert with ``cv2.cvtColor(img,
cv2.COLOR_RGB2BGR)`` before ``cv2.imwrite``. Units are SI and radians, except where pixels are
stated.

Pixel coordinates. ``(u, v)`` are continuous pixel coordinates with ``u`` to the right and
``v`` downwards; the pixel at array index ``[j, i]`` (row ``j``, column ``i``) covers
``i <= u < i + 1``, ``j <= v < j + 1``, so its centre is ``(i + 0.5, j + 0.5)`` and the image
centre is ``(W / 2, H / 2)``: the convention of :class:`estimators.camera.HeadCamera`.

Top markers (:class:`PatchPattern`). Every robot seen from above carries, as in SSL-Vision's
standard pattern and MiroSot, a team patch at its centre (blue for team 0, yellow for team 1;
radius 25 mm) and four player dots (radius 20 mm) around it: two at the front, ``(35, +-54.8)``
mm in the body frame (``+x`` forward, ``+y`` left), and two at the back, ``(-54.8, +-35)`` mm,
all 65 mm from the centre. The front pair is 110 mm apart and the back pair 70 mm, so the
layout shows the heading; the dots' colours (pink or green) give the robot's number within its
team (:data:`PATTERN_IDS`, 16 combinations). Robots of another size (humanoids seen from
above) carry the pattern scaled by ``radius / 0.09 m``. Dimensions and positions are our
reading of the SSL standard pattern; ids 0-11 follow the SSL rules of 2013 (figure 6, as
transcribed by the RoboJackets team), ids 12-15 are the four remaining combinations in an
order of ours.

Overhead frames (:class:`OverheadRenderer`). An orthographic view of the field plane from a
camera above the centre of the region it sees (the whole walled area by default, scaled to fit
the image with square pixels and centred): carpet, field lines, defense areas, centre circle,
goals and walls come from a background image drawn once; every frame copies it and draws the
robots (SSL: the flat-front outline in a dark body colour; humanoids: a dark disc; both with
their patch pattern) and the orange ball. Robots are drawn at their ground position (an
SSL-Vision-like calibration per object height); a ball in the air is seen by the camera at
``camera_height`` above the region's centre (or the given :class:`~soccer_env.vision.Camera`)
and is drawn where the camera's ray through its centre meets the plane of a resting ball's
centre, enlarged by the same factor (``chip_parallax``; a ball on the carpet is drawn at its
position with its true size). A ball on the carpet is drawn before the robots (a robot over it
hides it), a ball higher than the tallest robot after them.

Motion blur: each object whose image moves by half a pixel or more during the exposure
(``exposure`` [s], centred on the frame's time; translation plus rotation at the body's
radius) is drawn at ``K`` poses spread evenly over the exposure, ``K = clip(ceil(smear) + 1,
2, blur_samples)`` with ``smear`` its image displacement in pixels, each on a copy of the
image region it sweeps, and the copies are averaged: the object is smeared along its image
velocity and blended with what lies behind it.

Lighting and noise (both renderers): per frame a global gain ``g = 1 + gain_sigma * N(0, 1)``
(clipped to [0.3, 2]) and a linear brightness ramp of amplitude ``a ~ U(0, gradient)`` in a
random direction ``phi ~ U(0, 2 pi)``: pixel values are multiplied by ``g (1 + a (cos(phi) x_n
+ sin(phi) y_n))``, ``x_n, y_n`` in [-1, 1] across the image; then Gaussian noise of
``noise_sigma`` grey levels is added to each channel and the result saturated to [0, 255]. The
noise (rounded to grey levels) is read at a random offset from a bank of Gaussian samples
twice the image's size, drawn once per renderer from a fixed seed (drawing 900 k normals per
frame would cost more than the rest of the frame): within a frame the samples are
independent; consecutive frames read different, shifted windows. All per-frame draws come
from the ``rng`` given to ``render``, so the same generator state gives the same image.

Head frames (:class:`HeadFrameRenderer`). The pinhole view of :class:`estimators.camera.HeadCamera`
(geometry in :mod:`soccer_env.headcam`) from the observer's head with the TRUE orientation
(pan + sway_pan, tilt + sway_tilt): sky above the horizon, floor below it, the carpet of the
walled area, the field lines as ground polygons of their true width (so they thin with
distance), then in painter's order (farthest first, by ground distance from the camera) the goal
posts (vertical cylinders of ``goal_wall_thickness`` diameter and ``goal_height``), the
crossbars, the other robots (dark cylinders of their radius and height, the top fifth in team
colour) and the ball (a disc of radius ``f r / depth`` px). Polygons are clipped at 5 cm in
front of the camera. No motion blur in head frames; robots are drawn standing (the state does
not say who has fallen).

Helpers: :func:`hue_histogram` and :func:`back_project` (paper 004's target model),
:class:`ColourTable` (paper 003's offline colour look-up table) and :func:`frame_difference`
(paper 003's motion factor).

Needs OpenCV (``pip install 'soccer-env[pixels]'``). Cost on a 2-core machine with OpenCV 5
(``python -m soccer_env.frames`` measures it): a 640 x 480 overhead frame with 12 robots about
0.5 ms clean, 2 ms with lighting and noise (1.5 ms of which are the two full-image passes),
2.6 ms when all 12 robots and the ball are also motion-blurred; a 320 x 240 head frame about
0.6 ms clean and 1.1 ms with lighting and noise, 720 x 625 about 0.8 and 3 ms.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

try:
    import cv2
except ImportError as err:  # pragma: no cover - depends on the installation
    raise ImportError("soccer_env.frames needs OpenCV; install it with: "
                      "pip install 'soccer-env[pixels]'") from err

from estimators import HeadCamera
from soccer_env.headcam import HeadCameraSpec, HeadState
from soccer_env.physics import robot_outline
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.state import WorldState
from soccer_env.vision import Camera

__all__ = [
    "RGB",
    "COLOURS",
    "Patch",
    "PatchPattern",
    "PATTERN",
    "PATTERN_IDS",
    "patch_pattern",
    "OverheadFrameSpec",
    "OVERHEAD_FRAMES",
    "overhead_frame",
    "OverheadRenderer",
    "HeadFrameSpec",
    "HEAD_FRAMES",
    "head_frame",
    "HeadFrameRenderer",
    "ColourTable",
    "hue_histogram",
    "back_project",
    "frame_difference",
]

RGB = tuple[int, int, int]

#: Nominal colours [RGB] of what the cameras see. Ball, team colours and carpet as the
#: top-down renderer (:mod:`soccer_env.render`); pink and a light green for the player dots
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

_TEAM_COLOUR = ("blue", "yellow")
_SHIFT = 4  # cv2 drawing with 4 fractional bits
_ONE = 1 << _SHIFT


# --------------------------------------------------------------------------------------------
# Top markers
# --------------------------------------------------------------------------------------------


class Patch(NamedTuple):
    """One coloured disc on a robot's top: centre ``x, y`` in the body frame [m] (``+x``
    forward, ``+y`` left), ``radius`` [m] and colour ``rgb``."""

    x: float
    y: float
    radius: float
    rgb: RGB


#: Player-dot colours per robot number (0-15), dots in the order front-left, front-right,
#: rear-right, rear-left (clockwise seen from above, starting front-left). 0-11: SSL rules
#: 2013, figure 6 (magenta = pink); 12-15: the remaining combinations (our order).
PATTERN_IDS: tuple[tuple[str, str, str, str], ...] = tuple(
    tuple("pink" if c == "m" else "green" for c in code)  # type: ignore[misc]
    for code in ("mmmg", "gmmg", "ggmg", "mgmg", "mmgm", "gmgm", "gggm", "mggm",
                 "gggg", "mmmm", "mmgg", "ggmm", "mgmm", "mggg", "gmmm", "gmgg")
)


@dataclass(frozen=True)
class PatchPattern:
    """Geometry of the top markers (module docstring), for a robot of ``reference_radius``.

    Attributes:
        centre_radius: radius of the team patch [m].
        dot_radius: radius of a player dot [m].
        dot_positions: body-frame centres of the four dots [m], in :data:`PATTERN_IDS` order.
        reference_radius: the robot radius these dimensions are for [m]; other robots get the
            pattern scaled by ``radius / reference_radius``.
    """

    centre_radius: float = 0.025
    dot_radius: float = 0.020
    dot_positions: tuple[tuple[float, float], ...] = (
        (0.035, 0.054772), (0.035, -0.054772), (-0.054772, -0.035), (-0.054772, 0.035))
    reference_radius: float = 0.09

    def patches(self, team: int, index: int, robot_radius: float | None = None,
                colours: Mapping[str, RGB] | None = None) -> list[Patch]:
        """The discs on robot ``index`` (0-15) of ``team`` (0 blue, 1 yellow): the team patch
        first, then the four dots; scaled to ``robot_radius`` [m] if given."""
        if team not in (0, 1):
            raise ValueError(f"team must be 0 (blue) or 1 (yellow), got {team!r}")
        if not 0 <= index < len(PATTERN_IDS):
            raise ValueError(f"index must be in [0, {len(PATTERN_IDS) - 1}], got {index!r}")
        pal = COLOURS if colours is None else colours
        k = 1.0 if robot_radius is None else robot_radius / self.reference_radius
        out = [Patch(0.0, 0.0, k * self.centre_radius, pal[_TEAM_COLOUR[team]])]
        for (x, y), name in zip(self.dot_positions, PATTERN_IDS[index]):
            out.append(Patch(k * x, k * y, k * self.dot_radius, pal[name]))
        return out

    @staticmethod
    def identify(dot_colours: Sequence[str]) -> int | None:
        """The robot number whose dots (front-left, front-right, rear-right, rear-left) have
        these colour names, or None."""
        try:
            return PATTERN_IDS.index(tuple(dot_colours))
        except ValueError:
            return None


#: The default pattern (SSL standard pattern dimensions).
PATTERN = PatchPattern()


def patch_pattern(team: int, index: int, robot_radius: float | None = None
                  ) -> list[tuple[float, float, float, RGB]]:
    """``(offset_x, offset_y, radius, rgb)`` [m, m, m, RGB] of the discs on robot ``index`` of
    ``team``, body frame, team patch first (:class:`PatchPattern`)."""
    return [tuple(p) for p in PATTERN.patches(team, index, robot_radius)]  # type: ignore


# --------------------------------------------------------------------------------------------
# Specs
# --------------------------------------------------------------------------------------------


def _check_number(prefix: str, name: str, v: object, low: float, high: float,
                  low_open: bool = False) -> None:
    ok = (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
          and (v > low if low_open else v >= low) and v <= high)
    if not ok:
        lo = "(" if low_open else "["
        raise ValueError(f"{prefix}.{name} must be in {lo}{low}, {high}], got {v!r}")


def _check_int(prefix: str, name: str, v: object, low: int, high: int) -> None:
    if not (isinstance(v, (int, np.integer)) and not isinstance(v, bool) and low <= v <= high):
        raise ValueError(f"{prefix}.{name} must be an integer in [{low}, {high}], got {v!r}")


def _check_rgb(prefix: str, name: str, v: object) -> None:
    ok = (isinstance(v, tuple) and len(v) == 3
          and all(isinstance(c, int) and not isinstance(c, bool) and 0 <= c <= 255 for c in v))
    if not ok:
        raise ValueError(f"{prefix}.{name} must be an (r, g, b) tuple of integers in [0, 255], "
                         f"got {v!r}")


def _check_bool(prefix: str, name: str, v: object) -> None:
    if not isinstance(v, bool):
        raise ValueError(f"{prefix}.{name} must be True or False, got {v!r}")


@dataclass(frozen=True)
class OverheadFrameSpec:
    """An overhead camera's image (module docstring).

    Attributes:
        name: preset name.
        width, height: image size [pixels].
        region: ``(x_min, x_max, y_min, y_max)`` [m, field frame] that the image must show
            (scaled to fit with square pixels and centred; the image may show more along one
            axis); None: the whole walled area. A :class:`~soccer_env.vision.Camera` given to
            the renderer overrides it.
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
        _check_int(p, "width", self.width, 16, 8192)
        _check_int(p, "height", self.height, 16, 8192)
        if self.region is not None:
            r = self.region
            ok = (isinstance(r, tuple) and len(r) == 4
                  and all(isinstance(c, (int, float)) and math.isfinite(c) for c in r)
                  and r[0] < r[1] and r[2] < r[3])
            if not ok:
                raise ValueError(f"{p}.region must be None or (x_min, x_max, y_min, y_max) with "
                                 f"x_min < x_max and y_min < y_max [m], got {r!r}")
        _check_number(p, "frame_rate", self.frame_rate, 1.0, 1000.0)
        _check_number(p, "exposure", self.exposure, 0.0, 0.1)
        _check_int(p, "blur_samples", self.blur_samples, 2, 64)
        _check_number(p, "gain_sigma", self.gain_sigma, 0.0, 0.5)
        _check_number(p, "gradient", self.gradient, 0.0, 0.9)
        _check_number(p, "noise_sigma", self.noise_sigma, 0.0, 64.0)
        _check_number(p, "camera_height", self.camera_height, 0.5, 50.0)
        _check_bool(p, "chip_parallax", self.chip_parallax)
        _check_bool(p, "antialias", self.antialias)
        _check_rgb(p, "carpet", self.carpet)
        _check_rgb(p, "line", self.line)


OVERHEAD_FRAMES: dict[str, OverheadFrameSpec] = {
    # No imperfection: no blur, no lighting change, no noise. 640 x 480 (paper 003's image)
    # at 60 Hz (SSL-Vision's 60-75 Hz, as vision.VISION["realistic"]).
    "clean": OverheadFrameSpec(
        name="clean", source="no imperfection; 640 x 480 (paper 003), 60 Hz (SSL-Vision)"),
    # An SSL-Vision-like camera: 60 Hz, 4 m high (vision.VISION). Assumptions (ours): 5 ms
    # exposure (teams shorten it to limit blur), 3 % flicker of the hall lighting, up to 15 %
    # brightness ramp across the image (uneven lighting), 3 grey levels of sensor noise.
    "realistic": OverheadFrameSpec(
        name="realistic", frame_rate=60.0, exposure=0.005, gain_sigma=0.03, gradient=0.15,
        noise_sigma=3.0, camera_height=4.0,
        source="SSL-Vision rate and height (vision.VISION); exposure, lighting and noise "
               "assumed",
    ),
    # Paper 003's MiroSot camera: 640 x 480, about 33 ms per cycle (30 Hz). Assumptions
    # (ours): an analog camera of the era integrating a 1/60 s field, 2.5 m above the field,
    # 5 % flicker, 20 % ramp, 5 grey levels of noise.
    "mirosot": OverheadFrameSpec(
        name="mirosot", frame_rate=30.0, exposure=1.0 / 60.0, blur_samples=12,
        gain_sigma=0.05, gradient=0.2, noise_sigma=5.0, camera_height=2.5,
        source="paper 003 (640 x 480, 33 ms cycle); exposure, height, lighting and noise "
               "assumed",
    ),
}


def overhead_frame(spec: str | OverheadFrameSpec = "realistic", **overrides: object
                   ) -> OverheadFrameSpec:
    """Return an overhead-frame preset (by name or spec) with optional validated overrides."""
    from soccer_env.presets import _resolve

    return _resolve("overhead_frame", OVERHEAD_FRAMES, spec, overrides)


@dataclass(frozen=True)
class HeadFrameSpec:
    """A head camera's image appearance (module docstring); the geometry comes from the
    :class:`~soccer_env.headcam.HeadCameraSpec`.

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
        _check_number(p, "gain_sigma", self.gain_sigma, 0.0, 0.5)
        _check_number(p, "gradient", self.gradient, 0.0, 0.9)
        _check_number(p, "noise_sigma", self.noise_sigma, 0.0, 64.0)
        _check_bool(p, "antialias", self.antialias)
        for name in ("sky", "floor", "carpet", "line", "body"):
            _check_rgb(p, name, getattr(self, name))


HEAD_FRAMES: dict[str, HeadFrameSpec] = {
    "clean": HeadFrameSpec(name="clean", source="no imperfection"),
    # Paper 000's CCD camera of 2012 under hall lighting. Assumptions (ours): 5 % gain
    # changes (auto exposure, flicker), up to 20 % ramp, 4 grey levels of noise.
    "realistic": HeadFrameSpec(
        name="realistic", gain_sigma=0.05, gradient=0.2, noise_sigma=4.0,
        source="lighting and noise assumed (CCD head camera of paper 000's era)",
    ),
}


def head_frame(spec: str | HeadFrameSpec = "realistic", **overrides: object) -> HeadFrameSpec:
    """Return a head-frame preset (by name or spec) with optional validated overrides."""
    from soccer_env.presets import _resolve

    return _resolve("head_frame", HEAD_FRAMES, spec, overrides)


# --------------------------------------------------------------------------------------------
# Shared: lighting and noise, robots' lists
# --------------------------------------------------------------------------------------------


class _Photometry:
    """Per-frame lighting and noise of an image of ``(height, width)`` (module docstring)."""

    def __init__(self, width: int, height: int, gain_sigma: float, gradient: float,
                 noise_sigma: float) -> None:
        self.width, self.height = width, height
        self.gain_sigma, self.gradient, self.noise_sigma = gain_sigma, gradient, noise_sigma
        self.active = gain_sigma > 0.0 or gradient > 0.0 or noise_sigma > 0.0
        self._xn = np.linspace(-1.0, 1.0, width, dtype=np.float32)
        self._yn = np.linspace(-1.0, 1.0, height, dtype=np.float32)
        self._bank: np.ndarray | None = None
        if noise_sigma > 0.0:
            # A fixed table of noise samples (the same for every renderer of this size and
            # sigma), rounded to grey levels; frames read random windows of it.
            bank_rng = np.random.default_rng(0x5EED)
            self._bank = np.rint(noise_sigma * bank_rng.standard_normal(
                (2 * height, 2 * width, 3), dtype=np.float32)).astype(np.int16)

    def apply(self, img: np.ndarray, rng: np.random.Generator | None) -> np.ndarray:
        if not self.active:
            return img
        if rng is None:
            raise ValueError("this spec has lighting or noise: render() needs an rng")
        z = float(rng.standard_normal())
        a_u, phi_u = rng.random(2).tolist()
        oy, ox = rng.integers(0, (self.height + 1, self.width + 1)).tolist()
        out = img
        if self.gain_sigma > 0.0 or self.gradient > 0.0:
            gain = min(2.0, max(0.3, 1.0 + self.gain_sigma * z))
            a = self.gradient * a_u
            phi = 2.0 * math.pi * phi_u
            gx, gy = gain * a * math.cos(phi), gain * a * math.sin(phi)
            ramp = (gain + gx * self._xn)[None, :] + (gy * self._yn)[:, None]
            # 16-bit intermediate: values above 255 saturate only after the noise.
            dtype = cv2.CV_16S if self._bank is not None else cv2.CV_8U
            out = cv2.multiply(img, cv2.merge([ramp, ramp, ramp]), dtype=dtype)
        if self._bank is not None:
            window = self._bank[oy:oy + self.height, ox:ox + self.width]
            out = cv2.add(out, window, dtype=cv2.CV_8U)
        return out


def _per_robot(robot_specs: RobotSpec | Sequence[RobotSpec], teams: Sequence[int]
               ) -> tuple[list[RobotSpec], list[int], list[int]]:
    team_list = [int(t) for t in teams]
    if any(t not in (0, 1) for t in team_list):
        raise ValueError(f"teams must hold 0 (blue) or 1 (yellow) per robot, got {list(teams)}")
    n = len(team_list)
    if isinstance(robot_specs, (list, tuple)):
        specs = list(robot_specs)
        if len(specs) != n:
            raise ValueError(f"robot_specs must have one spec per robot ({n}), got {len(specs)}")
    else:
        specs = [robot_specs] * n
    counts = [0, 0]
    index = []
    for t in team_list:
        index.append(counts[t])
        counts[t] += 1
    if max(counts) > len(PATTERN_IDS):
        raise ValueError(f"at most {len(PATTERN_IDS)} robots per team can be told apart, "
                         f"got {max(counts)}")
    return specs, team_list, index


def _check_state(state: WorldState, n: int) -> None:
    if state.robots.shape[0] != n:
        raise ValueError(f"state has {state.robots.shape[0]} robots, the renderer {n}")


# --------------------------------------------------------------------------------------------
# Overhead camera
# --------------------------------------------------------------------------------------------


class OverheadRenderer:
    """Overhead camera images of a field (module docstring).

    Args:
        spec: image characteristics (or a preset name of :data:`OVERHEAD_FRAMES`).
        field: the field.
        robot_specs: one spec for every robot or one per robot (world order).
        ball_spec: the ball.
        teams: ``(N,)`` team per robot, 0 blue, 1 yellow; a robot's number within its team
            (its patch pattern) is its rank among its team's robots in world order.
        camera: show this :class:`~soccer_env.vision.Camera`'s area (overrides
            ``spec.region``) and take its position and height for the ball's parallax.

    :meth:`render` returns ``(spec.height, spec.width, 3)`` uint8 RGB.
    """

    def __init__(self, spec: OverheadFrameSpec | str, field: FieldSpec,
                 robot_specs: RobotSpec | Sequence[RobotSpec], ball_spec: BallSpec,
                 teams: Sequence[int], camera: Camera | None = None) -> None:
        if isinstance(spec, str):
            spec = overhead_frame(spec)
        self.spec, self.field, self.ball_spec = spec, field, ball_spec
        self.robot_specs, self.teams, self.numbers = _per_robot(robot_specs, teams)
        self.n_robots = len(self.teams)
        W, H = spec.width, spec.height
        if camera is not None:
            region = (camera.x_min, camera.x_max, camera.y_min, camera.y_max)
            self._cam = (camera.x, camera.y, camera.height)
        elif spec.region is not None:
            region = spec.region
            self._cam = (0.5 * (region[0] + region[1]), 0.5 * (region[2] + region[3]),
                         spec.camera_height)
        else:
            wx, wy = field.half_length + field.boundary, field.half_width + field.boundary
            region = (-wx, wx, -wy, wy)
            self._cam = (0.0, 0.0, spec.camera_height)
        self.region = tuple(float(c) for c in region)
        x0, x1, y0, y1 = self.region
        #: Metres per pixel (square pixels).
        self.metres_per_pixel = max((x1 - x0) / W, (y1 - y0) / H)
        self._cx, self._cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        self._k = 1.0 / self.metres_per_pixel
        self._line_type = cv2.LINE_AA if spec.antialias else cv2.LINE_8
        self._photo = _Photometry(W, H, spec.gain_sigma, spec.gradient, spec.noise_sigma)
        # Per robot: body outline (body frame) and patches (centres, radii, colours).
        outlines, patches = [], []
        for rs, team, num in zip(self.robot_specs, self.teams, self.numbers):
            if rs.kind == "ssl":
                outline = np.array(robot_outline(rs, n_arc=16))
            else:
                a = np.linspace(0.0, 2.0 * math.pi, 24, endpoint=False)
                outline = rs.radius * np.column_stack([np.cos(a), np.sin(a)])
            outlines.append(outline)
            patches.append(PATTERN.patches(team, num, rs.radius))
        self._outlines = outlines
        self._patch_xy = [np.array([(p.x, p.y) for p in ps]) for ps in patches]
        self._patch_r = [[p.radius * self._k * _ONE for p in ps] for ps in patches]
        self._patch_rgb = [[p.rgb for p in ps] for ps in patches]
        self._radii = np.array([rs.radius for rs in self.robot_specs])
        self._max_height = max((rs.height for rs in self.robot_specs), default=0.0)
        self._background = self._draw_background()

    # ---------------------------------------------------------------- mapping

    def to_pixel(self, x: float | np.ndarray, y: float | np.ndarray
                 ) -> tuple[float | np.ndarray, float | np.ndarray]:
        """Continuous pixel ``(u, v)`` of the field point ``(x, y)`` [m] (module docstring:
        pixel ``[j, i]`` covers ``i <= u < i + 1``)."""
        k = self._k
        return (0.5 * self.spec.width + (x - self._cx) * k,
                0.5 * self.spec.height - (y - self._cy) * k)

    def to_field(self, u: float | np.ndarray, v: float | np.ndarray
                 ) -> tuple[float | np.ndarray, float | np.ndarray]:
        """Field point ``(x, y)`` [m] at continuous pixel ``(u, v)``; inverse of
        :meth:`to_pixel`."""
        m = self.metres_per_pixel
        return (self._cx + (u - 0.5 * self.spec.width) * m,
                self._cy - (v - 0.5 * self.spec.height) * m)

    def _fixed(self, x: np.ndarray, y: np.ndarray, ox: float = 0.0, oy: float = 0.0
               ) -> np.ndarray:
        """Fixed-point drawing coordinates (``shift = 4``) of field points, minus a pixel
        offset ``(ox, oy)``: cv2 puts integer coordinates at pixel centres."""
        u, v = self.to_pixel(x, y)
        return np.column_stack([np.rint((u - 0.5 - ox) * _ONE), np.rint((v - 0.5 - oy) * _ONE)]
                               ).astype(np.int32)

    def colour_table(self, tolerance: float = 30.0, bits: int = 5) -> ColourTable:
        """A :class:`ColourTable` of this renderer's colours, with a gain range that covers its
        lighting variation (3 sigma of gain plus the largest ramp)."""
        s = self.spec
        spread = 3.0 * s.gain_sigma + s.gradient
        colours = {c: COLOURS[c] for c in ColourTable.CLASSES}
        colours["carpet"] = s.carpet
        return ColourTable(colours, tolerance=max(tolerance, 3.0 * s.noise_sigma),
                           gain_range=(max(0.3, 1.0 - spread - 0.1), 1.0 + spread + 0.1),
                           bits=bits)

    # ---------------------------------------------------------------- background

    def _draw_background(self) -> np.ndarray:
        s, f = self.spec, self.field
        img = np.empty((s.height, s.width, 3), np.uint8)
        img[:] = COLOURS["floor"]
        lt = self._line_type
        k = self._k

        def pt(x: float, y: float) -> tuple[int, int]:
            return tuple(self._fixed(np.array([x]), np.array([y]))[0].tolist())

        def thick(width_m: float) -> int:
            return max(1, int(round(width_m * k)))

        hx, hy = f.half_length, f.half_width
        wx, wy = hx + f.boundary, hy + f.boundary
        cv2.fillPoly(img, [np.array([pt(-wx, wy), pt(wx, wy), pt(wx, -wy), pt(-wx, -wy)])],
                     s.carpet, lt, _SHIFT)
        lw = thick(f.line_width)
        corners = np.array([pt(-hx, hy), pt(hx, hy), pt(hx, -hy), pt(-hx, -hy)])
        cv2.polylines(img, [corners], True, s.line, lw, lt, _SHIFT)
        cv2.line(img, pt(0.0, hy), pt(0.0, -hy), s.line, lw, lt, _SHIFT)
        if f.center_circle_radius > 0.0:
            cv2.circle(img, pt(0.0, 0.0), int(round(f.center_circle_radius * k * _ONE)), s.line,
                       lw, lt, _SHIFT)
        dw, dd = 0.5 * f.defense_width, f.defense_depth
        gw, gd = 0.5 * f.goal_width, f.goal_depth
        gt = thick(f.goal_wall_thickness)
        for sgn in (-1.0, 1.0):
            if dw > 0.0 and dd > 0.0:
                xa, xb = sgn * hx, sgn * (hx - dd)
                cv2.polylines(img, [np.array([pt(xa, dw), pt(xb, dw), pt(xb, -dw),
                                              pt(xa, -dw)])], False, s.line, lw, lt, _SHIFT)
            # Goal walls: outside the goal line, wall_thickness beyond the goal's inside.
            e = 0.5 * f.goal_wall_thickness
            gx = sgn * (hx + gd + e)
            cv2.polylines(img, [np.array([pt(sgn * hx, gw + e), pt(gx, gw + e), pt(gx, -gw - e),
                                          pt(sgn * hx, -gw - e)])], False, COLOURS["goal"], gt,
                          lt, _SHIFT)
        cv2.polylines(img, [np.array([pt(-wx, wy), pt(wx, wy), pt(wx, -wy), pt(-wx, -wy)])],
                      True, COLOURS["wall"], thick(0.02), lt, _SHIFT)
        img.flags.writeable = False
        return img

    # ---------------------------------------------------------------- objects

    def _draw_robot(self, img: np.ndarray, i: int, x: float, y: float, th: float,
                    ox: float = 0.0, oy: float = 0.0) -> None:
        c, s = math.cos(th), math.sin(th)
        lt = self._line_type
        o = self._outlines[i]
        pts = self._fixed(x + c * o[:, 0] - s * o[:, 1], y + s * o[:, 0] + c * o[:, 1], ox, oy)
        cv2.fillPoly(img, [pts], COLOURS["body"], lt, _SHIFT)
        p = self._patch_xy[i]
        centres = self._fixed(x + c * p[:, 0] - s * p[:, 1], y + s * p[:, 0] + c * p[:, 1],
                              ox, oy).tolist()
        for centre, r, rgb in zip(centres, self._patch_r[i], self._patch_rgb[i]):
            cv2.circle(img, centre, int(round(r)), rgb, -1, lt, _SHIFT)

    def _ball_view(self, bx: float, by: float, bz: float) -> tuple[float, float, float]:
        """Where the ball appears (as a point of the field plane) and its apparent radius [m]
        (module docstring: chip parallax)."""
        r = self.ball_spec.radius
        if bz <= 0.0 or not self.spec.chip_parallax:
            return bx, by, r
        cx, cy, h = self._cam
        zc = bz + r
        if zc >= h - 1e-3:
            zc = h - 1e-3
        k = (h - r) / (h - zc)
        return cx + (bx - cx) * k, cy + (by - cy) * k, r * k

    def _draw_ball(self, img: np.ndarray, bx: float, by: float, bz: float, ox: float = 0.0,
                   oy: float = 0.0) -> None:
        x, y, r = self._ball_view(bx, by, bz)
        centre = self._fixed(np.array([x]), np.array([y]), ox, oy)[0].tolist()
        cv2.circle(img, centre, max(1, int(round(r * self._k * _ONE))), COLOURS["orange"], -1,
                   self._line_type, _SHIFT)

    def _smeared(self, img: np.ndarray, draw, poses: list[tuple[float, ...]], reach: float
                 ) -> None:
        """Average ``draw(tile, *pose, ox, oy)`` over ``poses`` on the image region they sweep
        (``reach`` [m] around each pose's position)."""
        xs = np.array([p[0] for p in poses])
        ys = np.array([p[1] for p in poses])
        us, vs = self.to_pixel(xs, ys)
        rpx = reach * self._k + 2.0
        H, W = img.shape[:2]
        u0, u1 = max(0, int(math.floor(us.min() - rpx))), min(W, int(math.ceil(us.max() + rpx)))
        v0, v1 = max(0, int(math.floor(vs.min() - rpx))), min(H, int(math.ceil(vs.max() + rpx)))
        if u0 >= u1 or v0 >= v1:
            return
        base = img[v0:v1, u0:u1]
        acc = np.zeros(base.shape, np.float32)
        for pose in poses:
            tile = base.copy()
            draw(tile, *pose, u0, v0)
            acc += tile
        img[v0:v1, u0:u1] = np.rint(acc * (1.0 / len(poses))).astype(np.uint8)

    def _samples(self, smear_px: float) -> int:
        return min(self.spec.blur_samples, max(2, int(math.ceil(smear_px)) + 1))

    def render(self, state: WorldState, rng: np.random.Generator | None = None) -> np.ndarray:
        """The camera image of ``state``: ``(height, width, 3)`` uint8 RGB. ``rng`` draws the
        lighting and noise (needed only if the spec has any)."""
        _check_state(state, self.n_robots)
        img = self._background.copy()
        T = self.spec.exposure
        k = self._k
        bx, by, bz, bvx, bvy, bvz = state.ball.tolist()
        ball_first = bz < self._max_height
        if ball_first:
            self._ball(img, bx, by, bz, bvx, bvy, bvz, T)
        robots = state.robots.tolist()
        radii = self._radii.tolist()
        for i, (x, y, th, vx, vy, om) in enumerate(robots):
            smear = T * (math.hypot(vx, vy) + abs(om) * radii[i]) * k
            if smear < 0.5:
                self._draw_robot(img, i, x, y, th)
                continue
            poses = [(x + vx * t, y + vy * t, i, th + om * t)
                     for t in np.linspace(-0.5 * T, 0.5 * T, self._samples(smear)).tolist()]
            self._smeared(img, self._draw_robot_at, poses, radii[i])
        if not ball_first:
            self._ball(img, bx, by, bz, bvx, bvy, bvz, T)
        return self._photo.apply(img, rng)

    def _draw_robot_at(self, tile: np.ndarray, x: float, y: float, i: int, th: float,
                       ox: float, oy: float) -> None:
        self._draw_robot(tile, i, x, y, th, ox, oy)

    def _ball(self, img: np.ndarray, bx: float, by: float, bz: float, vx: float, vy: float,
              vz: float, T: float) -> None:
        smear = T * math.sqrt(vx * vx + vy * vy + vz * vz) * self._k
        if smear < 0.5:
            self._draw_ball(img, bx, by, bz)
            return
        poses = []
        for t in np.linspace(-0.5 * T, 0.5 * T, self._samples(smear)).tolist():
            x, y, _ = self._ball_view(bx + vx * t, by + vy * t, max(0.0, bz + vz * t))
            poses.append((x, y, bx + vx * t, by + vy * t, max(0.0, bz + vz * t)))
        _, _, r = self._ball_view(bx, by, bz)

        def draw(tile: np.ndarray, x: float, y: float, tx: float, ty: float, tz: float,
                 ox: float, oy: float) -> None:
            self._draw_ball(tile, tx, ty, tz, ox, oy)

        self._smeared(img, draw, poses, 1.5 * r + self.ball_spec.radius)


# --------------------------------------------------------------------------------------------
# Head camera
# --------------------------------------------------------------------------------------------

_NEAR = 0.05  # [m] polygons are clipped this far in front of the camera


def _clip_near(poly: np.ndarray) -> np.ndarray | None:
    """Sutherland-Hodgman clip of a camera-frame polygon ``(k, 3)`` (columns ``x_c, depth,
    z_c``) to ``depth >= _NEAR``; None if nothing is left."""
    out = []
    n = len(poly)
    for j in range(n):
        a, b = poly[j], poly[(j + 1) % n]
        ina, inb = a[1] >= _NEAR, b[1] >= _NEAR
        if ina:
            out.append(a)
        if ina != inb:
            t = (_NEAR - a[1]) / (b[1] - a[1])
            out.append(a + t * (b - a))
    return np.array(out) if len(out) >= 3 else None


class HeadFrameRenderer:
    """Head-camera images of the robots of a world (module docstring).

    Args:
        camera_spec: the head camera (height, field of view, image size, goal colours:
            ``distinct_goals`` draws the goal at ``x = -L/2`` blue and the other yellow, else
            both white).
        field, robot_specs, ball_spec, teams: as :class:`OverheadRenderer`.
        spec: image appearance (or a preset name of :data:`HEAD_FRAMES`).
        size: ``(width, height)`` [pixels] to render at instead of the camera's, keeping its
            horizontal field of view (the focal length in pixels scales with the width).

    :attr:`camera` is the :class:`estimators.camera.HeadCamera` of the rendered image:
    ``camera.project(points, pan, tilt)`` gives the pixels of robot-frame points.
    """

    def __init__(self, camera_spec: HeadCameraSpec, field: FieldSpec,
                 robot_specs: RobotSpec | Sequence[RobotSpec], ball_spec: BallSpec,
                 teams: Sequence[int], spec: HeadFrameSpec | str = "clean",
                 size: tuple[int, int] | None = None) -> None:
        if isinstance(spec, str):
            spec = head_frame(spec)
        if size is None:
            size = (camera_spec.width, camera_spec.height_px)
        if not (len(size) == 2 and all(isinstance(s, (int, np.integer)) and 16 <= s <= 8192
                                       for s in size)):
            raise ValueError(f"size must be (width, height) in pixels, each in [16, 8192], "
                             f"got {size!r}")
        self.spec, self.camera_spec, self.field, self.ball_spec = spec, camera_spec, field, \
            ball_spec
        self.robot_specs, self.teams, _ = _per_robot(robot_specs, teams)
        self.n_robots = len(self.teams)
        self.camera = HeadCamera(height=camera_spec.height, hfov=camera_spec.hfov,
                                 width=int(size[0]), height_px=int(size[1]))
        self.width, self.height = int(size[0]), int(size[1])
        self._f = self.camera.focal_px
        self._u0, self._v0 = self.camera.centre
        self._line_type = cv2.LINE_AA if spec.antialias else cv2.LINE_8
        self._photo = _Photometry(self.width, self.height, spec.gain_sigma, spec.gradient,
                                  spec.noise_sigma)
        self._quads = self._line_quads()
        self._sky_img = np.empty((self.height, self.width, 3), np.uint8)
        self._sky_img[:] = spec.sky
        self._floor_img = np.empty_like(self._sky_img)
        self._floor_img[:] = spec.floor
        f = field
        hl, wx, wy = f.half_length, f.half_length + f.boundary, f.half_width + f.boundary
        self._carpet = np.array([[-wx, wy, 0.0], [wx, wy, 0.0], [wx, -wy, 0.0], [-wx, -wy, 0.0]])
        py = 0.5 * (f.goal_width + f.goal_wall_thickness)
        # Posts (as headcam.field_landmarks): centres, colour per goal.
        if camera_spec.distinct_goals:
            goal_rgb = (COLOURS["blue"], COLOURS["yellow"])
        else:
            goal_rgb = (spec.line, spec.line)
        self._posts = [(sx * hl, sy * py, goal_rgb[g])
                       for g, sx in enumerate((-1.0, 1.0)) for sy in (-1.0, 1.0)]
        a = np.linspace(0.0, 2.0 * math.pi, 16, endpoint=False)
        self._ring = np.column_stack([np.cos(a), np.sin(a)])

    def _line_quads(self) -> np.ndarray:
        """Field lines as ground quads ``(Q, 4, 3)`` of the line width."""
        f = self.field
        hx, hy = f.half_length, f.half_width
        segs = [((-hx, hy), (hx, hy)), ((hx, hy), (hx, -hy)), ((hx, -hy), (-hx, -hy)),
                ((-hx, -hy), (-hx, hy)), ((0.0, hy), (0.0, -hy))]
        dw, dd = 0.5 * f.defense_width, f.defense_depth
        if dw > 0.0 and dd > 0.0:
            for sgn in (-1.0, 1.0):
                xa, xb = sgn * hx, sgn * (hx - dd)
                segs += [((xa, dw), (xb, dw)), ((xb, dw), (xb, -dw)), ((xb, -dw), (xa, -dw))]
        r = f.center_circle_radius
        if r > 0.0:
            n = 48
            a = np.linspace(0.0, 2.0 * math.pi, n + 1)
            pts = r * np.column_stack([np.cos(a), np.sin(a)])
            segs += [(tuple(pts[j]), tuple(pts[j + 1])) for j in range(n)]
        w = max(0.5 * f.line_width, 1e-3)
        quads = []
        for (x1, y1), (x2, y2) in segs:
            dx, dy = x2 - x1, y2 - y1
            length = math.hypot(dx, dy)
            nx, ny = -dy / length * w, dx / length * w
            ex, ey = dx / length * w, dy / length * w  # extend the ends: closed corners
            quads.append([(x1 - ex + nx, y1 - ey + ny, 0.0), (x2 + ex + nx, y2 + ey + ny, 0.0),
                          (x2 + ex - nx, y2 + ey - ny, 0.0), (x1 - ex - nx, y1 - ey - ny, 0.0)])
        return np.array(quads, dtype=np.float64)

    # ---------------------------------------------------------------- geometry

    def _to_camera(self, p: np.ndarray) -> np.ndarray:
        """Camera coordinates ``(..., 3)`` (``x_c`` right, depth, ``z_c`` up) of field points
        ``(..., 3)`` for the current pose (headcam module docstring)."""
        return (p - self._origin) @ self._rot_t

    def _fixed(self, cam: np.ndarray) -> np.ndarray:
        """Fixed-point drawing coordinates of camera-frame points in front of the camera."""
        f = self._f * _ONE
        d = cam[..., 1]
        out = np.empty(cam.shape[:-1] + (2,), np.int32)
        out[..., 0] = np.rint((self._u0 - 0.5) * _ONE + f * cam[..., 0] / d)
        out[..., 1] = np.rint((self._v0 - 0.5) * _ONE - f * cam[..., 2] / d)
        return out

    def _polygons(self, cam: np.ndarray) -> list[np.ndarray]:
        """Drawable polygons of camera-frame polygons ``(Q, k, 3)``, clipped at the near
        plane."""
        front = cam[..., 1] >= _NEAR
        whole = front.all(axis=1)
        out = list(self._fixed(cam[whole])) if whole.any() else []
        for j in np.nonzero(front.any(axis=1) & ~whole)[0].tolist():
            poly = _clip_near(cam[j])
            if poly is not None:
                out.append(self._fixed(poly))
        return out

    def _fill(self, img: np.ndarray, cam_polys: np.ndarray, rgb: RGB) -> None:
        """Fill convex camera-frame polygons ``(Q, k, 3)`` one by one (``cv2.fillPoly`` fills
        several polygons with the even-odd rule: overlaps would become holes)."""
        lt = self._line_type
        for poly in self._polygons(cam_polys):
            cv2.fillConvexPoly(img, poly, rgb, lt, _SHIFT)

    def _cylinder(self, img: np.ndarray, x: float, y: float, radius: float, z0: float,
                  z1: float, rgb: RGB) -> None:
        """A vertical cylinder: the convex hull of its projected end circles, or (partly
        behind the camera) its clipped silhouette quad."""
        cx, cy = self._pose[0], self._pose[1]
        ring = self._ring * radius + (x, y)
        pts = np.empty((2 * len(ring), 3))
        pts[:len(ring), :2] = ring
        pts[len(ring):, :2] = ring
        pts[:len(ring), 2] = z0
        pts[len(ring):, 2] = z1
        cam = self._to_camera(pts)
        if (cam[:, 1] >= _NEAR).all():
            hull = cv2.convexHull(self._fixed(cam))
            cv2.fillConvexPoly(img, hull, rgb, self._line_type, _SHIFT)
            return
        dx, dy = x - cx, y - cy
        d = math.hypot(dx, dy)
        if d < 1e-9:
            return
        nx, ny = -dy / d * radius, dx / d * radius
        quad = np.array([[x + nx, y + ny, z0], [x - nx, y - ny, z0], [x - nx, y - ny, z1],
                         [x + nx, y + ny, z1]])
        self._fill(img, self._to_camera(quad)[None], rgb)

    # ---------------------------------------------------------------- render

    def horizon_row(self, tilt: float) -> float:
        """Continuous ``v`` [px] of the horizon for a true camera tilt [rad]."""
        return self._v0 - self._f * math.tan(tilt)

    def render(self, state: WorldState, heads: HeadState, observer: int,
               rng: np.random.Generator | None = None) -> np.ndarray:
        """The image seen by robot ``observer``'s head camera in ``state`` with the TRUE head
        orientation of ``heads`` (servo plus sway): ``(height, width, 3)`` uint8 RGB."""
        _check_state(state, self.n_robots)
        if not 0 <= observer < self.n_robots:
            raise ValueError(f"observer must be a robot index in [0, {self.n_robots - 1}], "
                             f"got {observer!r}")
        sp, f = self.spec, self.field
        x, y, th = state.robots[observer, 0:3].tolist()
        psi = th + float(heads.pan[observer]) + float(heads.sway_pan[observer])
        beta = float(heads.tilt[observer]) + float(heads.sway_tilt[observer])
        h = self.camera.height
        c, s, cb, sb = math.cos(psi), math.sin(psi), math.cos(beta), math.sin(beta)
        self._pose = (x, y)
        self._origin = np.array([x, y, h])
        # Rows: x_c (right), depth, z_c (up) of a field offset (dx, dy, dz).
        self._rot_t = np.array([[s, -c, 0.0], [cb * c, cb * s, -sb], [sb * c, sb * s, cb]]).T
        H = self.height
        # Sky above the horizon, floor below it (no roll: a horizontal line).
        if beta >= 0.5 * math.pi - 1e-9:
            row = -1
        elif beta <= -0.5 * math.pi + 1e-9:
            row = H
        else:
            row = int(min(H, max(-1, math.floor(self.horizon_row(beta) - 0.5) + 1)))
        row = max(0, row)
        img = self._floor_img.copy()
        img[:row] = self._sky_img[:row]
        self._fill(img, self._to_camera(self._carpet)[None], sp.carpet)
        self._fill(img, self._to_camera(self._quads), sp.line)
        # Objects, farthest first.
        objects: list[tuple[float, int, tuple]] = []
        gh, gt = f.goal_height, f.goal_wall_thickness
        post_d = []
        for px, py, rgb in self._posts:
            d = math.hypot(px - x, py - y)
            post_d.append(d)
            objects.append((d, 0, (px, py, 0.5 * gt, 0.0, gh, rgb)))
        for g in (0, 2):  # crossbars, behind their posts
            (ax, ay, rgb), (bx_, by_, _) = self._posts[g], self._posts[g + 1]
            objects.append((max(post_d[g], post_d[g + 1]) + 1e-3, 1,
                            (ax, ay, bx_, by_, gh - gt, gh, rgb)))
        for j, (rx, ry) in enumerate(state.robots[:, 0:2].tolist()):
            if j == observer:
                continue
            rs = self.robot_specs[j]
            objects.append((math.hypot(rx - x, ry - y), 2, (rx, ry, rs.radius, rs.height,
                                                            self.teams[j])))
        bx, by, bz = state.ball[0:3].tolist()
        objects.append((math.hypot(bx - x, by - y), 3, (bx, by, bz)))
        objects.sort(key=lambda o: -o[0])
        team_rgb = (COLOURS["blue"], COLOURS["yellow"])
        for _, kind, a in objects:
            if kind == 0:
                self._cylinder(img, a[0], a[1], a[2], a[3], a[4], a[5])
            elif kind == 1:
                ax, ay, bx_, by_, z0, z1, rgb = a
                bar = np.array([[ax, ay, z0], [bx_, by_, z0], [bx_, by_, z1], [ax, ay, z1]])
                self._fill(img, self._to_camera(bar)[None], rgb)
            elif kind == 2:
                rx, ry, rr, rh, team = a
                self._cylinder(img, rx, ry, rr, 0.0, 0.8 * rh, sp.body)
                self._cylinder(img, rx, ry, rr, 0.8 * rh, rh, team_rgb[team])
            else:
                self._draw_ball(img, *a)
        return self._photo.apply(img, rng)

    def _draw_ball(self, img: np.ndarray, bx: float, by: float, bz: float) -> None:
        r = self.ball_spec.radius
        cam = self._to_camera(np.array([bx, by, bz + r]))
        depth = float(cam[1])
        if depth < _NEAR + r:
            return
        radius = self._f * r / depth
        centre = self._fixed(cam)
        u, v = centre.tolist()
        lim = 4 * _ONE * (self.width + self.height)
        if abs(u) > lim or abs(v) > lim:
            return
        cv2.circle(img, (u, v), max(1, int(round(radius * _ONE))), COLOURS["orange"], -1,
                   self._line_type, _SHIFT)


# --------------------------------------------------------------------------------------------
# Trackers' helpers
# --------------------------------------------------------------------------------------------


def _valid_hue(hsv: np.ndarray, min_saturation: int, min_value: int) -> np.ndarray:
    return cv2.inRange(hsv, (0, min_saturation, min_value), (180, 255, 255))


def hue_histogram(image_patch: np.ndarray, bins: int = 16, mask: np.ndarray | None = None,
                  min_saturation: int = 60, min_value: int = 32) -> np.ndarray:
    """Hue histogram ``(bins,)`` float32 of an RGB patch, scaled to a maximum of 1 (paper
    004's target model). Pixels darker than ``min_value`` or less saturated than
    ``min_saturation`` (0-255; OpenCV's CamShift sample uses 60 and 32) have no reliable hue
    and are left out, as are those where ``mask`` (uint8, same size) is 0."""
    if image_patch.ndim != 3 or image_patch.shape[2] != 3 or image_patch.dtype != np.uint8:
        raise ValueError(f"image_patch must be an (h, w, 3) uint8 RGB array, got "
                         f"{image_patch.shape} {image_patch.dtype}")
    if not (isinstance(bins, int) and 1 <= bins <= 180):
        raise ValueError(f"bins must be an integer in [1, 180], got {bins!r}")
    hsv = cv2.cvtColor(image_patch, cv2.COLOR_RGB2HSV)
    valid = _valid_hue(hsv, min_saturation, min_value)
    if mask is not None:
        valid = cv2.bitwise_and(valid, np.asarray(mask, np.uint8))
    hist = cv2.calcHist([hsv], [0], valid, [bins], [0, 180]).reshape(-1)
    peak = float(hist.max())
    return (hist / peak if peak > 0 else hist).astype(np.float32)


def back_project(image: np.ndarray, histogram: np.ndarray, min_saturation: int = 60,
                 min_value: int = 32) -> np.ndarray:
    """Back-projection of a :func:`hue_histogram` on an RGB image: float32 ``(H, W)`` in
    [0, 1], each pixel the histogram's value at its hue (0 where its hue is unreliable, as in
    :func:`hue_histogram`)."""
    hist = np.asarray(histogram, np.float32).reshape(-1)
    if hist.size < 1 or hist.size > 180:
        raise ValueError(f"histogram must have 1-180 bins, got {hist.size}")
    hsv = cv2.cvtColor(image, cv2.COLOR_RGB2HSV)
    scaled = np.clip(hist, 0.0, 1.0) * 255.0
    bp = cv2.calcBackProject([hsv], [0], scaled, [0, 180], scale=1)
    bp = cv2.bitwise_and(bp, _valid_hue(hsv, min_saturation, min_value))
    return bp.astype(np.float32) * (1.0 / 255.0)


def frame_difference(prev: np.ndarray, cur: np.ndarray) -> np.ndarray:
    """Absolute grey-level difference of two RGB (or grey) uint8 frames, float32 in [0, 1]
    (paper 003's motion image)."""
    if prev.shape != cur.shape:
        raise ValueError(f"frames must have the same shape, got {prev.shape} and {cur.shape}")
    a = cv2.cvtColor(prev, cv2.COLOR_RGB2GRAY) if prev.ndim == 3 else prev
    b = cv2.cvtColor(cur, cv2.COLOR_RGB2GRAY) if cur.ndim == 3 else cur
    return cv2.absdiff(a, b).astype(np.float32) * (1.0 / 255.0)


class ColourTable:
    """A colour look-up table (paper 003's, built offline): quantised RGB -> class
    probabilities.

    The RGB cube is cut into ``2**bits`` levels per channel. For each cell centre ``x`` and
    class ``c`` of nominal colour ``n_c``, ``d_c`` is the distance from ``x`` to the nearest
    colour ``g n_c`` (saturated at 255) with the lighting gain ``g`` in ``gain_range``, and
    ``w_c = exp(-d_c^2 / (2 tolerance^2))``; the probability of class ``c`` is ``w_c /
    max(1, sum_k w_k)``: near 1 at a nominal colour (under any gain of the range), shared where
    classes overlap, near 0 far from every class (lines, robot bodies).

    Args:
        colours: class name -> nominal RGB (the classes, in this order); default the
            classes of :attr:`CLASSES` with their :data:`COLOURS`.
        tolerance: distance scale [grey levels].
        gain_range: lighting gains the table must cover.
        bits: quantisation (1-8 bits per channel).
    """

    CLASSES = ("orange", "blue", "yellow", "pink", "green", "carpet")
    ALIASES = {"ball": "orange"}

    def __init__(self, colours: Mapping[str, RGB] | None = None, tolerance: float = 30.0,
                 gain_range: tuple[float, float] = (0.75, 1.25), bits: int = 5) -> None:
        if colours is None:
            colours = {c: COLOURS[c] for c in self.CLASSES}
        if not colours:
            raise ValueError("colours must name at least one class")
        if not (math.isfinite(tolerance) and tolerance > 0.0):
            raise ValueError(f"tolerance must be > 0 grey levels, got {tolerance!r}")
        g0, g1 = gain_range
        if not (0.0 < g0 <= g1 <= 10.0):
            raise ValueError(f"gain_range must be (low, high) with 0 < low <= high <= 10, got "
                             f"{gain_range!r}")
        if not (isinstance(bits, int) and 1 <= bits <= 8):
            raise ValueError(f"bits must be an integer in [1, 8], got {bits!r}")
        self.classes = tuple(colours)
        self.colours = {k: tuple(int(c) for c in v) for k, v in colours.items()}
        self.tolerance, self.gain_range, self.bits = float(tolerance), (g0, g1), bits
        n = 1 << bits
        step = 256.0 / n
        centres = (np.arange(n) + 0.5) * step
        grid = np.stack(np.meshgrid(centres, centres, centres, indexing="ij"), axis=-1)
        cells = grid.reshape(-1, 3)
        gains = np.linspace(g0, g1, 17)
        weights = []
        for name in self.classes:
            ref = np.minimum(gains[:, None] * np.array(self.colours[name], float), 255.0)
            d2 = ((cells[:, None, :] - ref[None, :, :]) ** 2).sum(axis=2).min(axis=1)
            weights.append(np.exp(-0.5 * d2 / self.tolerance**2))
        w = np.stack(weights)
        p = w / np.maximum(1.0, w.sum(axis=0))
        #: ``(C, n, n, n)`` float32 probabilities, indexed by class then R, G, B level.
        self.table = p.reshape(len(self.classes), n, n, n).astype(np.float32)
        # cv2.Mat(..., wrap_channels=False): a 3-D histogram, not a 2-D image of 32 channels.
        self._hists = [cv2.Mat(np.ascontiguousarray(t * 255.0), wrap_channels=False)
                       for t in self.table]

    def _index(self, cls: str) -> int:
        name = self.ALIASES.get(cls, cls)
        if name not in self.classes:
            raise ValueError(f"unknown colour class {cls!r}; known: {list(self.classes)}")
        return self.classes.index(name)

    def lookup(self, rgb: Sequence[int]) -> dict[str, float]:
        """Class probabilities of one RGB colour."""
        s = 8 - self.bits
        r, g, b = (int(c) >> s for c in rgb)
        return {c: float(self.table[k, r, g, b]) for k, c in enumerate(self.classes)}

    def probability(self, image: np.ndarray, cls: str) -> np.ndarray:
        """Probability image of class ``cls`` (``"ball"`` means ``"orange"``) for an RGB uint8
        image: float32 ``(H, W)`` in [0, 1] (paper 003's colour image)."""
        k = self._index(cls)
        if image.ndim != 3 or image.shape[2] != 3 or image.dtype != np.uint8:
            raise ValueError(f"image must be an (H, W, 3) uint8 RGB array, got {image.shape} "
                             f"{image.dtype}")
        bp = cv2.calcBackProject([image], [0, 1, 2], self._hists[k], [0, 256, 0, 256, 0, 256],
                                 scale=1)
        return bp.astype(np.float32) * (1.0 / 255.0)

    def classify(self, image: np.ndarray, threshold: float = 0.5) -> np.ndarray:
        """Most probable class index per pixel (``int8``), -1 where no class reaches
        ``threshold``."""
        probs = np.stack([self.probability(image, c) for c in self.classes])
        best = probs.argmax(axis=0).astype(np.int8)
        best[probs.max(axis=0) < threshold] = -1
        return best


# --------------------------------------------------------------------------------------------
# Timing
# --------------------------------------------------------------------------------------------


def _benchmark(repeats: int = 200) -> dict[str, float]:  # pragma: no cover - manual tool
    """Milliseconds per frame of the renderers on a 6 v 6 scene (run ``python -m
    soccer_env.frames``)."""
    import time

    from soccer_env import presets
    from soccer_env.headcam import head_camera

    rng = np.random.default_rng(0)
    out = {}
    field = presets.field("ssl-div-b")
    n = 12
    teams = [0] * 6 + [1] * 6
    robots = np.column_stack([rng.uniform(-4, 4, n), rng.uniform(-2.8, 2.8, n),
                              rng.uniform(-3, 3, n), rng.uniform(-2, 2, (n, 2)),
                              rng.uniform(-3, 3, n)])
    state = WorldState(0.0, np.array([0.3, 0.2, 0.0, 4.0, 1.0, 0.0]), robots,
                       tuple(f"r{i}" for i in range(n)), np.array(teams))
    for name in ("clean", "realistic", "mirosot"):
        r = OverheadRenderer(name, field, presets.robot("ssl"), presets.ball("ssl"), teams)
        r.render(state, rng)
        t0 = time.perf_counter()
        for _ in range(repeats):
            r.render(state, rng)
        out[f"overhead {name} 640x480, 12 robots"] = (time.perf_counter() - t0) / repeats * 1e3
    hfield = presets.field("humanoid-kid")
    hrob = np.column_stack([rng.uniform(-4, 4, n), rng.uniform(-2.8, 2.8, n),
                            rng.uniform(-3, 3, n), np.zeros((n, 3))])
    hstate = WorldState(0.0, np.array([1.0, 0.2, 0.0, 0.0, 0.0, 0.0]), hrob, state.names,
                        np.array(teams))
    heads = HeadState.steady(n, 0.0, 0.3)
    for size in ((320, 240), (720, 625)):
        for name in ("clean", "realistic"):
            r = HeadFrameRenderer(head_camera("kidsize"), hfield, presets.robot("humanoid"),
                                  presets.ball("kidsize"), teams, name, size)
            r.render(hstate, heads, 0, rng)
            t0 = time.perf_counter()
            for _ in range(repeats):
                r.render(hstate, heads, 0, rng)
            out[f"head {name} {size[0]}x{size[1]}"] = (time.perf_counter() - t0) / repeats * 1e3
    return out


if __name__ == "__main__":  # pragma: no cover
    for key, ms in _benchmark().items():
        print(f"{key}: {ms:.2f} ms")
