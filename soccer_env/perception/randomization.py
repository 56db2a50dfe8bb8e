"""Sensor randomisation: a team's sensor figures drawn afresh every episode.

``perception={"vision": "ssl-2012", "randomize": {"latency": (0.03, 0.12), "ball_sigma":
(0.001, 0.03), "ball_detection": (0.8, 1.0), "frame_rate": (25, 75)}}`` draws each named
figure of the team's sensor spec uniformly from its range at every reset, from the episode's
sensor stream (so a seed gives the same draws), so that one policy can be trained across the
conditions of several presets (domain randomisation). The figures not named keep the preset's
values. The team's filters are tuned to the drawn figures, as a team calibrates its vision.

``"preset": ["ssl-2012", "realistic"]`` among the entries draws a whole preset per episode
(each with equal probability, before the figures; the figures then replace the drawn preset's),
so that training alternates between setups whose figures differ together (a 25 Hz camera with
large noise and latency, a 60 Hz one with little) instead of mixing them independently.

SSL teams randomise their :class:`~soccer_env.presets.VisionSpec` (:data:`RANDOMIZABLE`
``["ssl"]``; presets of :data:`~soccer_env.presets.VISION`), including the actuation latency
and command loss of their radio link, humanoid teams their
:class:`~soccer_env.presets.HeadCameraSpec` (``["humanoid"]``; presets of
:data:`~soccer_env.presets.HEAD_CAMERAS`).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np

from soccer_env.presets import HEAD_CAMERAS, VISION

__all__ = ["RANDOMIZABLE", "PRESET", "Ranges", "Randomization", "ranges", "check_ranges",
           "draw"]

#: Figures that can be randomised, per robot kind (fields of the sensor spec).
RANDOMIZABLE: dict[str, tuple[str, ...]] = {
    "ssl": ("frame_rate", "latency", "latency_jitter", "actuation_latency", "command_loss",
            "ball_sigma", "robot_sigma", "robot_sigma_theta", "ball_detection",
            "robot_detection", "dribbler_false_rate", "random_false_rate",
            "occlusion_threshold"),
    "humanoid": ("frame_rate", "latency", "latency_jitter", "pixel_sigma", "ball_range",
                 "landmark_range", "robot_range", "ball_detection", "landmark_detection",
                 "robot_detection", "false_ball_rate"),
}

#: The entry of ``randomize=`` that draws a whole preset per episode.
PRESET = "preset"

#: The presets ``"preset"`` may name, per robot kind.
_TABLES: dict[str, Mapping[str, Any]] = {"ssl": VISION, "humanoid": HEAD_CAMERAS}

#: Figure ranges as sorted ``(field, low, high)`` triples.
Ranges = tuple[tuple[str, float, float], ...]

_S = TypeVar("_S")


@dataclass(frozen=True)
class Randomization:
    """What :class:`~soccer_env.perception.base.PerceptionConfig` keeps of ``randomize=``
    (hashable, so configurations compare and hash).

    Attributes:
        presets: preset names drawn from per episode (empty: the configuration's own spec).
        figures: figure ranges drawn per episode, sorted ``(field, low, high)`` triples.
    """

    presets: tuple[str, ...] = ()
    figures: Ranges = ()

    def __bool__(self) -> bool:
        return bool(self.presets or self.figures)


def ranges(value: Mapping[str, Any] | Ranges | Randomization | None) -> Randomization:
    """The randomisation of ``randomize=``: a mapping ``{figure: (low, high), "preset":
    [names]}`` (or the figures' triples, a :class:`Randomization`, or None for none). Figures
    must be names of :data:`RANDOMIZABLE`; each range two finite numbers with ``low <= high``;
    ``"preset"`` a non-empty list of names; otherwise ``ValueError`` naming the entry."""
    if value is None:
        return Randomization()
    if isinstance(value, Randomization):
        return value
    if isinstance(value, Mapping):
        items = list(value.items())
    elif isinstance(value, tuple):
        items = [(name, (lo, hi)) for name, lo, hi in value]
    else:
        raise TypeError(f"perception randomize must be a mapping {{figure: (low, high)}}, got "
                        f"{type(value).__name__}")
    known = sorted(set(RANDOMIZABLE["ssl"]) | set(RANDOMIZABLE["humanoid"]))
    out, presets = [], ()
    for name, rng in items:
        if name == PRESET:
            names = [rng] if isinstance(rng, str) else rng
            if (not isinstance(names, (list, tuple)) or not names
                    or not all(isinstance(n, str) for n in names)):
                raise ValueError(f"perception randomize[{PRESET!r}] must be a non-empty list "
                                 f"of preset names, got {rng!r}")
            presets = tuple(names)
            continue
        if name not in known:
            raise ValueError(f"perception randomize: unknown figure {name!r}; allowed: "
                             f"{[PRESET, *known]}")
        try:
            lo, hi = (float(v) for v in rng)
        except (TypeError, ValueError):
            raise ValueError(f"perception randomize[{name!r}] must be (low, high), got "
                             f"{rng!r}") from None
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            raise ValueError(f"perception randomize[{name!r}] must be two finite numbers with "
                             f"low <= high, got {rng!r}")
        out.append((str(name), lo, hi))
    return Randomization(presets, tuple(sorted(out)))


def check_ranges(spec: _S, value: Randomization, kind: str) -> None:
    """Raise ``ValueError`` unless every preset of ``value`` is one of ``kind``'s, every
    figure belongs to ``kind``'s sensor spec and both ends of its range make a valid spec
    from ``spec`` (or each drawn preset; the spec's own checks name the figure and its allowed
    values)."""
    table = _TABLES[kind]
    unknown = [name for name in value.presets if name not in table]
    if unknown:
        raise ValueError(f"perception randomize[{PRESET!r}]: unknown {kind} sensor preset(s) "
                         f"{unknown}; known: {sorted(table)}")
    allowed = RANDOMIZABLE[kind]
    bases = [table[name] for name in value.presets] or [spec]
    for name, lo, hi in value.figures:
        if name not in allowed:
            raise ValueError(f"perception randomize: {name!r} is no figure of a {kind} "
                             f"team's sensor; allowed: {list(allowed)}")
        for base in bases:
            for end in (lo, hi):
                try:
                    dataclasses.replace(base, **{name: end})
                except (ValueError, TypeError) as err:
                    raise ValueError(f"perception randomize[{name!r}] = ({lo}, {hi}): {err}"
                                     ) from None


def draw(spec: _S, value: Randomization, rng: np.random.Generator, kind: str = "ssl") -> _S:
    """``spec``, or one of ``value``'s presets (equally likely, one draw), with every figure
    of ``value`` drawn uniformly from its range (in the ranges' sorted order, one draw
    each)."""
    if value.presets:
        spec = _TABLES[kind][value.presets[int(rng.integers(len(value.presets)))]]
    if not value.figures:
        return spec
    drawn = {name: float(rng.uniform(lo, hi)) for name, lo, hi in value.figures}
    return dataclasses.replace(spec, **drawn)
