"""Agents: scripted baselines (and, with the training extra, learning utilities)."""

from soccer_env.envs.keeper import ScriptedGoalkeeper

__all__ = ["ScriptedGoalkeeper"]
