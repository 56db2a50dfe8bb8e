"""World presets: fields, balls, SSL robots and humanoid robots (see :mod:`soccer_env.presets`
for the conventions).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from estimators.registry import Registry
from soccer_env.validation import check_number, preset_table, resolve_preset

__all__ = ["ROBOTS", "FieldSpec", "BallSpec", "SSLRobotSpec", "HumanoidRobotSpec", "RobotSpec",
           "FIELDS", "BALLS", "field", "ball", "robot", "default_field", "GRAVITY"]

#: Standard gravity [m/s^2] (ISO 80000-3).
GRAVITY = 9.80665


@dataclass(frozen=True)
class FieldSpec:
    """Geometry of a field, its goals and its boundary walls.

    All lengths in metres. ``length`` and ``width`` are the field of play between the outer
    edges of the goal lines and touch lines. Walls stand ``boundary`` beyond those lines, so the
    walled area is ``(length + 2 boundary) x (width + 2 boundary)``. Goals sit behind the goal
    lines, ``goal_width`` between the inner edges of the posts and ``goal_depth`` deep inside.
    The defense (goal) area is modelled as a rectangle ``defense_width`` (along y) by
    ``defense_depth`` (along x from the goal line).
    """

    name: str
    length: float
    width: float
    boundary: float
    goal_width: float
    goal_depth: float
    goal_height: float
    goal_wall_thickness: float
    defense_width: float
    defense_depth: float
    center_circle_radius: float
    line_width: float
    wall_restitution: float
    ball: str
    source: str

    def __post_init__(self) -> None:
        check_number("length", self.length, 0.5, 50.0)
        check_number("width", self.width, 0.5, 50.0)
        check_number("boundary", self.boundary, 0.05, 5.0)
        check_number("goal_width", self.goal_width, 0.1, self.width)
        check_number("goal_depth", self.goal_depth, 0.05, self.boundary - 0.01)
        check_number("goal_height", self.goal_height, 0.05, 5.0)
        check_number("goal_wall_thickness", self.goal_wall_thickness, 0.001, 0.5)
        check_number("defense_width", self.defense_width, 0.0, self.width)
        check_number("defense_depth", self.defense_depth, 0.0, self.length / 2)
        check_number("center_circle_radius", self.center_circle_radius, 0.0, self.width / 2)
        check_number("line_width", self.line_width, 0.0, 0.5)
        check_number("wall_restitution", self.wall_restitution, 0.0, 1.0)

    @property
    def half_length(self) -> float:
        """Distance from the centre spot to a goal line [m]."""
        return 0.5 * self.length

    @property
    def half_width(self) -> float:
        """Distance from the centre spot to a touch line [m]."""
        return 0.5 * self.width


@dataclass(frozen=True)
class BallSpec:
    """The ball and its contact with the carpet.

    Straight two-phase model (the SSL vision ``BallModelStraightTwoPhase``, described in
    ER-Force's 2016 team description paper): after a kick the ball slides with constant
    deceleration ``sliding_deceleration`` until its speed falls to ``k_switch`` times the
    kick speed, then rolls with ``rolling_deceleration``. Deceleration acts against the
    velocity and stops the ball; it never reverses it.

    Chip kicks follow the fixed-loss model (SSL vision ``BallModelChipFixedLoss``): ballistic
    flight under gravity; at each bounce the vertical speed is multiplied by ``chip_damping_z``
    and the horizontal speed by ``chip_damping_xy_first`` (first bounce) or
    ``chip_damping_xy_other``; a hop lower than ``min_hop_height`` ends the flight.

    ``surface_friction`` is the ball's Coulomb friction coefficient in pymunk, which multiplies
    the coefficients of the two shapes in contact (walls have 1, robots their own).
    """

    name: str
    radius: float
    mass: float
    sliding_deceleration: float
    rolling_deceleration: float
    k_switch: float
    chip_damping_xy_first: float
    chip_damping_xy_other: float
    chip_damping_z: float
    min_hop_height: float
    surface_friction: float
    source: str

    def __post_init__(self) -> None:
        check_number("radius", self.radius, 0.005, 0.5)
        check_number("mass", self.mass, 0.001, 5.0)
        check_number("sliding_deceleration", self.sliding_deceleration, 0.0, 50.0)
        check_number("rolling_deceleration", self.rolling_deceleration, 0.0, 50.0)
        check_number("k_switch", self.k_switch, 0.0, 1.0)
        check_number("chip_damping_xy_first", self.chip_damping_xy_first, 0.0, 1.0)
        check_number("chip_damping_xy_other", self.chip_damping_xy_other, 0.0, 1.0)
        check_number("chip_damping_z", self.chip_damping_z, 0.0, 0.99)
        check_number("min_hop_height", self.min_hop_height, 0.0, 1.0)
        check_number("surface_friction", self.surface_friction, 0.0, 2.0)

    @property
    def diameter(self) -> float:
        """Ball diameter [m]."""
        return 2.0 * self.radius


@dataclass(frozen=True)
class SSLRobotSpec:
    """A Small Size League omnidirectional robot.

    The body is a cylinder of ``radius`` with its front cut flat at ``front_distance`` from the
    centre; the kicker and the dribbler sit on that flat front, ``kicker_width`` wide. The action
    is a body-frame velocity command scaled from [-1, 1] to ``max_speed`` (the translational
    command's norm is capped at ``max_speed``) and ``max_angular_speed``; the wheels reach it
    with at most ``max_acceleration`` [m/s^2] and ``max_angular_acceleration`` [rad/s^2], and
    push other bodies with at most ``mass * max_acceleration`` newtons.

    A flat kick sends the ball along the heading at ``power * kicker_max_speed``, capped at
    ``kick_speed_cap`` (the rules' 6.5 m/s ball speed limit); a chip kick launches it at
    ``chip_angle`` above the ground at ``power * chip_max_speed`` (3D speed, same cap). After
    firing, the kicker needs ``kick_cooldown`` seconds before it can fire again. The dribbler
    pulls a ball touching the front towards the robot with ``dribbler_force`` newtons and
    resists its sideways slip with up to the same force; anything pushing harder steals it.

    ``restitution`` and ``surface_friction`` are the robot shape's pymunk coefficients, which
    pymunk multiplies with those of the other shape in a contact (the ball has restitution 1).
    """

    name: str
    radius: float
    front_distance: float
    height: float
    mass: float
    moment_of_inertia: float
    max_speed: float
    max_acceleration: float
    max_angular_speed: float
    max_angular_acceleration: float
    kicker_width: float
    kicker_max_speed: float
    kick_speed_cap: float
    chip_max_speed: float
    chip_angle: float
    kick_cooldown: float
    dribbler_force: float
    dribbler_restitution: float
    restitution: float
    surface_friction: float
    source: str

    kind = "ssl"

    def __post_init__(self) -> None:
        check_number("radius", self.radius, 0.02, 1.0)
        check_number("front_distance", self.front_distance, 0.3 * self.radius, self.radius)
        check_number("height", self.height, 0.01, 2.0)
        check_number("mass", self.mass, 0.1, 100.0)
        check_number("moment_of_inertia", self.moment_of_inertia, 0.0, 100.0, low_open=True)
        check_number("max_speed", self.max_speed, 0.0, 20.0, low_open=True)
        check_number("max_acceleration", self.max_acceleration, 0.0, 100.0, low_open=True)
        check_number("max_angular_speed", self.max_angular_speed, 0.0, 100.0, low_open=True)
        check_number("max_angular_acceleration", self.max_angular_acceleration, 0.0, 1000.0,
               low_open=True)
        chord = 2.0 * math.sqrt(self.radius**2 - self.front_distance**2)
        check_number("kicker_width", self.kicker_width, 0.0, chord, low_open=True)
        check_number("kicker_max_speed", self.kicker_max_speed, 0.0, 20.0)
        check_number("kick_speed_cap", self.kick_speed_cap, 0.0, 20.0, low_open=True)
        check_number("chip_max_speed", self.chip_max_speed, 0.0, 20.0)
        check_number("chip_angle", self.chip_angle, 0.0, 0.5 * math.pi, low_open=True)
        check_number("kick_cooldown", self.kick_cooldown, 0.0, 60.0)
        check_number("dribbler_force", self.dribbler_force, 0.0, 100.0)
        check_number("dribbler_restitution", self.dribbler_restitution, 0.0, 1.0)
        check_number("restitution", self.restitution, 0.0, 1.0)
        check_number("surface_friction", self.surface_friction, 0.0, 2.0)

    @property
    def front_width(self) -> float:
        """Length of the flat front (chord of the cut) [m]."""
        return 2.0 * math.sqrt(self.radius**2 - self.front_distance**2)


@dataclass(frozen=True)
class HumanoidRobotSpec:
    """A biped (RoboCup Humanoid KidSize) robot driven by a walk engine.

    Body: a disc of ``radius`` (the feet and legs, what collides), ``height`` tall (a ball in
    flight above it passes over), ``mass`` and ``moment_of_inertia``.

    Walk engine (:mod:`soccer_env.sim.walk`): the commanded body-frame velocity
    ``(vx, vy, omega)`` is limited to the ellipsoid ``(vx / v_x)^2 + (vy / v_y)^2 +
    (omega / omega_max)^2 <= 1`` with ``v_x`` = ``max_forward_speed`` or
    ``max_backward_speed`` by the sign of ``vx``, ``v_y`` = ``max_sideways_speed`` and
    ``omega_max`` = ``max_turn_speed``; the gait's velocity ramps towards it with at most
    ``max_acceleration`` [m/s^2] and ``max_angular_acceleration`` [rad/s^2]. The gait steps at
    ``step_frequency`` steps per second while walking, swaying the torso and so the camera by
    ``sway_pan`` (yaw, once per stride of two steps) and ``sway_tilt`` (pitch, once per step)
    [rad amplitude].

    Head: pan within ``+-head_pan_limit``, tilt (positive looking down) within
    ``[head_tilt_min, head_tilt_max]``, both servos turning at up to ``head_speed`` [rad/s];
    the camera is the :data:`soccer_env.presets.HEAD_CAMERAS` preset ``camera``.

    Kick: a timed motion of ``kick_duration`` seconds during which the robot stands; its foot
    strikes ``kick_fire_time`` seconds after the start, and sends the ball along the heading
    (plus Gaussian ``kick_direction_sigma`` [rad]) at ``power * kick_max_speed`` only if the
    ball is then at a foot: its centre between ``radius`` and ``radius + kick_reach`` in front
    of the robot's centre (plus the ball radius) and within ``kick_width / 2`` sideways.

    Dive: a keeper's deliberate fall to one side; the body hits the ground ``fall_time``
    seconds after the command.

    Falls: a contact with another robot or a wall whose approach speed (along the contact
    normal) is ``v`` fells the robot with probability ``(v - fall_speed_min) /
    (fall_speed_certain - fall_speed_min)`` clipped to [0, 1], in a random direction. A fallen
    (or diving) robot neither acts, sees, nor sends for ``get_up_time`` seconds; from
    ``fall_time`` after the fall its body lies on the ground, a capsule ``lying_width`` thick
    reaching ``lying_length`` from its centre, an obstacle for the ball and other robots; it
    stands up turned by a Gaussian ``fall_heading_sigma`` [rad] that its odometry does not
    report.

    Odometry (what the walk engine believes it walked): the gait's displacement with, per gait
    step, Gaussian relative errors ``odometry_trans_sigma`` on the translation and
    ``odometry_rot_sigma`` on the rotation, plus ``odometry_turn_slip`` metres of sideways
    slip per radian turned (turns slip most, as Guo and Li (2013) observed).
    """

    name: str
    radius: float
    height: float
    mass: float
    moment_of_inertia: float
    max_forward_speed: float
    max_backward_speed: float
    max_sideways_speed: float
    max_turn_speed: float
    max_acceleration: float
    max_angular_acceleration: float
    step_frequency: float
    sway_pan: float
    sway_tilt: float
    head_pan_limit: float
    head_tilt_min: float
    head_tilt_max: float
    head_speed: float
    camera: str
    kick_duration: float
    kick_fire_time: float
    kick_max_speed: float
    kick_reach: float
    kick_width: float
    kick_direction_sigma: float
    fall_speed_min: float
    fall_speed_certain: float
    fall_time: float
    lying_length: float
    lying_width: float
    get_up_time: float
    fall_heading_sigma: float
    odometry_trans_sigma: float
    odometry_rot_sigma: float
    odometry_turn_slip: float
    restitution: float
    surface_friction: float
    source: str

    kind = "humanoid"

    def __post_init__(self) -> None:
        check_number("radius", self.radius, 0.02, 1.0)
        check_number("height", self.height, 0.1, 3.0)
        check_number("mass", self.mass, 0.1, 200.0)
        check_number("moment_of_inertia", self.moment_of_inertia, 0.0, 100.0, low_open=True)
        for name in ("max_forward_speed", "max_backward_speed", "max_sideways_speed"):
            check_number(name, getattr(self, name), 0.0, 5.0, low_open=True)
        check_number("max_turn_speed", self.max_turn_speed, 0.0, 20.0, low_open=True)
        check_number("max_acceleration", self.max_acceleration, 0.0, 50.0, low_open=True)
        check_number("max_angular_acceleration", self.max_angular_acceleration, 0.0, 500.0,
               low_open=True)
        check_number("step_frequency", self.step_frequency, 0.0, 10.0, low_open=True)
        check_number("sway_pan", self.sway_pan, 0.0, 0.5)
        check_number("sway_tilt", self.sway_tilt, 0.0, 0.5)
        check_number("head_pan_limit", self.head_pan_limit, 0.0, math.pi)
        check_number("head_tilt_min", self.head_tilt_min, -0.5 * math.pi, 0.5 * math.pi)
        check_number("head_tilt_max", self.head_tilt_max, self.head_tilt_min, 0.5 * math.pi)
        check_number("head_speed", self.head_speed, 0.0, 50.0, low_open=True)
        check_number("kick_duration", self.kick_duration, 0.0, 10.0, low_open=True)
        check_number("kick_fire_time", self.kick_fire_time, 0.0, self.kick_duration)
        check_number("kick_max_speed", self.kick_max_speed, 0.0, 20.0)
        check_number("kick_reach", self.kick_reach, 0.0, 1.0, low_open=True)
        check_number("kick_width", self.kick_width, 0.0, 2.0 * self.radius + 0.5, low_open=True)
        check_number("kick_direction_sigma", self.kick_direction_sigma, 0.0, math.pi)
        check_number("fall_speed_min", self.fall_speed_min, 0.0, 10.0)
        check_number("fall_speed_certain", self.fall_speed_certain, self.fall_speed_min, 10.0,
               low_open=True)
        if not self.fall_speed_certain > self.fall_speed_min:
            raise ValueError(f"fall_speed_certain must be greater than fall_speed_min "
                             f"({self.fall_speed_min}), got {self.fall_speed_certain!r}")
        check_number("fall_time", self.fall_time, 0.0, 5.0)
        check_number("lying_length", self.lying_length, 0.0, 3.0)
        check_number("lying_width", self.lying_width, 0.0, 1.0)
        check_number("get_up_time", self.get_up_time, self.fall_time, 120.0)
        check_number("fall_heading_sigma", self.fall_heading_sigma, 0.0, math.pi)
        check_number("odometry_trans_sigma", self.odometry_trans_sigma, 0.0, 2.0)
        check_number("odometry_rot_sigma", self.odometry_rot_sigma, 0.0, 2.0)
        check_number("odometry_turn_slip", self.odometry_turn_slip, 0.0, 1.0)
        check_number("restitution", self.restitution, 0.0, 1.0)
        check_number("surface_friction", self.surface_friction, 0.0, 2.0)

    @property
    def max_speed(self) -> float:
        """The fastest translation [m/s] (forward)."""
        return max(self.max_forward_speed, self.max_backward_speed, self.max_sideways_speed)

    @property
    def max_angular_speed(self) -> float:
        """The fastest turn [rad/s]."""
        return self.max_turn_speed


#: Any robot preset.
RobotSpec = SSLRobotSpec | HumanoidRobotSpec


# --------------------------------------------------------------------------------------------
# Fields
# --------------------------------------------------------------------------------------------

FIELDS: Registry[FieldSpec] = preset_table('field', {
    # Zhao, Wang and Li (2012): "a 6.1 m x 4.7 m green carpet", the SSL 5 vs 5 field of
    # 2012. Goal 0.7 m wide, 0.18 m deep, 0.16 m high (SSL rules 2012). The 2012 defense area
    # was two quarter circles of radius 0.8 m around the posts joined by a 0.35 m line; it is
    # approximated by its bounding rectangle, 0.35 + 2 * 0.8 = 1.95 m by 0.8 m. The paper does not
    # give the boundary; 0.25 m is assumed.
    "ssl-2012": FieldSpec(
        name="ssl-2012", length=6.1, width=4.7, boundary=0.25,
        goal_width=0.7, goal_depth=0.18, goal_height=0.16, goal_wall_thickness=0.02,
        defense_width=1.95, defense_depth=0.8, center_circle_radius=0.5, line_width=0.01,
        wall_restitution=0.5, ball="ssl-2012",
        source="Zhao et al. (2012) (6.1 x 4.7 m carpet); SSL rules 2012 (goal, defense area)",
    ),
    # SSL rules (2023 onwards), Division B: 9 x 6 m, boundary 0.3 m, goal 1.0 m wide,
    # 0.18 m deep, 0.155 m high inside, walls 0.02 m; defense area 2 x 1 m; centre circle 0.5 m.
    "ssl-div-b": FieldSpec(
        name="ssl-div-b", length=9.0, width=6.0, boundary=0.3,
        goal_width=1.0, goal_depth=0.18, goal_height=0.155, goal_wall_thickness=0.02,
        defense_width=2.0, defense_depth=1.0, center_circle_radius=0.5, line_width=0.01,
        wall_restitution=0.5, ball="ssl",
        source="SSL rules 2023+, Division B",
    ),
    # SSL rules (2023 onwards), Division A: 12 x 9 m, goal 1.8 m, defense area 3.6 x 1.8 m.
    "ssl-div-a": FieldSpec(
        name="ssl-div-a", length=12.0, width=9.0, boundary=0.3,
        goal_width=1.8, goal_depth=0.18, goal_height=0.155, goal_wall_thickness=0.02,
        defense_width=3.6, defense_depth=1.8, center_circle_radius=0.5, line_width=0.01,
        wall_restitution=0.5, ball="ssl",
        source="SSL rules 2023+, Division A",
    ),
    # Xu et al. (2012): "RoboCup standard, 4 m x 6 m" humanoid field. The paper gives
    # nothing else; the other dimensions are our reading of the RoboCup Humanoid League KidSize
    # rules of that era (goal 1.5 m wide, goal area 2.2 x 0.6 m, centre circle 1.2 m diameter,
    # border strip 0.7 m) and assumptions where we found no figure (goal 0.5 m deep, 0.8 m high).
    "humanoid-2012": FieldSpec(
        name="humanoid-2012", length=6.0, width=4.0, boundary=0.7,
        goal_width=1.5, goal_depth=0.5, goal_height=0.8, goal_wall_thickness=0.05,
        defense_width=2.2, defense_depth=0.6, center_circle_radius=0.6, line_width=0.05,
        wall_restitution=0.3, ball="kidsize-2012",
        source="Xu et al. (2012) (6 x 4 m); RoboCup Humanoid KidSize rules 2012",
    ),
    # RoboCup Humanoid League KidSize rules (2020 onwards): 9 x 6 m, goal 2.6 m wide, 0.6 m
    # deep, 1.2 m high; goal area 3 x 1 m; centre circle 1.5 m diameter; border strip 1 m.
    "humanoid-kid": FieldSpec(
        name="humanoid-kid", length=9.0, width=6.0, boundary=1.0,
        goal_width=2.6, goal_depth=0.6, goal_height=1.2, goal_wall_thickness=0.1,
        defense_width=3.0, defense_depth=1.0, center_circle_radius=0.75, line_width=0.05,
        wall_restitution=0.3, ball="kidsize",
        source="RoboCup Humanoid KidSize rules 2020+",
    ),
})

# --------------------------------------------------------------------------------------------
# Balls
# --------------------------------------------------------------------------------------------

# Orange golf ball of the SSL rules: 42.7-43 mm, 46 g. Two-phase deceleration as used by SSL
# teams' ball models: sliding about 3 m/s^2, rolling 0.26-0.35 m/s^2 (we take 0.3), and
# k_switch 0.64 (TIGERs Mannheim's measured value). Chip losses are TIGERs Mannheim's fixed-loss
# defaults (0.75 / 0.95 horizontal, 0.6 vertical, 10 mm minimum hop).
_SSL_BALL = BallSpec(
    name="ssl", radius=0.0215, mass=0.046,
    sliding_deceleration=3.0, rolling_deceleration=0.3, k_switch=0.64,
    chip_damping_xy_first=0.75, chip_damping_xy_other=0.95, chip_damping_z=0.6,
    min_hop_height=0.01, surface_friction=0.2,
    source="SSL rules (golf ball); SSL teams' two-phase and fixed-loss ball models",
)

BALLS: Registry[BallSpec] = preset_table('ball', {
    "ssl": _SSL_BALL,
    # Humanoid KidSize of 2012 (Xu et al.'s 2012 era): an orange ball of tennis-ball size on green
    # carpet. Our reading of the rules of that era and assumptions where we found no figure:
    # radius 33 mm, 57 g; a felt ball on carpet slides briefly and rolls with about
    # 0.5 m/s^2 (assumed); no chip kicks, so the chip parameters keep the golf ball's.
    "kidsize-2012": dataclasses.replace(
        _SSL_BALL, name="kidsize-2012", radius=0.033, mass=0.057,
        sliding_deceleration=2.0, rolling_deceleration=0.5, k_switch=0.7,
        surface_friction=0.5,
        source="Humanoid KidSize of 2012 (orange tennis-size ball, our reading); "
               "decelerations assumed",
    ),
    # Humanoid KidSize (2020 onwards): a FIFA size 1 ball (circumference about 0.48 m) on
    # 30 mm artificial grass, which brakes it hard; decelerations are assumptions of the
    # order reported by teams (about 1 m/s^2 rolling).
    "kidsize": dataclasses.replace(
        _SSL_BALL, name="kidsize", radius=0.076, mass=0.2,
        sliding_deceleration=2.5, rolling_deceleration=1.0, k_switch=0.7,
        surface_friction=0.6,
        source="Humanoid KidSize rules 2020+ (size 1 ball); decelerations on artificial grass "
               "assumed",
    ),
    # Zhao et al. (2012): the ball of 2012 on that carpet rolls with a_f = 0.23 m/s^2 (measured);
    # the paper does not model a sliding phase, so that keeps the current SSL values.
    "ssl-2012": dataclasses.replace(
        _SSL_BALL, name="ssl-2012", rolling_deceleration=0.23,
        source="Zhao et al. (2012) (a_f = 0.23 m/s^2); otherwise as 'ssl'",
    ),
})

# --------------------------------------------------------------------------------------------
# Robots
# --------------------------------------------------------------------------------------------

# SSL rules: diameter at most 0.18 m, height at most 0.15 m. Flat front 0.073 m from the centre
# with an 0.08 m kicker (grSim's default robot). Mass 2.5 kg; moment of inertia of a uniform
# disc, m r^2 / 2. Speed 3 m/s and acceleration 3 m/s^2: the "about 3 m/s, a few m/s^2" of
# current SSL robots. Kicker up to 8 m/s, limited to the rules' 6.5 m/s; chip at 45 degrees up
# to 6 m/s (about 3.7 m of flight). Dribbler force 0.15 N holds the 46 g ball against about
# 3 m/s^2 of backward acceleration.
_SSL_ROBOT = SSLRobotSpec(
    name="ssl", radius=0.09, front_distance=0.073, height=0.15, mass=2.5,
    moment_of_inertia=0.5 * 2.5 * 0.09**2,
    max_speed=3.0, max_acceleration=3.0, max_angular_speed=10.0,
    max_angular_acceleration=50.0,
    kicker_width=0.08, kicker_max_speed=8.0, kick_speed_cap=6.5,
    chip_max_speed=6.0, chip_angle=math.radians(45.0), kick_cooldown=0.5,
    dribbler_force=0.15, dribbler_restitution=0.1, restitution=0.5, surface_friction=0.5,
    source="SSL rules (size, 6.5 m/s); grSim default robot (front, kicker)",
)

ROBOTS: Registry[RobotSpec] = preset_table('robot', {
    "ssl": _SSL_ROBOT,
    # Zhao et al. (2012): SSL robots of 2012 reach more than 2.5 m/s with more than 2.5 m/s^2 and
    # kick at 5.0 m/s or more; the paper's decision cycle is 40 ms. Body as 'ssl'.
    "ssl-2012": dataclasses.replace(
        _SSL_ROBOT, name="ssl-2012", max_speed=2.5, max_acceleration=2.5,
        max_angular_speed=8.0, max_angular_acceleration=40.0, kicker_max_speed=5.0,
        chip_max_speed=5.0,
        source="Zhao et al. (2012) (2.5 m/s, 2.5 m/s^2, 5 m/s kicks); body as 'ssl'",
    ),
})

# A KidSize humanoid (RoboCup Humanoid League, 2020 onwards; the figures are of the order of
# published KidSize platforms such as Darwin-OP, NimbRo-OP and Wolfgang-OP, rounded, and
# assumptions where marked). 0.6 m tall with the camera at 0.56 m (Xu et al. 2012), 3.5 kg; the
# feet and legs collide as a disc of 0.1 m radius. Walk: 0.3 m/s forward, half that backward
# and sideways, 1 rad/s turning (Guo and Li 2013 keeps its robot at 0.5 m/s or less; "a few
# tenths of m/s"), reaching full speed in under a second (0.4 m/s^2, 3 rad/s^2), stepping at
# 2.5 steps per second with 2 degrees of yaw and pitch sway (assumed). Head: pan +-120
# degrees, tilt from 10 degrees up to 70 degrees down, servos at 5 rad/s. Kick: a 1 s motion
# striking after 0.5 s, up to 3 m/s. Falls: contacts approaching at 0.15 m/s can fell it,
# at 0.5 m/s always (assumed); the body is down 0.4 s after a fall or dive and lies as a
# 0.15 m thick capsule reaching 0.5 m from its feet (most of its height); 5 s to fall and get
# up (KidSize get-up motions take a few seconds). Odometry: 10 % translation and 15 %
# rotation error per step, 3 cm of slip per radian turned (assumed).
_KIDSIZE = HumanoidRobotSpec(
    name="humanoid", radius=0.1, height=0.6, mass=3.5, moment_of_inertia=0.5 * 3.5 * 0.1**2,
    max_forward_speed=0.3, max_backward_speed=0.15, max_sideways_speed=0.15,
    max_turn_speed=1.0, max_acceleration=0.4, max_angular_acceleration=3.0,
    step_frequency=2.5, sway_pan=math.radians(2.0), sway_tilt=math.radians(2.0),
    head_pan_limit=math.radians(120.0), head_tilt_min=math.radians(-10.0),
    head_tilt_max=math.radians(70.0), head_speed=5.0, camera="kidsize",
    kick_duration=1.0, kick_fire_time=0.5, kick_max_speed=3.0, kick_reach=0.08,
    kick_width=0.2, kick_direction_sigma=math.radians(5.0),
    fall_speed_min=0.15, fall_speed_certain=0.5, fall_time=0.4, lying_length=0.5,
    lying_width=0.15, get_up_time=5.0,
    fall_heading_sigma=0.3, odometry_trans_sigma=0.1, odometry_rot_sigma=0.15,
    odometry_turn_slip=0.03, restitution=0.2, surface_friction=0.8,
    source="KidSize platforms (Darwin-OP, NimbRo-OP, Wolfgang-OP), rounded; Xu et al. (2012) "
           "(camera 0.56 m); gait sway, falls and odometry noise assumed",
)

ROBOTS.register("humanoid", _KIDSIZE, _KIDSIZE.source)
# Xu et al.'s (2012) 21-servo robot of 2012: the same body with the slower walk of that era's
# KidSize robots (0.2 m/s forward, assumed) and Xu et al.'s (2012) camera (25 Hz, 720 x 625, 51
# degrees at 0.56 m).
_KIDSIZE_2012 = dataclasses.replace(
    _KIDSIZE, name="humanoid-2012", max_forward_speed=0.2, max_backward_speed=0.1,
    max_sideways_speed=0.1, max_turn_speed=0.6, max_acceleration=0.3, kick_max_speed=2.5,
    camera="kidsize-2012",
    source="Xu et al. (2012) (21 servos, head camera 0.56 m, 51 degrees, 25 Hz); walk of 2012 "
           "KidSize robots assumed; otherwise as 'humanoid'",
)
ROBOTS.register("humanoid-2012", _KIDSIZE_2012, _KIDSIZE_2012.source)

#: The field a robot preset plays on by default (by preset name, then by kind).
DEFAULT_FIELDS = {"humanoid-2012": "humanoid-2012", "humanoid": "humanoid-kid", "ssl": "ssl-div-b"}


def default_field(spec: RobotSpec) -> str:
    """The name of the field preset that ``spec`` plays on unless told otherwise."""
    return DEFAULT_FIELDS.get(spec.name, DEFAULT_FIELDS[spec.kind])


def field(spec: str | FieldSpec = "ssl-div-b", **overrides: Any) -> FieldSpec:
    """Return a field preset (by name or spec) with optional validated overrides."""
    return resolve_preset("field", FIELDS, spec, overrides)


def ball(spec: str | BallSpec = "ssl", **overrides: Any) -> BallSpec:
    """Return a ball preset (by name or spec) with optional validated overrides."""
    return resolve_preset("ball", BALLS, spec, overrides)


def robot(spec: str | RobotSpec = "ssl", **overrides: Any) -> RobotSpec:
    """Return a robot preset (by name or spec, SSL or humanoid) with optional validated
    overrides."""
    return resolve_preset("robot", ROBOTS, spec, overrides)
