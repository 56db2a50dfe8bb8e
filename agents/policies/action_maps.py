"""The learners' action maps: a learner's action as the robot's native command.

Goalkeeper-v0 takes the SSL robot's native command: a body-frame velocity, a turn rate and the
kicker, chip and dribbler (6 numbers), sent 60 times a second. That is a hard space to learn a
keeper in: one command changes the robot's velocity by at most ``a_max / 60`` (5 cm/s), so a
single step's Gaussian exploration hardly moves the outcome, and a sideways wish has to be
rotated through a heading the exploration keeps changing. PPO on the native command learned
nothing in millions of steps here (its deterministic actions ended saturated at +-1 while the
keeper spun). RoboCup teams' software does not command wheels either: the decision layer picks
where a robot should be and a motion controller gets it there. The keeper's learner gets the
same split, as these maps from a learner's action to the native command (the wrappers of
:mod:`agents.policies.wrappers` put them in front of an environment):

* ``"native"``: the environment's own 6-number command;
* ``"velocity"``: ``(vx, vy, omega)`` with the velocity in the team frame, kicker off
  (:class:`~agents.policies.wrappers.FieldVelocityActions`);
* ``"target"``: a point ``(x, y)`` in front of the goal that a braking-profile controller
  (:func:`soccer_env.envs.keeper.drive_command`) drives the keeper to, facing the field, kicker
  off (:class:`~agents.policies.wrappers.TargetActions`);
* ``"guard"``: the same with the point on the scripted keeper's guard line (5 cm in front of
  the goal line, beyond the robot's radius): only ``y`` is chosen
  (:class:`~agents.policies.wrappers.GuardActions`);
* ``"guard-residual"``: the point on the guard line the scripted keeper would choose from the
  same observation (:meth:`~soccer_env.envs.keeper.ScriptedGoalkeeper.guard_y`) plus the
  learner's correction ``a * residual`` (0.3 m): an action of 0 plays the scripted keeper's
  positioning, and the learner only has to learn where to differ from it (residual policy
  learning, Silver et al. 2018; Johannink et al. 2019;
  :class:`~agents.policies.wrappers.GuardResidualActions`);
* ``"ball-residual"``: for SSL and humanoid keepers alike, the scripted keeper
  (:class:`~soccer_env.envs.keeper.ScriptedGoalkeeper`, walking and diving for a humanoid)
  acting on the observation with the believed ball velocity corrected by
  ``a * ball_residual`` (2 numbers, team frame, 3 m/s at most): an action of 0 plays the
  scripted keeper, and the learner learns how the belief it is given misleads that keeper (a
  particle filter that learns a kick's speed over several frames makes the scripted humanoid
  dive late or not at all; :class:`~agents.policies.wrappers.BallResidualActions`).

The first four maps drive an SSL robot's native command and refuse a humanoid.

Each map reads the keeper's pose **from the agent's own observation** (``self.x``, ``self.y``,
``self.ax``, ``self.ay``), so under perceived observations it uses the estimated pose, as on a
real robot, never the truth. :func:`action_to_command` is the map as a function of
``(obs, action)``; :class:`~agents.policies.numpy_policy.NumpyPolicy` applies it, so a policy
trained through a wrapper acts on the plain environment.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import lru_cache
from types import SimpleNamespace
from typing import Any

import gymnasium as gym
import numpy as np

from agents.scripted import team_residual_command
from soccer_env.envs.keeper import TURN_GAIN, ScriptedGoalkeeper

__all__ = ["ACTION_MAPS", "POLICY_MAPS", "SSL_MAPS", "RESIDUAL", "BALL_RESIDUAL",
           "target_params", "residual_params", "ball_residual_params", "scripted_guard_y",
           "team_frame_ball_velocity", "action_to_command", "check_observation_layout"]

#: Action spaces of a learning keeper (see the module docstring) and their sizes.
ACTION_MAPS = {"native": 6, "velocity": 3, "target": 2, "guard": 1,
               "guard-residual": 1, "ball-residual": 2}

#: Every map a numpy policy may act through, with its size: the keeper's maps and the match
#: team's ``"team-residual"`` (:mod:`agents.scripted.residual`).
POLICY_MAPS = {**ACTION_MAPS, "team-residual": 6}

#: The maps that drive an SSL robot's native command (``"ball-residual"`` takes any keeper).
SSL_MAPS = ("velocity", "target", "guard", "guard-residual")

#: The largest correction of the ``"ball-residual"`` map to the believed ball velocity [m/s]
#: (per axis): humanoid kicks are 3-5 m/s, and a tracker that has just seen one may believe
#: a fraction of it.
BALL_RESIDUAL = 3.0

#: Attributes of the specs that :class:`~soccer_env.envs.keeper.ScriptedGoalkeeper` reads,
#: by spec and robot kind: what ``"ball-residual"``'s params carry to rebuild it.
_KEEPER_SPEC = {
    "field": ("half_length", "goal_width"),
    "ball": ("radius", "rolling_deceleration"),
    "ssl": ("radius", "max_speed", "max_acceleration", "max_angular_speed", "front_distance",
            "kicker_width"),
    "humanoid": ("radius", "lying_length", "fall_time", "max_forward_speed",
                 "max_backward_speed", "max_sideways_speed", "max_acceleration",
                 "max_turn_speed", "kick_reach", "kick_width"),
}

#: Indices of ``ball.dx, ball.dy, ball.vx, ball.vy`` in every observation layout.
_BALL = (7, 8, 9, 10)

#: The largest correction of the ``"guard-residual"`` map [m].
RESIDUAL = 0.3

#: Indices of ``self.x, self.y, self.ax, self.ay`` in every observation layout of
#: :mod:`soccer_env.observations` (they open it).
_POSE = (0, 1, 2, 3)

#: The entries the maps read, at the indices ``_POSE + _BALL``.
_ENTRIES = ("self.x", "self.y", "self.ax", "self.ay", "ball.dx", "ball.dy", "ball.vx",
            "ball.vy")


def target_params(env: gym.Env, depth: float = 0.5) -> dict[str, float]:
    """The constants of the ``"target"`` map for a Goalkeeper environment: the box of
    targets (``x`` from the robot's radius + 5 cm in front of the goal line to ``depth``
    beyond that, ``|y|`` up to half the goal width plus the robot's radius) and the robot's
    limits [m, m/s, m/s^2, rad/s]."""
    u = env.unwrapped
    f, r = u.field, u.robot_spec
    x0 = -f.half_length + r.radius + 0.05
    return {"x_min": x0, "x_max": x0 + depth, "y_max": 0.5 * f.goal_width + r.radius,
            "max_speed": r.max_speed, "max_acceleration": r.max_acceleration,
            "max_angular_speed": r.max_angular_speed}


def residual_params(env: gym.Env, residual: float = RESIDUAL) -> dict[str, float]:
    """The constants of the ``"guard-residual"`` map: :func:`target_params`, the goal line
    ``goal_x`` [m], the half-width of the mouth the scripted keeper guards ``half_goal``
    (goal and ball) [m], the ball's rolling ``deceleration`` [m/s^2] and the largest
    correction ``residual`` [m]."""
    u = env.unwrapped
    f, b = u.field, u.ball_spec
    return {**target_params(env), "goal_x": -f.half_length,
            "half_goal": 0.5 * f.goal_width + b.radius,
            "deceleration": b.rolling_deceleration, "residual": float(residual)}


def _keeper_params(kind: str) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """``(part, attributes)`` of what the scripted keeper of robot ``kind`` (``"ssl"`` or
    ``"humanoid"``) reads: its field, ball and robot specs' attributes (:data:`_KEEPER_SPEC`)."""
    return (("field", _KEEPER_SPEC["field"]), ("ball", _KEEPER_SPEC["ball"]),
            ("robot", _KEEPER_SPEC[kind]))


def ball_residual_params(env: gym.Env, residual: float = BALL_RESIDUAL) -> dict[str, float]:
    """The constants of the ``"ball-residual"`` map: what the scripted keeper reads of the
    field, ball and robot specs (``"field.half_length"``, ``"robot.fall_time"``, ...; see
    :data:`_KEEPER_SPEC`), ``humanoid`` (1.0 for a humanoid keeper, else 0.0) and the largest
    correction ``residual`` [m/s]."""
    u = env.unwrapped
    kind = "humanoid" if u.robot_spec.kind == "humanoid" else "ssl"
    specs = {"field": u.field, "ball": u.ball_spec, "robot": u.robot_spec}
    params = {"humanoid": float(kind == "humanoid"), "residual": float(residual)}
    for part, attrs in _keeper_params(kind):
        params.update({f"{part}.{a}": float(getattr(specs[part], a)) for a in attrs})
    return params


#: Entry names the rebuilt scripted keeper reads, at their indices in every observation
#: layout (``_POSE`` and ``_BALL``); the rest is never read.
_LAYOUT = tuple(dict(zip(_POSE + _BALL, _ENTRIES)).get(i, "") for i in range(max(_BALL) + 1))


@lru_cache(maxsize=8)
def _keeper(items: tuple[tuple[str, float], ...]) -> ScriptedGoalkeeper:
    """The scripted keeper of ``"ball-residual"`` params (as sorted items), rebuilt from the
    numbers alone so that a saved policy needs no environment."""
    params = dict(items)
    kind = "humanoid" if params.get("humanoid") else "ssl"
    needed = ["residual", *(f"{part}.{a}" for part, attrs in _keeper_params(kind)
                            for a in attrs)]
    missing = [k for k in needed if k not in params]
    if missing:
        raise ValueError(f"the 'ball-residual' map's params lack {missing} (see "
                         "ball_residual_params)")

    def spec(part: str, **extra: Any) -> SimpleNamespace:
        return SimpleNamespace(**{k.split(".", 1)[1]: v for k, v in params.items()
                                  if k.startswith(part + ".")}, **extra)

    return ScriptedGoalkeeper(spec("field"), spec("ball"), spec("robot", kind=kind), _LAYOUT)


def _ball_residual_command(obs: np.ndarray, act: np.ndarray,
                           params: Mapping[str, float]) -> np.ndarray:
    """The ``"ball-residual"`` map on a batch: the believed ball velocity of each observation
    plus ``a * residual`` in the team frame (rotated into the body frame the observation
    stores it in: ``(c dvx + s dvy, -s dvx + c dvy)``), then the scripted keeper's command."""
    keeper = _keeper(tuple(sorted(params.items())))
    flat = np.array(obs, dtype=np.float64).reshape(-1, obs.shape[-1])
    corr = act.reshape(-1, 2) * params["residual"]
    bx, by = _to_body(*_heading(flat), corr[:, 0], corr[:, 1])
    flat[:, _BALL[2]] += bx
    flat[:, _BALL[3]] += by
    out = np.stack([keeper(o) for o in flat]) if len(flat) else np.empty((0, 6), np.float32)
    return out.reshape(act.shape[:-1] + (6,))


def scripted_guard_y(obs: np.ndarray, params: Mapping[str, float]) -> np.ndarray:
    """:meth:`~soccer_env.envs.keeper.ScriptedGoalkeeper.guard_y` on a batch of observations
    ``(..., n_obs)``: with the ball's position ``b`` and velocity ``v`` in the team frame,
    ``y = b_y + v_y / v_x (x_g - b_x)`` where a ball moving towards the goal faster than
    5 cm/s reaches the guard line ``x_g`` before it stops (it rolls straight, decelerating:
    it covers ``s = (x_g - b_x) |v| / v_x <= |v|^2 / (2 a)``), else the crossing of the line
    from the ball to the goal centre; within ``+-half_goal``."""
    obs = np.asarray(obs, dtype=np.float64)
    c, s = _heading(obs)
    px, py = obs[..., _POSE[0]], obs[..., _POSE[1]]
    dx, dy = obs[..., _BALL[0]], obs[..., _BALL[1]]
    bx, by = px + c * dx - s * dy, py + s * dx + c * dy
    vx, vy = _rotate(c, s, obs[..., _BALL[2]], obs[..., _BALL[3]])
    gx, a = params["x_min"], params["deceleration"]
    speed = np.hypot(vx, vy)
    with np.errstate(divide="ignore", invalid="ignore"):
        path = (gx - bx) * speed / vx
        crossing = by + vy / vx * (gx - bx)
    reaches = (vx < -0.05) & (path >= 0.0) & ((a == 0.0) | (speed * speed - 2.0 * a * path
                                                             >= 0.0))
    frac = (gx - params["goal_x"]) / np.maximum(bx - params["goal_x"], 1e-3)
    y = np.where(reaches, crossing, by * np.minimum(frac, 1.0))
    return np.clip(y, -params["half_goal"], params["half_goal"])


def team_frame_ball_velocity(obs: np.ndarray) -> np.ndarray:
    """The believed ball velocity of observations ``(..., n_obs)`` in the team frame [m/s],
    ``(..., 2)``: the body-frame entries rotated by the heading, ``(c v_x - s v_y,
    s v_x + c v_y)``."""
    obs = np.asarray(obs, dtype=np.float64)
    return np.stack(_rotate(*_heading(obs), obs[..., _BALL[2]], obs[..., _BALL[3]]), axis=-1)


def _rotate(c: np.ndarray, s: np.ndarray, x: np.ndarray, y: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray]:
    """The body-frame vector ``(x, y)`` in the team frame of a robot with heading
    ``(cos, sin) = (c, s)``: rotated by the heading, ``(c x - s y, s x + c y)``."""
    return c * x - s * y, s * x + c * y


def _to_body(c: np.ndarray, s: np.ndarray, x: np.ndarray, y: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray]:
    """The team-frame vector ``(x, y)`` in the body frame of a robot with heading
    ``(cos, sin) = (c, s)``: rotated by ``-heading``, ``(c x + s y, -s x + c y)``."""
    return c * x + s * y, -s * x + c * y


def _heading(obs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Cosine and sine of the heading in the team frame (the observation stores
    ``(cos, -sin)`` in ``self.ax, self.ay``), normalised."""
    ax, ay = obs[..., _POSE[2]], obs[..., _POSE[3]]
    norm = np.sqrt(ax * ax + ay * ay)
    norm = np.where(norm > 1e-6, norm, 1.0)
    return ax / norm, -ay / norm


def action_to_command(kind: str, obs: np.ndarray, action: np.ndarray,
                      params: Mapping[str, float] | None = None) -> np.ndarray:
    """The native command ``(vx, vy, omega, kick, chip, dribble)`` of an action of map
    ``kind`` (one ``(k,)`` action with its observation, or ``(n, k)`` and ``(n, n_obs)``
    batches).

    * ``"velocity"``: with ``(c, s)`` the heading's cosine and sine, the body-frame velocity is
      the field-frame one rotated by ``-heading``, ``(c vx + s vy, -s vx + c vy)``; ``omega``
      passes through.
    * ``"target"``: the target ``x = x_min + (a_0 + 1) / 2 (x_max - x_min)``,
      ``y = a_1 y_max`` (``"guard"``: ``x = x_min``, ``y = a_0 y_max``); the velocity points
      at it with speed
      ``min(v_max, sqrt(2 a_max d))`` at distance ``d`` (the fastest approach that still stops
      there), rotated into the body frame and scaled by ``v_max``; the turn rate brings the
      heading to 0 (facing the field) with gain ``TURN_GAIN`` (8 /s).

    Kick 0, chip and dribbler off (-1).

    * ``"ball-residual"`` (2 numbers): the believed ball velocity of the observation plus
      ``(a_0, a_1) residual`` in the team frame, and the scripted keeper's command on that
      observation (an SSL robot's or a humanoid's; see :func:`ball_residual_params`).
    * ``"team-residual"`` (6 numbers, whole teams of a match, robots in order): the scripted
      SSL team's command plus ``a * residual``
      (:func:`agents.scripted.residual.team_residual_command`).
    """
    if kind not in POLICY_MAPS or kind == "native":
        raise ValueError(f"kind must be one of {[k for k in POLICY_MAPS if k != 'native']}, "
                         f"got {kind!r}")
    if kind == "team-residual":
        if params is None:
            raise ValueError("the 'team-residual' map needs its params (see "
                             "agents.scripted.residual.team_residual_params)")
        return team_residual_command(obs, action, params)
    obs = np.asarray(obs, dtype=np.float64)
    act = np.clip(np.asarray(action, dtype=np.float64), -1.0, 1.0)
    size = ACTION_MAPS[kind]
    if act.shape[-1] != size or act.shape[:-1] != obs.shape[:-1]:
        raise ValueError(f"a {kind!r} action must have shape (..., {size}) matching obs "
                         f"{obs.shape}, got {act.shape}")
    if kind == "ball-residual":
        if params is None:
            raise ValueError("the 'ball-residual' map needs its params (see "
                             "ball_residual_params)")
        return _ball_residual_command(obs, act, params)
    c, s = _heading(obs)
    out = np.empty(act.shape[:-1] + (6,), dtype=np.float32)
    if kind == "velocity":
        wx, wy, omega = act[..., 0], act[..., 1], act[..., 2]
    else:
        if params is None:
            raise ValueError(f"the {kind!r} map needs its params (see target_params)")
        p = params
        if kind == "guard":
            tx = np.full(act.shape[:-1], p["x_min"])
            ty = act[..., 0] * p["y_max"]
        elif kind == "guard-residual":
            tx = np.full(act.shape[:-1], p["x_min"])
            ty = np.clip(scripted_guard_y(obs, p) + act[..., 0] * p["residual"], -p["y_max"],
                         p["y_max"])
        else:
            tx = p["x_min"] + 0.5 * (act[..., 0] + 1.0) * (p["x_max"] - p["x_min"])
            ty = act[..., 1] * p["y_max"]
        # drive_command and turn_command (soccer_env.envs.keeper) on whole batches: they are scalar
        # for the scripted keeper's speed; test_wrappers checks the velocity against the former.
        ex, ey = tx - obs[..., _POSE[0]], ty - obs[..., _POSE[1]]
        dist = np.hypot(ex, ey)
        speed = np.minimum(p["max_speed"], np.sqrt(2.0 * p["max_acceleration"] * dist))
        scale = np.where(dist > 1e-6, speed / np.maximum(dist, 1e-6), 0.0) / p["max_speed"]
        wx, wy = ex * scale, ey * scale
        omega = np.clip(TURN_GAIN * -np.arctan2(s, c) / p["max_angular_speed"], -1.0, 1.0)
    out[..., 0], out[..., 1] = _to_body(c, s, wx, wy)
    out[..., 2] = omega
    out[..., 3] = 0.0
    out[..., 4] = -1.0
    out[..., 5] = -1.0
    return out


def check_observation_layout(names: Sequence[str]) -> None:
    """Raise ``ValueError`` unless the observation entry ``names`` have what the maps read,
    ``self.x, self.y, self.ax, self.ay, ball.dx, ball.dy, ball.vx, ball.vy``, at the indices
    of every layout of :mod:`soccer_env.observations`."""
    if tuple(names[i] for i in _POSE + _BALL) != _ENTRIES:
        raise ValueError(f"the observation must have {', '.join(_ENTRIES)} at indices "
                         f"{_POSE + _BALL}")
