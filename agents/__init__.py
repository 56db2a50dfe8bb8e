"""Agents: scripted baselines (and, with the training extra, learning utilities)."""

from .goalkeeper import ScriptedGoalkeeper

__all__ = ["ScriptedGoalkeeper"]
