"""How a scripted SSL team plays the game flow's restarts (SSL rules, 2025 edition;
:mod:`soccer_env.sim.game`), from the referee state at the end of each robot's observation
(:data:`~soccer_env.envs.match.GAME_FLOW_NAMES`).

* **Stop**: every robot keeps ``stop_distance`` plus a robot radius and 10 cm from the ball
  (robots inside that circle leave it radially, the others go round it) and drives slower
  than 80 % of ``stop_speed``. The field players wait on their open-play spots, the one that
  would attack waiting behind the ball on the line to the goal it attacks (the own team's
  restart) or to the goal it defends (the opponents').
* **Ball placement by the own team**: the field player nearest the ball (the keeper when it
  is alone) places it (:class:`~agents.scripted.placement.BallPlacement`); the others keep
  the stop distance.
* **Ball placement by the opponents**: as stop, and also ``placement_interference_distance``
  plus a margin from the line between the ball and the designated position.
* **Kick-off, free kick or penalty kick of the own team**: the field player nearest the ball
  (the penalty kicker: the one the formation put behind the ball) takes it with one flat kick,
  no faster than the rules' ball speed limit: a shot when the goal is open, else a pass to the
  team-mate with the most open line, else a shot at the goal centre; the others hold their
  spots (at a kick-off outside the centre circle in the own
  half; at a penalty kick they stand still).
* **The opponents' kick-off, free kick or penalty kick**: every robot keeps the stop distance
  from the ball (at a kick-off also the own half); at a penalty kick only the keeper moves.
* **Open play**: as without the game flow (:class:`~agents.scripted.open_play.OpenPlay`),
  except that the robot that took a restart (``game.barred``) leaves the ball to the others
  until another robot has touched it (8.2), keeping :data:`BARRED_CLEARANCE` from it.
* During stop and before a free kick is in play, every robot keeps ``defense_area_distance``
  plus a margin from the opponent defense area (8.4.1). Robots off the field stand still.

All positions are in the team frame [m], which attacks ``+x``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from agents.scripted.attack import Opponents
from agents.scripted.geometry import MARGIN
from agents.scripted.motion import drive_and_turn
from agents.scripted.open_play import OpenPlay
from agents.scripted.placement import BallPlacement
from agents.scripted.view import Frame
from soccer_env.presets.rules import RuleSpec

__all__ = ["RestartPlay", "SITUATION_NAMES", "BARRED_CLEARANCE", "STOP_SPEED_FRACTION",
           "PASS_SPEED"]

#: The situation one-hot's entries, in the order of the game block
#: (:data:`~soccer_env.envs.match.GAME_FLOW_NAMES`), as ``(kind, ours)``.
SITUATION_NAMES = {
    "game.stop": ("stop", None), "game.placement_ours": ("placement", True),
    "game.placement_theirs": ("placement", False), "game.kickoff_ours": ("kickoff", True),
    "game.kickoff_theirs": ("kickoff", False), "game.penalty_ours": ("penalty", True),
    "game.penalty_theirs": ("penalty", False), "game.free_kick_ours": ("free_kick", True),
    "game.free_kick_theirs": ("free_kick", False), "game.running": ("running", None),
}
#: The game block's entries that tell open play from the rest.
_RESTART_ENTRIES = ("game.running", "game.on_field", "game.barred")
#: Fraction of the stop speed limit driven during stop.
STOP_SPEED_FRACTION = 0.8
#: Speed [m/s] at which a pass from a restart reaches the team-mate (over the rolling
#: deceleration alone: the sliding phase after the kick makes it arrive a little slower).
PASS_SPEED = 1.5
#: How far the robot that took a restart keeps from the ball until another robot has touched
#: it, beyond a robot and a ball radius [m].
BARRED_CLEARANCE = 0.25
#: The kicker of a restart is armed while the ball is in front of it, within a kicker's width
#: sideways, and the robot faces the kick's direction within this angle [rad]
#: (:meth:`RestartPlay.take_kick`).
ARM_HEADING = 0.3


class RestartPlay:
    """The restart play of a scripted SSL team (see the module docstring).

    Args:
        open_play: the team's open play (its roles, attack, defence and keeper).
        placement: the team's ball placement.
        rules: the rules whose distances and limits the team keeps.
        game: the game block's entry indices by name
            (:attr:`~agents.scripted.view.ObservationView.game`).
    """

    def __init__(self, open_play: OpenPlay, placement: BallPlacement, rules: RuleSpec,
                 game: dict[str, int]) -> None:
        self.open_play, self.placement = open_play, placement
        self.roles, self.attack = open_play.roles, open_play.attack
        self.geometry = open_play.attack.geometry
        self.rules, self.game = rules, game
        self.kick_power = open_play.kick_power
        r = self.geometry.robot
        #: Distance kept from the ball at stop and at the opponents' restarts [m].
        self.keep = rules.stop_distance + r.radius + MARGIN
        #: Distance kept from the opponent defense area at stop and free kicks [m].
        self.defense_margin = rules.defense_area_distance + r.radius + MARGIN

    def situation(self, o: Sequence[float]) -> tuple[str, bool | None]:
        """``(kind, ours)`` of the observation's situation one-hot."""
        g = self.game
        for name, value in SITUATION_NAMES.items():
            if o[g[name]] > 0.5:
                return value
        return "running", None

    def needs_restart_play(self, o: np.ndarray | Sequence[float]) -> bool | np.ndarray:
        """Whether an observation (a sequence) or each observation row (an array
        ``(n, obs_dim)``) asks for more than open play."""
        g = self.game
        if isinstance(o, np.ndarray) and o.ndim == 2:
            running, on_field, barred = (o[:, g[n]] for n in _RESTART_ENTRIES)
        else:
            running, on_field, barred = (o[g[n]] for n in _RESTART_ENTRIES)
        return (running < 0.5) | (on_field < 0.5) | (barred > 0.5)

    # ------------------------------------------------------------------------------------

    def act(self, o: list[float], index: int, f: Frame, xs: list[float], ys: list[float],
            opps: Opponents) -> list[float]:
        """The action of robot ``index`` from its observation ``o`` in a restart (its frame
        ``f``; ``xs, ys``: every robot of the team by index, self included [m])."""
        g = self.game
        if o[g["game.on_field"]] < 0.5:
            return [0.0] * 6
        kind, ours = self.situation(o)
        keeper = self.roles.has_keeper and index == 0
        if kind == "running":
            barred = int(round(o[g["game.barred"]])) - 1
            return self.barred_open_play(o, index, f, xs, ys, opps, barred)
        nearest = self.roles.nearest_to_ball(xs, ys, f.bx, f.by)
        if kind == "placement" and ours and index == nearest:
            return self.placement.act(o, f)
        if kind in ("kickoff", "free_kick", "penalty") and ours and index == nearest:
            return self.take_kick(index, f, xs, ys, opps, shoot_only=kind == "penalty")
        if kind == "penalty":
            if keeper and not ours:
                return self.open_play.keeper_guard(o)
            return [0.0] * 6  # everybody else waits behind the ball
        return self.wait(o, index, f, xs, ys, kind, ours, nearest)

    def barred_open_play(self, o: list[float], index: int, f: Frame, xs: list[float],
                         ys: list[float], opps: Opponents, barred: int) -> list[float]:
        """Open play when robot ``barred`` of the team (-1: none) may not touch the ball:
        it defends without clearing the ball, and another robot attacks."""
        if self.roles.has_keeper and index == 0 and barred != 0:
            return self.open_play.keeper_act(o, f, opps)
        if index == barred:
            return self.leave_ball(f)
        return self.open_play.field_player_act(index, f, xs, ys, opps, barred)

    def leave_ball(self, f: Frame) -> list[float]:
        """The robot that took a restart: it defends from the first slot, keeping off the
        ball's path: at least :data:`BARRED_CLEARANCE` from it, going round it."""
        geo, roles = self.geometry, self.roles
        r = geo.robot
        px, py = f.px, f.py
        n_def = max(1, roles.team_size - roles.first - 1)
        tx, ty = self.open_play.defence.target(f.bx, f.by, 0, n_def)
        keep = r.radius + geo.ball.radius + BARRED_CLEARANCE
        bx, by = self.attack.ball_ahead(f)  # where the ball will be
        tx, ty = geo.clear_of(tx, ty, bx, by, keep)
        if math.hypot(px - bx, py - by) < keep:
            tx, ty = geo.clear_of(px, py, bx, by, keep + 0.05)
        else:
            tx, ty = geo.around_ball(px, py, tx, ty, bx, by, keep, 0.05)
        tx, ty = geo.outside_defense_area(tx, ty)
        return drive_and_turn(r, f, tx, ty, math.atan2(by - py, bx - px))

    # ------------------------------------------------------------------------------------
    # Taking a restart

    def kick_target(self, index: int, px: float, py: float, bx: float, by: float,
                    xs: list[float], ys: list[float], opps: Opponents
                    ) -> tuple[float, float, float]:
        """Where a restart's kick goes and its kicker power: an open shot at the goal; else a
        pass, arriving at :data:`PASS_SPEED`, to the team-mate with the most open line
        (nearer the opponent goal breaking ties); else a shot at the goal centre."""
        geo = self.geometry
        (ax, ay), shoot = self.attack.aim(px, py, bx, by, opps)
        if shoot:
            return ax, ay, self.kick_power
        best, best_gap = None, 0.0
        for k in range(self.roles.first, self.roles.team_size):
            if k == index:
                continue
            gap = min(self.attack.clearance(bx, by, xs[k], ys[k], opps), 1.0) + 0.05 * xs[k]
            if gap > best_gap:
                best, best_gap = k, gap
        if best is None:
            return geo.goal_x, 0.0, self.kick_power
        d = math.hypot(xs[best] - bx, ys[best] - by)
        speed = math.sqrt(PASS_SPEED ** 2 + 2.0 * geo.ball.rolling_deceleration * d)
        return xs[best], ys[best], min(self.kick_power, speed / geo.robot.kicker_max_speed)

    def take_kick(self, index: int, f: Frame, xs: list[float], ys: list[float],
                  opps: Opponents, shoot_only: bool = False) -> list[float]:
        """Line up behind the ball facing the kick's target and kick once, flat, no faster
        than the rules allow (``shoot_only``: at the goal, as at a penalty kick)."""
        geo = self.geometry
        r = geo.robot
        px, py, c, s, bx, by = f.px, f.py, f.c, f.s, f.bx, f.by
        if shoot_only:
            (ax, ay), _ = self.attack.aim(px, py, bx, by, opps)
            power = self.kick_power
        else:
            ax, ay, power = self.kick_target(index, px, py, bx, by, xs, ys, opps)
        ex, ey = ax - bx, ay - by
        d = math.hypot(ex, ey) or 1.0
        ex, ey = ex / d, ey / d
        nx, ny = -ey, ex
        along = (px - bx) * ex + (py - by) * ey
        lateral = (px - bx) * nx + (py - by) * ny
        face = math.atan2(ey, ex)
        heading_err = abs(math.remainder(face - math.atan2(s, c), 2.0 * math.pi))
        contact = geo.contact
        # The kicker is armed whenever the ball is roughly in front of it, not only once the
        # robot believes itself lined up (the kick goes off only when the ball touches it): a
        # robot that sees its pose through noisy, late vision, a few centimetres off, would
        # otherwise push the ball into play with its body and be barred from touching it
        # again (SSL rules 8.2).
        armed = along < 0.0 and abs(lateral) <= r.kicker_width and heading_err <= ARM_HEADING
        kick = power if armed else 0.0
        if along > -contact + 0.01 or abs(lateral) > 0.5 * r.kicker_width:
            # Not yet behind the ball: go to the waiting point (round the ball if needed).
            tx, ty = bx - (contact + 0.1) * ex, by - (contact + 0.1) * ey
            tx, ty = geo.around_ball(px, py, tx, ty, bx, by,
                                     r.radius + geo.ball.radius + 0.05, 0.05)
            cap = None
        elif heading_err > 0.1:
            tx, ty, cap = bx - (contact + 0.1) * ex, by - (contact + 0.1) * ey, 0.5
        else:
            # Lined up: drive slowly into the ball with the kicker armed.
            tx, ty, cap = bx + 0.1 * ex, by + 0.1 * ey, 0.5
        return drive_and_turn(r, f, tx, ty, face, cap, kick)

    # ------------------------------------------------------------------------------------
    # Waiting for a restart

    def wait(self, o: list[float], index: int, f: Frame, xs: list[float], ys: list[float],
             kind: str, ours: bool | None, nearest: int) -> list[float]:
        """Everybody but the robot taking the restart: the open-play spot, kept clear of the
        ball, of the defense areas and of the placement's corridor as the situation asks."""
        r = self.geometry.robot
        px, py, c, s, bx, by = f.px, f.py, f.c, f.s, f.bx, f.by
        keeper = self.roles.has_keeper and index == 0
        if keeper:
            action = list(self.open_play.keeper(o).tolist())
            if math.hypot(px - bx, py - by) >= self.keep and kind != "stop":
                return action
            tx, ty = px + action[0] * r.max_speed * c - action[1] * r.max_speed * s, \
                py + action[0] * r.max_speed * s + action[1] * r.max_speed * c
        else:
            tx, ty = self.waiting_spot(o, index, f, xs, ys, kind, ours, nearest)
        return self.keep_clear(o, f, tx, ty, kind, ours, keeper)

    def waiting_spot(self, o: list[float], index: int, f: Frame, xs: list[float],
                     ys: list[float], kind: str, ours: bool | None, nearest: int
                     ) -> tuple[float, float]:
        """A field player's spot during a restart [m]: the robot that would attack (or is
        nearest the ball) waits behind the ball on the line to the goal its team attacks if
        the restart is its team's, else to the goal it defends; the defenders hold their
        slots."""
        g, geo = self.game, self.geometry
        bx, by = f.bx, f.by
        role, rank, n_def = self.roles.role(index, xs, ys, bx, by)
        if role == "attacker" or index == nearest:
            # Wait behind the ball: towards the goal we attack if the restart is ours.
            coming = o[g["game.next_team"]] if kind in ("stop", "placement") else (
                1.0 if ours else -1.0)
            gx = geo.goal_x if coming > 0.0 else -geo.goal_x
            ex, ey = gx - bx, -by
            d = math.hypot(ex, ey) or 1.0
            return bx - self.keep * ex / d, by - self.keep * ey / d
        return self.open_play.defence.target(bx, by, rank, n_def)

    def keep_clear(self, o: list[float], f: Frame, tx: float, ty: float, kind: str,
                   ours: bool | None, keeper: bool) -> list[float]:
        """The action that drives to the target ``(tx, ty)`` [m] moved as the rules ask
        (their distances last: they are fouls; the own defense area first: it is not), off
        the ball's circle and the placement's corridor, slower than the stop speed at stop
        and placement, facing the ball."""
        g, geo, rules = self.game, self.geometry, self.rules
        r = geo.robot
        px, py, bx, by = f.px, f.py, f.bx, f.by
        keep = self.keep
        clear_kick = kind in ("stop", "placement") or (kind in ("kickoff", "free_kick")
                                                       and not ours)
        if not keeper:
            tx, ty = geo.outside_defense_area(tx, ty)
        if kind in ("stop", "placement", "free_kick"):
            tx, ty = geo.outside_opponent_defense(tx, ty, self.defense_margin)
        if kind == "kickoff":
            tx = min(tx, -r.radius - MARGIN)
        if clear_kick:
            tx, ty = geo.clear_of(tx, ty, bx, by, keep)
        # The opponents' placement: the corridor from the ball to the designated position
        # (qx, qy) and its half-width [m].
        corridor = None
        if kind == "placement" and not ours and o[g["game.target_set"]] > 0.5:
            corridor = (o[g["game.target_x"]], o[g["game.target_y"]],
                        rules.placement_interference_distance + r.radius + MARGIN)
            qx, qy, gap = corridor
            tx, ty = geo.off_segment(tx, ty, bx, by, qx, qy, gap)
        tx, ty = geo.within_walls(tx, ty)
        # Inside the circle (or the placement's corridor): leave it; outside: go round it.
        if corridor is not None:
            qx, qy, gap = corridor
            if geo.off_segment(px, py, bx, by, qx, qy, gap) != (px, py):
                tx, ty = geo.leave_segment(px, py, bx, by, qx, qy, gap + 0.05)
                clear_kick = False  # leaving the corridor sideways leaves the circle too
        if math.hypot(px - bx, py - by) < keep and clear_kick:
            tx, ty = geo.clear_of(px, py, bx, by, keep + 0.05)
        else:
            tx, ty = geo.around_ball(px, py, tx, ty, bx, by, keep if clear_kick else
                                     r.radius + geo.ball.radius + 0.15, 0.05)
        cap = rules.stop_speed * STOP_SPEED_FRACTION if kind in ("stop", "placement") else None
        return drive_and_turn(r, f, tx, ty, math.atan2(by - py, bx - px), cap)
