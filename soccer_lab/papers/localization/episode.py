"""One walk of Guo and Li's (2013) reproduction, recorded once: the scripted route of a
walking ``humanoid-2012`` robot with its scanning head, the kidnapping, and what the robot's
brain gets (the odometry per control step, the frames' landmarks as delivered) beside the truth
(see :mod:`soccer_lab.papers.localization`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from soccer_env import presets
from soccer_env.perception.humanoid import HumanoidTeamPerception
from soccer_env.perception.sighting import landmark_sightings
from soccer_env.presets.sensors import RADIO_PRESETS, head_camera
from soccer_env.sim.heads import HeadController
from soccer_env.sim.world import World

__all__ = ["ROBOT", "FIELD", "CAMERA", "CONTROL_DT", "CRUISE", "TURN_RATE", "EDGE_TURN_RATE",
           "EDGE_MARGIN", "KIDNAP_AT", "TURNING", "route_command", "kidnap_pose", "record_walk"]

#: The robot, field and head-camera presets, and the control step [s].
ROBOT = "humanoid-2012"
FIELD = "humanoid-2012"
CAMERA = "kidsize-2012"
CONTROL_DT = 1.0 / 60.0

#: Forward speed of the route as a fraction of the robot's top speed.
CRUISE = 0.75

#: Turn rate of the route's turns, and of the turns back from the edges [rad/s].
TURN_RATE, EDGE_TURN_RATE = 0.3, 0.5

#: The route turns back once the robot is this close to a field line [m].
EDGE_MARGIN = 0.7
#: The kidnapping, as a fraction of the episode.
KIDNAP_AT = 2.0 / 3.0

#: Frames captured while the gait turns faster than this [rad/s] count as "in turns".
TURNING = 0.1


def route_command(pose: np.ndarray, t: float, segments: list[tuple[float, float]],
                  state: dict[str, Any], field: Any, vmax: float) -> tuple[float, float]:
    """Forward speed and turn rate of the scripted route at ``t`` for the true ``pose``."""
    x, y, th = float(pose[0]), float(pose[1]), float(pose[2])
    hx, hy = field.half_length - EDGE_MARGIN, field.half_width - EDGE_MARGIN
    to_centre = math.remainder(math.atan2(-y, -x) - th, 2.0 * math.pi)
    if abs(x) > hx or abs(y) > hy:
        if abs(to_centre) > math.radians(60.0):
            state["returning"] = True
    if state["returning"]:
        if abs(to_centre) < math.radians(20.0):
            state["returning"] = False
        else:
            return 0.4 * vmax, math.copysign(EDGE_TURN_RATE, to_centre)
    while state["segment"] + 1 < len(segments) and segments[state["segment"] + 1][0] <= t:
        state["segment"] += 1
    return CRUISE * vmax, segments[state["segment"]][1]


def kidnap_pose(pose: np.ndarray, field: Any, rng: np.random.Generator) -> np.ndarray:
    """A pose inside the field at least 2 m from ``pose``, turned by 90 degrees or more."""
    hx, hy = field.half_length - EDGE_MARGIN, field.half_width - EDGE_MARGIN
    while True:
        cand = np.array([rng.uniform(-hx, hx), rng.uniform(-hy, hy), rng.uniform(-math.pi,
                                                                                 math.pi)])
        if (math.hypot(*(cand[:2] - pose[:2])) >= 2.0
                and abs(math.remainder(cand[2] - pose[2], 2.0 * math.pi)) >= 0.5 * math.pi):
            return cand


def record_walk(duration: float, seed: int, kidnap: bool) -> dict[str, Any]:
    """Walk the route once (``duration`` [s], the route, walk, camera noise and kidnapping
    drawn from ``seed``; ``kidnap``: pick the robot up at :data:`KIDNAP_AT` of the walk): the
    events a robot brain gets (``("odo", t, odometry)`` per control step, ``("frame",
    t_capture, kinds, ranges, bearings)`` per frame as delivered), the truth per step and at
    each frame's capture, the team perception (landmark table, bounds, KLD noise model), the
    kidnapping and the falls."""
    rng = np.random.default_rng(seed)
    walk_rng, cam_rng, route_rng = rng.spawn(3)
    field = presets.field(FIELD)
    ball = presets.ball(field.ball)
    spec = presets.robot(ROBOT)
    world = World(field, ball, spec, 1, 0, CONTROL_DT)
    camera = head_camera(CAMERA)
    # The perception of one humanoid, for its camera, landmark table, bounds, KLD noise model
    # and scanning head; no brain runs (the filters are replayed on the record), so it needs no
    # perception config.
    team = HumanoidTeamPerception(None, field, ball, world.robot_specs, world.teams,
                                  world.names, [0], camera, RADIO_PRESETS["ideal"])
    head = HeadController(spec, camera.height, "scan")
    start = np.array([-1.5, 0.6, 0.3])
    world.reset(start[None, :], (0.0, -(field.half_width + 0.45)), walk_rng)
    n_steps = int(round(duration / CONTROL_DT))
    segments, t = [], 0.0
    while t < duration:
        segments.append((t, float(route_rng.choice([0.0, 0.0, 0.0, TURN_RATE, -TURN_RATE]))))
        t += float(route_rng.uniform(2.0, 5.0))
    route = {"returning": False, "segment": 0}
    kidnap_step = int(round(KIDNAP_AT * n_steps)) if kidnap else -1
    vmax = spec.max_forward_speed

    def frames_to_events(frames: list[Any]) -> None:
        for f in frames:  # the landmarks with a ground point, as the brain takes them
            events.append(("frame", f.t_capture, *landmark_sightings(f)))

    events: list[tuple] = []
    times, poses, omegas = [world.time], [world.robot_array()[0, 0:3].copy()], [0.0]
    frames_to_events(team.sensor.reset(world.snapshot(), world.head_state(), cam_rng))
    kidnap_time, kidnap_to = None, None
    falls = 0
    for k in range(n_steps):
        now = world.time
        pose = world.robot_array()[0, 0:3]
        vx, w = route_command(pose, now, segments, route, field, vmax)
        pan, tilt = head.targets(now, pose, None, math.inf, math.inf)  # the scan
        world.step(np.array([[vx, 0.0, w, 0.0, pan, tilt]]))
        if k == kidnap_step:
            kidnap_to = kidnap_pose(world.robot_array()[0, 0:3], field, route_rng)
            world.set_robot(0, *kidnap_to)
            kidnap_time = world.time
        state = world.snapshot()
        events.append(("odo", state.time, tuple(world.walk.odometry[0])))
        times.append(state.time)
        poses.append(state.robots[0, 0:3].copy())
        omegas.append(float(world.walk.gait[0][2]))
        frames_to_events(team.sensor.step(state, world.head_state()))
        falls = world.walk.falls[0]
    times_a, poses_a = np.array(times), np.array(poses)
    frame_t = np.array([ev[1] for ev in events if ev[0] == "frame"])
    # The truth at each frame's capture (a control step's time; the warm-up frame's, before
    # the start, is the start pose).
    at = np.minimum(np.searchsorted(times_a, frame_t - 1e-9), len(times_a) - 1)
    return {"events": events, "times": times_a, "poses": poses_a, "frame_t": frame_t,
            "frame_truth": poses_a[at], "frame_turning": np.abs(np.array(omegas)[at]) > TURNING,
            "team": team, "kidnap_time": kidnap_time, "kidnap_to": kidnap_to, "falls": falls,
            "start": start}
