"""Agents: scripted baselines (and, with the training extra, learning utilities)."""

from agents.goalkeeper import ScriptedGoalkeeper

__all__ = ["ScriptedGoalkeeper"]
