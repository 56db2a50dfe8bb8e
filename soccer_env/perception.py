"""Perception: what a team believes about the world, fed to the observation builder.

A perception pipeline turns the true :class:`~soccer_env.state.WorldState` into a belief with
the same ``ball`` and ``robots`` arrays (field frame). ``obs_mode="truth"`` uses
:class:`TruthPerception`, the oracle that passes the truth through. The sensor models and
estimators of the perception stack (``obs_mode="raw"`` and ``"perceived"``) implement the
same protocol.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from .state import WorldState

__all__ = ["Belief", "Perception", "TruthPerception", "OBS_MODES", "make_perception"]

#: Observation modes available now.
OBS_MODES = ("truth",)


class Belief(Protocol):
    """Anything with field-frame ``ball`` ``(6,)`` and ``robots`` ``(N, 6)`` arrays laid out as
    in :class:`~soccer_env.state.WorldState`, and the ``time`` they refer to."""

    time: float
    ball: np.ndarray
    robots: np.ndarray


class Perception(Protocol):
    """One team's perception pipeline."""

    def reset(self, state: WorldState, rng: np.random.Generator) -> Belief:
        """Start a new episode at ``state``; return the first belief."""
        ...

    def update(self, state: WorldState) -> Belief:
        """Advance to ``state`` (one control step later); return the new belief."""
        ...


class TruthPerception:
    """The oracle of ``obs_mode="truth"``: the belief is the true state itself."""

    def reset(self, state: WorldState, rng: np.random.Generator) -> Belief:
        return state

    def update(self, state: WorldState) -> Belief:
        return state


def make_perception(obs_mode: str) -> Perception:
    """Perception pipeline for ``obs_mode``; unknown modes raise ``ValueError``."""
    if obs_mode == "truth":
        return TruthPerception()
    raise ValueError(f"obs_mode must be one of {list(OBS_MODES)}, got {obs_mode!r}")
