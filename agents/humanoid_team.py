"""Moved to :mod:`agents.scripted.humanoid`; this re-export goes when its importers move."""

from agents.scripted.humanoid import HumanoidTeam

__all__ = ["HumanoidTeam"]
