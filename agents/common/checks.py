"""Argument checks shared by the runs, the evaluation and the environment adapters."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

__all__ = ["check_full_infos", "check_counts", "positive_seconds"]


def check_full_infos(env_kwargs: Mapping[str, Any] | None, where: str) -> None:
    """Raise ``ValueError`` if ``env_kwargs`` ask for flat infos: the package's evaluation,
    training and match adapter read the full infos (truth, estimate, outcome names)."""
    mode = (env_kwargs or {}).get("info_mode", "full")
    if mode != "full":
        raise ValueError(f"{where} reads the environments' full infos: info_mode must be "
                         f"'full' (the default) there, got {mode!r} (info_mode='flat' is for "
                         "other RL libraries)")


def check_counts(config: Any, fields: tuple[tuple[str, int], ...]) -> None:
    """Raise ``ValueError`` naming the field unless each ``(name, low)`` of ``fields`` is an
    integer (not a bool) >= ``low`` on ``config``: the counts of a training configuration."""
    for name, low in fields:
        value = getattr(config, name)
        if not isinstance(value, (int, np.integer)) or isinstance(value, bool) or value < low:
            raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")


def positive_seconds(value: Any, name: str) -> float:
    """``value`` as a float number of seconds; ``ValueError`` naming the argument ``name``
    unless it is a real number (not a bool), finite and > 0."""
    seconds = math.nan
    if not isinstance(value, bool) and isinstance(value, (int, float, np.integer, np.floating)):
        try:
            seconds = float(value)
        except OverflowError:  # an integer beyond any float
            seconds = math.inf
    if not math.isfinite(seconds) or seconds <= 0:
        raise ValueError(f"{name} must be a finite number of seconds > 0, got {value!r}")
    return seconds
