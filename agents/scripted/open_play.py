"""Open play of a scripted SSL team: each robot plays its role (:mod:`agents.scripted.roles`);
the single and batched paths side by side.

* the **keeper** plays :class:`~soccer_env.envs.keeper.ScriptedGoalkeeper` (guard line in front
  of the goal, moving to where the ball's predicted path crosses it), its kicker power capped
  at the team's, except that it clears a slow ball lying in its own defense area as the
  attacker would (:class:`~agents.scripted.attack.Attack`);
* the **attacker** plays :class:`~agents.scripted.attack.Attack`;
* the **defenders** play :class:`~agents.scripted.defence.Defence`.

The batched path (:meth:`OpenPlay.act_rows`) gives the single path's actions for many rows at
once: the same arithmetic in the same order, on arrays.
"""

from __future__ import annotations

import numpy as np

from agents.scripted.attack import Attack, Opponents
from agents.scripted.defence import Defence
from agents.scripted.roles import Roles
from agents.scripted.view import Frame, ObservationView
from soccer_env.envs.keeper import ScriptedGoalkeeper

__all__ = ["OpenPlay"]


class OpenPlay:
    """The open play of a scripted SSL team (see the module docstring).

    Args:
        view: the team's observation view.
        roles: the team's roles.
        attack: the attacker's play.
        defence: the defenders' play.
        keeper: the scripted goalkeeper robot 0 plays (of a team of two or more).
        kick_power: the kicker power the keeper's kicks are capped at (``(0, 1]``).
    """

    def __init__(self, view: ObservationView, roles: Roles, attack: Attack, defence: Defence,
                 keeper: ScriptedGoalkeeper, kick_power: float) -> None:
        self.view, self.roles, self.attack, self.defence = view, roles, attack, defence
        self.keeper = keeper
        self.kick_power = kick_power

    # ------------------------------------------------------------------------------------
    # One robot

    def act(self, o: list[float], index: int, f: Frame, opps: Opponents) -> list[float]:
        """The action of robot ``index`` from its observation ``o`` (its frame ``f``, the
        opponents ``opps``)."""
        if self.roles.has_keeper and index == 0:
            return self.keeper_act(o, f, opps)
        xs, ys = self.view.team_positions(o, index, f)
        return self.field_player_act(index, f, xs, ys, opps)

    def keeper_act(self, o: list[float], f: Frame, opps: Opponents) -> list[float]:
        """The keeper's action: clearing a slow ball in its defense area, else guarding."""
        if self.roles.keeper_should_clear(f.bx, f.by, f.bvx, f.bvy):
            return self.attack.act(f, opps, keeper=True)
        return self.keeper_guard(o)

    def keeper_guard(self, o: list[float]) -> list[float]:
        """The scripted goalkeeper's action, its kicker power capped at the team's."""
        action = self.keeper(o).tolist()  # it reads entries by index: a list will do
        action[3] = min(action[3], self.kick_power)
        return action

    def field_player_act(self, index: int, f: Frame, xs: list[float], ys: list[float],
                         opps: Opponents, barred: int = -1) -> list[float]:
        """The action of field player ``index`` (``xs``, ``ys``: the team's robots by index
        [m]; robot ``barred`` never attacks)."""
        role, rank, n_def = self.roles.role(index, xs, ys, f.bx, f.by, barred)
        if role == "attacker":
            return self.attack.act(f, opps)
        return self.defence.act(f, rank, n_def)

    # ------------------------------------------------------------------------------------
    # Observation rows

    def act_rows(self, obs: np.ndarray, index: np.ndarray) -> np.ndarray:
        """Actions ``(n, 6)`` float32 for ``n`` observation rows ``(n, obs_dim)`` of robots
        ``index`` (``(n,)`` ints): :meth:`act` row by row."""
        view = self.view
        o = view.columns(obs)
        frame = view.frame_rows(o)
        opps = view.opponents_rows(o, frame)
        out = np.empty((len(index), 6), dtype=np.float32)
        attack = np.zeros(len(index), dtype=bool)
        clear = np.zeros(len(index), dtype=bool)
        field = np.ones(len(index), dtype=bool)
        if self.roles.has_keeper:
            keeper = index == 0
            clear = keeper & self.roles.keeper_should_clear_rows(frame.bx, frame.by, frame.bvx,
                                                                 frame.bvy)
            guard = keeper & ~clear
            out[guard] = self.keeper.act_batch(obs[guard])
            if self.kick_power < 1.0:
                out[guard, 3] = np.minimum(out[guard, 3], self.kick_power)
            attack |= clear
            field = ~keeper
        if field.any():
            # Team-mates in the team frame, indexed by robot (self included), (team_size, n).
            xs, ys = view.team_positions_rows(o, index, frame)
            is_attacker, rank = self.roles.role_rows(index[field], xs[:, field], ys[:, field],
                                                     frame.bx[field], frame.by[field])
            attack[field] = is_attacker
            defend = np.flatnonzero(field)[~is_attacker]
            if len(defend):
                out[defend] = self.defence.act_rows(frame.take(defend), rank[~is_attacker])
        if attack.any():
            out[attack] = self.attack.act_rows(frame.take(attack),
                                               tuple(v[:, attack] for v in opps), clear[attack])
        return out
