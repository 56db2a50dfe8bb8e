"""Moved to :mod:`agents.scripted.team`; this re-export goes when its importers move."""

from agents.scripted.team import TEAMS, ScriptedTeam

__all__ = ["ScriptedTeam", "TEAMS"]
