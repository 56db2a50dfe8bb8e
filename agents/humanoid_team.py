"""A scripted humanoid team for the match: a keeper and chasers, from observations only.

Each robot decides from its own observation vector (entries found by name, in its team
frame), so the team plays on whatever its perception provides:

* **keeper** (robot 0 of a team of two or more): :class:`~soccer_env.envs.keeper.ScriptedGoalkeeper`
  for humanoids (guards its goal line, walks to the predicted crossing point, dives).
* **chasers** (the others): the one nearest the ball walks to a point ``behind`` metres behind
  the ball on the line from the opponent goal's centre through the ball, turning to face the
  goal, then walks into the ball and kicks when it lies at its foot; the others hold a
  position between the ball and their own goal, spread across the field, facing the ball.

In a match with the game flow (``game=...``, the humanoid laws) the team reads the referee
state at the end of its observations: at the opponents' kick-off every robot stays in its half
and outside the centre circle, at their throw-ins, goal kicks and corner kicks it keeps the
laws' 0.75 m (plus its radius and 10 cm) from the ball, until the ball is in play; a robot
with a removal penalty stands still.

Walking commands are normalised per axis by the robot's forward, backward, sideways and turn
limits. The head is left to the environment's head controller (action entries 4 and 5 are
zero).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from soccer_env.envs.keeper import ScriptedGoalkeeper, drive_command, turn_command
from soccer_env.presets import BallSpec, FieldSpec, HumanoidRobotSpec
from soccer_env.sim.game import segment_distance

__all__ = ["HumanoidTeam"]


class HumanoidTeam:
    """Scripted policy for one humanoid team of
    :class:`~soccer_env.envs.match.SoccerParallelEnv` (see the module docstring).

    Args:
        field, ball, robot: the match's specs.
        names: the entry names of this team's observations (``env.builder.names_for(t)``).
        agents: this team's agent names, in robot order.
        behind: how far behind the ball a chaser lines up before kicking [m].
    """

    def __init__(self, field: FieldSpec, ball: BallSpec, robot: HumanoidRobotSpec,
                 names: Sequence[str], agents: Sequence[str], behind: float = 0.25) -> None:
        if robot.kind != "humanoid":
            raise ValueError(f"HumanoidTeam plays humanoids, got a {robot.kind!r} robot")
        self.field, self.ball, self.robot = field, ball, robot
        self.agents = list(agents)
        self.behind = behind
        index = {n: i for i, n in enumerate(names)}
        self._idx = [index[n] for n in ("self.x", "self.y", "self.ax", "self.ay", "ball.dx",
                                        "ball.dy")]
        n_mates = len(self.agents) - 1
        self._mates = [(index[f"mate{j}.dx"], index[f"mate{j}.dy"]) for j in range(n_mates)]
        self.keeper = (ScriptedGoalkeeper(field, ball, robot, names)
                       if len(self.agents) >= 2 else None)
        game = ("game.kickoff_theirs", "game.free_kick_theirs", "game.on_field")
        self._game = [index[n] for n in game] if all(n in index for n in game) else None
        # Distance kept from the ball at the opponents' restarts [m] (Law 13: 0.75 m).
        self.keep = 0.75 + robot.radius + 0.1

    @classmethod
    def for_env(cls, env: Any, team: str = "blue", **kwargs: Any) -> HumanoidTeam:
        """The policy of ``team`` (``"blue"`` or ``"yellow"``) of a match environment."""
        t = ("blue", "yellow").index(team)
        agents = [a for a, tt in zip(env.possible_agents, env.world.teams.tolist()) if tt == t]
        return cls(env.field, env.ball_spec, env.team_specs[t], env.builder.names_for(t),
                   agents, **kwargs)

    def __call__(self, observations: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Actions of this team's live agents."""
        out = {}
        for k, a in enumerate(self.agents):
            if a in observations:
                out[a] = self.act_one(observations[a], k)
        return out

    def act_one(self, obs: np.ndarray, k: int) -> np.ndarray:
        """The action of the team's ``k``-th robot."""
        waiting = False
        if self._game is not None:
            kickoff, free_kick, on_field = (float(obs[i]) for i in self._game)
            if on_field < 0.5:
                return np.zeros(6, dtype=np.float32)
            waiting = kickoff > 0.5 or free_kick > 0.5
        if k == 0 and self.keeper is not None:
            ball_distance = math.hypot(float(obs[self._idx[4]]), float(obs[self._idx[5]]))
            if not waiting or ball_distance >= self.keep:
                return self.keeper(obs)
        r, f = self.robot, self.field
        px, py, ax, ay, dx, dy = (float(obs[i]) for i in self._idx)
        c, s = ax, -ay
        bx, by = px + c * dx - s * dy, py + s * dx + c * dy
        # Team-mates' positions; the chaser is the field player nearest the ball.
        mates = [(px + c * float(obs[i]) - s * float(obs[j]),
                  py + s * float(obs[i]) + c * float(obs[j])) for i, j in self._mates]
        # Team-mates come in robot order skipping self: the keeper (robot 0) is the first.
        field_mates = mates[1:] if self.keeper is not None else mates
        mine = math.hypot(bx - px, by - py)
        rank = sum(1 for mx, my in field_mates if math.hypot(bx - mx, by - my) < mine)
        gx = f.half_length
        if rank == 0:
            ux, uy = bx - gx, by
            d = math.hypot(ux, uy) or 1.0
            tx, ty = bx + self.behind * ux / d, by + self.behind * uy / d
            face = math.atan2(-uy, -ux)
            lined_up = math.hypot(tx - px, ty - py) < 0.1
            if lined_up or (0.0 < dx < r.radius + self.ball.radius + r.kick_reach + 0.1
                            and abs(dy) < 0.5 * r.kick_width):
                tx, ty = bx, by  # walk into the ball
            at_foot = (0.0 < dx < r.radius + self.ball.radius + r.kick_reach
                       and abs(dy) < 0.5 * r.kick_width)
            kick = 1.0 if at_foot else 0.0
        else:
            lane = (rank - 1) % 3 - 1  # -1, 0, 1 across the field
            tx = 0.5 * (bx - f.half_length)
            ty = lane * 0.3 * f.width
            face = math.atan2(by - ty, bx - tx)
            kick = 0.0
        if waiting:
            # The opponents' restart: keep away from the ball (and at a kick-off in the own
            # half, which also keeps the robot out of the centre circle).
            kick = 0.0
            if kickoff > 0.5:
                tx = min(tx, -r.radius - 0.1)
            ex, ey = tx - bx, ty - by
            d = math.hypot(ex, ey)
            if d < self.keep:  # the target outside the circle
                ex, ey, d = (ex, ey, d) if d > 1e-9 else (-1.0, 0.0, 1.0)
                tx, ty = bx + ex / d * (self.keep + 0.05), by + ey / d * (self.keep + 0.05)
            # A path through the circle: out along the radius first.
            if segment_distance(bx, by, px, py, tx, ty) < self.keep:
                ex, ey = px - bx, py - by
                d = math.hypot(ex, ey)
                ex, ey, d = (ex, ey, d) if d > 1e-9 else (-1.0, 0.0, 1.0)
                tx, ty = bx + ex / d * (self.keep + 0.2), by + ey / d * (self.keep + 0.2)
            face = math.atan2(by - py, bx - px)
        vx, vy = drive_command(px, py, c, s, tx, ty, r.max_forward_speed, r.max_acceleration)
        ax_ = vx / (r.max_forward_speed if vx >= 0.0 else r.max_backward_speed)
        ay_ = vy / r.max_sideways_speed
        omega = turn_command(c, s, face, r.max_turn_speed, gain=2.0)
        return np.array([max(-1.0, min(1.0, ax_)), max(-1.0, min(1.0, ay_)), omega, kick,
                         0.0, 0.0], dtype=np.float32)
