"""The measures of Guo and Li's (2013) reproduction: a filter's pose errors and the mirror
pose, the time to localize or to recover, and each filter's figures over the episodes (medians,
with "never" counted as infinitely late); see :mod:`soccer_lab.papers.localization`."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["SETTLE", "GLOBAL_WINDOW", "RECOVERED_M", "RECOVERED_HOLD", "MIRROR_M",
           "MIRROR_RAD", "WRONG_M", "TRI_OUTCOMES", "MEDIAN_KEYS", "NEVER_KEYS", "AIM_POS_M",
           "TRI_KEYS", "localized_after", "pose_errors", "deg", "median", "over_episodes",
           "Summaries", "summarise"]

#: Errors and tracking particles count after this [s] from the start, and from the
#: kidnapping.
SETTLE = 5.0
#: The mean particles "in the first second" [s].
GLOBAL_WINDOW = 1.0
#: Localized (or recovered): the position error below this [m] ...
RECOVERED_M = 0.3
#: ... for this long [s].
RECOVERED_HOLD = 1.0

#: An estimate within this distance [m] and angle [rad] of the mirrored true pose ``(-x, -y,
#: theta + pi)`` (and farther than this from the truth) counts as at the mirror pose.
MIRROR_M, MIRROR_RAD = 0.5, math.radians(30.0)

#: A triangulated pose farther than this from the truth [m] is a wrong assignment.
WRONG_M = 0.5

#: Triangulation outcomes per frame, in the table's order: a pose within WRONG_M of the
#: truth, a wrong assignment (ambiguous landmarks), or no pose for one of the reasons of
#: :data:`~estimators.fusion.triangulation.SEED_FAILURES`.
TRI_OUTCOMES = ("correct", "wrong", "too_few", "degenerate", "no_fit")

#: Per-episode figures summarized by their median over the episodes (None where an episode
#: has none: left out; None if no episode has one).
MEDIAN_KEYS = ("median_pos_m", "median_head_deg", "median_pos_turning_m",
               "median_pos_straight_m", "initial_particles", "first_second_particles",
               "tracking_particles", "tracking_particles_median", "ms_per_update", "mirror_pct")
#: Times that may never happen (None): their median counts "never" as infinitely late.
NEVER_KEYS = ("localized_s", "recovery_s")
#: The position aim while walking [m].
AIM_POS_M = 0.15
#: Per-episode figures of triangulation alone, summarized by their median over the episodes.
TRI_KEYS = (*(f"{o}_pct" for o in TRI_OUTCOMES), "fix_pct", "mirror_pct", "median_pos_m",
            "median_head_deg", "median_pos_correct_m", "median_head_correct_deg",
            "ms_per_frame")


def localized_after(t: np.ndarray, err: np.ndarray, since: float, until: float) -> float | None:
    """Seconds from ``since`` until the error is below :data:`RECOVERED_M` and stays so for
    :data:`RECOVERED_HOLD` seconds (or until ``until``); None if never."""
    ok = err < RECOVERED_M
    idx = np.nonzero((t >= since) & (t < until))[0]
    for j in idx:
        if not ok[j]:
            continue
        window = idx[(t[idx] >= t[j]) & (t[idx] <= t[j] + RECOVERED_HOLD)]
        if ok[window].all():
            return float(t[j] - since)
    return None


def pose_errors(est: np.ndarray, truth: np.ndarray, wrong: float
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Position [m] and heading [rad] errors of the poses ``est`` ((n, 3); NaN rows: no pose)
    against ``truth``, and whether each lies at the pose the field's 180-degree symmetry makes
    look the same (only the goal-post colours tell them apart), more than ``wrong`` [m] from
    the truth."""
    err = np.hypot(est[:, 0] - truth[:, 0], est[:, 1] - truth[:, 1])
    herr = np.abs(np.remainder(est[:, 2] - truth[:, 2] + math.pi, 2.0 * math.pi) - math.pi)
    mirror = ((np.hypot(est[:, 0] + truth[:, 0], est[:, 1] + truth[:, 1]) < MIRROR_M)
              & (np.abs(np.remainder(est[:, 2] - truth[:, 2], 2.0 * math.pi) - math.pi)
                 < MIRROR_RAD) & (err > wrong))
    return err, herr, mirror


def deg(v: float | None) -> float | None:
    """``v`` [rad] in degrees, None for None."""
    return None if v is None else math.degrees(v)


def median(x: np.ndarray) -> float | None:
    """The median of ``x``, None when it is empty."""
    return float(np.median(x)) if len(x) else None


def over_episodes(per: list[dict[str, Any]], kidnap: bool) -> dict[str, Any]:
    """One filter's figures over the episodes: the median of each episode's figure; for the
    times to localize and to recover, the median with "never" as infinitely late (None when
    that is the median) and the number of episodes in which it never happened."""
    out: dict[str, Any] = {"episodes": len(per)}
    for key in MEDIAN_KEYS:
        vals = [r[key] for r in per if r[key] is not None]
        out[key] = float(np.median(vals)) if vals else None
    for key in NEVER_KEYS:
        never = sum(r[key] is None for r in per)
        if key == "recovery_s" and not kidnap:
            out[key], out["recovery_never"] = None, 0
            continue
        med = float(np.median([math.inf if r[key] is None else r[key] for r in per]))
        out[key] = med if math.isfinite(med) else None
        out[key.replace("_s", "_never")] = never
    out["pos_aim_episodes"] = sum(r["median_pos_m"] < AIM_POS_M for r in per)
    out["median_pos_m_per_episode"] = [r["median_pos_m"] for r in per]
    return out


@dataclass(frozen=True)
class Summaries:
    """Every filter's and triangulation's figures, per episode and over the episodes.

    Attributes:
        per_episode: per episode, filter name -> the scalar figures of its results.
        summary: filter name -> :func:`over_episodes` of its per-episode figures.
        tri_per_episode: per episode, triangulation name -> the scalar figures of its results.
        tri_summary: triangulation name -> the episodes and the median over the episodes of
            each figure of :data:`TRI_KEYS` (:func:`median`, episodes without one left out).
    """

    per_episode: list[dict[str, dict[str, Any]]]
    summary: dict[str, dict[str, Any]]
    tri_per_episode: list[dict[str, dict[str, Any]]]
    tri_summary: dict[str, dict[str, Any]]


def summarise(eps: list[dict[str, Any]], kidnap: bool) -> Summaries:
    """The figures of the episodes' results ``eps`` (of
    :func:`~soccer_lab.papers.localization.filters.episode_results`, every episode with the
    same filters and triangulations) per episode (their lists of per-frame values left out)
    and over the episodes; ``kidnap``: whether the robot was kidnapped (else no recovery
    time)."""
    names = list(eps[0]["results"])
    tri_names = list(eps[0]["triangulation"])
    per_episode = [{name: {k: v for k, v in ep["results"][name].items()
                           if not isinstance(v, list)} for name in names} for ep in eps]
    summary = {name: over_episodes([pe[name] for pe in per_episode], kidnap)
               for name in names}
    tri_per_episode = [{name: {k: v for k, v in ep["triangulation"][name].items()
                               if not isinstance(v, list)} for name in tri_names}
                       for ep in eps]
    tri_summary = {name: {"episodes": len(eps), **{
        key: median(np.array([pe[name][key] for pe in tri_per_episode
                              if pe[name][key] is not None]))
        for key in TRI_KEYS}} for name in tri_names}
    return Summaries(per_episode, summary, tri_per_episode, tri_summary)
