"""Head camera: what a humanoid robot sees through the pan/tilt camera in its head (Xu et al.
2012; Guo and Li 2013).

Geometry. The camera of observer ``i`` sits ``spec.height`` above the robot's centre
``(x_i, y_i)`` and looks along the robot's heading ``theta_i`` turned by the head: pan ``alpha``
about the vertical (positive to the left) and then tilt ``beta`` about the panned horizontal
axis (positive looking down), the pinhole model of :class:`estimators.HeadCamera`. A
field point ``p`` at offset ``(dx, dy, dz)`` from the camera, with ``psi = theta_i + alpha``,
has the camera coordinates

    q_fwd = cos(psi) dx + sin(psi) dy,    x_c = sin(psi) dx - cos(psi) dy   (to the right),
    y_c = cos(beta) q_fwd - sin(beta) dz  (depth),   z_c = sin(beta) q_fwd + cos(beta) dz,

and the pixel ``u = u0 + f x_c / y_c``, ``v = v0 - f z_c / y_c`` (``f`` the focal length in
pixels, ``v`` growing downwards). The robot knows its servo angles ``alpha, beta`` (the
:class:`HeadState` ``pan, tilt``) but not the gait's sway of its torso, so the camera's TRUE
orientation is ``(alpha + sway_pan, beta + sway_tilt)``: the image is formed with the true
angles and interpreted with the believed ones.

Objects. Per frame the sensor looks for the ball (its centre, ``z = ball z + radius``), the
static landmarks of :func:`field_landmarks` (goal-post feet and line crossings, on the ground)
and every other robot's foot point nearest the observer (``c_j - R_j (c_j - c_i) / |c_j -
c_i|``, on the ground: Guo and Li's (2013) obstacle-ground corners). An object is detected if

1. its pixel with the true orientation lies inside the ``width x height_px`` image, in front of
   the camera;
2. its ground distance from the observer's centre is at most the range of its kind
   (``ball_range``, ``landmark_range``, ``robot_range``);
3. with ``occlusion``, the line of sight from the observer's centre to the object (in the ground
   plane) passes through no other robot's disc (radius from ``robot_radii``); robots are taken
   as taller than the camera, so the test is two-dimensional and a robot standing on a
   landmark hides it;
4. a detection draw with the probability of its kind succeeds.

The detected pixel gets Gaussian noise ``pixel_sigma`` on ``u`` and ``v`` (it may then lie a
little outside the image) and is projected back with the BELIEVED angles onto its plane: the
ball onto ``z = ball radius`` (a ball in the air lands farther away, as on a real robot),
landmarks and robot feet onto the ground. Pixel noise and sway thus give ground errors that grow
with distance (about ``d^2 / (h f)`` per pixel along the line of sight). Every detection also
carries a bearing, the azimuth ``atan2(y, x)`` of its pixel's ray in the robot frame, which is
defined even at and above the horizon where the ground point ``(x, y)`` is NaN.

Spurious balls: per frame, with probability ``1 - exp(-false_ball_rate * T)`` (``T`` the frame
period; with ``frame_rate=None`` the time since the observer's previous frame), one ball at a
random pixel, ``u`` uniform over the width and ``v`` uniform over the rows below the one whose
ray meets the ball plane ``ball_range`` straight ahead (believed angles): a point of the visible
ground within about ``ball_range`` (up to 1 / cos(hfov / 2) farther at the image's sides). It
follows the true ball in the frame's ``balls``.

Timing. Each observer's camera runs at ``frame_rate`` with a phase drawn uniformly per episode
(``frame_rate=None``: one frame per :meth:`HeadCameraSensor.step` call). A frame is captured at
the first step whose ``state.time`` is at or after the observer's next frame time, and is
stamped with ``state.time``: no interpolation of the truth, the robots being slow (at 0.3 m/s a
60 Hz step moves them 5 mm; a kicked ball moves farther, but the capture time stamp is exact for
the state used); capture times are thus quantised to the step times while the mean rate stays
``frame_rate`` (at most one frame per observer per step). It is delivered ``latency`` plus a
uniform ``[0, latency_jitter]`` seconds later; :meth:`step` returns the frames delivered by
``state.time``, ordered by delivery time. A blind observer (fallen or getting up) captures
nothing when a frame is due. :meth:`HeadCameraSensor.reset` returns a warm-up frame per seeing
observer, of the initial scene, captured ``latency`` earlier and delivered at once (as the
overhead vision does), so filters start with a sighting. Frames that detect nothing are still
delivered: an empty frame tells a filter that nothing was where the camera looked.

Cost: the visibility test, the occlusion test and the back-projection of every (frame, object)
pair of a step are one compiled kernel (:mod:`soccer_env.sensors.headcam_kernels`); Python
draws the random numbers and builds the frames: in a loop, about 20 to 30 microseconds for a
step that captures one frame and 30 to 50 for four (8 robots, 20 landmarks), four to six times
less than the numpy version on the same machine. All randomness comes from the generator given to
:meth:`HeadCameraSensor.reset`, drawn in fixed-size blocks per frame, so the same seed and
inputs give the same frames.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec
from soccer_env.presets.sensors import HeadCameraSpec
from soccer_env.sensors.headcam_kernels import back_project, head_detections
from soccer_env.state import HeadState, WorldState

__all__ = ["LANDMARK_KINDS", "field_landmarks", "HeadFrame", "HeadCameraSensor",
           "BALL_DETECTION_FIELDS", "LANDMARK_DETECTION_FIELDS", "ROBOT_DETECTION_FIELDS"]

#: Landmark kinds of :func:`field_landmarks`: goal-post feet (``"post"`` when the goals look
#: alike, otherwise ``"post_blue"`` for the goal at ``x = -L/2`` that blue defends and
#: ``"post_yellow"`` at ``x = +L/2``) and line crossings shaped ``"L"``, ``"T"`` and ``"X"``.
LANDMARK_KINDS = ("post", "post_blue", "post_yellow", "L", "T", "X")

#: Layout of a ball detection: pixel [px], ground point in the robot frame [m], bearing [rad].
BALL_DETECTION_FIELDS = ("u", "v", "x", "y", "bearing")
#: Layout of a landmark detection.
LANDMARK_DETECTION_FIELDS = ("kind", "u", "v", "x", "y", "bearing")
#: Layout of a robot detection (``team`` 0 blue, 1 yellow).
ROBOT_DETECTION_FIELDS = ("team", "u", "v", "x", "y", "bearing")


# --------------------------------------------------------------------------------------------
# Landmarks
# --------------------------------------------------------------------------------------------


def field_landmarks(field: FieldSpec, distinct_goals: bool
                    ) -> tuple[np.ndarray, tuple[str, ...]]:
    """The static landmarks of a field: positions ``(M, 2)`` [m, field frame] and their kinds.

    In this order:

    * goal posts (4): the feet of the posts, Guo and Li's (2013) obstacle-ground corners, at the
      posts' centres ``(+-L/2, +-(goal_width/2 + goal_wall_thickness/2))`` (``goal_width`` is
      between the posts' inner edges); ``"post_blue"`` at ``x = -L/2`` and ``"post_yellow"`` at
      ``x = +L/2`` if ``distinct_goals``, else ``"post"``;
    * ``"L"`` (8): the four field corners ``(+-L/2, +-W/2)`` and the four front corners of the
      goal areas ``(+-(L/2 - defense_depth), +-defense_width/2)``;
    * ``"T"`` (6): the ends of the centre line ``(0, +-W/2)`` and where the goal areas' side
      lines meet the goal lines ``(+-L/2, +-defense_width/2)``;
    * ``"X"`` (2): where the centre circle crosses the centre line ``(0, +-R)``.

    The points are the nominal dimensions of :class:`~soccer_env.presets.FieldSpec` (the line
    width, a few centimetres, is ignored). Goal-area features are left out when the field has
    no goal area (``defense_depth`` or ``defense_width`` zero), the ``"X"`` when it has no
    centre circle.
    """
    hl, hw = field.half_length, field.half_width
    py = 0.5 * (field.goal_width + field.goal_wall_thickness)
    pts: list[tuple[float, float]] = []
    kinds: list[str] = []
    for sx in (-1.0, 1.0):
        kind = ("post_blue" if sx < 0 else "post_yellow") if distinct_goals else "post"
        for sy in (-1.0, 1.0):
            pts.append((sx * hl, sy * py))
            kinds.append(kind)
    has_area = field.defense_depth > 0.0 and field.defense_width > 0.0
    dx, dy = hl - field.defense_depth, 0.5 * field.defense_width
    for sx in (-1.0, 1.0):
        for sy in (-1.0, 1.0):
            pts.append((sx * hl, sy * hw))
            kinds.append("L")
            if has_area:
                pts.append((sx * dx, sy * dy))
                kinds.append("L")
    for sy in (-1.0, 1.0):
        pts.append((0.0, sy * hw))
        kinds.append("T")
    if has_area:
        for sx in (-1.0, 1.0):
            for sy in (-1.0, 1.0):
                pts.append((sx * hl, sy * dy))
                kinds.append("T")
    if field.center_circle_radius > 0.0:
        for sy in (-1.0, 1.0):
            pts.append((0.0, sy * field.center_circle_radius))
            kinds.append("X")
    return np.array(pts, dtype=np.float64).reshape(-1, 2), tuple(kinds)


# --------------------------------------------------------------------------------------------
# Inputs and outputs
# --------------------------------------------------------------------------------------------


class HeadFrame(NamedTuple):
    """One head-camera frame as the observing robot's software receives it.

    Detections are plain tuples (see :data:`BALL_DETECTION_FIELDS` and the other layouts):
    pixel ``u, v`` [px] with noise; ``x, y`` the ground projection in the robot frame (x
    forward, y left, origin under the camera) [m] computed with the believed head angles, NaN
    at or above the horizon; ``bearing`` the azimuth of the pixel's ray in the robot frame
    [rad].

    Attributes:
        robot: index (in the world) of the observer.
        t_capture: when the image was taken [s]. t_delivered: when it reaches the software [s].
        pan, tilt: the head angles the robot believed at capture [rad].
        balls: ``(u, v, x, y, bearing)`` for the true ball (first, if seen) and any spurious
            one.
        landmarks: ``(kind, u, v, x, y, bearing)``, in :func:`field_landmarks` order.
        robots: ``(team, u, v, x, y, bearing)``: other robots' foot points nearest the observer,
            team 0 blue / 1 yellow (no identity), in world order.
        image: the rendered image, ``(H, W, 3)`` uint8 RGB, from
            :class:`~soccer_env.sensors.images.cameras.PixelHeadCamera` (its ``balls`` are
            then empty: the robot finds the ball in the image); None otherwise.
    """

    robot: int
    t_capture: float
    t_delivered: float
    pan: float
    tilt: float
    balls: tuple
    landmarks: tuple
    robots: tuple
    image: Any = None


# --------------------------------------------------------------------------------------------
# The sensor
# --------------------------------------------------------------------------------------------


class HeadCameraSensor:
    """The head cameras of the robots ``observers`` (see the module docstring).

    Args:
        spec: camera and processing characteristics.
        field: the field (its landmarks).
        ball: the ball (its radius: the plane of a resting ball's centre).
        robot_radii: ``(N,)`` radius of every robot of the world [m] (footprint discs, for
            occlusion and foot points).
        teams: ``(N,)`` team of every robot, 0 blue, 1 yellow.
        observers: indices of the robots that carry a head camera.

    Reads only :class:`~soccer_env.state.WorldState` and :class:`HeadState`: any robot can
    carry one.
    """

    def __init__(self, spec: HeadCameraSpec, field: FieldSpec, ball: BallSpec,
                 robot_radii: Sequence[float], teams: Sequence[int],
                 observers: Sequence[int]) -> None:
        radii = np.array(robot_radii, dtype=np.float64).reshape(-1)
        n = len(radii)
        if n == 0:
            raise ValueError("robot_radii must have one entry per robot, got none")
        if not (np.isfinite(radii) & (radii >= 0.0)).all():
            raise ValueError(f"robot_radii must be finite and >= 0, got {radii.tolist()}")
        team_list = [int(t) for t in teams]
        if len(team_list) != n or any(t not in (0, 1) for t in team_list):
            raise ValueError(f"teams must hold 0 or 1 for each of the {n} robots, "
                             f"got {list(teams)}")
        obs = [int(o) for o in observers]
        if any(not 0 <= o < n for o in obs) or len(set(obs)) != len(obs):
            raise ValueError(f"observers must be distinct robot indices in [0, {n - 1}], "
                             f"got {list(observers)}")
        self.spec, self.field, self.ball_spec = spec, field, ball
        self.camera = spec.camera
        self._f = self.camera.focal_px
        self._u0, self._v0 = self.camera.centre
        self.n_robots = n
        self.robot_radii = radii
        self.teams = tuple(team_list)
        self.observers = tuple(obs)
        self.landmarks, self.landmark_kinds = field_landmarks(field, spec.distinct_goals)
        m = len(self.landmarks)
        self._m = m
        # Object slots of a frame: 0 the ball, 1..m the landmarks, m+1.. the robots' feet.
        p = 1 + m + n
        self._p = p
        self._range2 = np.concatenate([[spec.ball_range**2], np.full(m, spec.landmark_range**2),
                                       np.full(n, spec.robot_range**2)])
        self._p_detect = np.concatenate([[spec.ball_detection],
                                         np.full(m, spec.landmark_detection),
                                         np.full(n, spec.robot_detection)])
        self._r2 = radii**2
        #: The kernels' camera constants: focal length and principal point ``(f, u0, v0)``
        #: [px]; height [m], those three, ball radius [m], pixel noise [px].
        self._lens = (float(self._f), float(self._u0), float(self._v0))
        self._kernel_camera = (float(spec.height), *self._lens, float(ball.radius),
                               float(spec.pixel_sigma))
        self._queue: list[tuple[float, float, int, int, HeadFrame]] = []
        self._seq = 0
        self._rng: np.random.Generator | None = None
        self._next: list[float] = []
        self._last: list[float] = []

    # ------------------------------------------------------------------------------------

    def reset(self, state: WorldState, heads: HeadState, rng: np.random.Generator
              ) -> list[HeadFrame]:
        """Start an episode at ``state``. Each observer's frame phase is drawn uniformly in one
        frame period. The cameras have been running while the scene stood still: one frame per
        seeing observer, captured ``latency`` ago of the initial scene, is delivered at once
        and returned (robot order)."""
        n = self.n_robots
        if state.robots.shape[0] != n:
            raise ValueError(f"state has {state.robots.shape[0]} robots, the sensor {n}")
        for name, arr in zip(HeadState._fields, heads):
            if np.shape(arr) != (n,):
                raise ValueError(f"heads.{name} must have shape ({n},), got {np.shape(arr)}")
        self._rng = rng
        self._queue = []
        period = self._period()
        k = len(self.observers)
        now = state.time
        self._next = ((now + period * rng.random(k)).tolist() if period is not None
                      else [now] * k)
        self._last = [now] * k
        blind = np.asarray(heads.blind, dtype=bool).tolist()
        due = [j for j, i in enumerate(self.observers) if not blind[i]]
        warm = self._capture(state, heads, due, interval=period or 0.0)
        return [f._replace(t_capture=now - self.spec.latency, t_delivered=now) for f in warm]

    def _period(self) -> float | None:
        return None if self.spec.frame_rate is None else 1.0 / self.spec.frame_rate

    def step(self, state: WorldState, heads: HeadState) -> list[HeadFrame]:
        """Capture the frames due by ``state.time`` and return those delivered by then,
        ordered by delivery time."""
        if self._rng is None:
            raise RuntimeError("call reset() before step()")
        now = state.time
        period = self._period()
        blind = np.asarray(heads.blind, dtype=bool).tolist()
        if period is None:  # a frame at every call
            due = [j for j, i in enumerate(self.observers) if not blind[i]]
        else:
            due = []
            nxt = self._next
            for j, i in enumerate(self.observers):
                if nxt[j] <= now + 1e-12:
                    while nxt[j] <= now + 1e-12:  # one frame, however many periods passed
                        nxt[j] += period
                    if not blind[i]:
                        due.append(j)
        queue = self._queue
        if due:
            for frame in self._capture(state, heads, due, period):
                self._seq += 1
                heapq.heappush(queue, (frame.t_delivered, frame.t_capture, frame.robot,
                                       self._seq, frame))
        out = []
        while queue and queue[0][0] <= now + 1e-12:
            out.append(heapq.heappop(queue)[4])
        return out

    # ------------------------------------------------------------------------------------

    def _capture(self, state: WorldState, heads: HeadState, due: list[int],
                 interval: float | None) -> list[HeadFrame]:
        """Frames of observers ``due`` (positions in ``observers``) at ``state.time``, in that
        order. ``interval``: the frame period for the spurious-ball probability (None: the time
        since each observer's previous frame).

        The steps: the frame's random numbers, drawn in fixed-size blocks; the visibility
        test, the occlusion test and the back-projection of every (frame, object) pair of
        the step (the frames due in one step share the truth) in one compiled kernel
        (:func:`~soccer_env.sensors.headcam_kernels.head_detections`); the detections sorted
        into each frame's lists (:meth:`_detections`); the spurious balls and the delivery
        times.
        """
        spec = self.spec
        p = self._p
        now = state.time
        F = len(due)
        rng = self._rng
        # Fixed-size draws per frame: a detection uniform per object slot, then the spurious
        # ball (3) and the latency jitter (1); two normals per slot.
        U = rng.random((F, p + 4))
        Z = rng.standard_normal((F, 2, p))
        ids = [self.observers[j] for j in due]
        pan = np.asarray(heads.pan, dtype=np.float64)
        tilt = np.asarray(heads.tilt, dtype=np.float64)
        where, found = head_detections(
            state.robots, state.ball, np.array(ids, dtype=np.int64), pan, tilt,
            np.asarray(heads.sway_pan, dtype=np.float64),
            np.asarray(heads.sway_tilt, dtype=np.float64), self.landmarks, self.robot_radii,
            self._r2, self._range2, self._p_detect, U, Z, self._kernel_camera, spec.occlusion)
        balls, lms, rbs = self._detections(where, found, F)
        pan_l, tilt_l = pan.tolist(), tilt.tolist()
        pans, tilts = [pan_l[i] for i in ids], [tilt_l[i] for i in ids]
        # Spurious balls after the true one, projected with the believed head.
        h, r_ball = self._kernel_camera[0], self._kernel_camera[4]
        for k, u, v in self._spurious(U[:, p:p + 3].tolist(), due, tilts, interval, now):
            head = (math.cos(pans[k]), math.sin(pans[k]), math.cos(tilts[k]),
                    math.sin(tilts[k]))
            balls[k].append((u, v) + back_project(u, v, head, self._lens, h, r_ball))
        delays = [spec.latency + spec.latency_jitter * d for d in U[:, p + 3].tolist()]
        return [HeadFrame(ids[k], now, now + delays[k], pans[k], tilts[k], tuple(balls[k]),
                          tuple(lms[k]), tuple(rbs[k])) for k in range(F)]

    def _detections(self, where: np.ndarray, found: np.ndarray, F: int
                    ) -> tuple[list[list], list[list], list[list]]:
        """The kernel's detections (rows ``where`` = ``(frame, slot)`` and ``found`` = ``(u,
        v, x, y, bearing)``) as :class:`HeadFrame` lists them: per frame its balls, landmarks
        (with their kind) and robots (with their team), each in slot order."""
        m = self._m
        balls: list[list] = [[] for _ in range(F)]
        lms: list[list] = [[] for _ in range(F)]
        rbs: list[list] = [[] for _ in range(F)]
        kinds, teams = self.landmark_kinds, self.teams
        first_robot = 1 + m
        for (k, slot), det in zip(where.tolist(), found.tolist()):
            if slot == 0:
                balls[k].append(tuple(det))
            elif slot <= m:
                lms[k].append((kinds[slot - 1], *det))
            else:
                rbs[k].append((teams[slot - first_robot], *det))
        return balls, lms, rbs

    def _spurious(self, draws: list[list[float]], due: list[int], tilts: list[float],
                  interval: float | None, now: float) -> list[tuple[int, float, float]]:
        """Spurious balls ``(frame, u, v)`` of the frames ``due``, from three uniforms per
        frame (occurrence, u, v) and the believed tilts."""
        spec, cam = self.spec, self.camera
        h, r_ball = spec.height, self.ball_spec.radius
        out = []
        for k, (j, (occur, du, dv), tilt) in enumerate(zip(due, draws, tilts)):
            dt = interval if interval is not None else now - self._last[j]
            self._last[j] = now
            if (spec.false_ball_rate <= 0.0 or h <= r_ball
                    or occur >= 1.0 - math.exp(-spec.false_ball_rate * dt)):
                continue
            a = math.atan2(h - r_ball, spec.ball_range) - tilt  # below the optical axis
            if a >= 0.5 * math.pi - 1e-6:
                continue  # the whole image lies beyond ball_range
            v0, f, H = self._v0, self._f, float(cam.height_px)
            v_lo = 0.0 if a <= -0.5 * math.pi + 1e-6 else max(0.0, v0 + f * math.tan(a))
            if v_lo < H:
                out.append((k, cam.width * du, v_lo + (H - v_lo) * dv))
        return out
