"""``soccer_env/Goalkeeper-v0``: one keeper robot defends its goal against shots."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from soccer_env import presets
from soccer_env.envs.registration import GOALKEEPER_ID
from soccer_env.envs.settings import settings_keywords
from soccer_env.envs.task import SingleAgentTask
from soccer_env.envs.task_rules import (
    EXIT_GOAL,
    EXIT_OUT,
    GOALKEEPER_CLEAR_SPEED,
    GOALKEEPER_OUTCOMES,
    GOALKEEPER_STOP_SPEED,
    NO_EXIT,
    goalkeeper_outcome,
    goalkeeper_terms,
)
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.sim.referee import classify_exit
from soccer_env.state import WorldState
from soccer_env.validation import check_int, check_number, check_pair, from_mapping

__all__ = ["GoalkeeperEnv", "ShotDistribution", "place_episode", "fire_shot",
           "GOALKEEPER_SHAPING", "STOP_SPEED",
           "CLEAR_SPEED", "HUMANOID_SHOTS", "MAX_MATES", "mate_poses"]

#: The ball counts as stopped below this speed [m/s]; cleared once it moves away from the
#: goal faster than ``CLEAR_SPEED`` [m/s] (defined with the task's rules).
STOP_SPEED, CLEAR_SPEED = GOALKEEPER_STOP_SPEED, GOALKEEPER_CLEAR_SPEED

#: Shaping terms of the goalkeeper task (all off unless given a scale). Rates are per second
#: and multiplied by the control step, so their sum over an episode does not depend on it.
GOALKEEPER_SHAPING = {
    "intercept": "-|y_keeper - y_cross| / goal_width per second, y_cross where the ball's "
                 "present line of motion crosses the goal line, limited to the goal mouth "
                 "(0 while the ball is not moving towards the goal faster than 0.05 m/s)",
    "ball_distance": "-distance from keeper to ball [m] per second",
    "action_cost": "-(vx^2 + vy^2 + omega^2) / 3 of the normalised action per second",
    "outside_area": "-1 per second while the keeper's centre is outside its defense area",
}


@dataclass(frozen=True)
class ShotDistribution:
    """The seeded distribution of shots at the keeper's goal (blue's, at ``x = -L/2``).

    A shot starts at rest at a point drawn uniformly from ``x`` in ``x_range`` (default: from
    0.3 m in front of the defense area to the centre line) and ``y`` in ``y_range`` (default:
    ``|y| <= W/2 - edge_margin``).
    After ``delay`` seconds (uniform) an invisible attacker kicks it towards a target on the
    goal line: with probability ``1 - wide_probability`` uniformly inside the goal mouth
    (``|y| <= goal_width/2 - r``), otherwise just wide of a post (uniform side, ``r`` to
    ``r + wide_margin`` outside it). With probability ``chip_probability`` the kick is a chip at
    the robot preset's ``chip_angle`` with a launch speed uniform in ``chip_speed``; otherwise
    a flat kick with speed uniform in ``speed`` (it slides, then rolls). Speeds in m/s, times in
    s, lengths in m.
    """

    speed: tuple[float, float] = (2.0, 6.5)
    chip_speed: tuple[float, float] = (2.0, 5.0)
    chip_probability: float = 0.2
    wide_probability: float = 0.2
    wide_margin: float = 0.15
    delay: tuple[float, float] = (0.0, 0.3)
    x_range: tuple[float, float] | None = None
    y_range: tuple[float, float] | None = None
    edge_margin: float = 0.3

    def __post_init__(self) -> None:
        for name in ("speed", "chip_speed", "delay"):
            lo, hi = check_pair(f"shots.{name}", getattr(self, name))
            top = 10.0 if name == "delay" else 20.0
            if not (0.0 <= lo <= hi <= top) or (name != "delay" and lo <= 0.0):
                raise ValueError(f"shots.{name} must be (low, high) with 0 < low <= high <= "
                                 f"{top} (delay may start at 0), got {(lo, hi)}")
        for name in ("chip_probability", "wide_probability"):
            check_number(f"shots.{name}", getattr(self, name), 0.0, 1.0)
        for name in ("wide_margin", "edge_margin"):
            check_number(f"shots.{name}", getattr(self, name), 0.0, 2.0, unit=" m")
        for name in ("x_range", "y_range"):
            r = getattr(self, name)
            if r is not None and check_pair(f"shots.{name}", r)[0] > r[1]:
                raise ValueError(f"shots.{name} must be None or (low, high) with low <= high, "
                                 f"got {r!r}")

    def check_field(self, fld: FieldSpec) -> None:
        """Raise ``ValueError`` if the shooting region is not inside ``fld``'s field of play."""
        hx, hy = fld.half_length, fld.half_width
        x_lo, x_hi = self.x_range or (-hx + fld.defense_depth + 0.3, 0.0)
        y_lo, y_hi = self.y_range or (-(hy - self.edge_margin), hy - self.edge_margin)
        if not (-hx < x_lo and x_hi <= hx and -hy <= y_lo and y_hi <= hy and y_lo <= y_hi):
            raise ValueError(
                f"shots: the shooting region x in [{x_lo}, {x_hi}], y in [{y_lo}, {y_hi}] "
                f"must lie inside the field of play (|x| < {hx}, |y| <= {hy} m)")

    @classmethod
    def create(cls, value: ShotDistribution | Mapping[str, Any] | None) -> ShotDistribution:
        """Accept an instance, a mapping of its fields (unknown keys rejected) or None."""
        return from_mapping(cls, value, "shots")

    def sample(self, rng: np.random.Generator, fld: FieldSpec, bl: BallSpec) -> dict[str, Any]:
        """Draw one shot: start point, target, speed, chip flag and delay."""
        hx, hy, gw = fld.half_length, fld.half_width, 0.5 * fld.goal_width
        x_lo, x_hi = self.x_range or (-hx + fld.defense_depth + 0.3, 0.0)
        y_lo, y_hi = self.y_range or (-(hy - self.edge_margin), hy - self.edge_margin)
        x = rng.uniform(x_lo, x_hi)
        y = rng.uniform(y_lo, y_hi)
        wide = bool(rng.random() < self.wide_probability)
        if wide:
            side = 1.0 if rng.random() < 0.5 else -1.0
            ty = side * (gw + bl.radius + rng.uniform(0.0, self.wide_margin))
        else:
            ty = rng.uniform(-(gw - bl.radius), gw - bl.radius)
        chip = bool(rng.random() < self.chip_probability)
        speed = rng.uniform(*(self.chip_speed if chip else self.speed))
        delay = rng.uniform(*self.delay)
        return {"position": (float(x), float(y)), "target": (float(-hx), float(ty)),
                "speed": float(speed), "chip": chip, "wide": wide, "delay": float(delay)}


#: Shots at a humanoid keeper: humanoid kicks (3-5 m/s, no chips), kicked after 0.5-1.5 s
#: (the keeper's team has looked at the ball by then), from at least 0.5 m inside the touch
#: lines (clear of the team-mates standing near them).
HUMANOID_SHOTS = ShotDistribution(speed=(3.0, 5.0), chip_probability=0.0, delay=(0.5, 1.5),
                                  edge_margin=0.5)
#: Most team-mates a humanoid keeper can have (see :func:`mate_poses`).
MAX_MATES = 3


def mate_poses(field: FieldSpec, n: int, radius: float) -> np.ndarray:
    """Poses ``(n, 3)`` of a humanoid keeper's team-mates, who stand and watch: one on each
    touch line level with the middle of the keeper's half (``0.15 m`` inside the lines,
    facing the field), then one just past the centre line facing the keeper's goal. They see
    the shots from the side and from behind, and stand clear of the shooting region."""
    hx, hy = field.half_length, field.half_width
    slots = [(-0.5 * hx, hy - 0.15 - radius, -0.5 * math.pi),
             (-0.5 * hx, -(hy - 0.15 - radius), 0.5 * math.pi),
             (0.5 + radius, 0.0, math.pi)]
    return np.array(slots[:n], dtype=np.float64).reshape(n, 3)


def place_episode(rng: np.random.Generator, field: FieldSpec, robot: RobotSpec,
                  ball: BallSpec, shots: ShotDistribution, n_mates: int
                  ) -> tuple[np.ndarray, tuple[float, float], dict[str, Any]]:
    """A Goalkeeper-v0 episode's start drawn from ``rng``: the robots' poses ``(N, 3)`` (the
    keeper on its goal line within a quarter of the goal's width of the centre, then the
    team-mates), the ball's position and the shot (:meth:`ShotDistribution.sample`)."""
    keeper = (-field.half_length + robot.radius + 0.05,
              rng.uniform(-0.25 * field.goal_width, 0.25 * field.goal_width), 0.0)
    shot = shots.sample(rng, field, ball)
    poses = np.concatenate([[keeper], mate_poses(field, n_mates, robot.radius)])
    return poses, shot["position"], shot


def fire_shot(world: Any, shot: dict[str, Any], robot: RobotSpec) -> None:
    """The invisible attacker's ``shot`` in ``world``: the ball kicked from where it lies
    towards the shot's target, flat (sliding) or chipped like an SSL robot at its chip angle
    (humanoids do not chip)."""
    bx, by = world.ball_array()[0:2]
    tx, ty = shot["target"]
    d = math.hypot(tx - bx, ty - by)
    ux, uy = (tx - bx) / d, (ty - by) / d
    v = shot["speed"]
    if shot["chip"]:
        a = getattr(robot, "chip_angle", presets.ROBOTS["ssl"].chip_angle)
        world.set_ball(bx, by, v * math.cos(a) * ux, v * math.cos(a) * uy, 0.0,
                       v * math.sin(a))
    else:
        world.set_ball(bx, by, v * ux, v * uy, sliding=True)


class GoalkeeperEnv(SingleAgentTask):
    """A keeper robot defends its goal against one shot per episode.

    ## Description
    The blue keeper (an SSL robot or a humanoid) starts on its goal line, at
    ``x = -L/2 + r + 0.05`` and ``y`` uniform in ``+-goal_width/4``, facing the field. An
    invisible attacker shoots once per episode, drawn from :class:`ShotDistribution` with the
    environment's seeded generator. Physics, kicks and the chip flight are those of
    :class:`~soccer_env.sim.world.World`.

    A humanoid keeper (``robot="humanoid"`` or ``"humanoid-2012"``, on the matching humanoid
    field by default) walks with its walk engine, can dive, and sees through its head camera
    (:mod:`soccer_env.perception.humanoid`); ``mates`` humanoid team-mates (default 3, see
    :func:`mate_poses`) stand, watch the ball and share their sightings over the team radio,
    so that the team's fused estimate reaches the keeper. Shots default to
    :data:`HUMANOID_SHOTS`.

    ## Action space
    ``Box(-1, 1, (6,), float32)``: for an SSL robot ``vx, vy, omega, kick, chip, dribble`` as
    in :class:`~soccer_env.sim.commands.SSLRobot` (body-frame velocity command scaled to the robot
    preset's limits; kick power; chip flag; dribbler); for a humanoid ``vx, vy, omega,
    motion, pan, tilt`` as in :class:`~soccer_env.sim.commands.HumanoidRobot` (walking velocity;
    kick or dive; head targets, used only with ``head="action"``).

    ## Observation space
    ``Box((19,), float32)``, the egocentric layout of
    :mod:`soccer_env.observations` with no team-mates, no opponents and no game state (with
    ``belief_features=True``, 11 more entries, 13 for a humanoid, 3 more with
    ``ball_filter="imm"``): the
    keeper's own pose and velocity (7), the ball relative to it and its velocity (4), the four
    goal posts relative to it (8). ``obs_mode`` chooses where the values come from:
    ``"truth"``, ``"raw"`` (latest delayed camera detections) or ``"perceived"`` (the
    estimation stack, predicted ahead by the actuation latency); see
    :mod:`soccer_env.perception.overhead`.

    ## Rewards
    +1 for a save, -1 for a goal, 0 otherwise, plus the shaping terms of
    :data:`GOALKEEPER_SHAPING` times their scales (all 0 by default). ``info["reward_terms"]``
    logs every term's scaled value each step (``"outcome"`` is the +-1 term).

    ## Episode end
    Terminated on a goal (the whole ball in the goal, under the bar), or a save: the ball
    stopped (speed below 0.05 m/s on the carpet), cleared (moving away from the goal faster
    than 0.1 m/s) or out of play without a goal (touch line, goal line beside the goal, over
    the bar). ``info["outcome"]`` names it (``"goal"``, ``"stopped"``, ``"cleared"``,
    ``"out"``) and ``info["is_success"]`` is True for saves. Truncated by the registration's
    ``max_episode_steps`` (480 steps, 8 s at the default 60 Hz) if the ball is still moving,
    e.g. held by the dribbler.

    ## Info
    Every step: ``truth`` (see :meth:`~soccer_env.state.WorldState.truth_dict`), ``estimate``
    (the perception's belief at the present time, same keys; the truth itself in truth mode),
    ``reward_terms``, ``outcome`` (``""`` until the end), ``shot`` (the drawn shot),
    ``shot_fired``, ``keeper_touched`` (the keeper has touched the ball this episode).
    With ``info_mode="flat"``: numbers only under fixed keys, the outcome as a code, and the
    task's ``shot_fired``, ``keeper_touched``, ``shot_speed``, ``shot_chip``
    (:mod:`soccer_env.envs.flat_info`).

    ## Arguments
    ``robot`` ("ssl", "ssl-2012", "humanoid", "humanoid-2012" or a robot spec), ``field``
    (preset name or :class:`FieldSpec`, default "ssl-div-b" for SSL robots and the humanoid
    field of the preset for humanoids), ``ball`` (preset or spec; default the field's),
    ``obs_mode`` ("truth", "raw", "perceived"), ``perception`` (a vision preset name,
    a :class:`~soccer_env.perception.base.PerceptionConfig` or a mapping of its fields; it also sets
    the actuation latency and command loss, in every mode), ``render_mode`` (None,
    "rgb_array", "human"), ``shots`` (a
    :class:`ShotDistribution` or a mapping of its fields), ``shaping`` ({term: scale}),
    ``control_dt`` (s, default 1/60), ``physics_dt`` (longest substep, s, default 1/240),
    ``out_of_range_actions`` ("clip", the default, clips actions into [-1, 1]; "raise" rejects
    them), ``render_width`` (pixels), ``render_view`` ("field", the default: the whole field;
    "follow": a window around the ball and the nearest robots, zoomed in at the same frame
    size; see :meth:`~soccer_env.render.RenderingMixin.render`); humanoids only: ``mates``
    (0..3), ``head`` ("auto": the head follows the believed ball and scans when needed;
    "scan"; "action": the policy's entries 4 and 5); ``belief_features`` (append how sure
    the belief is: 11 entries, 13 for humanoids, 3 more with the ``"imm"`` ball filter's mode
    probabilities; see :mod:`soccer_env.observations`);
    ``info_mode`` ("full", the default, or "flat": numbers only, see
    :mod:`soccer_env.envs.flat_info`). Unknown arguments raise ``TypeError``.

    ## Version history
    * v0: first release.
    """

    TASK_ID = GOALKEEPER_ID
    SHAPING = GOALKEEPER_SHAPING
    FLAT_TASK_KEYS = ("shot_fired", "keeper_touched", "shot_speed", "shot_chip")
    OUTCOME_TEXT = {"goal": ("GOAL", "the shot went in"),
                    "stopped": ("SAVED", "the ball stopped"),
                    "cleared": ("SAVED", "the ball was cleared"),
                    "out": ("SAVED", "the ball went out, no goal")}

    @settings_keywords
    def __init__(self, *, shots: ShotDistribution | Mapping[str, Any] | None = None,
                 mates: int | None = None, **settings: Any) -> None:
        s, spec, fld, bl = self._take_settings(settings)
        humanoid = spec.kind == "humanoid"
        if mates is None:
            mates = MAX_MATES if humanoid else 0
        self.n_mates = check_int("mates" + ("" if humanoid else " (team-mates watch only for "
                                            "humanoid keepers; SSL vision sees everything)"),
                                 mates, 0, MAX_MATES if humanoid else 0)
        self.shots = ShotDistribution.create(HUMANOID_SHOTS if humanoid and shots is None
                                             else shots)
        self.shots.check_field(fld)
        self._build_learner(s, spec, fld, bl, n_blue=1 + self.n_mates, n_yellow=0)
        self._shaping_on = any(self.shaping.values())
        self._zero_shaping = dict.fromkeys(GOALKEEPER_SHAPING, 0.0)
        self.builder = self._observation_builder([0], teams=[0])
        self.observation_space = self.builder.space()
        # Half-width of the goal mouth the intercept shaping limits its crossing point to [m].
        self._mouth = 0.5 * self.field.goal_width + self.ball_spec.radius
        #: The shaping's scales and the field's numbers, as the rule kernels take them.
        sc, f = self.shaping, self.field
        self._weights = tuple(float(sc[k]) for k in ("intercept", "ball_distance",
                                                     "action_cost", "outside_area"))
        self._geometry = (float(f.half_length), float(self._mouth), float(f.goal_width),
                          float(f.defense_depth), float(f.defense_width))
        self._shot: dict[str, Any] | None = None

    # ------------------------------------------------------------------------------------
    # Task hooks
    # ------------------------------------------------------------------------------------

    def _place(self, rng: np.random.Generator) -> tuple[np.ndarray, tuple[float, float]]:
        poses, ball, self._shot = place_episode(rng, self.field, self.robot_spec,
                                                self.ball_spec, self.shots, self.n_mates)
        return poses, ball

    def _streams(self, rng: np.random.Generator
                 ) -> tuple[np.random.Generator, np.random.Generator]:
        # This task seeds the sensors' stream before the world's (its recorded episodes
        # depend on the order).
        sensor_rng = np.random.default_rng(rng.integers(2**63))
        return np.random.default_rng(rng.integers(2**63)), sensor_rng

    def _begin(self, rng: np.random.Generator) -> None:
        self._fired = False
        self._touched = False
        if self._shot["delay"] <= 0.0:
            self._fire()

    def _after_physics(self) -> None:
        world = self.world
        if not self._fired and world.time >= self._shot["delay"] - 1e-9:
            self._fire()
        self._touched = self._touched or world.touched[0]

    def _success(self, outcome: str) -> bool:
        return outcome != "goal"

    def _task_info(self, info: dict[str, Any]) -> None:
        info["shot"] = dict(self._shot)
        info["shot_fired"] = self._fired
        info["keeper_touched"] = self._touched

    def _flat_task_info(self, info: dict[str, float]) -> None:
        info["shot_fired"] = 1.0 if self._fired else 0.0
        info["keeper_touched"] = 1.0 if self._touched else 0.0
        info["shot_speed"] = float(self._shot["speed"])
        info["shot_chip"] = 1.0 if self._shot["chip"] else 0.0

    # ------------------------------------------------------------------------------------

    def _fire(self) -> None:
        """The invisible attacker kicks the ball from where it lies towards the target."""
        fire_shot(self.world, self._shot, self.robot_spec)
        self._fired = True

    def _outcome(self, state: WorldState, event: Any = None) -> str | None:
        world = self.world
        exit_code = NO_EXIT
        if world.ball_exit is not None:
            kind = classify_exit(world.ball_exit, self.field, self.ball_spec)
            exit_code = EXIT_GOAL if kind.kind == "goal" and kind.end < 0 else EXIT_OUT
        ball = state.ball
        return GOALKEEPER_OUTCOMES[goalkeeper_outcome(exit_code, self._fired,
                                                      world.ball_airborne, ball[3], ball[4])]

    def _reward_terms(self, state: WorldState, act: np.ndarray, outcome: str | None
                      ) -> dict[str, float]:
        terms = {"outcome": 0.0 if outcome is None else (-1.0 if outcome == "goal" else 1.0)}
        if not self._shaping_on:
            terms.update(self._zero_shaping)
            return terms
        b, k = state.ball, state.robots[0]
        (terms["intercept"], terms["ball_distance"], terms["action_cost"],
         terms["outside_area"]) = goalkeeper_terms(
            (b[0], b[1], b[3], b[4]), (k[0], k[1]),
            (float(act[0]), float(act[1]), float(act[2])), self._weights, self._geometry,
            self.world.control_dt)
        return terms

    # ------------------------------------------------------------------------------------

    def _hud(self) -> list[str]:
        shot = self._shot or {}
        kind = "chip" if shot.get("chip") else "flat"
        target = "wide" if shot.get("wide") else "on target"
        fired = ("" if getattr(self, "_fired", True)
                 else f", kicked at {shot.get('delay', 0.0):.2f} s")
        return [f"t = {self.world.time:5.2f} s",
                f"shot {shot.get('speed', 0.0):.1f} m/s {kind}, {target}{fired}"]

    def _team_labels(self) -> tuple[str, str]:
        mates = getattr(self, "n_mates", 0)
        return ("blue: keeper 0" + (f", team-mates 1-{mates}" if mates > 1 else
                                     ", team-mate 1" if mates else ""), "yellow team")

