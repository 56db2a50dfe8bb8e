"""``soccer_env/Shootout-v0``: an attacker must score past the scripted keeper."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from soccer_env.envs.keeper import ScriptedGoalkeeper
from soccer_env.envs.registration import SHOOTOUT_ID
from soccer_env.envs.settings import settings_keywords
from soccer_env.envs.task import SingleAgentTask
from soccer_env.envs.task_rules import (
    EXIT_GOAL,
    EXIT_OUT,
    NO_EXIT,
    SHOOTOUT_CLEAR_SPEED,
    SHOOTOUT_OUTCOMES,
    SHOOTOUT_STOP_SPEED,
    goal_distance,
    shootout_outcome,
    shootout_terms,
)
from soccer_env.observations import ObservationBuilder
from soccer_env.presets import FieldSpec
from soccer_env.sim.referee import classify_exit
from soccer_env.state import WorldState
from soccer_env.validation import check_number, check_pair, from_mapping

__all__ = ["ShootoutEnv", "ShootoutStart", "SHOOTOUT_SHAPING", "CLEAR_SPEED", "STOP_SPEED"]

#: A ball moving away from the goal faster than ``CLEAR_SPEED`` [m/s], or slower than
#: ``STOP_SPEED`` [m/s], after the keeper touched it is saved (defined with the task's rules).
CLEAR_SPEED, STOP_SPEED = SHOOTOUT_CLEAR_SPEED, SHOOTOUT_STOP_SPEED

#: Shaping terms of the shootout (all off unless given a scale). Rates are per second and
#: multiplied by the control step, so their sum over an episode does not depend on it.
SHOOTOUT_SHAPING = {
    "ball_progress": "decrease of the ball's distance to the goal centre [m] (its rate per "
                     "second times the step)",
    "ball_distance": "-distance from the attacker to the ball [m] per second",
    "action_cost": "-(vx^2 + vy^2 + omega^2) / 3 of the normalised action per second",
}


@dataclass(frozen=True)
class ShootoutStart:
    """The seeded start of a shootout (lengths in m, angles in rad, field frame).

    The ball lies at rest ``d`` from the centre of the goal the attacker attacks (at
    ``x = +L/2``), ``d`` uniform in ``ball_distance`` (default: from 0.25 m beyond the far
    corner of the goal area to 1.5 m farther), in the direction ``a`` uniform in
    ``ball_angle`` from the goal's axis (0: straight in front of the goal, positive towards
    ``+y``). The attacker stands ``e`` uniform in ``robot_distance`` behind the ball on the
    line from the goal through the ball turned by up to ``+-robot_angle``, facing the ball.
    The keeper stands on its goal line, ``y`` uniform in ``+-goal_width/4``, facing the field.
    """

    ball_distance: tuple[float, float] | None = None
    ball_angle: tuple[float, float] = (-0.5, 0.5)
    robot_distance: tuple[float, float] = (0.3, 0.6)
    robot_angle: float = 0.3

    def __post_init__(self) -> None:
        for name, top in (("ball_distance", 20.0), ("robot_distance", 5.0)):
            value = getattr(self, name)
            if value is None and name == "ball_distance":
                continue
            lo, hi = check_pair(f"start.{name}", value)
            if not (0.0 < lo <= hi <= top):
                raise ValueError(f"start.{name} must be (low, high) with 0 < low <= high <= "
                                 f"{top} m, got {value!r}")
        lo, hi = check_pair("start.ball_angle", self.ball_angle)
        if not (-0.5 * math.pi < lo <= hi < 0.5 * math.pi):
            raise ValueError(f"start.ball_angle must be (low, high) with -pi/2 < low <= high "
                             f"< pi/2 rad, got {(lo, hi)}")
        check_number("start.robot_angle", self.robot_angle, 0.0, 0.5 * math.pi, unit=" rad")

    def distances(self, fld: FieldSpec) -> tuple[float, float]:
        """The range of the ball's distance from the goal centre on ``fld`` [m]."""
        if self.ball_distance is not None:
            return self.ball_distance
        near = math.hypot(fld.defense_depth, 0.5 * fld.defense_width) + 0.25
        return near, near + 1.5

    def check_field(self, fld: FieldSpec, robot_radius: float) -> None:
        """Raise ``ValueError`` unless every start lies inside ``fld``'s field of play (the
        attacker a radius inside the lines)."""
        hx, hy = fld.half_length, fld.half_width
        d_hi, e_hi = self.distances(fld)[1], self.robot_distance[1]
        a_max = max(abs(a) for a in self.ball_angle)
        b_max = min(a_max + self.robot_angle, 0.5 * math.pi)
        y_max = d_hi * math.sin(a_max) + e_hi * math.sin(b_max) + robot_radius
        x_min = hx - d_hi - e_hi - robot_radius
        if x_min < -hx or y_max > hy:
            raise ValueError(
                f"start: balls up to {d_hi:.2f} m from the goal within {a_max:.2f} rad of its "
                f"axis, attackers up to {e_hi} m behind them, reach y = {y_max:.2f} m; they "
                f"must stay inside the {fld.name!r} field (|x| <= {hx}, |y| <= {hy} m): "
                f"narrow start.ball_angle or shorten start.ball_distance")

    @classmethod
    def create(cls, value: ShootoutStart | Mapping[str, Any] | None) -> ShootoutStart:
        """Accept an instance, a mapping of its fields (unknown keys rejected) or None."""
        return from_mapping(cls, value, "start")

    def sample(self, rng: np.random.Generator, fld: FieldSpec, keeper_radius: float
               ) -> dict[str, Any]:
        """Draw one start: the ball, the attacker's and the keeper's poses."""
        hx, gw = fld.half_length, 0.5 * fld.goal_width
        d = rng.uniform(*self.distances(fld))
        a = rng.uniform(*self.ball_angle)
        ball = (hx - d * math.cos(a), d * math.sin(a))
        e = rng.uniform(*self.robot_distance)
        b = a + rng.uniform(-self.robot_angle, self.robot_angle)
        robot = (ball[0] - e * math.cos(b), ball[1] + e * math.sin(b))
        facing = math.atan2(ball[1] - robot[1], ball[0] - robot[0])
        keeper = (hx - keeper_radius - 0.05, rng.uniform(-0.5 * gw, 0.5 * gw), math.pi)
        return {"ball": (float(ball[0]), float(ball[1])),
                "attacker": (float(robot[0]), float(robot[1]), float(facing)),
                "keeper": tuple(float(v) for v in keeper)}


class ShootoutEnv(SingleAgentTask):
    """An attacker must score past the scripted keeper.

    ## Description
    The blue attacker (an SSL robot or a humanoid) starts behind the ball, which lies at rest
    in front of the yellow goal (at ``x = +L/2``), both drawn from :class:`ShootoutStart`
    with the environment's seeded generator. The yellow keeper, of the same robot preset, is
    :class:`~soccer_env.envs.keeper.ScriptedGoalkeeper` playing from its own team's
    perception of the ball in the same observation mode: it keeps to its guard line, moves to
    where the ball will cross it, clears a ball at its kicker and, as a humanoid, dives.
    Physics, kicks and chips are those of :class:`~soccer_env.sim.world.World`.

    ## Action space
    ``Box(-1, 1, (6,), float32)``: for an SSL robot ``vx, vy, omega, kick, chip, dribble`` as
    in :class:`~soccer_env.sim.commands.SSLRobot`; for a humanoid ``vx, vy, omega, motion,
    pan, tilt`` as in :class:`~soccer_env.sim.commands.HumanoidRobot` (head entries used only
    with ``head="action"``).

    ## Observation space
    ``Box((25,), float32)``, the egocentric layout of :mod:`soccer_env.observations` with the
    keeper as the one opponent: the attacker's own pose and velocity (7), the ball relative to
    it and its velocity (4), the keeper relative to it (6), the four goal posts (8). Entry
    names: ``env.unwrapped.builder.names``. ``obs_mode`` chooses where the values come from
    (``"truth"``, ``"raw"``, ``"perceived"``; see :mod:`soccer_env.perception`), for the
    attacker and the keeper alike.

    ## Rewards
    +1 for a goal, -1 when the ball is saved or leaves the field otherwise, 0 while play goes
    on, plus the shaping terms of :data:`SHOOTOUT_SHAPING` times their scales (all 0 by
    default). ``info["reward_terms"]`` logs every term's scaled value each step
    (``"outcome"`` is the +-1 term).

    ## Starting state
    :class:`ShootoutStart` (``start=``): by default the ball just beyond the goal area (up to
    1.5 m farther) within 0.5 rad of the goal's axis, the attacker 0.3-0.6 m behind it facing
    it, the keeper on its goal line, everything at rest.

    ## Episode end
    Terminated on a goal (the whole ball in the yellow goal, under the bar), a save (after the
    keeper touched the ball it moves away from the goal faster than 0.1 m/s or stops) or the
    ball leaving the field otherwise (touch line, goal line beside the goal, over the bar, the
    attacker's own goal). ``info["outcome"]`` names it (``"goal"``, ``"saved"``, ``"out"``)
    and ``info["is_success"]`` is True for goals. Truncated by the registration's
    ``max_episode_steps`` (600 steps, 10 s at the default 60 Hz).

    ## Info
    Every step: ``truth``, ``estimate`` (the attacker's belief at the present time, same
    keys), ``reward_terms``, ``outcome`` (``""`` until the end), ``start`` (the drawn start),
    ``keeper_touched`` (since the attacker's last touch); with humanoids ``robot_state``.
    With ``info_mode="flat"``: numbers only under fixed keys, the outcome as a code, and
    ``keeper_touched`` (:mod:`soccer_env.envs.flat_info`).

    ## Arguments
    ``robot`` (a preset name or spec, for both robots), ``field`` (default: Division B for
    SSL robots, the preset's humanoid field otherwise), ``ball``, ``obs_mode``,
    ``perception`` (as in :class:`~soccer_env.envs.goalkeeper.GoalkeeperEnv`, for both
    teams), ``render_mode``, ``start`` (a :class:`ShootoutStart` or a mapping of its fields),
    ``shaping`` ({term: scale}), ``control_dt``, ``physics_dt``, ``out_of_range_actions``,
    ``render_width``, ``render_view`` ("field" or "follow", as in
    :class:`~soccer_env.envs.goalkeeper.GoalkeeperEnv`), ``head`` (humanoids: ``"auto"``,
    ``"scan"`` or ``"action"``, the attacker's head only; the keeper's is always
    controlled), ``belief_features`` (as in
    :class:`~soccer_env.envs.goalkeeper.GoalkeeperEnv`), ``info_mode`` ("full" or "flat").
    Unknown arguments raise ``TypeError``.

    ## Version history
    * v0: first release.
    """

    TASK_ID = SHOOTOUT_ID
    SHAPING = SHOOTOUT_SHAPING
    FLAT_TASK_KEYS = ("keeper_touched",)
    OUTCOME_TEXT = {"goal": ("GOAL", "the attacker scored"),
                    "saved": ("SAVED", "the keeper stopped the ball"),
                    "out": ("MISSED", "the ball went out")}

    @settings_keywords
    def __init__(self, *, start: ShootoutStart | Mapping[str, Any] | None = None,
                 **settings: Any) -> None:
        s, spec, fld, bl = self._take_settings(settings)
        self.start = ShootoutStart.create(start)
        self.start.check_field(fld, spec.radius)
        self._build_learner(s, spec, fld, bl, n_blue=1, n_yellow=1)
        teams = self.world.teams
        self.builder = self._observation_builder([0])
        self.observation_space = self.builder.space()
        self._keeper_view = ObservationBuilder(self.field, teams, [1])
        self.keeper = ScriptedGoalkeeper(self.field, self.ball_spec, spec,
                                         self._keeper_view.names)
        self._goal = (float(self.field.half_length), 0.0)
        self._start_draw: dict[str, Any] | None = None

    # ------------------------------------------------------------------------------------
    # Task hooks
    # ------------------------------------------------------------------------------------

    def _place(self, rng: np.random.Generator) -> tuple[np.ndarray, tuple[float, float]]:
        self._start_draw = self.start.sample(rng, self.field, self.robot_spec.radius)
        s = self._start_draw
        return np.array([s["attacker"], s["keeper"]]), s["ball"]

    def _begin(self, rng: np.random.Generator) -> None:
        self._keeper_touched = False
        self._ball_to_goal = self._distance_to_goal(self.world.ball_array())

    def _others(self, actions: np.ndarray) -> None:
        belief = self._perception.belief(1)
        actions[1] = np.clip(self.keeper(self._keeper_view.build(belief)[0]), -1.0, 1.0)

    def _after_physics(self) -> None:
        touched = self.world.touched
        if touched[0]:
            self._keeper_touched = False
        if touched[1]:
            self._keeper_touched = True

    def _outcome(self, state: WorldState, event: Any = None) -> str | None:
        world = self.world
        exit_code = NO_EXIT
        if world.ball_exit is not None:
            kind = classify_exit(world.ball_exit, self.field, self.ball_spec)
            exit_code = EXIT_GOAL if kind.kind == "goal" and kind.end > 0 else EXIT_OUT
        ball = state.ball
        return SHOOTOUT_OUTCOMES[shootout_outcome(exit_code, self._keeper_touched,
                                                  world.ball_airborne, ball[3], ball[4])]

    def _success(self, outcome: str) -> bool:
        return outcome == "goal"

    def _reward_terms(self, state: WorldState, action: np.ndarray, outcome: str | None
                      ) -> dict[str, float]:
        sc = self.shaping
        terms = {"outcome": 0.0 if outcome is None else (1.0 if outcome == "goal" else -1.0)}
        b, a = state.ball, state.robots[0]
        (terms["ball_progress"], terms["ball_distance"], terms["action_cost"],
         self._ball_to_goal) = shootout_terms(
            (b[0], b[1]), (a[0], a[1]), self._goal, self._ball_to_goal,
            (float(action[0]), float(action[1]), float(action[2])),
            (float(sc["ball_progress"]), float(sc["ball_distance"]), float(sc["action_cost"])),
            self.world.control_dt)
        return terms

    def _task_info(self, info: dict[str, Any]) -> None:
        info["start"] = dict(self._start_draw)
        info["keeper_touched"] = self._keeper_touched

    def _flat_task_info(self, info: dict[str, float]) -> None:
        info["keeper_touched"] = 1.0 if self._keeper_touched else 0.0

    def _hud(self) -> list[str]:
        return [f"t = {self.world.time:5.2f} s", "shootout"]

    def _team_labels(self) -> tuple[str, str]:
        return ("blue: attacker 0", "yellow: scripted keeper 0")

    # ------------------------------------------------------------------------------------

    def _distance_to_goal(self, ball: np.ndarray) -> float:
        return goal_distance((ball[0], ball[1]), self._goal)
