"""The game flow of a match in the world (:class:`GameFlow`): the game controller referees the
truth every step, and the world does what it asks (robots sent off to the run-off area and
brought back, the teams lined up for kick-offs and penalty kicks, the ball placed, robots
cleared from around it); and the referee's state as ``info["game"]`` (:meth:`GameFlow.info`).

The controllers are :class:`~soccer_env.sim.game.GameController` (the RoboCup SSL rules) and
:class:`~soccer_env.sim.humanoid_game.HumanoidGameController` (the Humanoid League laws); they
decide, this module moves the robots and the ball.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec
from soccer_env.presets.rules import HumanoidRuleSpec, RuleSpec
from soccer_env.sim.game import Decision, Frame, GameController, GameEvent, GameOptions
from soccer_env.sim.humanoid_game import HumanoidGameController
from soccer_env.sim.referee import place_kickoff, place_penalty
from soccer_env.sim.world import World

__all__ = ["GameFlow", "event_dict"]


class GameFlow:
    """A match's game controller and the world changes it asks for.

    Args:
        world: the match's world.
        rules: the rule preset (:class:`~soccer_env.presets.rules.RuleSpec` for SSL teams,
            :class:`~soccer_env.presets.rules.HumanoidRuleSpec` for humanoids).
        options: the SSL rules' :class:`~soccer_env.sim.game.GameOptions` (None for
            humanoids).
        match_duration: the match's playing time [s].
        formation_jitter: metres of uniform jitter of the kick-off formation.

    Attributes:
        game: the episode's game controller (None before the first :meth:`start`).
        off_field: the robots off the field (by cards or removal penalties), in the order
            they left.
        decision: the game controller's decision of the last step (or of the start).
    """

    def __init__(self, world: World, rules: RuleSpec | HumanoidRuleSpec,
                 options: GameOptions | None, match_duration: float,
                 formation_jitter: float) -> None:
        self.world = world
        self.field: FieldSpec = world.field
        self.ball_spec: BallSpec = world.ball_spec
        self.rules, self.options = rules, options
        self.match_duration = match_duration
        self.formation_jitter = formation_jitter
        self.game: GameController | HumanoidGameController | None = None
        self.off_field: list[int] = []
        self.decision: Decision | None = None

    def start(self, kickoff: int, rng: np.random.Generator) -> None:
        """A new game controller for an episode whose team ``kickoff`` kicks off, seeded from
        the episode's generator ``rng``; every robot on the field."""
        w = self.world
        self.off_field = []
        game_rng = np.random.default_rng(rng.integers(2**63))
        if isinstance(self.rules, RuleSpec):
            self.game = GameController(self.field, self.ball_spec, w.teams, w.radii,
                                       self.rules, self.options, self.match_duration, game_rng)
        else:
            self.game = HumanoidGameController(self.field, self.ball_spec, w.teams, w.radii,
                                               self.rules, self.match_duration, game_rng)
        self.decision = self.game.start(kickoff)

    def step(self, rng: np.random.Generator) -> Decision:
        """One step of the game controller on the truth, and what it asks of the world
        (``rng``: the episode's generator, for a kick-off formation's jitter). Returns its
        decision."""
        w, g = self.world, self.game
        for i in self.off_field:  # delayed commands may have moved it
            x, y = self.bench_spot(i)
            pose = w.robot_array()[i]
            if math.hypot(pose[0] - x, pose[1] - y) > 0.01:
                w.set_robot(i, x, y, float(pose[2]))
        d = g.step(Frame(w.time, w.ball_array(), w.robot_array(), w.touched, w.ball_exit))
        if w.ball_exit is not None:
            w.clear_exit()
        self.apply(d, rng)
        self.decision = d
        return d

    def apply(self, d: Decision, rng: np.random.Generator) -> None:
        """Do in the world what the game controller asks: robots off and back on, the
        teams lined up, the ball placed, robots cleared from around it."""
        w, g = self.world, self.game
        for i in d.send_off:
            if i not in self.off_field:
                self.off_field.append(i)
        for i in d.bring_on:
            if i in self.off_field:
                self.off_field.remove(i)
                x, y = self.entry_spot(i)
                w.set_robot(i, x, y, 0.0 if w.teams[i] == 0 else math.pi)
        if d.line_up is not None:
            kind, team = d.line_up
            if kind == "kickoff":
                poses, ball = place_kickoff(w, team, rng, self.formation_jitter), (0.0, 0.0)
            else:
                ball = g.designated
                poses = place_penalty(w, team, ball, self.rules.penalty_behind)
            for i in self.off_field:
                poses[i, 0:2] = self.bench_spot(i)
            w.place_all(poses, ball)
        elif d.place_ball is not None:
            w.set_ball(*d.place_ball)
        for i in d.send_off:
            pose = w.robot_array()[i]
            w.set_robot(i, *self.bench_spot(i), float(pose[2]))
        if d.place_ball is not None or d.clear is not None:
            keep, team = d.clear if d.clear is not None else (0.0, -1)
            self.clear_ball(keep, team)

    def clear_ball(self, keep: float, team: int) -> None:
        """Move robots not of ``team`` (-1: all) whose centres lie within ``keep`` metres of
        the ball (and any robot overlapping it) radially out to that distance, at rest."""
        w = self.world
        bx, by = (float(v) for v in w.ball_array()[0:2])
        lim_x = w.field.half_length + w.field.boundary
        lim_y = w.field.half_width + w.field.boundary
        for i, (x, y, th) in enumerate(w.robot_array()[:, 0:3].tolist()):
            if i in self.off_field:
                continue
            r = float(w.radii[i])
            need = r + self.ball_spec.radius + 0.01
            if team < 0 or int(w.teams[i]) != team:
                need = max(need, keep)
            dx, dy = x - bx, y - by
            dist = math.hypot(dx, dy)
            if dist >= need:
                continue
            if dist < 1e-9:  # on the ball: away from the centre spot, or along -x
                dx, dy, dist = (-bx, -by, math.hypot(bx, by)) if math.hypot(bx, by) > 1e-9 \
                    else (-1.0, 0.0, 1.0)
            nx = float(np.clip(bx + dx / dist * need, -lim_x + r, lim_x - r))
            ny = float(np.clip(by + dy / dist * need, -lim_y + r, lim_y - r))
            w.set_robot(i, nx, ny, th)

    def bench_spot(self, robot: int) -> tuple[float, float]:
        """Where a robot off the field waits [m]: beyond the touch line at ``y < 0``, in the
        middle of the run-off area, in its own half, the team's robots side by side."""
        w = self.world
        t = int(w.teams[robot])
        r = float(w.radii[robot])
        k = [i for i in self.off_field if int(w.teams[i]) == t].index(robot)
        f = self.field
        x = (0.5 + k * (2.0 * r + 0.1)) * (-1.0 if t == 0 else 1.0)
        y = -min(f.half_width + 0.5 * f.boundary, f.half_width + f.boundary - r - 0.01)
        return x, y

    def entry_spot(self, robot: int) -> tuple[float, float]:
        """Where a robot comes back on [m]: on its side of the halfway line, on the touch
        line nearer the bench (the other one if the ball lies within a metre, beyond the
        distance either rule book asks robots to keep at restarts)."""
        w = self.world
        t = int(w.teams[robot])
        r = float(w.radii[robot])
        x = (r + 0.1) * (-1.0 if t == 0 else 1.0)
        y = -(self.field.half_width - r - 0.05)
        ball = w.ball_array()
        if math.hypot(ball[0] - x, ball[1] - y) < r + 1.0:
            y = -y
        return x, y

    def info(self, score: list[int]) -> dict[str, Any]:
        """``info["game"]``: the referee state and the step's game events, with the
        ``score`` (blue's and yellow's goals). What is not there reads as empty, never None:
        ``""`` for no team, ``()`` for no next command and no designated position."""
        g, w = self.game, self.world
        teams = ("blue", "yellow")

        def team_name(t: int) -> str:
            return teams[t] if t >= 0 else ""

        events = [] if self.decision is None else self.decision.events
        kind, team = g.situation()
        out: dict[str, Any] = {
            "command": g.command, "command_team": team_name(g.command_team),
            "situation": kind, "situation_team": team_name(team),
            "next_command": (() if g.next_command is None else
                             (g.next_command[0], team_name(g.next_command[1]))),
            "designated": () if g.designated is None else g.designated,
            "in_play": bool(g.in_play), "stage": g.stage,
            "stage_time_left": float(g.stage_time_left),
            "playing_time_left": float(g.playing_time_left),
            "events": [event_dict(e, w.names) for e in events],
        }
        for t, name in enumerate(teams):
            info = g.team_info[t]
            out[name] = {"goals": score[t], "fouls": info.fouls,
                         "yellow_cards": [float(c) for c in info.yellow_cards],
                         "red_cards": info.red_cards,
                         "placement_failures": info.placement_failures,
                         "can_place": bool(info.can_place),
                         "robots_allowed": g.robots_allowed(t),
                         "off_field": [w.names[i] for i in self.off_field
                                       if int(w.teams[i]) == t]}
        return out


def event_dict(event: GameEvent, names: list[str]) -> dict[str, Any]:
    """A game event as ``info["game"]["events"]`` holds it (team and robot by name, ``""``
    for none)."""
    return {"kind": event.kind,
            "team": "" if event.team < 0 else ("blue", "yellow")[event.team],
            "robot": "" if event.robot < 0 else names[event.robot],
            "x": event.x, "y": event.y}
