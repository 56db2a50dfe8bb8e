"""A learned correction to the scripted SSL team (or the scripted humanoid team): the action
map of the shipped match team.

A team trained from scratch in the match has to learn to reach the ball, turn with it, aim and
kick before it can learn anything about playing against opponents; with the scripted team's
keeper in goal, goals are rare, and the learning signal is thin. Residual policy learning
(Silver et al. 2018, "Residual policy learning", arXiv:1812.06298; Johannink et al. 2019,
"Residual reinforcement learning for robot control", ICRA) starts the learner from a
controller that already plays: the robot's command is the scripted team's command
(:class:`~agents.scripted.team.ScriptedTeam`, from the same observation) plus the learner's
correction,

    ``u = clip(u_s + a * residual, -1, 1)``, per entry of ``(vx, vy, omega, kick, chip,
    dribble)``,

with ``a`` the learner's action in ``[-1, 1]^6``. The scripted team's "off" of a switch
(kick ``0``, chip and dribbler ``-1``) is first moved to ``-1``, so that an action of ``0``
plays the scripted team exactly and switching the kicker, the chip or the dribbler on takes
a correction of more than ``+1`` (``residual = 1`` lets the learner override every entry).

The map reads the robot's number in its team from the row's place in the batch: the scripted
team's roles depend on it (robot 0 keeps goal), and an observation does not carry it. Rows
come as whole teams, robots in order (``(M * team_size, obs_dim)``, match after match), as
:class:`~agents.vec.match.MatchVecEnv` lays out a team's entries and as
:func:`agents.studies.matches.team_policy` calls a team's policy. Under the game flow a robot
sent off keeps its row (its observation says so, ``game.on_field``, and its team-mates' say
which slot is empty), and the correction applies in open play only: while the game is
stopped, at restarts, for a robot off the field and for the robot that took a restart and may
not touch the ball again, the command is the scripted team's, which keeps the rules'
distances, speeds and the double-touch rule (:meth:`~agents.scripted.restarts.RestartPlay.
needs_restart_play`). The learner still sees every step and its observations carry the
referee state, so its open play can prepare for what the restarts do.

:func:`team_residual_params` records what rebuilds the scripted team (the specs as numbers, the
observation's entry names, the team size), so a saved :class:`~agents.policies.NumpyPolicy`
with ``action_map={"kind": "team-residual", "params": ...}`` acts on the plain match without
the environment it was trained in (:func:`team_residual_command`). A caller that applies the
map at every step rebuilds the team once (:func:`scripted_team_from_params`) and calls
:func:`residual_command` with it, as :class:`~agents.vec.team_residual.TeamResidualVecEnv`
does in training.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Mapping
from functools import lru_cache
from typing import Any

import numpy as np

from agents.scripted.humanoid import HumanoidTeam
from agents.scripted.team import TEAMS, ScriptedTeam, scripted_team
from soccer_env.presets import BallSpec, FieldSpec, HumanoidRobotSpec, SSLRobotSpec
from soccer_env.presets.rules import RuleSpec

__all__ = ["TEAM_RESIDUAL", "HUMANOID_IDLE_MOTION", "team_residual_params", "team_residual_command",
           "scripted_team_from_params", "residual_command", "ignored_rows"]

#: The largest correction of every command entry (1: the learner can override the scripted
#: command entirely).
TEAM_RESIDUAL = 1.0

#: The command entries that are switches (on when ``> 0``): kick, chip, dribble.
_SWITCHES = (3, 4, 5)
#: The keys of the map's params.
_PARAMS = ("team_size", "residual", "names", "field", "ball", "robot")
#: A humanoid's motion entry (3) when the scripted team neither kicks nor dives: the middle of
#: the band that does neither, ``(-0.5, 0]``, so that a correction of up to 0.25 either way
#: changes nothing.
HUMANOID_IDLE_MOTION = -0.25


def team_residual_params(env: Any, team: str = "blue", residual: float = TEAM_RESIDUAL
                         ) -> dict[str, Any]:
    """The constants of the ``"team-residual"`` map for ``team`` of the match ``env`` (possibly
    wrapped): the field, ball and robot specs as numbers, the observation's entry names, the
    team size, ``residual`` and, under the SSL game flow, the rule preset as numbers; for a
    humanoid team ``"kind": "humanoid"`` (its scripted team is
    :class:`~agents.scripted.humanoid.HumanoidTeam`)."""
    u = getattr(env, "unwrapped", env)
    if team not in TEAMS:
        raise ValueError(f"team must be one of {list(TEAMS)}, got {team!r}")
    if not (np.isfinite(residual) and 0.0 < residual <= 2.0):
        raise ValueError(f"residual must be in (0, 2], got {residual!r}")
    scripted = scripted_team(u, team)
    params = {"team_size": scripted.team_size, "residual": float(residual),
              "names": list(u.builder.names_for(team)),
              "field": dataclasses.asdict(scripted.field),
              "ball": dataclasses.asdict(scripted.ball),
              "robot": dataclasses.asdict(scripted.robot)}
    if isinstance(scripted, HumanoidTeam):
        params["kind"] = "humanoid"
    elif scripted.restarts is not None:
        params["rules"] = dataclasses.asdict(scripted.rules)
    return params


def scripted_team_from_params(params: Mapping[str, Any]) -> ScriptedTeam | HumanoidTeam:
    """The scripted team of ``"team-residual"`` params (:func:`team_residual_params`),
    rebuilt from them alone; the last few are kept, keyed by the params' sorted JSON.

    Raises:
        ValueError: params lacking one of their keys.
    """
    return _team_of(json.dumps(dict(params), sort_keys=True))


@lru_cache(maxsize=8)
def _team_of(key: str) -> ScriptedTeam | HumanoidTeam:
    """:func:`scripted_team_from_params` of the params as sorted JSON."""
    params = json.loads(key)
    missing = [k for k in _PARAMS if k not in params]
    if missing:
        raise ValueError(f"the 'team-residual' map's params lack {missing} (see "
                         "team_residual_params)")

    def spec(cls: type, d: Mapping[str, Any]) -> Any:
        d = {k: tuple(v) if isinstance(v, list) else v for k, v in d.items()}
        return cls(**d)

    field, ball = spec(FieldSpec, params["field"]), spec(BallSpec, params["ball"])
    size = int(params["team_size"])
    if params.get("kind", "ssl") == "humanoid":
        return HumanoidTeam(field, ball, spec(HumanoidRobotSpec, params["robot"]),
                            params["names"], [f"robot_{k}" for k in range(size)])
    rules = spec(RuleSpec, params["rules"]) if "rules" in params else None
    return ScriptedTeam(field, ball, spec(SSLRobotSpec, params["robot"]), params["names"],
                        size, rules=rules)


def team_residual_command(obs: np.ndarray, act: np.ndarray, params: Mapping[str, Any]
                          ) -> np.ndarray:
    """The ``"team-residual"`` map: native commands ``(n, 6)`` float32 for observations
    ``(n, obs_dim)`` and actions ``(n, 6)`` of whole teams, robots in order (``n`` a multiple
    of the team size): ``clip(u_s + a * residual, -1, 1)`` with ``u_s`` the scripted team's
    command, its switches' "off" moved to ``-1`` (see the module docstring)."""
    return residual_command(scripted_team_from_params(params), float(params["residual"]),
                            obs, act)


def ignored_rows(team: ScriptedTeam | HumanoidTeam, obs: np.ndarray) -> np.ndarray:
    """Which rows of ``obs`` ``(n, obs_dim)`` the map plays the scripted command for, whatever
    the correction: an SSL robot in a restart, off the field or barred from the ball
    (:meth:`~agents.scripted.restarts.RestartPlay.needs_restart_play`, under the game flow
    only), a humanoid off the field or waiting out the opponents' restart
    (:meth:`~agents.scripted.HumanoidTeam.waiting_rows`). A bool array ``(n,)``."""
    obs = np.asarray(obs)
    if isinstance(team, HumanoidTeam):
        return np.asarray(team.waiting_rows(obs), dtype=bool)
    if team.restarts is None:
        return np.zeros(len(obs), dtype=bool)
    return np.asarray(team.restarts.needs_restart_play(obs), dtype=bool)


def residual_command(team: ScriptedTeam | HumanoidTeam, residual: float, obs: np.ndarray,
                     act: np.ndarray, ignored: np.ndarray | None = None) -> np.ndarray:
    """:func:`team_residual_command` with the scripted team already rebuilt
    (:func:`scripted_team_from_params`) and its ``residual`` read from the params.

    For humanoids the motion entry's "neither kick nor dive" moves to
    :data:`HUMANOID_IDLE_MOTION` instead; the correction is zero on :func:`ignored_rows`
    (``ignored``, when the caller has them already)."""
    obs = np.asarray(obs)
    act = np.clip(np.asarray(act, dtype=np.float64), -1.0, 1.0)
    if obs.ndim != 2 or act.shape != (len(obs), 6):
        raise ValueError(f"the 'team-residual' map takes observations (n, obs_dim) and actions "
                         f"(n, 6) of whole teams, got {obs.shape} and {act.shape}")
    size = team.team_size
    if len(obs) % size:
        raise ValueError(f"the 'team-residual' map acts on whole teams of {size} robots, in "
                         f"order (its roles depend on the robot's number); got {len(obs)} "
                         "rows")
    base = team.act_batch(obs.reshape(-1, size, obs.shape[1])).reshape(-1, 6)
    base = base.astype(np.float64)
    act[ignored_rows(team, obs) if ignored is None else ignored] = 0.0
    if isinstance(team, HumanoidTeam):
        base[:, 3] = np.where(base[:, 3] != 0.0, base[:, 3], HUMANOID_IDLE_MOTION)
    else:
        switches = list(_SWITCHES)
        base[:, switches] = np.where(base[:, switches] > 0.0, base[:, switches], -1.0)
    return np.clip(base + act * residual, -1.0, 1.0).astype(np.float32)
