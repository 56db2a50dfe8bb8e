"""Moved to :mod:`agents.scripted.restarts`; this re-export goes when its importers move."""

from agents.scripted.restarts import SITUATION_NAMES, RestartPlay

__all__ = ["RestartPlay", "SITUATION_NAMES"]
