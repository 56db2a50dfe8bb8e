"""Scripted teams, the lowest layer of :mod:`agents` (numpy only: no stable-baselines3, torch
or Ray).

* :class:`ScriptedTeam` (:mod:`agents.scripted.team`): the SSL match team, built from its
  parts: the observation view (:mod:`~agents.scripted.view`), the team-frame geometry
  (:mod:`~agents.scripted.geometry`), the roles (:mod:`~agents.scripted.roles`), the attack
  (:mod:`~agents.scripted.attack`), the defence (:mod:`~agents.scripted.defence`), open play
  (:mod:`~agents.scripted.open_play`) and the game flow's restarts
  (:mod:`~agents.scripted.restarts`, :mod:`~agents.scripted.placement`);
* :class:`HumanoidTeam` (:mod:`agents.scripted.humanoid`): the humanoid match team;
* the ``"team-residual"`` action map (:mod:`agents.scripted.residual`): a learned correction
  to the scripted SSL or humanoid team's commands.
"""

from __future__ import annotations

from agents.scripted.humanoid import HumanoidTeam
from agents.scripted.residual import (
    HUMANOID_IDLE_MOTION,
    TEAM_RESIDUAL,
    ignored_rows,
    residual_command,
    scripted_team_from_params,
    team_residual_command,
    team_residual_params,
)
from agents.scripted.restarts import SITUATION_NAMES, RestartPlay
from agents.scripted.team import TEAMS, ScriptedTeam, scripted_team

__all__ = ["ScriptedTeam", "TEAMS", "HumanoidTeam", "scripted_team", "RestartPlay",
           "SITUATION_NAMES", "TEAM_RESIDUAL", "HUMANOID_IDLE_MOTION", "team_residual_params",
           "team_residual_command", "scripted_team_from_params", "residual_command",
           "ignored_rows"]
