"""Moved to :mod:`agents.scripted.residual`; this re-export goes when its importers move.

``_team`` and ``_command`` remain for :mod:`agents.team_residual_vec_env` until it imports
:func:`~agents.scripted.residual.scripted_team_from_params` and
:func:`~agents.scripted.residual.residual_command`.
"""

from __future__ import annotations

import json

from agents.scripted import ScriptedTeam
from agents.scripted.residual import (
    TEAM_RESIDUAL,
    scripted_team_from_params,
    team_residual_command,
    team_residual_params,
)
from agents.scripted.residual import residual_command as _command  # noqa: F401

__all__ = ["TEAM_RESIDUAL", "team_residual_params", "team_residual_command"]


def _team(key: str) -> ScriptedTeam:
    return scripted_team_from_params(json.loads(key))
