"""The first table of Xu et al.'s (2012) Hough-fusion reproduction: the head camera and the
paper's reading along the path, each weighting's error, the robots' own errors and the error
against the number of robots (see :mod:`soccer_lab.papers.hough`)."""

from __future__ import annotations

from itertools import combinations
from typing import Any

import numpy as np

from estimators import HeadCamera
from soccer_lab.papers.hough.sightings import (
    PAPER_SIGMA,
    ROBOTS_MM,
    WEIGHTINGS,
    ball_path,
    fuse,
    sightings_camera,
    sightings_paper,
)

__all__ = ["evaluate", "simulate"]


def evaluate(model: str, trials: int, rng: np.random.Generator, **kw: float
             ) -> dict[str, Any]:
    """The errors [m] of noise model ``model`` (``"camera"``: :func:`sightings_camera` with
    ``kw``'s ``pixel_sigma``, ``pose_sigma``, ``heading_sigma`` and ``sway_sigma``;
    ``"paper"``: :func:`sightings_paper` with ``kw``'s ``sigma``), ``trials`` draws from
    ``rng`` per ball position along the path: each weighting's mean error of the fused
    position, each robot's own mean error and the best of them, the mean error against the
    number of robots (``1/L`` weights, every subset of that many robots; one robot: its own
    estimate) and the number of (nearly) parallel line sets that fell back to a weighted
    mean."""
    robots = ROBOTS_MM / 1000.0
    path = ball_path() / 1000.0
    cam = HeadCamera()
    n = len(robots)
    err = {w: [] for w in WEIGHTINGS}
    single = [[] for _ in range(n)]
    by_count: dict[int, list[float]] = {m: [] for m in range(1, n + 1)}
    fallbacks = [0]
    for ball in path:
        for _ in range(trials):
            if model == "camera":
                pos, est = sightings_camera(ball, robots, rng, cam, kw["pixel_sigma"],
                                            kw["pose_sigma"], kw["heading_sigma"],
                                            kw["sway_sigma"])
            else:
                pos, est = sightings_paper(ball, robots, rng, kw["sigma"])
            for i in range(n):
                single[i].append(float(np.hypot(*(est[i] - ball))))
            for w in WEIGHTINGS:
                fused = fuse(pos, est, w, fallbacks)
                err[w].append(float(np.hypot(*(fused - ball))))
            for m in range(1, n + 1):  # every subset of m robots, inverse weights
                for sub in combinations(range(n), m):
                    idx = list(sub)
                    if m == 1:
                        by_count[m].append(single[idx[0]][-1])
                    elif m == n:  # all robots: fused above
                        by_count[m].append(err["inverse"][-1])
                    else:
                        fused = fuse(pos[idx], est[idx], "inverse", fallbacks)
                        by_count[m].append(float(np.hypot(*(fused - ball))))
    singles = [float(np.mean(s)) for s in single]
    return {"mean_m": {w: float(np.mean(v)) for w, v in err.items()},
            "single_m": singles, "best_single_m": min(singles),
            "by_count_m": {m: float(np.mean(v)) for m, v in by_count.items()},
            "parallel_fallbacks": fallbacks[0]}


def simulate(s: Any) -> tuple[dict[str, Any], dict[str, Any]]:
    """Both noise models' errors (:func:`evaluate`) for the settings ``s``
    (:class:`~soccer_lab.papers.hough.Settings`), the head camera's first, from one generator
    seeded with ``s.seed``."""
    rng = np.random.default_rng(s.seed)
    cam = evaluate("camera", int(s.trials), rng, pixel_sigma=s.pixel_sigma,
                   pose_sigma=s.pose_sigma, heading_sigma=s.heading_sigma,
                   sway_sigma=s.sway_sigma)
    paper = evaluate("paper", int(s.trials), rng, sigma=PAPER_SIGMA)
    return cam, paper
