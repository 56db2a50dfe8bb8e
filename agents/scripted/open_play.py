"""Open play of a scripted SSL team: each robot plays its role (:mod:`agents.scripted.roles`).

* the **keeper** plays :class:`~soccer_env.envs.keeper.ScriptedGoalkeeper` (guard line in front
  of the goal, moving to where the ball's predicted path crosses it), its kicker power capped
  at the team's, except that it clears a slow ball lying in its own defense area as the
  attacker would (:class:`~agents.scripted.attack.Attack`). Under the game flow it catches
  instead of deflecting (no kick, the dribbler on; ``catch``): the goalkeeper's save kicks
  the ball back the way it came, which in a match sends it over a touch line or the far goal
  line (an aimless kick), and each time the game stops for a ball placement; the caught ball
  lies slow in the defense area, and the keeper clears it as the attacker plays (a shot or a
  pass, under the speed limit);
* the **attacker** plays :class:`~agents.scripted.attack.Attack`;
* the **defenders** play :class:`~agents.scripted.defence.Defence`.

The rule is one compiled kernel per robot: :func:`field_player` for a field player (its role,
then the attacker's or a defender's action), :func:`~agents.scripted.attack.attacker_act` for
a keeper clearing the ball. The single path (:meth:`OpenPlay.act`) calls them on one robot's
floats, the batched path (:meth:`OpenPlay.act_rows`) calls :func:`open_play_rows` once, which
reads each observation row and calls the same kernels: the actions are the same, bit for
bit. Only the guarding keepers' rows go through
:meth:`~soccer_env.envs.keeper.ScriptedGoalkeeper.act_batch`.
"""

from __future__ import annotations

import numpy as np

from agents.scripted.attack import Attack, Opponents, Striker, attacker_act, opponent_array
from agents.scripted.defence import Defence, defender_act
from agents.scripted.geometry import Pitch
from agents.scripted.motion import Action
from agents.scripted.roles import Roles, keeper_should_clear, role
from agents.scripted.view import Frame, ObservationView
from estimators.compiled import kernel
from soccer_env.envs.keeper import ScriptedGoalkeeper

__all__ = ["OpenPlay", "field_player", "open_play_rows"]


@kernel
def field_player(p: Pitch, a: Striker, spacing: float, first: int, team_size: int,
                 px: float, py: float, c: float, s: float, bx: float, by: float, bvx: float,
                 bvy: float, dx: float, dy: float, index: int, xs: np.ndarray, ys: np.ndarray,
                 opps: np.ndarray, barred: int) -> Action:
    """The action of field player ``index`` (:func:`~agents.scripted.roles.role`, then
    :func:`~agents.scripted.attack.attacker_act` or
    :func:`~agents.scripted.defence.defender_act` with the attacker's kicker power): the robot
    at ``(px, py)`` with heading ``(c, s)``, the ball at ``(bx, by)`` [m] moving at ``(bvx,
    bvy)`` [m/s] and ``(dx, dy)`` from the robot in its body frame [m], the team's robots
    ``xs``, ``ys`` by index and the opponents ``opps`` ``(k, 2)`` [m]; robot ``barred`` never
    attacks."""
    attacker, rank, n_def = role(p, first, team_size, index, xs, ys, bx, by, barred)
    if attacker:
        return attacker_act(p, a, px, py, c, s, bx, by, bvx, bvy, dx, opps, False)
    return defender_act(p, spacing, a.kick_power, px, py, c, s, bx, by, dx, dy, rank, n_def)


@kernel
def open_play_rows(p: Pitch, a: Striker, spacing: float, has_keeper: bool, team_size: int,
                   obs: np.ndarray, index: np.ndarray, frame_index: np.ndarray,
                   mates: np.ndarray, opponents: np.ndarray, out: np.ndarray) -> np.ndarray:
    """The open-play actions of the observation rows ``obs`` ``(n, obs_dim)`` of robots
    ``index`` ``(n,)`` into ``out`` ``(n, 6)``: each row's frame, team and opponents in the
    team frame (:mod:`agents.scripted.view`'s arithmetic; ``frame_index``: the columns of
    :data:`~agents.scripted.view.FRAME_ENTRIES`, ``mates`` and ``opponents``: the ``(dx,
    dy)`` columns of each, ``(m, 2)`` ints), then :func:`field_player`, or for a keeper
    (robot 0 of a team with one) :func:`~agents.scripted.attack.attacker_act` when it clears
    the ball. Returns the rows left to the guarding keeper (their ``out`` rows unset)."""
    n = obs.shape[0]
    first = 1 if has_keeper else 0
    guard = np.zeros(n, dtype=np.bool_)
    xs, ys = np.empty(team_size), np.empty(team_size)
    opps = np.empty((opponents.shape[0], 2))
    for i in range(n):
        o = obs[i]
        px, py, c = o[frame_index[0]], o[frame_index[1]], o[frame_index[2]]
        s = -o[frame_index[3]]  # self.ay is -sin(heading)
        dx, dy = o[frame_index[4]], o[frame_index[5]]
        vbx, vby = o[frame_index[6]], o[frame_index[7]]
        bx, by = px + c * dx - s * dy, py + s * dx + c * dy
        bvx, bvy = c * vbx - s * vby, s * vbx + c * vby
        for j in range(opponents.shape[0]):
            mx, my = o[opponents[j, 0]], o[opponents[j, 1]]
            opps[j, 0], opps[j, 1] = px + c * mx - s * my, py + s * mx + c * my
        k = index[i]
        if has_keeper and k == 0:
            if not keeper_should_clear(p, bx, by, bvx, bvy):
                guard[i] = True
                continue
            action = attacker_act(p, a, px, py, c, s, bx, by, bvx, bvy, dx, opps, True)
        else:
            xs[k], ys[k] = px, py
            for j in range(mates.shape[0]):
                m = j if j < k else j + 1
                mx, my = o[mates[j, 0]], o[mates[j, 1]]
                xs[m], ys[m] = px + c * mx - s * my, py + s * mx + c * my
            action = field_player(p, a, spacing, first, team_size, px, py, c, s, bx, by, bvx,
                                  bvy, dx, dy, k, xs, ys, opps, -1)
        for j in range(6):
            out[i, j] = action[j]
    return guard


class OpenPlay:
    """The open play of a scripted SSL team (see the module docstring).

    Args:
        view: the team's observation view.
        roles: the team's roles.
        attack: the attacker's play.
        defence: the defenders' play.
        keeper: the scripted goalkeeper robot 0 plays (of a team of two or more).
        kick_power: the kicker power the keeper's kicks are capped at (``(0, 1]``).
        catch: whether the guarding keeper catches the ball (no kick, the dribbler on)
            instead of kicking it away (the game flow's play; see the module docstring).
    """

    def __init__(self, view: ObservationView, roles: Roles, attack: Attack, defence: Defence,
                 keeper: ScriptedGoalkeeper, kick_power: float, catch: bool = False) -> None:
        self.view, self.roles, self.attack, self.defence = view, roles, attack, defence
        self.keeper = keeper
        self.kick_power = kick_power
        self.catch = bool(catch)
        self.pitch = attack.geometry.pitch
        # The observation columns open_play_rows reads.
        self.frame_index = np.array(view.frame_index, dtype=np.int64)
        self.mate_index = np.array(view.mates, dtype=np.int64).reshape(-1, 2)
        self.opponent_index = np.array(view.opponents, dtype=np.int64).reshape(-1, 2)

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
        if keeper_should_clear(self.pitch, f.bx, f.by, f.bvx, f.bvy):
            return self.attack.act(f, opps, keeper=True)
        return self.keeper_guard(o)

    def keeper_guard(self, o: list[float]) -> list[float]:
        """The scripted goalkeeper's action, its kicker power capped at the team's (or, with
        ``catch``, no kick and the dribbler on)."""
        action = self.keeper(o).tolist()  # it reads entries by index: a list will do
        if self.catch:
            action[3], action[5] = 0.0, 1.0
        else:
            action[3] = min(action[3], self.kick_power)
        return action

    def field_player_act(self, index: int, f: Frame, xs: list[float], ys: list[float],
                         opps: Opponents, barred: int = -1) -> list[float]:
        """:func:`field_player` for field player ``index`` (``xs``, ``ys``: the team's robots
        by index [m]; robot ``barred`` never attacks)."""
        roles = self.roles
        return list(field_player(self.pitch, self.attack.striker, self.defence.spacing,
                                 roles.first, roles.team_size, f.px, f.py, f.c, f.s, f.bx,
                                 f.by, f.bvx, f.bvy, f.dx, f.dy, index,
                                 np.array(xs, dtype=np.float64),
                                 np.array(ys, dtype=np.float64), opponent_array(opps), barred))

    # ------------------------------------------------------------------------------------
    # Observation rows

    def act_rows(self, obs: np.ndarray, index: np.ndarray) -> np.ndarray:
        """Actions ``(n, 6)`` float32 for ``n`` observation rows ``(n, obs_dim)`` of robots
        ``index`` (``(n,)`` ints): :meth:`act` row by row, by :func:`open_play_rows` and, for
        the guarding keepers, the goalkeeper's ``act_batch``."""
        out = np.empty((len(index), 6), dtype=np.float32)
        guard = open_play_rows(self.pitch, self.attack.striker, self.defence.spacing,
                               self.roles.has_keeper, self.roles.team_size,
                               np.ascontiguousarray(obs, dtype=np.float64),
                               np.asarray(index, dtype=np.int64), self.frame_index,
                               self.mate_index, self.opponent_index, out)
        if guard.any():
            out[guard] = self.keeper.act_batch(obs[guard])
            if self.catch:
                out[guard, 3], out[guard, 5] = 0.0, 1.0
            elif self.kick_power < 1.0:
                out[guard, 3] = np.minimum(out[guard, 3], self.kick_power)
        return out
