"""Rules: goals, ball out of play, restarts, kick-off and the match clock.

The referee works on the truth only. Goals and outs are decided from the physics' record of the
first substep at which the whole ball lay beyond a line (:class:`~soccer_env.sim.world.BallExit`),
so a fast ball cannot slip in and out of a goal between two control steps.

Rules implemented (SSL rules, simplified where noted):

* **Goal**: the whole ball crosses the goal line between the posts and under the crossbar
  (its top below ``goal_height``). The team attacking that goal scores.
* **Out of play** over a touch line, over a goal line outside the goal, or over the crossbar:
  a free kick for the team that did not touch the ball last (if nobody touched it, the team
  defending that end), with the ball placed 0.2 m inside the field: at the point where it
  crossed a touch line, or 0.2 m from both the goal line and the touch line on the side where
  it crossed a goal line (SSL places goal kicks and corner kicks there).
* **Kick-off** after a goal and at the start: both teams in a formation in their own half,
  the ball on the centre spot, the team that conceded (at the start: drawn at random) in
  possession with one robot just behind the ball.
* Robots are moved instantly: the SSL's stop phase and ball placement by robots are not
  modelled. Opponents of the team in possession are moved to at least 0.5 m from a placed ball.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec
from soccer_env.presets.rules import RULES
from soccer_env.sim.world import BallExit, World

__all__ = ["ExitKind", "classify_exit", "exit_end", "exit_side", "defending_team", "formation",
           "free_kick_spot", "place_free_kick", "place_kickoff", "place_penalty",
           "FREE_KICK_INSET", "STOP_DISTANCE"]

#: Distance [m] from the lines at which a ball out of play is placed back (the SSL rules'
#: free-kick margin).
FREE_KICK_INSET = RULES["ssl-2025-div-b"].line_margin
#: Distance [m] opponents must keep from the ball at a restart (SSL rules, stop state).
STOP_DISTANCE = RULES["ssl-2025-div-b"].stop_distance

# Formation slots in units of (half length, half width) for a team attacking +x. The first
# slot is the keeper (used when a team has at least two robots), the second the kick-off taker.
_SLOTS = [
    (-0.92, 0.0), (-0.1, 0.0), (-0.45, 0.35), (-0.45, -0.35), (-0.7, 0.15), (-0.7, -0.15),
    (-0.25, 0.7), (-0.25, -0.7), (-0.6, 0.6), (-0.6, -0.6), (-0.3, 0.0),
]


@dataclass(frozen=True)
class ExitKind:
    """How the ball left the field.

    ``kind`` is ``"goal"``, ``"touch"`` (touch line), ``"goal_line"`` (goal line outside the
    goal) or ``"over_bar"``. ``end`` is +1 for the goal line at ``x > 0``, -1 for ``x < 0``
    (0 for touch lines). ``scorer`` is the team (0 blue, 1 yellow) that scored, or -1.
    """

    kind: str
    end: int
    scorer: int


def classify_exit(exit: BallExit, field: FieldSpec, ball: BallSpec) -> ExitKind:
    """Classify the first substep at which the whole ball was beyond a line."""
    beyond_goal_line = abs(exit.x) > field.half_length + ball.radius
    end = (1 if exit.x > 0 else -1) if beyond_goal_line else 0
    if beyond_goal_line and abs(exit.y) < 0.5 * field.goal_width:
        if exit.z + 2.0 * ball.radius <= field.goal_height:
            # Blue attacks +x: a ball in the goal at x > 0 is a blue goal.
            return ExitKind("goal", end, 0 if end > 0 else 1)
        return ExitKind("over_bar", end, -1)
    if beyond_goal_line:
        return ExitKind("goal_line", end, -1)
    return ExitKind("touch", 0, -1)


def exit_end(exit: BallExit, kind: ExitKind) -> int:
    """The end of the field the ball left by: ``kind.end`` over a goal line (+1 at
    ``x > 0``, -1 at ``x < 0``), over a touch line the end of the half it left from."""
    return kind.end if kind.end else (1 if exit.x > 0 else -1)


def exit_side(exit: BallExit) -> float:
    """The side of the field the ball left on: +1 (``y >= 0``, the touch line at
    ``y > 0`` and the corners beside it) or -1; a restart on a touch line is taken on this
    side."""
    return math.copysign(1.0, exit.y) if exit.y != 0.0 else 1.0


def defending_team(end: int) -> int:
    """The team that defends the goal at ``end`` (+1: ``x > 0``); blue (0) defends
    ``x < 0``."""
    return 1 if end > 0 else 0


def restart_team(last_team: int, exit: BallExit, kind: ExitKind) -> int:
    """The team awarded the restart after the ball went out by ``exit`` (of kind ``kind``):
    the opponents of ``last_team``, the team that touched it last; if nobody touched it
    since the last restart (``last_team < 0``), the team defending the end (over a goal
    line) or the half (over a touch line) where it went out. One convention for every
    referee of the package (the simple referee, the SSL game controller, the humanoid
    referee): neither league's laws settle the untouched case."""
    if last_team >= 0:
        return 1 - int(last_team)
    return defending_team(exit_end(exit, kind))


def formation(field: FieldSpec, team: int, n: int, kickoff: bool, robot_radius: float,
              rng: np.random.Generator, jitter: float) -> np.ndarray:
    """Kick-off poses ``(n, 3)`` (field frame) of a team in its own half.

    Slots come from a fixed table scaled to the field, each shifted by up to ``jitter`` metres
    (uniform, from ``rng``), kept out of the centre circle and, for the kick-off taker of the
    team in possession, placed just behind the ball facing the opponent goal. Team 0 (blue)
    plays towards +x. With one robot the robot takes the kick-off slot; otherwise the first
    robot is the keeper.
    """
    hx, hy = field.half_length, field.half_width
    slots = _SLOTS[1:] if n == 1 else _SLOTS
    if n > len(slots):
        raise ValueError(f"at most {len(slots)} robots per team, got {n}")
    poses = np.zeros((n, 3))
    keep_out = field.center_circle_radius + robot_radius + 0.05
    for i in range(n):
        sx, sy = slots[i]
        x = sx * hx + rng.uniform(-jitter, jitter)
        y = sy * hy + rng.uniform(-jitter, jitter)
        x = min(x, -robot_radius - 0.05)
        is_taker = slots[i] == _SLOTS[1]
        if is_taker and kickoff:
            x, y = -(robot_radius + 0.05), 0.0
        elif math.hypot(x, y) < keep_out:
            scale = keep_out / max(math.hypot(x, y), 1e-9)
            x, y = (x * scale, y * scale) if x < -1e-9 else (-keep_out, y)
        x = max(x, -hx + robot_radius)
        y = float(np.clip(y, -hy + robot_radius, hy - robot_radius))
        poses[i] = (x, y, 0.0)
    if team == 1:
        poses[:, 0:2] *= -1.0
        poses[:, 2] = math.pi
    return poses


def place_kickoff(world: World, kickoff_team: int, rng: np.random.Generator, jitter: float
                  ) -> np.ndarray:
    """Kick-off poses ``(N, 3)`` of all robots of ``world`` (blue first), no two closer than
    ``2 r + 0.05`` m (jittered slots can come close on small fields; they are pushed apart)."""
    r = float(world.radii.max())
    blue = formation(world.field, 0, world.n_blue, kickoff_team == 0, r, rng, jitter)
    yellow = formation(world.field, 1, world.n_yellow, kickoff_team == 1, r, rng, jitter)
    poses = np.concatenate([blue, yellow])
    _separate(poses, 2.0 * r + 0.05)
    return poses


def place_penalty(world: World, team: int, mark: tuple[float, float], behind: float
                  ) -> np.ndarray:
    """Penalty-kick poses ``(N, 3)`` of all robots of ``world`` (blue first) for ``team``
    shooting from ``mark`` (SSL rules 2025, 5.3.5): the defending keeper (its team's robot 0)
    on its goal line between the posts, facing the field; the attacking team's robot 1 (robot
    0 when it has one robot) just behind the ball facing the goal; every other robot in a line
    ``behind`` metres plus a robot radius behind the ball, spread across the field and facing
    the goal. Team 0 (blue) attacks +x."""
    f = world.field
    r = float(world.radii.max())
    direction = 1.0 if team == 0 else -1.0
    goal_x = direction * f.half_length
    mx, my = mark
    poses = np.zeros((world.n_robots, 3))
    heading = 0.0 if team == 0 else math.pi
    line_x = mx - direction * (behind + r + 0.05)
    line_x = float(np.clip(line_x, -f.half_length + r, f.half_length - r))
    others = []
    for t in (0, 1):
        members = [i for i in range(world.n_robots) if int(world.teams[i]) == t]
        for k, i in enumerate(members):
            if t != team and k == 0:  # the keeper, touching its goal line, facing the field
                poses[i] = (goal_x - direction * r, 0.0, 0.0 if t == 0 else math.pi)
            elif t == team and k == min(1, len(members) - 1):  # the kicker
                poses[i] = (mx - direction * (r + world.ball_spec.radius + 0.05), my, heading)
            else:
                others.append(i)
    if others:
        gap = 2.0 * r + 0.1
        ys = (np.arange(len(others)) - (len(others) - 1) / 2.0) * gap
        limit = f.half_width - r
        for i, y in zip(others, np.clip(ys, -limit, limit)):
            poses[i] = (line_x, float(y), heading)
    _separate(poses, 2.0 * r + 0.05)
    return poses


def _separate(poses: np.ndarray, gap: float, rounds: int = 20) -> None:
    """Push pairs of robots closer than ``gap`` apart, in place: each moves half the shortfall
    along the line joining them, for up to ``rounds`` sweeps."""
    for _ in range(rounds):
        moved = False
        for i in range(len(poses)):
            for j in range(i + 1, len(poses)):
                d = poses[j, 0:2] - poses[i, 0:2]
                dist = math.hypot(*d)
                if dist < gap:
                    u = d / dist if dist > 1e-9 else np.array([0.0, 1.0])
                    push = 0.5 * (gap - dist) * u
                    poses[i, 0:2] -= push
                    poses[j, 0:2] += push
                    moved = True
        if not moved:
            return


def free_kick_spot(exit: BallExit, kind: ExitKind, field: FieldSpec,
                   inset: float = FREE_KICK_INSET) -> tuple[float, float]:
    """Where the ball is placed after leaving the field, ``inset`` metres inside the lines
    (see the module docstring)."""
    hx, hy = field.half_length, field.half_width
    if kind.kind == "touch":
        x = float(np.clip(exit.x, -hx + inset, hx - inset))
        return x, math.copysign(hy - inset, exit.y)
    return kind.end * (hx - inset), exit_side(exit) * (hy - inset)


def place_free_kick(world: World, exit: BallExit, kind: ExitKind) -> int:
    """Put the ball back in after an out; return the team awarded the free kick.

    Robots of the other team within :data:`STOP_DISTANCE` of the spot, and team-mates
    overlapping the ball, are moved radially away (and stopped).
    """
    last = world.last_touch
    team = restart_team(int(world.teams[last]) if last >= 0 else -1, exit, kind)
    bx, by = free_kick_spot(exit, kind, world.field)
    world.set_ball(bx, by)
    robots = world.robot_array().copy()
    for i, (x, y, th) in enumerate(robots[:, 0:3]):
        r = float(world.radii[i])
        lim_x = world.field.half_length + world.field.boundary - r
        lim_y = world.field.half_width + world.field.boundary - r
        keep = STOP_DISTANCE + r if world.teams[i] != team else r + world.ball_spec.radius + 0.02
        dx, dy = x - bx, y - by
        d = math.hypot(dx, dy)
        if d < keep:
            if d < 1e-9:
                dx, dy, d = -bx, -by, math.hypot(bx, by)
            nx = float(np.clip(bx + dx / d * keep, -lim_x, lim_x))
            ny = float(np.clip(by + dy / d * keep, -lim_y, lim_y))
            world.set_robot(i, nx, ny, th)
    return team
