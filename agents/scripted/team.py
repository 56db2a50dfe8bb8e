"""A scripted team for the match: a keeper, an attacker and defenders, from observations only.

Every robot decides from its own observation vector (the layout of
:mod:`soccer_env.observations`, found by entry name: :mod:`agents.scripted.view`), so the team
runs on whatever the observation mode provides (``"truth"``, ``"raw"`` or ``"perceived"``) and
on either side (observations are in each team's own frame, which attacks ``+x``). No state is
kept between steps: the same observations always give the same actions.

Roles, decided by each robot from the team-mates' relative positions in its observation (all
robots of a team read the same belief, so they agree; :mod:`agents.scripted.roles`):

* **keeper**: robot 0 when the team has two or more robots. It plays
  :class:`~soccer_env.envs.keeper.ScriptedGoalkeeper` (guard line in front of the goal, moving to
  where the ball's predicted path crosses it), except that it clears a slow ball lying in its
  own defense area, which no other robot may enter (:mod:`agents.scripted.open_play`).
* **attacker**: the non-keeper robot with the lowest cost to reach the ball (distance, plus a
  penalty when it stands between the ball and the opponent goal). It drives to a point behind
  the ball on the line from an open point of the opponent goal mouth through the ball (the
  one needing the least repositioning), turns to face it, drives through the ball and arms
  its kicker while its heading points into the goal mouth past every opponent. When every
  shooting line is blocked by a nearby opponent it dribbles diagonally past it instead. It
  predicts a moving ball's position with :class:`~estimators.FrictionBallModel` and stays
  out of the own defense area (:mod:`agents.scripted.attack`).
* **defenders**: the others, in lines of up to three between the ball and the own goal,
  spread across the goal-ball line and kept out of the own defense area. They face the ball
  and clear it forward when it reaches their kicker (:mod:`agents.scripted.defence`).

Without the game flow, restarts are played like open play (the simple referee moves robots at
a restart but does not enforce the stop distance afterwards), and the opponent defense area is
not avoided. In a match with the game flow (``game=...``) the team reads the referee state
at the end of its observations and plays the restarts as the rules ask
(:mod:`agents.scripted.restarts`, :mod:`agents.scripted.placement`): keeping its distance at
stop and at the opponents' restarts, placing the ball with the dribbler, taking its kick-offs,
free kicks and penalty kicks with one kick no faster than the ball speed limit, and leaving
the ball alone after taking a restart until another robot has touched it.

All positions are in the team frame [m], headings in radians, speeds in m/s.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from agents.scripted.attack import Attack
from agents.scripted.defence import Defence
from agents.scripted.geometry import TeamGeometry
from agents.scripted.humanoid import HumanoidTeam
from agents.scripted.open_play import OpenPlay
from agents.scripted.placement import BallPlacement
from agents.scripted.restarts import RestartPlay
from agents.scripted.roles import Roles
from agents.scripted.view import ObservationView
from estimators import FrictionBallModel
from soccer_env import MAX_TEAM_SIZE, presets
from soccer_env.envs.keeper import ScriptedGoalkeeper
from soccer_env.presets import BallSpec, FieldSpec, SSLRobotSpec
from soccer_env.presets.rules import RuleSpec

__all__ = ["ScriptedTeam", "TEAMS", "scripted_team"]

#: Team names accepted by :meth:`ScriptedTeam.for_env`, in team-index order.
TEAMS = ("blue", "yellow")


class ScriptedTeam:
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
        exact: kept for compatibility, without effect: every rule of the team, the keeper's
            included, is a compiled kernel that computes lengths as ``math.hypot`` does, bit
            for bit, one robot or many.
        rules: the rule preset whose distances and limits the team keeps at restarts when
            its observations carry the game flow (default ``"ssl-2025-div-b"``;
            :meth:`for_env` passes the match's).

    Use :meth:`for_env` to build it from a match. Calls:

    * ``team(observations)``: a dict ``{agent: obs}`` (agents of other teams are ignored) to
      ``{agent: action}`` for this team's agents in it;
    * ``team.act(obs_batch)``: ``(n, obs_dim)`` observations of robots ``0..n-1`` of the team
      (``n = team_size``) to ``(n, 6)`` float32 actions; what
      :class:`~agents.vec.match.MatchVecEnv` uses for an opponent;
    * ``team.act_batch(obs)``: the same for ``M`` matches at once, ``(M, n, obs_dim)`` to
      ``(M, n, 6)``, computed on whole arrays.

    Its parts, each with one job: ``view`` (:class:`~agents.scripted.view.ObservationView`),
    ``geometry`` (:class:`~agents.scripted.geometry.TeamGeometry`), ``roles``
    (:class:`~agents.scripted.roles.Roles`), ``open_play``
    (:class:`~agents.scripted.open_play.OpenPlay`, with the attack, the defence and the
    ``keeper``) and, with the game flow, ``restarts``
    (:class:`~agents.scripted.restarts.RestartPlay`; else None).
    """

    def __init__(self, field: FieldSpec, ball: BallSpec, robot: SSLRobotSpec,
                 names: Sequence[str], team_size: int, prefix: str = "blue_",
                 guard_offset: float = 0.05, attack_speed: float = 2.0,
                 defender_spacing: float = 0.45, exact: bool = True,
                 rules: str | RuleSpec | None = None) -> None:
        if not 1 <= int(team_size) <= MAX_TEAM_SIZE:
            raise ValueError(f"team_size must be 1..{MAX_TEAM_SIZE}, got {team_size}")
        #: Where each robot finds its entries (raises for names that lack some).
        self.view = ObservationView(names, int(team_size))
        self.field, self.ball, self.robot = field, ball, robot
        self.team_size = int(team_size)
        self.prefix = prefix
        self.obs_size = self.view.size
        self.exact = bool(exact)
        self.geometry = TeamGeometry(field, ball, robot)
        self.roles = Roles(self.geometry, self.team_size)
        self.has_keeper = self.roles.has_keeper
        self.model = FrictionBallModel(ball.rolling_deceleration)
        self.keeper = ScriptedGoalkeeper(field, ball, robot, names, guard_offset=guard_offset)
        game = self.view.game
        self.rules = presets.rules(rules if rules is not None else "ssl-2025-div-b")
        # Kicker power of every kick: full without the game flow; with it, 0.2 m/s under
        # the ball speed limit (8.4.2).
        self.kick_power = 1.0 if game is None else min(
            1.0, (self.rules.ball_speed_limit - 0.2) / robot.kicker_max_speed)
        attack = Attack(self.geometry, self.model, attack_speed, self.kick_power,
                        avoid_opponent_defense=game is not None)
        self.attack_speed = attack.attack_speed
        defence = Defence(self.geometry, self.team_size, defender_spacing, self.kick_power)
        self.defender_spacing = defence.spacing
        self.open_play = OpenPlay(self.view, self.roles, attack, defence, self.keeper,
                                  self.kick_power, catch=game is not None)
        #: The restart play, with the game flow (else None).
        self.restarts = None if game is None else RestartPlay(
            self.open_play, BallPlacement(self.geometry, self.rules, game), self.rules, game)

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

    def act_one(self, obs: np.ndarray | Sequence[float], index: int) -> list[float]:
        """Action ``[vx, vy, omega, kick, chip, dribble]`` of robot ``index`` of the team from
        its own observation ``obs``."""
        if not 0 <= index < self.team_size:
            raise ValueError(f"index must be in 0..{self.team_size - 1}, got {index}")
        o = obs.tolist() if isinstance(obs, np.ndarray) else list(obs)
        f = self.view.frame(o)
        opps = self.view.opponents_of(o, f)
        if self.restarts is not None and self.restarts.needs_restart_play(o):
            xs, ys = self.view.team_positions(o, index, f)
            return self.restarts.act(o, index, f, xs, ys, opps)
        return self.open_play.act(o, index, f, opps)

    def act_batch(self, obs: np.ndarray) -> np.ndarray:
        """Actions ``(M, team_size, 6)`` float32 for the observations ``(M, team_size,
        obs_dim)`` (float32 or float64) of the team's robots ``0 .. team_size - 1`` in ``M``
        matches: ``np.stack([self.act(o) for o in obs])``, computed on all ``M * team_size``
        rows at once (``M = 0`` gives an empty array).

        The open-play rows go through one kernel call
        (:func:`~agents.scripted.open_play.open_play_rows`), which runs the same compiled
        rules as :meth:`act_one` (the same arithmetic on the same floats: the actions are
        equal bit for bit); the guarding keepers' rows through
        :meth:`~soccer_env.envs.keeper.ScriptedGoalkeeper.act_batch` (the keeper's compiled
        rule on each row, equal to its single path bit for bit too).
        Rows in a restart (:meth:`~agents.scripted.restarts.RestartPlay.needs_restart_play`)
        go through :meth:`act_one` one by one.
        """
        obs = np.asarray(obs)
        if obs.ndim != 3 or obs.shape[1:] != (self.team_size, self.obs_size):
            raise ValueError(f"obs must have shape (M, {self.team_size}, {self.obs_size}) (M "
                             f"matches, one row per robot of the team, in order), got "
                             f"{obs.shape}")
        rows = obs.reshape(-1, self.obs_size)
        index = np.tile(np.arange(self.team_size), obs.shape[0])
        if self.restarts is not None:
            special = self.restarts.needs_restart_play(rows)
            if special.any():
                # Restarts (and the rare rows that must leave the ball alone) row by row.
                out = np.empty((len(rows), 6), dtype=np.float32)
                plain = ~special
                if plain.any():
                    out[plain] = self.open_play.act_rows(rows[plain], index[plain])
                for k in np.flatnonzero(special):
                    out[k] = self.act_one(rows[k], int(index[k]))
                return out.reshape(obs.shape[:2] + (6,))
        return self.open_play.act_rows(rows, index).reshape(obs.shape[:2] + (6,))


def scripted_team(env: Any, team: str = "blue") -> ScriptedTeam | HumanoidTeam:
    """The scripted team of ``team`` (``"blue"`` or ``"yellow"``) of a (possibly wrapped)
    match, for its robots: :class:`~agents.scripted.humanoid.HumanoidTeam` for humanoids,
    :class:`ScriptedTeam` for SSL robots."""
    if team not in TEAMS:
        raise ValueError(f"team must be one of {list(TEAMS)}, got {team!r}")
    u = getattr(env, "unwrapped", env)
    spec = u.team_specs[TEAMS.index(team)] if hasattr(u, "team_specs") else u.robot_spec
    return (HumanoidTeam if spec.kind == "humanoid" else ScriptedTeam).for_env(u, team)
