"""Sensor randomisation: a team's sensor figures drawn afresh every episode.

``perception={"vision": "ssl-2012", "randomize": {"latency": (0.03, 0.12), "ball_sigma":
(0.001, 0.03), "ball_detection": (0.8, 1.0), "frame_rate": (25, 75)}}`` draws each named
figure of the team's sensor spec uniformly from its range at every reset, from the episode's
sensor stream (so a seed gives the same draws), so that one policy can be trained across the
conditions of several presets (domain randomisation). The figures not named keep the preset's
values. The team's filters are tuned to the drawn figures, as a team calibrates its vision.

SSL teams randomise their :class:`~soccer_env.presets.VisionSpec` (:data:`RANDOMIZABLE`
``["ssl"]``), humanoid teams their :class:`~soccer_env.presets.HeadCameraSpec`
(``["humanoid"]``). The actuation latency and command loss stay the preset's: the command
channels are built once per environment.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any, TypeVar

import numpy as np

__all__ = ["RANDOMIZABLE", "Ranges", "ranges", "check_ranges", "draw"]

#: Figures that can be randomised, per robot kind (fields of the sensor spec).
RANDOMIZABLE: dict[str, tuple[str, ...]] = {
    "ssl": ("frame_rate", "latency", "latency_jitter", "ball_sigma", "robot_sigma",
            "robot_sigma_theta", "ball_detection", "robot_detection", "dribbler_false_rate",
            "random_false_rate", "occlusion_threshold"),
    "humanoid": ("frame_rate", "latency", "latency_jitter", "pixel_sigma", "ball_range",
                 "landmark_range", "robot_range", "ball_detection", "landmark_detection",
                 "robot_detection", "false_ball_rate"),
}

#: Ranges as :class:`~soccer_env.perception.base.PerceptionConfig` keeps them: sorted
#: ``(field, low, high)`` triples (hashable, so configurations compare and hash).
Ranges = tuple[tuple[str, float, float], ...]

_S = TypeVar("_S")


def ranges(value: Mapping[str, Any] | Ranges | None) -> Ranges:
    """The ranges of ``randomize=``: a mapping ``{field: (low, high)}`` (or the triples, or
    None for none). Fields must be names of :data:`RANDOMIZABLE`; each range two finite numbers
    with ``low <= high``; otherwise ``ValueError`` naming the field."""
    if value is None:
        return ()
    if isinstance(value, Mapping):
        items = list(value.items())
    elif isinstance(value, tuple):
        items = [(name, (lo, hi)) for name, lo, hi in value]
    else:
        raise TypeError(f"perception randomize must be a mapping {{figure: (low, high)}}, got "
                        f"{type(value).__name__}")
    known = sorted(set(RANDOMIZABLE["ssl"]) | set(RANDOMIZABLE["humanoid"]))
    out = []
    for name, rng in items:
        if name not in known:
            raise ValueError(f"perception randomize: unknown figure {name!r}; allowed: {known}")
        try:
            lo, hi = (float(v) for v in rng)
        except (TypeError, ValueError):
            raise ValueError(f"perception randomize[{name!r}] must be (low, high), got "
                             f"{rng!r}") from None
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            raise ValueError(f"perception randomize[{name!r}] must be two finite numbers with "
                             f"low <= high, got {rng!r}")
        out.append((str(name), lo, hi))
    return tuple(sorted(out))


def check_ranges(spec: _S, value: Ranges, kind: str) -> None:
    """Raise ``ValueError`` unless every figure of ``value`` belongs to ``kind``'s sensor spec
    and both ends of its range make a valid ``spec`` (the spec's own checks name the
    figure and its allowed values)."""
    allowed = RANDOMIZABLE[kind]
    for name, lo, hi in value:
        if name not in allowed:
            raise ValueError(f"perception randomize: {name!r} is no figure of a {kind} "
                             f"team's sensor; allowed: {list(allowed)}")
        for end in (lo, hi):
            try:
                dataclasses.replace(spec, **{name: end})
            except (ValueError, TypeError) as err:
                raise ValueError(f"perception randomize[{name!r}] = ({lo}, {hi}): {err}"
                                 ) from None


def draw(spec: _S, value: Ranges, rng: np.random.Generator) -> _S:
    """``spec`` with every figure of ``value`` drawn uniformly from its range (in the
    ranges' sorted order, one draw each)."""
    if not value:
        return spec
    drawn = {name: float(rng.uniform(lo, hi)) for name, lo, hi in value}
    return dataclasses.replace(spec, **drawn)
