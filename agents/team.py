"""A scripted team for the match: a keeper, an attacker and defenders, from observations only.

Every robot decides from its own observation vector (the layout of
:mod:`soccer_env.observations`, found by entry name), so the team runs on whatever the
observation mode provides (``"truth"``, ``"raw"`` or ``"perceived"``) and on either side
(observations are in each team's own frame, which attacks ``+x``). No state is kept between
steps: the same observations always give the same actions.

Roles, decided by each robot from the team-mates' relative positions in its observation (all
robots of a team read the same belief, so they agree):

* **keeper**: robot 0 when the team has two or more robots. It plays
  :class:`~soccer_env.envs.keeper.ScriptedGoalkeeper` (guard line in front of the goal, moving to
  where the ball's predicted path crosses it), except that it clears a slow ball lying in its
  own defense area, which no other robot may enter.
* **attacker**: the non-keeper robot with the lowest cost to reach the ball (distance, plus a
  penalty when it stands between the ball and the opponent goal). It drives to a point behind
  the ball on the line from an open point of the opponent goal mouth through the ball (the
  one needing the least repositioning), turns to face it, drives through the ball and arms
  its kicker while its heading points into the goal mouth past every opponent. When every
  shooting line is blocked by a nearby opponent it dribbles diagonally past it instead. It
  predicts a moving ball's position with :class:`~estimators.FrictionBallModel` and stays
  out of the own defense area.
* **defenders**: the others, in lines of up to three between the ball and the own goal,
  spread across the goal-ball line and kept out of the own defense area. They face the ball
  and clear it forward when it reaches their kicker.

Without the game flow, restarts are played like open play (the simple referee moves robots at
a restart but does not enforce the stop distance afterwards), and the opponent defense area is
not avoided. In a match with the game flow (``game=...``) the team reads the referee state
at the end of its observations and plays the restarts as the rules ask
(:mod:`agents.team_restarts`): keeping its distance at stop and at the opponents' restarts,
placing the ball with the dribbler, taking its kick-offs, free kicks and penalty kicks with
one kick no faster than the ball speed limit, and leaving the ball alone after taking a
restart until another robot has touched it.

All positions are in the team frame [m], headings in radians, speeds in m/s.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from agents.team_restarts import RestartPlay
from estimators import FrictionBallModel
from soccer_env import MAX_TEAM_SIZE, presets
from soccer_env.envs.keeper import (
    ScriptedGoalkeeper,
    drive_command,
    drive_commands,
    hypots,
    turn_command,
    turn_commands,
    wrap_angles,
)
from soccer_env.envs.match import GAME_FLOW_NAMES
from soccer_env.presets import BallSpec, FieldSpec, SSLRobotSpec
from soccer_env.presets.rules import RuleSpec

__all__ = ["ScriptedTeam", "TEAMS"]

#: How far the robot that took a restart keeps from the ball until another robot has touched
#: it, beyond a robot and a ball radius [m].
BARRED_CLEARANCE = 0.25
#: Team names accepted by :meth:`ScriptedTeam.for_env`, in team-index order.
TEAMS = ("blue", "yellow")


class ScriptedTeam(RestartPlay):
    """Scripted policy for one team of :class:`~soccer_env.envs.match.SoccerParallelEnv`.

    Args:
        field: the match's field (geometry).
        ball: the match's ball (its rolling deceleration).
        robot: the team's robot spec (its limits).
        names: the entry names of this team's observations
            (``env.builder.names_for(team_index)``).
        team_size: robots in the team (1 .. ``MAX_TEAM_SIZE``).
        prefix: agent name prefix (``"blue_"`` or ``"yellow_"``), used by :meth:`__call__`.
        guard_offset: keeper's guard line in front of the goal line, beyond its radius [m].
        attack_speed: speed [m/s] at which the attacker drives through the ball.
        defender_spacing: lateral distance between defenders of one line [m].
        exact: :meth:`act_batch` computes lengths as ``math.hypot`` does, bit for bit
            (:func:`~soccer_env.envs.keeper.hypots`), so that its actions equal :meth:`act`'s;
            False uses ``np.hypot``, which makes :meth:`act_batch` about 40 % faster and
            differs in the last bit for about one pair in 160 (the float32 actions almost
            always come out the same).
        rules: the rule preset whose distances and limits the team keeps at restarts when
            its observations carry the game flow (default ``"ssl-2025-div-b"``;
            :meth:`for_env` passes the match's).

    Use :meth:`for_env` to build it from a match. Calls:

    * ``team(observations)``: a dict ``{agent: obs}`` (agents of other teams are ignored) to
      ``{agent: action}`` for this team's agents in it;
    * ``team.act(obs_batch)``: ``(n, obs_dim)`` observations of robots ``0..n-1`` of the team
      (``n = team_size``) to ``(n, 6)`` float32 actions; what
      :class:`~agents.multiagent.MatchVecEnv` uses for an opponent;
    * ``team.act_batch(obs)``: the same for ``M`` matches at once, ``(M, n, obs_dim)`` to
      ``(M, n, 6)``, computed on whole arrays.
    """

    def __init__(self, field: FieldSpec, ball: BallSpec, robot: SSLRobotSpec,
                 names: Sequence[str], team_size: int, prefix: str = "blue_",
                 guard_offset: float = 0.05, attack_speed: float = 2.0,
                 defender_spacing: float = 0.45, exact: bool = True,
                 rules: str | RuleSpec | None = None) -> None:
        if not 1 <= int(team_size) <= MAX_TEAM_SIZE:
            raise ValueError(f"team_size must be 1..{MAX_TEAM_SIZE}, got {team_size}")
        index = {n: i for i, n in enumerate(names)}
        needed = ("self.x", "self.y", "self.ax", "self.ay", "ball.dx", "ball.dy", "ball.vx",
                  "ball.vy")
        missing = [n for n in needed if n not in index]
        if missing:
            raise ValueError(f"names lack the entries {missing}; pass the observation's entry "
                             "names (env.builder.names_for(team))")
        self.field, self.ball, self.robot = field, ball, robot
        self.team_size = int(team_size)
        self.prefix = prefix
        self.attack_speed = float(attack_speed)
        self.defender_spacing = float(defender_spacing)
        self.model = FrictionBallModel(ball.rolling_deceleration)
        self.has_keeper = self.team_size >= 2
        self.keeper = ScriptedGoalkeeper(field, ball, robot, names, guard_offset=guard_offset)
        self.exact = bool(exact)
        self._hypot = hypots if self.exact else np.hypot
        self.keeper.hypot = None if self.exact else np.hypot
        self._idx = [index[n] for n in needed]
        n_mates = sum(1 for n in names if n.startswith("mate") and n.endswith(".dx"))
        if n_mates != self.team_size - 1:
            raise ValueError(f"the observation names list {n_mates} team-mates, a team of "
                             f"{self.team_size} needs {self.team_size - 1}")
        self._mate_idx = [(index[f"mate{j}.dx"], index[f"mate{j}.dy"]) for j in range(n_mates)]
        n_opps = sum(1 for n in names if n.startswith("opp") and n.endswith(".dx"))
        self._opp_idx = [(index[f"opp{j}.dx"], index[f"opp{j}.dy"]) for j in range(n_opps)]
        self.obs_size = len(names)
        # The game flow's referee state, when the observations carry it.
        self._game = ({n: index[n] for n in GAME_FLOW_NAMES}
                      if all(n in index for n in GAME_FLOW_NAMES) else None)
        self._rules = presets.rules(rules if rules is not None else "ssl-2025-div-b")
        # Kicker power of every kick: full without the game flow; with it, 0.2 m/s under
        # the ball speed limit (8.4.2).
        self._kick_power = 1.0 if self._game is None else min(
            1.0, (self._rules.ball_speed_limit - 0.2) / robot.kicker_max_speed)
        # Geometry (team frame).
        hx, hy = field.half_length, field.half_width
        r = robot.radius
        self._goal_x = hx
        self._half_goal = 0.5 * field.goal_width
        # Aim points across the goal mouth, a ball radius and 5 cm inside the posts [m].
        inner = self._half_goal - ball.radius - 0.05
        self._aim_ys = [inner * f for f in (-1.0, -0.5, 0.0, 0.5, 1.0)]
        # Sideways offset [m] over which the attacker's alignment with the ball fades out, and
        # how far beyond the ball it drives when lined up [m].
        self._lateral_scale = 0.06
        self._through = 0.4
        # Dribbling direction off the goal direction when every shot is blocked by a nearby
        # opponent: 60 degrees to either side.
        self._escape_cos, self._escape_sin = 0.5, math.sqrt(3.0) / 2.0
        # Defenders per line.
        self._per_line = 3
        # Kicker-centre to ball-centre distance with the ball touching the front [m].
        self._contact = robot.front_distance + ball.radius
        # Keep-out rectangle of the own defense area for the robot centre [m].
        self._def_front = -hx + field.defense_depth + r + 0.05
        self._def_side = 0.5 * field.defense_width + r + 0.05
        # Walls minus a robot radius: targets are clipped into this box [m].
        self._lim_x = hx + field.boundary - r - 0.02
        self._lim_y = hy + field.boundary - r - 0.02

    @classmethod
    def for_env(cls, env: Any, team: str = "blue", **kwargs: Any) -> ScriptedTeam:
        """Build the team ``"blue"`` or ``"yellow"`` of a (possibly wrapped) match."""
        if team not in TEAMS:
            raise ValueError(f"team must be one of {list(TEAMS)}, got {team!r}")
        u = getattr(env, "unwrapped", env)
        t = TEAMS.index(team)
        size = int(u.world.n_blue if t == 0 else u.world.n_yellow)
        if size < 1:
            raise ValueError(f"the {team} team of this match has no robots")
        # In a mixed match each team has its own robot model.
        spec = u.team_specs[t] if hasattr(u, "team_specs") else u.robot_spec
        game_rules = getattr(u, "game_rules", None)
        if isinstance(game_rules, RuleSpec):
            kwargs.setdefault("rules", game_rules)
        return cls(u.field, u.ball_spec, spec, u.builder.names_for(t), size,
                   prefix=f"{team}_", **kwargs)

    # ------------------------------------------------------------------------------------

    def __call__(self, observations: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Actions ``{agent: (6,) float32}`` for this team's agents in ``observations``."""
        out = {}
        p = self.prefix
        for agent, obs in observations.items():
            if agent.startswith(p):
                out[agent] = np.asarray(self.act_one(obs, int(agent[len(p):])),
                                        dtype=np.float32)
        return out

    def act(self, obs_batch: np.ndarray) -> np.ndarray:
        """Actions ``(team_size, 6)`` float32 for observations ``(team_size, obs_dim)`` of
        robots ``0 .. team_size - 1`` in order."""
        obs_batch = np.asarray(obs_batch)
        if obs_batch.shape != (self.team_size, self.obs_size):
            raise ValueError(f"obs_batch must have shape ({self.team_size}, {self.obs_size}) "
                             f"(one row per robot of the team, in order), got "
                             f"{obs_batch.shape}")
        return np.array([self.act_one(o, i) for i, o in enumerate(obs_batch.tolist())],
                        dtype=np.float32)

    def act_batch(self, obs: np.ndarray) -> np.ndarray:
        """Actions ``(M, team_size, 6)`` float32 for the observations ``(M, team_size,
        obs_dim)`` (float32 or float64) of the team's robots ``0 .. team_size - 1`` in ``M``
        matches: ``np.stack([self.act(o) for o in obs])``, computed on all ``M * team_size``
        rows at once (``M = 0`` gives an empty array).

        Each row goes through the same arithmetic in the same order as :meth:`act_one`
        (:func:`~soccer_env.envs.keeper.hypots` computes ``math.hypot``'s bits,
        :func:`~soccer_env.envs.keeper.wrap_angles` ``math.remainder``'s, ``np.float_power``
        the C library's ``pow``), except that ``np.arctan2`` stands for ``math.atan2``: it can
        differ in the last bit of a float64 heading, which the float32 actions absorb except
        in very rare cases (a last-bit difference in a turn rate or velocity).
        """
        obs = np.asarray(obs)
        if obs.ndim != 3 or obs.shape[1:] != (self.team_size, self.obs_size):
            raise ValueError(f"obs must have shape (M, {self.team_size}, {self.obs_size}) (M "
                             f"matches, one row per robot of the team, in order), got "
                             f"{obs.shape}")
        rows = obs.reshape(-1, self.obs_size)
        index = np.tile(np.arange(self.team_size), obs.shape[0])
        if self._game is not None:
            special = self._needs_restart_play(rows)
            if special.any():
                # Restarts (and the rare rows that must leave the ball alone) row by row.
                out = np.empty((len(rows), 6), dtype=np.float32)
                plain = ~special
                if plain.any():
                    out[plain] = self._act_rows(rows[plain], index[plain])
                for k in np.flatnonzero(special):
                    out[k] = self.act_one(rows[k], int(index[k]))
                return out.reshape(obs.shape[:2] + (6,))
        return self._act_rows(rows, index).reshape(obs.shape[:2] + (6,))

    def act_one(self, obs: np.ndarray | Sequence[float], index: int) -> list[float]:
        """Action ``[vx, vy, omega, kick, chip, dribble]`` of robot ``index`` of the team from
        its own observation ``obs``."""
        if not 0 <= index < self.team_size:
            raise ValueError(f"index must be in 0..{self.team_size - 1}, got {index}")
        o = obs.tolist() if isinstance(obs, np.ndarray) else list(obs)
        px, py, c, neg_s, dx, dy, bvx_b, bvy_b = (o[i] for i in self._idx)
        s = -neg_s  # self.ay is -sin(heading)
        # Ball in the team frame.
        bx, by = px + c * dx - s * dy, py + s * dx + c * dy
        bvx, bvy = c * bvx_b - s * bvy_b, s * bvx_b + c * bvy_b
        # Opponents in the team frame.
        opps = [(px + c * mx - s * my, py + s * mx + c * my)
                for mx, my in ((o[ix], o[iy]) for ix, iy in self._opp_idx)]
        if self._game is not None and self._needs_restart_play(o):
            xs, ys = self._team_positions(o, index, px, py, c, s)
            return self._restart(o, index, px, py, c, s, bx, by, bvx, bvy, dx, dy, xs, ys,
                                 opps)
        if self.has_keeper and index == 0:
            if self._keeper_should_clear(bx, by, bvx, bvy):
                return self._attack(px, py, c, s, bx, by, bvx, bvy, dx, dy, opps, keeper=True)
            action = self.keeper(o).tolist()  # it reads entries by index: a list will do
            action[3] = min(action[3], self._kick_power)
            return action
        xs, ys = self._team_positions(o, index, px, py, c, s)
        role, rank, n_def = self._role(index, xs, ys, bx, by)
        if role == "attacker":
            return self._attack(px, py, c, s, bx, by, bvx, bvy, dx, dy, opps)
        return self._defend(px, py, c, s, bx, by, dx, dy, rank, n_def)

    def _team_positions(self, o: list[float], index: int, px: float, py: float, c: float,
                        s: float) -> tuple[list[float], list[float]]:
        """The team's robots in the team frame, indexed by robot (self included) [m]."""
        xs, ys = [0.0] * self.team_size, [0.0] * self.team_size
        xs[index], ys[index] = px, py
        for j, (ix, iy) in enumerate(self._mate_idx):
            k = j if j < index else j + 1
            mx, my = o[ix], o[iy]
            xs[k], ys[k] = px + c * mx - s * my, py + s * mx + c * my
        return xs, ys

    def _open_play(self, o: list[float], index: int, px: float, py: float, c: float,
                   s: float, bx: float, by: float, bvx: float, bvy: float, dx: float,
                   dy: float, xs: list[float], ys: list[float],
                   opps: list[tuple[float, float]], barred: int) -> list[float]:
        """Open play when robot ``barred`` of the team (-1: none) may not touch the ball:
        it defends without clearing the ball, and another robot attacks."""
        if self.has_keeper and index == 0 and barred != 0:
            if self._keeper_should_clear(bx, by, bvx, bvy):
                return self._attack(px, py, c, s, bx, by, bvx, bvy, dx, dy, opps, keeper=True)
            action = self.keeper(o).tolist()
            action[3] = min(action[3], self._kick_power)
            return action
        if index == barred:
            # It defends from the first slot, keeping off the ball's path: at least
            # BARRED_CLEARANCE from it, going round it.
            first = 1 if self.has_keeper else 0
            n_def = max(1, self.team_size - first - 1)
            tx, ty = self._defend_target(bx, by, 0, n_def)
            keep = self.robot.radius + self.ball.radius + BARRED_CLEARANCE
            reach = min(math.hypot(bx - px, by - py) / self.robot.max_speed, 1.0)
            if bvx * bvx + bvy * bvy > 1e-4:  # where the ball will be
                bx, by = (float(v) for v in self.model.predict(np.array([bx, by, bvx, bvy]),
                                                               reach)[0:2])
            tx, ty = self._clear_of(tx, ty, bx, by, keep)
            if math.hypot(px - bx, py - by) < keep:
                tx, ty = self._clear_of(px, py, bx, by, keep + 0.05)
            else:
                tx, ty = self._around_ball(px, py, tx, ty, bx, by, keep, 0.05)
            tx, ty = self._outside_defense_area(tx, ty)
            r = self.robot
            vx, vy = drive_command(px, py, c, s, tx, ty, r.max_speed, r.max_acceleration)
            omega = turn_command(c, s, math.atan2(by - py, bx - px), r.max_angular_speed)
            return [vx / r.max_speed, vy / r.max_speed, omega, 0.0, -1.0, -1.0]
        role, rank, n_def = self._role(index, xs, ys, bx, by, barred)
        if role == "attacker":
            return self._attack(px, py, c, s, bx, by, bvx, bvy, dx, dy, opps)
        return self._defend(px, py, c, s, bx, by, dx, dy, rank, n_def)

    # ------------------------------------------------------------------------------------

    def _role(self, index: int, xs: list[float], ys: list[float], bx: float, by: float,
              barred: int = -1) -> tuple[str, int, int]:
        """``(role, rank, defenders)``: this robot's role, its rank among the defenders and
        their number (robot ``barred`` is never the attacker)."""
        first = 1 if self.has_keeper else 0
        field_players = range(first, self.team_size)
        # Cost to take the ball [m]: distance to the point behind the ball on the line from
        # the opponent goal centre, plus a penalty for standing goal-side of the ball (the
        # robot would have to go round it). A robot passing the ball on its way elsewhere
        # does not steal the role from one already lined up behind it.
        ex, ey = self._goal_x - bx, -by
        d = math.hypot(ex, ey) or 1.0
        ex, ey = ex / d, ey / d
        back = self._contact + 0.12
        qx, qy = bx - back * ex, by - back * ey
        best, attacker = math.inf, -1
        for k in field_players:
            if k == barred:
                continue
            ahead = (xs[k] - bx) * ex + (ys[k] - by) * ey > self._contact
            cost = math.hypot(xs[k] - qx, ys[k] - qy) + (0.5 if ahead else 0.0)
            if cost < best:
                best, attacker = cost, k
        if index == attacker:
            return "attacker", 0, 0
        defenders = [k for k in field_players if k != attacker]
        # Lines of up to three by robot index (so that a robot keeps its line); within a
        # line, slots by lateral position across the goal-ball line, so that defenders do not
        # cross each other's paths to their slots.
        per = self._per_line
        start = defenders.index(index) // per * per
        line = defenders[start:start + per]
        ox = -self._goal_x
        fx, fy = bx - ox, by
        norm = math.hypot(fx, fy) or 1.0
        nx, ny = -fy / norm, fx / norm
        line.sort(key=lambda k: ((xs[k] - ox) * nx + ys[k] * ny, k))
        return "defender", start + line.index(index), len(defenders)

    def _keeper_should_clear(self, bx: float, by: float, bvx: float, bvy: float) -> bool:
        """A slow ball inside the own defense area: only the keeper may fetch it."""
        f = self.field
        inside = bx < -self._goal_x + f.defense_depth and abs(by) < 0.5 * f.defense_width
        return inside and bx > -self._goal_x and math.hypot(bvx, bvy) < 0.5

    def _attack(self, px: float, py: float, c: float, s: float, bx: float, by: float,
                bvx: float, bvy: float, dx: float, dy: float, opps: list[tuple[float, float]],
                keeper: bool = False) -> list[float]:
        """Go behind the ball on the line from the aim point through the ball, face the aim,
        drive through the ball and shoot when the heading points into the open goal mouth.
        Only the ``keeper`` may enter the own defense area."""
        r = self.robot
        # Where the ball will be when we get there (at most a second ahead).
        reach = min(math.hypot(bx - px, by - py) / r.max_speed, 1.0)
        if bvx * bvx + bvy * bvy > 1e-4:
            bx, by = (float(v) for v in self.model.predict(np.array([bx, by, bvx, bvy]),
                                                           reach)[0:2])
        (ax, ay), shoot = self._aim(px, py, bx, by, opps)
        ex, ey = ax - bx, ay - by
        d_aim = math.hypot(ex, ey) or 1.0
        ex, ey = ex / d_aim, ey / d_aim  # ball -> aim point
        nx, ny = -ey, ex
        along = (px - bx) * ex + (py - by) * ey  # < 0: behind the ball
        lateral = (px - bx) * nx + (py - by) * ny
        face = math.atan2(ey, ex)
        heading_err = abs(math.remainder(face - math.atan2(s, c), 2.0 * math.pi))
        contact = self._contact
        cap = None
        if along > -contact and abs(lateral) < contact + r.radius + 0.05:
            # In front of or beside the ball: step round it on the near side first.
            side = 1.0 if lateral >= 0.0 else -1.0
            clear = r.radius + self.ball.radius + 0.12
            tx, ty = bx + side * clear * nx - 0.1 * ex, by + side * clear * ny - 0.1 * ey
        else:
            # Behind the ball: the better lined up (sideways offset and heading), the further
            # forward the target, from a waiting point behind the ball to a point beyond it.
            align = (max(0.0, 1.0 - abs(lateral) / self._lateral_scale)
                     * max(0.0, 1.0 - heading_err / 0.5)) ** 2
            back = contact + 0.12 - (contact + 0.12 + self._through) * align
            tx, ty = bx - back * ex, by - back * ey
            if align > 0.25:
                cap = self.attack_speed
        if not keeper:
            tx, ty = self._outside_defense_area(tx, ty)
        if self._game is not None:  # touching the ball partly inside it is a foul (8.4.2)
            tx, ty = self._outside_opponent_defense(tx, ty, r.radius + 0.03)
        tx = max(-self._lim_x, min(self._lim_x, tx))
        ty = max(-self._lim_y, min(self._lim_y, ty))
        vx, vy = drive_command(px, py, c, s, tx, ty, r.max_speed, r.max_acceleration, cap)
        omega = turn_command(c, s, face, r.max_angular_speed)
        kick = self._kick_power if shoot and dx > 0.0 and self._on_target(px, py, c, s, opps) \
            else 0.0
        return [vx / r.max_speed, vy / r.max_speed, omega, kick, -1.0, -1.0]

    def _aim(self, px: float, py: float, bx: float, by: float,
             opps: list[tuple[float, float]]) -> tuple[tuple[float, float], bool]:
        """Where to send the ball: ``((x, y), shoot)``.

        Candidates are points spread across the opponent goal mouth; a candidate is open if
        no opponent stands within a robot radius plus a ball radius (and a margin growing
        with distance) of the line from the ball to it. Among the open ones the attacker
        takes the one needing the least repositioning (its current bearing from the ball).
        If none is open (``shoot`` False), it carries the ball towards the goal centre while
        the blockers are more than a metre away, and otherwise dribbles it 60 degrees off the
        goal direction, to the side with more room.
        """
        best, best_cost = None, math.inf
        rbx, rby = bx - px, by - py  # robot -> ball, the current approach direction
        norm = math.hypot(rbx, rby) or 1.0
        rbx, rby = rbx / norm, rby / norm
        for ty in self._aim_ys:
            clearance = self._clearance(bx, by, self._goal_x, ty, opps)
            if clearance <= 0.0:
                continue
            ex, ey = self._goal_x - bx, ty - by
            d = math.hypot(ex, ey) or 1.0
            # Turning cost (1 - cos of the angle between approach and shot), minus a bonus
            # for clearance.
            cost = 1.0 - (rbx * ex + rby * ey) / d - 0.5 * min(clearance, 0.5)
            if cost < best_cost:
                best, best_cost = (self._goal_x, ty), cost
        if best is not None:
            return best, True
        # Blocked. With the blocker far away, carry the ball towards the goal centre (an
        # opening may appear); with it close, dribble diagonally forward on the side with
        # more room, preferring the side the robot already stands behind (so that it does
        # not hesitate between two equal sides).
        if self._nearest_ahead(bx, by, opps) > 1.0:
            return (self._goal_x, 0.0), False
        gx, gy = self._goal_x - bx, -by
        d = math.hypot(gx, gy) or 1.0
        gx, gy = gx / d, gy / d
        options = []
        for sign in (1.0, -1.0):
            cos_a, sin_a = self._escape_cos, sign * self._escape_sin
            ux, uy = gx * cos_a - gy * sin_a, gx * sin_a + gy * cos_a
            tx, ty = bx + ux, by + uy
            room = min(self._clearance(bx, by, tx, ty, opps), 0.3)
            inside = abs(ty) < self.field.half_width - 0.3
            behind = rbx * ux + rby * uy  # > 0: the robot is behind the ball for u
            options.append((room + (0.0 if inside else -1.0) + 0.5 * behind, (tx, ty)))
        return max(options)[1], False

    def _nearest_ahead(self, bx: float, by: float, opps: list[tuple[float, float]]) -> float:
        """Distance [m] from the ball to the nearest opponent nearer the opponent goal."""
        return min((math.hypot(ox - bx, oy - by) for ox, oy in opps if ox > bx - 0.1),
                   default=math.inf)

    def _clearance(self, bx: float, by: float, tx: float, ty: float,
                   opps: list[tuple[float, float]]) -> float:
        """Smallest gap [m] between the segment from the ball ``(bx, by)`` to ``(tx, ty)`` and
        an opponent, beyond a robot radius, a ball radius and a margin of 3 % of the
        opponent's distance along the segment (it can move while the ball travels); positive
        means open."""
        ex, ey = tx - bx, ty - by
        length = math.hypot(ex, ey) or 1e-9
        ex, ey = ex / length, ey / length
        reach = self.robot.radius + self.ball.radius
        gap = math.inf
        for ox, oy in opps:
            t = (ox - bx) * ex + (oy - by) * ey
            if t < -reach or t > length + reach:
                continue
            perp = abs((ox - bx) * ey - (oy - by) * ex)
            gap = min(gap, perp - reach - 0.02 - 0.03 * max(t, 0.0))
        return gap

    def _on_target(self, px: float, py: float, c: float, s: float,
                   opps: list[tuple[float, float]]) -> bool:
        """Whether the robot's heading line crosses the opponent goal mouth (a ball radius
        plus 3 cm inside each post) with no opponent on the way."""
        if c < 0.2:
            return False
        y_goal = py + s / c * (self._goal_x - px)
        if abs(y_goal) >= self._half_goal - self.ball.radius - 0.03:
            return False
        return self._clearance(px, py, self._goal_x, y_goal, opps) > 0.0

    def _defend_target(self, bx: float, by: float, rank: int, n_def: int
                       ) -> tuple[float, float]:
        """Slot ``rank`` of ``n_def`` defenders between the ball and the own goal [m]."""
        r = self.robot
        ox = -self._goal_x
        fx, fy = bx - ox, by
        d_ball = math.hypot(fx, fy) or 1e-3
        fx, fy = fx / d_ball, fy / d_ball  # own goal -> ball
        nx, ny = -fy, fx
        per_line = self._per_line
        line, slot = divmod(rank, per_line)
        in_line = min(per_line, n_def - line * per_line)
        base = max(self.field.defense_depth + r.radius + 0.4, 0.45 * d_ball)
        dist = min(base + 0.9 * line, max(d_ball - 0.6, self.field.defense_depth + 0.3))
        offset = (slot - 0.5 * (in_line - 1)) * self.defender_spacing * (1 + line)
        return ox + dist * fx + offset * nx, dist * fy + offset * ny

    def _defend(self, px: float, py: float, c: float, s: float, bx: float, by: float,
                dx: float, dy: float, rank: int, n_def: int) -> list[float]:
        """Hold slot ``rank`` of ``n_def`` between the ball and the own goal."""
        r = self.robot
        tx, ty = self._defend_target(bx, by, rank, n_def)
        tx, ty = self._around_ball(px, py, tx, ty, bx, by)
        tx, ty = self._outside_defense_area(tx, ty)
        tx = max(-self._lim_x, min(self._lim_x, tx))
        ty = max(-self._lim_y, min(self._lim_y, ty))
        vx, vy = drive_command(px, py, c, s, tx, ty, r.max_speed, r.max_acceleration)
        omega = turn_command(c, s, math.atan2(by - py, bx - px), r.max_angular_speed)
        # Clear the ball forward if it reaches the kicker while we face the opponent half.
        in_front = 0.0 < dx < r.front_distance + 0.1 and abs(dy) < 0.5 * r.kicker_width
        kick = self._kick_power if in_front and c > 0.3 else 0.0
        return [vx / r.max_speed, vy / r.max_speed, omega, kick, -1.0, -1.0]

    def _around_ball(self, px: float, py: float, tx: float, ty: float, bx: float, by: float,
                     clear: float | None = None, pad: float = 0.0) -> tuple[float, float]:
        """A waypoint beside the ball, ``clear + pad`` from it, if the straight path from
        ``(px, py)`` to ``(tx, ty)`` passes within ``clear`` of the ball (default a robot
        radius, a ball radius and 15 cm), else the target (a defender on its way to its slot
        must not knock the ball about)."""
        ux, uy = tx - px, ty - py
        length = math.hypot(ux, uy)
        if length < 1e-6:
            return tx, ty
        ux, uy = ux / length, uy / length
        if clear is None:
            clear = self.robot.radius + self.ball.radius + 0.15
        along = (bx - px) * ux + (by - py) * uy
        side = (px - bx) * -uy + (py - by) * ux  # the robot's side of the ball, along n
        if not 0.0 < along < length or abs(side) >= clear:
            return tx, ty
        sign = 1.0 if side >= 0.0 else -1.0
        return bx - sign * (clear + pad) * uy, by + sign * (clear + pad) * ux

    def _outside_defense_area(self, x: float, y: float) -> tuple[float, float]:
        """Move a target inside the own defense area (widened by a robot radius and 5 cm) to
        the nearest point on its edge."""
        ox = -self._goal_x
        if x >= self._def_front or abs(y) >= self._def_side:
            return x, y
        to_front = self._def_front - x
        to_side = self._def_side - abs(y)
        if to_front <= to_side or x < ox:
            return self._def_front, y
        return x, math.copysign(self._def_side, y if y != 0.0 else 1.0)

    # ------------------------------------------------------------------------------------
    # The same on arrays: one element per robot row (see act_batch).

    def _act_rows(self, obs: np.ndarray, index: np.ndarray) -> np.ndarray:
        """Actions ``(n, 6)`` float32 for ``n`` observation rows ``(n, obs_dim)`` of robots
        ``index`` (``(n,)`` ints): :meth:`act_one` row by row."""
        o = np.asarray(obs, dtype=np.float64).T  # one entry per row
        px, py, c, neg_s, dx, dy, bvx_b, bvy_b = o[self._idx]
        s = -neg_s  # self.ay is -sin(heading)
        # Ball in the team frame.
        bx, by = px + c * dx - s * dy, py + s * dx + c * dy
        bvx, bvy = c * bvx_b - s * bvy_b, s * bvx_b + c * bvy_b
        # Opponents in the team frame, (n_opps, n).
        mx, my = o[[i for i, _ in self._opp_idx]], o[[j for _, j in self._opp_idx]]
        opps = (px + c * mx - s * my, py + s * mx + c * my)
        frame = (px, py, c, s, bx, by, bvx, bvy, dx, dy)
        out = np.empty((len(index), 6), dtype=np.float32)
        attack = np.zeros(len(index), dtype=bool)
        clear = np.zeros(len(index), dtype=bool)
        field = np.ones(len(index), dtype=bool)
        if self.has_keeper:
            keeper = index == 0
            clear = keeper & self._keeper_should_clear_rows(bx, by, bvx, bvy)
            guard = keeper & ~clear
            out[guard] = self.keeper.act_batch(obs[guard])
            if self._kick_power < 1.0:
                out[guard, 3] = np.minimum(out[guard, 3], self._kick_power)
            attack |= clear
            field = ~keeper
        if field.any():
            # Team-mates in the team frame, indexed by robot (self included), (team_size, n).
            xs = np.empty((self.team_size, len(index)))
            ys = np.empty_like(xs)
            for k in range(self.team_size):
                # Robot k is mate k of the robots after it and mate k - 1 of those before.
                xs[k], ys[k] = px, py
                for j, rows in ((k, index > k), (k - 1, index < k)):
                    if 0 <= j < len(self._mate_idx) and rows.any():
                        ix, iy = self._mate_idx[j]
                        xs[k, rows] = (px + c * o[ix] - s * o[iy])[rows]
                        ys[k, rows] = (py + s * o[ix] + c * o[iy])[rows]
            sub = (index[field], xs[:, field], ys[:, field], bx[field], by[field])
            is_attacker, rank = self._role_rows(*sub)
            attack[field] = is_attacker
            defend = np.flatnonzero(field)[~is_attacker]
            if len(defend):
                out[defend] = self._defend_rows(*(v[defend] for v in frame[:6]),
                                                *(v[defend] for v in frame[8:]),
                                                rank[~is_attacker])
        if attack.any():
            out[attack] = self._attack_rows(*(v[attack] for v in frame),
                                            tuple(v[:, attack] for v in opps),
                                            clear[attack])
        return out

    def _role_rows(self, index: np.ndarray, xs: np.ndarray, ys: np.ndarray, bx: np.ndarray,
                   by: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_role` for field-player rows: ``(attacker, rank)``, whether each row's robot
        is the attacker, and else its rank among the defenders. ``xs``, ``ys``: the team's
        robots in the team frame as each row sees them, ``(team_size, n)`` [m]."""
        first = 1 if self.has_keeper else 0
        ex, ey = self._goal_x - bx, -by
        d = self._hypot(ex, ey)
        d = np.where(d == 0.0, 1.0, d)
        ex, ey = ex / d, ey / d
        back = self._contact + 0.12
        qx, qy = bx - back * ex, by - back * ey
        # The first field player of least cost (act_one's strict "<" keeps the first).
        ahead = (xs[first:] - bx) * ex + (ys[first:] - by) * ey > self._contact
        cost = self._hypot(xs[first:] - qx, ys[first:] - qy) + np.where(ahead, 0.5, 0.0)
        attacker = first + np.argmin(cost, axis=0)
        is_attacker = index == attacker
        # Defenders: the field players but the attacker, by index; lines of up to three
        # (position // per), within a line slots by (lateral position, index).
        per = self._per_line
        position = index - first - (attacker < index)
        ox = -self._goal_x
        fx, fy = bx - ox, by
        norm = self._hypot(fx, fy)
        norm = np.where(norm == 0.0, 1.0, norm)
        nx, ny = -fy / norm, fx / norm
        cols = np.arange(len(index))
        mine = (xs[index, cols] - ox) * nx + ys[index, cols] * ny
        rank = position // per * per
        for p in range(self.team_size - first - 1):
            k = first + p + (first + p >= attacker)
            lateral = (xs[k, cols] - ox) * nx + ys[k, cols] * ny
            before = (lateral < mine) | ((lateral == mine) & (k < index))
            rank = rank + (before & (p // per == position // per))
        return is_attacker, rank

    def _keeper_should_clear_rows(self, bx: np.ndarray, by: np.ndarray, bvx: np.ndarray,
                                  bvy: np.ndarray) -> np.ndarray:
        """:meth:`_keeper_should_clear` on arrays."""
        f = self.field
        inside = (bx < -self._goal_x + f.defense_depth) & (np.abs(by) < 0.5 * f.defense_width)
        return inside & (bx > -self._goal_x) & (self._hypot(bvx, bvy) < 0.5)

    def _attack_rows(self, px: np.ndarray, py: np.ndarray, c: np.ndarray, s: np.ndarray,
                     bx: np.ndarray, by: np.ndarray, bvx: np.ndarray, bvy: np.ndarray,
                     dx: np.ndarray, dy: np.ndarray, opps: tuple[np.ndarray, np.ndarray],
                     keeper: np.ndarray) -> np.ndarray:
        """:meth:`_attack` on arrays: actions ``(n, 6)``; ``opps``: opponents' ``(x, y)`` in
        the team frame, each ``(n_opps, n)`` [m]; ``keeper``: rows that may enter the own
        defense area."""
        r = self.robot
        reach = np.minimum(self._hypot(bx - px, by - py) / r.max_speed, 1.0)
        moving = bvx * bvx + bvy * bvy > 1e-4
        if moving.any():
            ahead = self.model.predict(np.stack([bx, by, bvx, bvy], axis=-1)[moving],
                                       reach[moving])
            bx, by = bx.copy(), by.copy()
            bx[moving], by[moving] = ahead[:, 0], ahead[:, 1]
        ax, ay, shoot = self._aim_rows(px, py, bx, by, opps)
        ex, ey = ax - bx, ay - by
        d_aim = self._hypot(ex, ey)
        d_aim = np.where(d_aim == 0.0, 1.0, d_aim)
        ex, ey = ex / d_aim, ey / d_aim  # ball -> aim point
        nx, ny = -ey, ex
        along = (px - bx) * ex + (py - by) * ey  # < 0: behind the ball
        lateral = (px - bx) * nx + (py - by) * ny
        face = np.arctan2(ey, ex)
        heading_err = np.abs(wrap_angles(face - np.arctan2(s, c)))
        contact = self._contact
        beside = (along > -contact) & (np.abs(lateral) < contact + r.radius + 0.05)
        # In front of or beside the ball: step round it on the near side first.
        side = np.where(lateral >= 0.0, 1.0, -1.0)
        clear = r.radius + self.ball.radius + 0.12
        tx_round = bx + side * clear * nx - 0.1 * ex
        ty_round = by + side * clear * ny - 0.1 * ey
        # Behind the ball: the better lined up, the further forward the target. Python's
        # ``** 2`` is the C library's pow, which np.float_power calls (x * x can differ).
        align = np.float_power(np.maximum(0.0, 1.0 - np.abs(lateral) / self._lateral_scale)
                               * np.maximum(0.0, 1.0 - heading_err / 0.5), 2.0)
        back = contact + 0.12 - (contact + 0.12 + self._through) * align
        tx = np.where(beside, tx_round, bx - back * ex)
        ty = np.where(beside, ty_round, by - back * ey)
        cap = np.where(~beside & (align > 0.25), self.attack_speed, r.max_speed)
        outside_x, outside_y = self._outside_defense_area_rows(tx, ty)
        tx, ty = np.where(keeper, tx, outside_x), np.where(keeper, ty, outside_y)
        if self._game is not None:  # touching the ball partly inside it is a foul (8.4.2)
            tx, ty = self._outside_opponent_defense_rows(tx, ty, r.radius + 0.03)
        tx = np.clip(tx, -self._lim_x, self._lim_x)
        ty = np.clip(ty, -self._lim_y, self._lim_y)
        vx, vy = drive_commands(px, py, c, s, tx, ty, r.max_speed, r.max_acceleration, cap,
                                hypot=self._hypot)
        out = np.empty((len(px), 6))
        out[:, 0], out[:, 1] = vx / r.max_speed, vy / r.max_speed
        out[:, 2] = turn_commands(c, s, face, r.max_angular_speed)
        out[:, 3] = (shoot & (dx > 0.0) & self._on_target_rows(px, py, c, s, opps)) \
            * self._kick_power
        out[:, 4:] = -1.0
        return out

    def _aim_rows(self, px: np.ndarray, py: np.ndarray, bx: np.ndarray, by: np.ndarray,
                  opps: tuple[np.ndarray, np.ndarray]
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`_aim` on arrays: ``(x, y, shoot)`` [m]."""
        rbx, rby = bx - px, by - py  # robot -> ball, the current approach direction
        norm = self._hypot(rbx, rby)
        norm = np.where(norm == 0.0, 1.0, norm)
        rbx, rby = rbx / norm, rby / norm
        # All aim points at once, (5, n); the first open one of least cost.
        aim_ys = np.array(self._aim_ys)[:, None]
        ex, ey = np.broadcast_arrays(self._goal_x - bx, aim_ys - by)
        d = self._hypot(ex, ey)  # also the length of the shooting lines, for _clearance
        clearance = self._clearance_rows(bx, by, self._goal_x, aim_ys, opps, d)
        d = np.where(d == 0.0, 1.0, d)
        cost = 1.0 - (rbx * ex + rby * ey) / d - 0.5 * np.minimum(clearance, 0.5)
        open_ = clearance > 0.0
        shoot = open_.any(axis=0)
        ax = np.full(len(px), self._goal_x)
        ay = aim_ys[np.argmin(np.where(open_, cost, math.inf), axis=0), 0]
        blocked = np.flatnonzero(~shoot)
        if len(blocked) == 0:
            return ax, ay, shoot
        # Blocked: towards the goal centre while the blockers are far, else the escape side.
        bx, by, rbx, rby = bx[blocked], by[blocked], rbx[blocked], rby[blocked]
        opps = (opps[0][:, blocked], opps[1][:, blocked])
        gx, gy = self._goal_x - bx, -by
        d = self._hypot(gx, gy)
        d = np.where(d == 0.0, 1.0, d)
        gx, gy = gx / d, gy / d
        # Both sides at once, (2, n): sign +1 first.
        cos_a, sin_a = self._escape_cos, np.array([[1.0], [-1.0]]) * self._escape_sin
        ux, uy = gx * cos_a - gy * sin_a, gx * sin_a + gy * cos_a
        tx, ty = bx + ux, by + uy
        room = np.minimum(self._clearance_rows(bx, by, tx, ty, opps), 0.3)
        inside = np.abs(ty) < self.field.half_width - 0.3
        behind = rbx * ux + rby * uy  # > 0: the robot is behind the ball for u
        score = room + np.where(inside, 0.0, -1.0) + 0.5 * behind
        # max() of (score, (x, y)) tuples: the second side only if strictly greater.
        (s0, s1), (x0, x1), (y0, y1) = score, tx, ty
        second = (s1 > s0) | ((s1 == s0) & ((x1 > x0) | ((x1 == x0) & (y1 > y0))))
        far = self._nearest_ahead_rows(bx, by, opps) > 1.0
        ax[blocked] = np.where(far, self._goal_x, np.where(second, x1, x0))
        ay[blocked] = np.where(far, 0.0, np.where(second, y1, y0))
        return ax, ay, shoot

    def _nearest_ahead_rows(self, bx: np.ndarray, by: np.ndarray,
                            opps: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
        """:meth:`_nearest_ahead` on arrays [m]."""
        ox, oy = opps
        d = np.where(ox > bx - 0.1, self._hypot(ox - bx, oy - by), math.inf)
        return np.min(d, axis=0, initial=math.inf)

    def _clearance_rows(self, bx: np.ndarray, by: np.ndarray, tx: np.ndarray | float,
                        ty: np.ndarray | float, opps: tuple[np.ndarray, np.ndarray],
                        length: np.ndarray | None = None) -> np.ndarray:
        """:meth:`_clearance` on arrays [m], for ``k`` targets per row at once: ``tx``, ``ty``
        broadcast to ``(k, n)`` against the balls ``(n,)``; returns ``(k, n)``. ``length``:
        ``hypots(tx - bx, ty - by)`` if the caller has it."""
        ex, ey = np.broadcast_arrays(tx - bx, ty - by)
        length = self._hypot(ex, ey) if length is None else length
        length = np.where(length == 0.0, 1e-9, length)
        ex, ey = (ex / length)[:, None], (ey / length)[:, None]  # (k, 1, n)
        rx, ry = opps[0] - bx, opps[1] - by  # ball -> opponents, (n_opps, n)
        reach = self.robot.radius + self.ball.radius
        t = rx * ex + ry * ey  # (k, n_opps, n)
        perp = np.abs(rx * ey - ry * ex)
        near = (t >= -reach) & (t <= length[:, None] + reach)
        gap = perp - reach - 0.02 - 0.03 * np.maximum(t, 0.0)
        return np.min(np.where(near, gap, math.inf), axis=1, initial=math.inf)

    def _on_target_rows(self, px: np.ndarray, py: np.ndarray, c: np.ndarray, s: np.ndarray,
                        opps: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
        """:meth:`_on_target` on arrays."""
        facing = c >= 0.2
        y_goal = py + s / np.where(facing, c, 1.0) * (self._goal_x - px)
        inside = np.abs(y_goal) < self._half_goal - self.ball.radius - 0.03
        open_ = self._clearance_rows(px, py, self._goal_x, y_goal[None], opps)[0] > 0.0
        return facing & inside & open_

    def _defend_rows(self, px: np.ndarray, py: np.ndarray, c: np.ndarray, s: np.ndarray,
                     bx: np.ndarray, by: np.ndarray, dx: np.ndarray, dy: np.ndarray,
                     rank: np.ndarray) -> np.ndarray:
        """:meth:`_defend` on arrays: actions ``(n, 6)`` for the defenders of ranks
        ``rank``."""
        r = self.robot
        n_def = self.team_size - (2 if self.has_keeper else 1)
        ox = -self._goal_x
        fx, fy = bx - ox, by
        d_ball = self._hypot(fx, fy)
        d_ball = np.where(d_ball == 0.0, 1e-3, d_ball)
        fx, fy = fx / d_ball, fy / d_ball  # own goal -> ball
        nx, ny = -fy, fx
        per_line = self._per_line
        line, slot = rank // per_line, rank % per_line
        in_line = np.minimum(per_line, n_def - line * per_line)
        base = np.maximum(self.field.defense_depth + r.radius + 0.4, 0.45 * d_ball)
        dist = np.minimum(base + 0.9 * line,
                          np.maximum(d_ball - 0.6, self.field.defense_depth + 0.3))
        offset = (slot - 0.5 * (in_line - 1)) * self.defender_spacing * (1 + line)
        tx = ox + dist * fx + offset * nx
        ty = dist * fy + offset * ny
        tx, ty = self._around_ball_rows(px, py, tx, ty, bx, by)
        tx, ty = self._outside_defense_area_rows(tx, ty)
        tx = np.clip(tx, -self._lim_x, self._lim_x)
        ty = np.clip(ty, -self._lim_y, self._lim_y)
        vx, vy = drive_commands(px, py, c, s, tx, ty, r.max_speed, r.max_acceleration)
        out = np.empty((len(px), 6))
        out[:, 0], out[:, 1] = vx / r.max_speed, vy / r.max_speed
        out[:, 2] = turn_commands(c, s, np.arctan2(by - py, bx - px), r.max_angular_speed)
        in_front = (0.0 < dx) & (dx < r.front_distance + 0.1) & (np.abs(dy)
                                                                  < 0.5 * r.kicker_width)
        out[:, 3] = (in_front & (c > 0.3)) * self._kick_power
        out[:, 4:] = -1.0
        return out

    def _around_ball_rows(self, px: np.ndarray, py: np.ndarray, tx: np.ndarray,
                          ty: np.ndarray, bx: np.ndarray, by: np.ndarray
                          ) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_around_ball` on arrays [m]."""
        ux, uy = tx - px, ty - py
        length = self._hypot(ux, uy)
        short = length < 1e-6
        safe = np.where(short, 1.0, length)
        ux, uy = ux / safe, uy / safe
        clear = self.robot.radius + self.ball.radius + 0.15
        along = (bx - px) * ux + (by - py) * uy
        side = (px - bx) * -uy + (py - by) * ux  # the robot's side of the ball, along n
        detour = ~short & (0.0 < along) & (along < length) & (np.abs(side) < clear)
        sign = np.where(side >= 0.0, 1.0, -1.0)
        return (np.where(detour, bx - sign * clear * uy, tx),
                np.where(detour, by + sign * clear * ux, ty))

    def _outside_defense_area_rows(self, x: np.ndarray, y: np.ndarray
                                   ) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_outside_defense_area` on arrays [m]."""
        ox = -self._goal_x
        inside = (x < self._def_front) & (np.abs(y) < self._def_side)
        to_front = self._def_front - x
        to_side = self._def_side - np.abs(y)
        front = (to_front <= to_side) | (x < ox)
        return (np.where(inside & front, self._def_front, x),
                np.where(inside & ~front,
                         np.copysign(self._def_side, np.where(y != 0.0, y, 1.0)), y))
