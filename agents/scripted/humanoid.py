"""A scripted humanoid team for the match: a keeper and chasers, from observations only.

Each robot decides from its own observation vector (entries found by name, in its team
frame: :class:`~agents.scripted.view.ObservationView`), so the team plays on whatever its
perception provides:

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
zero). Positions are in the team frame [m], headings in radians.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from agents.scripted.view import Frame, ObservationView
from soccer_env.envs.keeper import ScriptedGoalkeeper, drive_command, turn_command
from soccer_env.presets import BallSpec, FieldSpec, HumanoidRobotSpec
from soccer_env.sim.game import segment_distance

__all__ = ["HumanoidTeam"]

#: The game block's entries the humanoid team reads.
_GAME_ENTRIES = ("game.kickoff_theirs", "game.free_kick_theirs", "game.on_field")


class HumanoidTeam:
    """Scripted policy for one humanoid team of
    :class:`~soccer_env.envs.match.SoccerParallelEnv` (see the module docstring).

    Args:
        field: the match's field.
        ball: the match's ball.
        robot: the team's humanoid robot spec.
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
        #: Robots in the team.
        self.team_size = len(self.agents)
        self.behind = behind
        #: Where each robot finds its entries.
        self.view = ObservationView(names, self.team_size)
        self.keeper = (ScriptedGoalkeeper(field, ball, robot, names)
                       if len(self.agents) >= 2 else None)
        index = self.view.index
        self._game = ([index[n] for n in _GAME_ENTRIES]
                      if all(n in index for n in _GAME_ENTRIES) else None)
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

    def act(self, obs_batch: np.ndarray) -> np.ndarray:
        """Actions ``(team_size, 6)`` float32 for observations ``(team_size, obs_dim)`` of
        the team's robots in order."""
        return self.act_batch(np.asarray(obs_batch)[None])[0]

    def act_batch(self, obs: np.ndarray) -> np.ndarray:
        """Actions ``(M, team_size, 6)`` float32 for the observations ``(M, team_size,
        obs_dim)`` of the team's robots in ``M`` matches (robot ``k`` of each match by
        :meth:`act_one` as robot ``k``)."""
        obs = np.asarray(obs)
        if obs.ndim != 3 or obs.shape[1] != self.team_size:
            raise ValueError(f"obs must have shape (M, {self.team_size}, obs_dim) (M matches, "
                             f"one row per robot of the team, in order), got {obs.shape}")
        out = np.zeros(obs.shape[:2] + (6,), dtype=np.float32)
        for m in range(obs.shape[0]):
            for k in range(self.team_size):
                out[m, k] = self.act_one(obs[m, k], k)
        return out

    def waiting_rows(self, obs: np.ndarray) -> np.ndarray:
        """``(n,)`` bool for observations ``(n, obs_dim)``: the robots whose play the laws
        decide under the game flow (off the field, or waiting out the opponents' kick-off or
        free kick); all False without the game block."""
        obs = np.asarray(obs)
        if self._game is None:
            return np.zeros(len(obs), dtype=bool)
        kickoff, free_kick, on_field = (obs[:, i] for i in self._game)
        return (on_field < 0.5) | (kickoff > 0.5) | (free_kick > 0.5)

    def act_one(self, obs: np.ndarray, k: int) -> np.ndarray:
        """The action of the team's ``k``-th robot."""
        o = obs.tolist() if isinstance(obs, np.ndarray) else list(obs)
        kickoff, waiting = 0.0, False
        if self._game is not None:
            kickoff, free_kick, on_field = (o[i] for i in self._game)
            if on_field < 0.5:
                return np.zeros(6, dtype=np.float32)
            waiting = kickoff > 0.5 or free_kick > 0.5
        f = self.view.frame(o)
        if k == 0 and self.keeper is not None:
            if not waiting or math.hypot(f.dx, f.dy) >= self.keep:
                return self.keeper(obs)
        tx, ty, face, kick = self._play(o, f)
        if waiting:
            tx, ty = self._keep_away(f, tx, ty, kickoff > 0.5)
            face, kick = math.atan2(f.by - f.py, f.bx - f.px), 0.0
        r = self.robot
        vx, vy = drive_command(f.px, f.py, f.c, f.s, tx, ty, r.max_forward_speed,
                               r.max_acceleration)
        ax_ = vx / (r.max_forward_speed if vx >= 0.0 else r.max_backward_speed)
        ay_ = vy / r.max_sideways_speed
        omega = turn_command(f.c, f.s, face, r.max_turn_speed, gain=2.0)
        return np.array([max(-1.0, min(1.0, ax_)), max(-1.0, min(1.0, ay_)), omega, kick,
                         0.0, 0.0], dtype=np.float32)

    def _play(self, o: list[float], f: Frame) -> tuple[float, float, float, float]:
        """``(tx, ty, face, kick)``: where a chaser walks [m], the heading it turns to [rad]
        and its kick (0 or 1) in open play."""
        r, fs = self.robot, self.field
        px, py, bx, by, dx, dy = f.px, f.py, f.bx, f.by, f.dx, f.dy
        # Team-mates' positions; the chaser is the field player nearest the ball.
        mates = self.view.mates_of(o, f)
        # Team-mates come in robot order skipping self: the keeper (robot 0) is the first.
        field_mates = mates[1:] if self.keeper is not None else mates
        mine = math.hypot(bx - px, by - py)
        rank = sum(1 for mx, my in field_mates if math.hypot(bx - mx, by - my) < mine)
        if rank > 0:
            lane = (rank - 1) % 3 - 1  # -1, 0, 1 across the field
            tx = 0.5 * (bx - fs.half_length)
            ty = lane * 0.3 * fs.width
            return tx, ty, math.atan2(by - ty, bx - tx), 0.0
        ux, uy = bx - fs.half_length, by
        d = math.hypot(ux, uy) or 1.0
        tx, ty = bx + self.behind * ux / d, by + self.behind * uy / d
        face = math.atan2(-uy, -ux)
        lined_up = math.hypot(tx - px, ty - py) < 0.1
        if lined_up or (0.0 < dx < r.radius + self.ball.radius + r.kick_reach + 0.1
                        and abs(dy) < 0.5 * r.kick_width):
            tx, ty = bx, by  # walk into the ball
        at_foot = (0.0 < dx < r.radius + self.ball.radius + r.kick_reach
                   and abs(dy) < 0.5 * r.kick_width)
        return tx, ty, face, 1.0 if at_foot else 0.0

    def _keep_away(self, f: Frame, tx: float, ty: float, kickoff: bool
                   ) -> tuple[float, float]:
        """The target moved for the opponents' restart: out of the circle of
        :attr:`keep` round the ball (and at a kick-off into the own half, which also keeps
        the robot out of the centre circle), by way of the circle's radius when the path
        crosses it [m]."""
        r = self.robot
        px, py, bx, by = f.px, f.py, f.bx, f.by
        if kickoff:
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
        return tx, ty
