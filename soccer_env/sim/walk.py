"""The humanoid robots' walk engine: gait, head, kick motion, falls and odometry.

A biped does not drive like a wheeled robot. Per control step of ``dt`` seconds, for every
humanoid of a world (:class:`~soccer_env.presets.HumanoidRobotSpec` holds the numbers):

* **Gait velocity.** The command ``(vx, vy, omega)`` (body frame, m/s and rad/s) is scaled into
  the ellipsoid ``(vx / v_x)^2 + (vy / v_y)^2 + (omega / omega_max)^2 <= 1`` (``v_x`` the
  forward or backward limit by the sign of ``vx``), and the gait's velocity moves towards it by
  at most ``max_acceleration * dt`` (translation, as a vector) and
  ``max_angular_acceleration * dt`` (turning). The robot's kinematic control body moves at the
  gait velocity; the physics (:class:`~soccer_env.sim.world.World`) makes the body follow it
  with bounded force, so a blocked robot stays blocked while its gait walks on.
* **Gait phase and sway.** While the gait moves (ellipsoid norm above 1 %), its phase advances
  by ``step_frequency * dt`` steps. The torso, and the camera with it, sways by
  ``sway_pan * a * sin(pi phase)`` in yaw (one cycle per stride of two steps) and
  ``sway_tilt * a * sin(2 pi phase)`` in pitch (one per step), ``a = min(1, 5 s)`` the gait's
  activity for the ellipsoid norm ``s`` of its velocity: nothing while standing.
* **Head.** Pan and tilt servos turn towards their targets at up to ``head_speed``.
* **Kick.** A positive motion command starts a kick of ``kick_duration`` seconds (ignored
  while one runs or while fallen) during which the gait stops; at ``kick_fire_time`` the foot
  strikes, and the world launches the ball if it lies at a foot (:meth:`kick_due`).
* **Dive.** A motion command of -1 throws the robot to its left (``vy >= 0``) or right: a
  deliberate fall, as KidSize keepers block shots.
* **Falls.** :meth:`fall` fells a robot (towards a random direction; a dive to its side): for
  ``get_up_time`` seconds it neither walks, kicks, moves its head nor sees; ``fall_time``
  after the fall its body lies on the ground along that direction (the world adds the lying
  body, :meth:`lying_due`); then it stands up turned by a Gaussian ``fall_heading_sigma``
  that its odometry does not report (:meth:`stand_up_due`).
* **Odometry.** The displacement the gait believes it made in the step, ``(dx, dy, dtheta)``
  in the body frame at the start of the step: the gait velocity times ``dt`` with relative
  errors drawn once per gait step (``odometry_trans_sigma`` per axis, ``odometry_rot_sigma``
  on the rotation) plus sideways slip ``odometry_turn_slip * N(0, 1)`` metres per radian
  turned. While fallen it reports nothing.

Plain Python over the robots: a world has at most a few dozen, and per-robot numpy calls would
cost more than they save. Every draw comes from the generator given to :meth:`reset`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from soccer_env.presets import HumanoidRobotSpec

__all__ = ["WalkEngine", "HUMANOID_COMMAND_FIELDS", "WALK_THRESHOLD", "DIVE", "speed_norm",
           "sway_share"]

#: Columns of a humanoid's row of the ``(N, 6)`` command array of
#: :meth:`World.step <soccer_env.sim.world.World.step>`: body-frame ``vx, vy`` [m/s] and
#: ``omega`` [rad/s]; ``motion``: > 0 starts a kick at that speed [m/s], <= -1 a dive (to the
#: left if ``vy >= 0``, else to the right), otherwise nothing; ``head_pan`` and ``head_tilt``
#: targets [rad].
HUMANOID_COMMAND_FIELDS = ("vx", "vy", "omega", "motion", "head_pan", "head_tilt")
#: The ``motion`` command value that dives.
DIVE = -1.0
#: Ellipsoid norm of the gait velocity above which the gait steps (and sways).
WALK_THRESHOLD = 0.01


def speed_norm(spec: HumanoidRobotSpec, vx: float, vy: float, w: float) -> float:
    """The body-frame velocity's norm in the robot's speed ellipsoid:
    ``sqrt((vx / v_x)^2 + (vy / v_y)^2 + (w / omega_max)^2)``, ``v_x`` the forward or backward
    limit by the sign of ``vx`` (1: at the limit)."""
    vx_lim = spec.max_forward_speed if vx >= 0.0 else spec.max_backward_speed
    return math.sqrt((vx / vx_lim) ** 2 + (vy / spec.max_sideways_speed) ** 2
                     + (w / spec.max_turn_speed) ** 2)


def sway_share(s: float) -> float:
    """How much of its full sway a humanoid's torso sways at the gait's ellipsoid norm ``s``
    (:func:`speed_norm`): ``min(1, 5 s)`` while the gait steps (``s`` above
    :data:`WALK_THRESHOLD`), 0 standing."""
    return min(1.0, 5.0 * s) if s > WALK_THRESHOLD else 0.0


class WalkEngine:
    """Walk engines of the humanoids ``indices`` (robot indices in the world) with specs
    ``specs`` (see the module docstring).

    State, per humanoid in the order of ``indices`` (read-only outside this class):
    ``gait`` body-frame velocities ``[vx, vy, omega]``; ``pan``, ``tilt`` head servo angles
    [rad]; ``sway_pan``, ``sway_tilt`` [rad]; ``fallen`` and ``down_until`` [s] (fallen
    until then); ``lie_at`` [s] and ``lie_angle`` [rad, body frame]: when and where the
    fallen body comes to lie; ``kick_start`` [s] (None when not kicking); ``odometry`` the
    last step's ``(dx, dy, dtheta)``; ``falls``, ``dives`` and ``kicks`` counted since
    reset.
    """

    def __init__(self, specs: Sequence[HumanoidRobotSpec], indices: Sequence[int],
                 control_dt: float) -> None:
        if len(specs) != len(indices):
            raise ValueError("specs and indices must have the same length")
        self.specs = list(specs)
        self.indices = list(indices)
        self.n = len(self.indices)
        self.dt = float(control_dt)
        self.reset(np.random.default_rng(0))

    def reset(self, rng: np.random.Generator, poses: np.ndarray | None = None) -> None:
        """Stand every robot still, head level and forward, gait phase 0."""
        self.rng = rng
        n = self.n
        self.gait = [[0.0, 0.0, 0.0] for _ in range(n)]
        self.phase = [0.0] * n
        self.pan = [0.0] * n
        self.tilt = [0.0] * n
        self.sway_pan = [0.0] * n
        self.sway_tilt = [0.0] * n
        self.down_until = [-math.inf] * n
        self.fallen = [False] * n
        self.lie_at: list[float | None] = [None] * n
        self.lie_angle = [0.0] * n
        self.dives = [0] * n
        self.kick_start: list[float | None] = [None] * n
        self.kick_speed = [0.0] * n
        self.odometry = [(0.0, 0.0, 0.0)] * n
        self.falls = [0] * n
        self.kicks = [0] * n
        self._slip = [self._draw_slip(s) for s in self.specs]

    def _draw_slip(self, spec: HumanoidRobotSpec) -> tuple[float, float, float, float]:
        """Odometry errors of one gait step: relative x, y and rotation errors, and the
        sideways slip per radian turned [m/rad]."""
        z = self.rng.standard_normal(4).tolist()
        return (spec.odometry_trans_sigma * z[0], spec.odometry_trans_sigma * z[1],
                spec.odometry_rot_sigma * z[2], spec.odometry_turn_slip * z[3])

    # ------------------------------------------------------------------------------------

    def command(self, rows: list[list[float]], headings: list[float], now: float
                ) -> list[tuple[float, float, float]]:
        """Advance the engines by one control step from ``now`` with the command ``rows``
        (per humanoid, :data:`HUMANOID_COMMAND_FIELDS`) and the robots' present headings
        [rad]; return each control body's field-frame velocity ``(vx, vy, omega)``."""
        dt = self.dt
        out = []
        for j, (spec, (vx, vy, w, kick, pan_t, tilt_t), th) in enumerate(
                zip(self.specs, rows, headings)):
            gait = self.gait[j]
            if self.fallen[j]:
                gait[0] = gait[1] = gait[2] = 0.0
                self.odometry[j] = (0.0, 0.0, 0.0)
                self.sway_pan[j] = self.sway_tilt[j] = 0.0
                out.append((0.0, 0.0, 0.0))
                continue
            if kick <= DIVE:
                self.fall(j, now, 0.5 * math.pi if vy >= 0.0 else -0.5 * math.pi)
                self.dives[j] += 1
                out.append((0.0, 0.0, 0.0))
                continue
            if self.kick_start[j] is None and kick > 0.0:
                self.kick_start[j] = now
                self.kick_speed[j] = min(kick, spec.kick_max_speed)
            if self.kick_start[j] is not None:
                vx = vy = w = 0.0  # the robot stands while it kicks
            else:
                norm = speed_norm(spec, vx, vy, w)
                if norm > 1.0:
                    vx, vy, w = vx / norm, vy / norm, w / norm
            # Ramp the gait velocity towards the command within the acceleration limits.
            dvx, dvy = vx - gait[0], vy - gait[1]
            dv = math.hypot(dvx, dvy)
            step = spec.max_acceleration * dt
            if dv > step:
                dvx, dvy = dvx * step / dv, dvy * step / dv
            dw = w - gait[2]
            wstep = spec.max_angular_acceleration * dt
            dw = wstep if dw > wstep else (-wstep if dw < -wstep else dw)
            gx, gy, gw = gait[0] + dvx, gait[1] + dvy, gait[2] + dw
            gait[0], gait[1], gait[2] = gx, gy, gw
            # Head servos.
            hs = spec.head_speed * dt
            pan_t = min(spec.head_pan_limit, max(-spec.head_pan_limit, pan_t))
            tilt_t = min(spec.head_tilt_max, max(spec.head_tilt_min, tilt_t))
            d = pan_t - self.pan[j]
            self.pan[j] += hs if d > hs else (-hs if d < -hs else d)
            d = tilt_t - self.tilt[j]
            self.tilt[j] += hs if d > hs else (-hs if d < -hs else d)
            # Gait phase, sway and odometry.
            s = speed_norm(spec, gx, gy, gw)
            if s > WALK_THRESHOLD:
                before = self.phase[j]
                self.phase[j] = before + spec.step_frequency * dt
                if math.floor(self.phase[j]) != math.floor(before):
                    self._slip[j] = self._draw_slip(spec)  # a new step lands
                a = sway_share(s)
                ph = self.phase[j]
                self.sway_pan[j] = spec.sway_pan * a * math.sin(math.pi * ph)
                self.sway_tilt[j] = spec.sway_tilt * a * math.sin(2.0 * math.pi * ph)
                ex, ey, er, slip = self._slip[j]
                dth = gw * dt
                self.odometry[j] = (gx * dt * (1.0 + ex), gy * dt * (1.0 + ey) + slip * dth,
                                    dth * (1.0 + er))
            else:
                self.sway_pan[j] = self.sway_tilt[j] = 0.0
                self.odometry[j] = (0.0, 0.0, 0.0)
            # Body frame -> field frame at the mid-step heading.
            h = th + 0.5 * dt * gw
            c, sn = math.cos(h), math.sin(h)
            out.append((c * gx - sn * gy, sn * gx + c * gy, gw))
        return out

    def kick_due(self, t_start: float, t_end: float) -> list[tuple[int, float]]:
        """Humanoids (positions in ``indices``) whose foot strikes in ``(t_start, t_end]``,
        with the kick speed [m/s]; finished kicks end here too."""
        due = []
        for j, start in enumerate(self.kick_start):
            if start is None:
                continue
            spec = self.specs[j]
            fire = start + spec.kick_fire_time
            if t_start < fire <= t_end + 1e-12 or (fire <= t_start and start >= t_start):
                due.append((j, self.kick_speed[j]))
            if t_end + 1e-12 >= start + spec.kick_duration:
                self.kick_start[j] = None
        return due

    def kick_direction_noise(self, j: int) -> float:
        """A draw of the kick's direction error [rad] for humanoid ``j``."""
        return self.specs[j].kick_direction_sigma * float(self.rng.standard_normal())

    def fall_probability(self, j: int, approach_speed: float) -> float:
        """Probability that a contact approaching at ``approach_speed`` [m/s] fells robot
        ``j``: a linear ramp from ``fall_speed_min`` (0) to ``fall_speed_certain`` (1)."""
        s = self.specs[j]
        p = (approach_speed - s.fall_speed_min) / (s.fall_speed_certain - s.fall_speed_min)
        return 0.0 if p < 0.0 else (1.0 if p > 1.0 else p)

    def maybe_fall(self, j: int, approach_speed: float, now: float) -> bool:
        """Draw whether a contact fells robot ``j`` (already fallen robots stay as they
        are); returns True if it fell now."""
        if self.fallen[j]:
            return False
        p = self.fall_probability(j, approach_speed)
        if p <= 0.0 or self.rng.random() >= p:
            return False
        self.fall(j, now)
        return True

    def fall(self, j: int, now: float, direction: float | None = None) -> None:
        """Fell robot ``j`` at time ``now`` towards ``direction`` [rad, body frame; None:
        uniformly random]: gait stopped, kick cancelled, blind."""
        self.fallen[j] = True
        self.down_until[j] = now + self.specs[j].get_up_time
        self.lie_at[j] = now + self.specs[j].fall_time
        self.lie_angle[j] = (float(self.rng.uniform(-math.pi, math.pi)) if direction is None
                             else float(direction))
        self.kick_start[j] = None
        self.gait[j] = [0.0, 0.0, 0.0]
        self.sway_pan[j] = self.sway_tilt[j] = 0.0
        self.odometry[j] = (0.0, 0.0, 0.0)
        self.falls[j] += 1

    def lying_due(self, now: float) -> list[tuple[int, float]]:
        """Fallen robots whose body reaches the ground by ``now``: their positions in
        ``indices`` and the direction of the lying body [rad, body frame]."""
        out = []
        for j, t in enumerate(self.lie_at):
            if t is not None and now + 1e-12 >= t:
                self.lie_at[j] = None
                out.append((j, self.lie_angle[j]))
        return out

    def stand_up_due(self, now: float) -> list[tuple[int, float]]:
        """Fallen robots whose get-up ends by ``now``: they stand again; returns their
        positions in ``indices`` and the unreported heading change [rad] to apply."""
        out = []
        for j in range(self.n):
            if self.fallen[j] and now + 1e-12 >= self.down_until[j]:
                self.fallen[j] = False
                self.lie_at[j] = None
                out.append((j, self.specs[j].fall_heading_sigma
                            * float(self.rng.standard_normal())))
        return out
