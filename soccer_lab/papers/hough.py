"""Cooperative ball localization of paper 000 (Xu, Xie, Wang, Ni 2012): Hough-space fusion
on its Table 1 geometry.

``soccer-env paper hough``: five robots at the paper's positions (a 6 m x 4 m field), the ball
moving in 50 mm steps in a straight line from (3000, 3200) to (4500, 1200) mm. Each robot's
sighting becomes a line from its (estimated) position towards its estimate of the ball, and
:func:`estimators.hough_fuse` fuses the lines with equal, ``1/L`` and ``1/L^2`` weights.
Two noise models:

* **head camera** (ours): each robot turns its head (:class:`estimators.HeadCamera`, 0.56 m,
  51 degrees, 720 x 625) to look at the ball, the ball's pixel gets Gaussian noise
  (``pixel_sigma``), the gait sways the head so that the true tilt differs from the one the
  robot assumes by ``sway_sigma`` (our assumption: a walking KidSize torso rocks by a few
  degrees), and the robot projects the pixel back onto the ground with its assumed tilt; its
  own pose is known to ``pose_sigma`` (position, m) and ``heading_sigma`` (rad), as a
  localization would give. A
  pixel error moves the ground point along the ray by about ``d^2 / (h f)``, so far sightings
  are poor in range but good in bearing: fusing bearings from several robots beats any one
  robot's own estimate.
* **the paper's reading**: Gaussian noise of 192 mm on each robot's estimate of the ball (the
  paper does not say exactly what it perturbs; this is one reading), lines from the true robot
  positions.

Reports the mean error of the fused position along the path (``trials`` noise draws per ball
position), the best single robot's own estimate, and the error against the number of robots
(1 to 5; for one robot, its own estimate), beside the paper's figures.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from itertools import combinations
from pathlib import Path
from typing import Any

import numpy as np

from estimators import HeadCamera, fusion_weights, hough_fuse
from soccer_env.render.plots import pyplot, save_figure
from soccer_lab.papers._io import write_report

__all__ = ["run", "Settings", "ROBOTS_MM", "PATH_MM", "PAPER"]

#: Table 1 of paper 000 (millimetres): robot positions, the ball's straight path.
ROBOTS_MM = np.array([[1000, 3500], [250, 2000], [1750, 350], [4250, 2400], [5600, 3900]],
                     dtype=float)
PATH_MM = (np.array([3000.0, 3200.0]), np.array([4500.0, 1200.0]))
#: The paper's figures: mean error [mm] equal / weighted (simulation), hardware single robot
#: and weighted cooperative [mm], improvement.
PAPER = {"equal_mm": 118.0, "weighted_mm": 87.0, "hardware_single_mm": 86.0,
         "hardware_fused_mm": 45.0, "hardware_gain": 0.48}
WEIGHTINGS = ("equal", "inverse", "inverse_square")


def _path(step_mm: float = 50.0) -> np.ndarray:
    a, b = PATH_MM
    n = int(round(np.hypot(*(b - a)) / step_mm))
    return a + (b - a) * np.linspace(0.0, 1.0, n + 1)[:, None]


def _fuse(pos: np.ndarray, est: np.ndarray, weighting: str, fallbacks: list[int]
          ) -> np.ndarray:
    """Hough fusion of the lines from ``pos`` towards ``est``; for (nearly) parallel lines
    (the ball on the line through two robots) the weighted mean of the robots' own estimates,
    counted in ``fallbacks``."""
    dist = np.hypot(*(est - pos).T)
    w = fusion_weights(dist, weighting)
    try:
        return hough_fuse(pos, est - pos, weights=w)
    except ValueError:
        fallbacks[0] += 1
        return (w[:, None] * est).sum(axis=0) / w.sum()


def _sightings_camera(ball: np.ndarray, robots: np.ndarray, rng: np.random.Generator,
                      cam: HeadCamera, pixel_sigma: float, pose_sigma: float,
                      heading_sigma: float, sway_sigma: float
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Per robot: its estimated position and its estimate of the ball (field frame, m)."""
    est_pos = robots + rng.normal(0.0, pose_sigma, robots.shape)
    est_ball = np.empty_like(robots)
    for i, p in enumerate(robots):
        heading = rng.uniform(-math.pi, math.pi)  # the body faces anywhere; the head turns
        rel = ball - p
        c, s = math.cos(heading), math.sin(heading)
        local = np.array([[c * rel[0] + s * rel[1], -s * rel[0] + c * rel[1]]])
        dist = float(np.hypot(*rel))
        pan = math.atan2(local[0, 1], local[0, 0])
        tilt = math.atan2(cam.height, dist)  # the ball centred in the image
        uv, _ = cam.project(local, pan, tilt + rng.normal(0.0, sway_sigma))  # swaying head
        uv = uv + rng.normal(0.0, pixel_sigma, uv.shape)
        g = cam.ground_point(uv, pan, tilt)[0]  # with the tilt the robot believes
        if not np.all(np.isfinite(g)):  # above the horizon: no range, only a bearing
            g = local[0] * (cam.height / math.tan(0.5 * cam.vfov)) / dist
        h_est = heading + rng.normal(0.0, heading_sigma)  # the robot's belief
        ce, se = math.cos(h_est), math.sin(h_est)
        est_ball[i] = est_pos[i] + [ce * g[0] - se * g[1], se * g[0] + ce * g[1]]
    return est_pos, est_ball


def _sightings_paper(ball: np.ndarray, robots: np.ndarray, rng: np.random.Generator,
                     sigma: float) -> tuple[np.ndarray, np.ndarray]:
    return robots.copy(), ball + rng.normal(0.0, sigma, robots.shape)


def _evaluate(model: str, trials: int, rng: np.random.Generator, **kw: float
              ) -> dict[str, Any]:
    robots = ROBOTS_MM / 1000.0
    path = _path() / 1000.0
    cam = HeadCamera()
    n = len(robots)
    err = {w: [] for w in WEIGHTINGS}
    single = [[] for _ in range(n)]
    by_count: dict[int, list[float]] = {m: [] for m in range(1, n + 1)}
    fallbacks = [0]
    for ball in path:
        for _ in range(trials):
            if model == "camera":
                pos, est = _sightings_camera(ball, robots, rng, cam, kw["pixel_sigma"],
                                             kw["pose_sigma"], kw["heading_sigma"],
                                             kw["sway_sigma"])
            else:
                pos, est = _sightings_paper(ball, robots, rng, kw["sigma"])
            for i in range(n):
                single[i].append(float(np.hypot(*(est[i] - ball))))
            for w in WEIGHTINGS:
                fused = _fuse(pos, est, w, fallbacks)
                err[w].append(float(np.hypot(*(fused - ball))))
            for m in range(1, n + 1):  # every subset of m robots, inverse weights
                for sub in combinations(range(n), m):
                    idx = list(sub)
                    if m == 1:
                        by_count[m].append(single[idx[0]][-1])
                    elif m == n:  # all robots: fused above
                        by_count[m].append(err["inverse"][-1])
                    else:
                        fused = _fuse(pos[idx], est[idx], "inverse", fallbacks)
                        by_count[m].append(float(np.hypot(*(fused - ball))))
    singles = [float(np.mean(s)) for s in single]
    return {"mean_m": {w: float(np.mean(v)) for w, v in err.items()},
            "single_m": singles, "best_single_m": min(singles),
            "by_count_m": {m: float(np.mean(v)) for m, v in by_count.items()},
            "parallel_fallbacks": fallbacks[0]}


@dataclass(frozen=True)
class Settings:
    """What one run simulates (validated on construction).

    Attributes:
        out: the output folder.
        trials: noise draws per ball position (>= 1).
        seed: seeds the noise of both models.
        pixel_sigma: the ball's pixel noise of the head-camera model [px].
        pose_sigma, heading_sigma: the error of a robot's belief about its position [m] and
            heading [rad].
        sway_sigma: the gait's tilt sway that the robot does not know of [rad].
    """

    out: Path
    trials: int = 20
    seed: int = 0
    pixel_sigma: float = 2.0
    pose_sigma: float = 0.03
    heading_sigma: float = math.radians(1.0)
    sway_sigma: float = math.radians(2.0)

    def __post_init__(self) -> None:
        trials = self.trials
        if isinstance(trials, bool) or int(trials) != trials or trials < 1:
            raise ValueError(f"trials must be an integer >= 1, got {trials!r}")
        for name in ("pixel_sigma", "pose_sigma", "heading_sigma", "sway_sigma"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0.0):
                raise ValueError(f"{name} must be >= 0, got {v!r}")


def run(out: str | Path = "paper_output", trials: int = 20, seed: int = 0,
        pixel_sigma: float = 2.0, pose_sigma: float = 0.03,
        heading_sigma: float = math.radians(1.0), sway_sigma: float = math.radians(2.0)
        ) -> dict[str, Any]:
    """Run both noise models; write ``paper_hough.md``, ``.csv``, ``.json``, ``.png``."""
    s = Settings(Path(out), trials, seed, pixel_sigma, pose_sigma, heading_sigma, sway_sigma)
    t0 = time.perf_counter()
    s.out.mkdir(parents=True, exist_ok=True)
    cam, paper = _simulate(s)
    text, rows = _tables(s, cam, paper)
    files = write_report(s.out, "paper_hough", text, rows, {
        "trials": s.trials, "seed": s.seed, "pixel_sigma": s.pixel_sigma,
        "pose_sigma": s.pose_sigma, "heading_sigma": s.heading_sigma,
        "sway_sigma": s.sway_sigma, "camera": cam, "paper_reading": paper, "paper": PAPER})
    files.append(_plot(s, cam, paper))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "camera": cam, "paper_reading": paper}


def _simulate(s: Settings) -> tuple[dict[str, Any], dict[str, Any]]:
    """Both noise models' errors, the head camera's first, from one generator."""
    rng = np.random.default_rng(s.seed)
    cam = _evaluate("camera", int(s.trials), rng, pixel_sigma=s.pixel_sigma,
                    pose_sigma=s.pose_sigma, heading_sigma=s.heading_sigma,
                    sway_sigma=s.sway_sigma)
    paper = _evaluate("paper", int(s.trials), rng, sigma=0.192)
    return cam, paper


# ------------------------------------------------------------------------------------------
# Report
# ------------------------------------------------------------------------------------------

#: Millimetres per metre, for the tables.
_MM = 1000.0


def _tables(s: Settings, cam: dict[str, Any], paper: dict[str, Any]
            ) -> tuple[str, list[dict[str, Any]]]:
    """The printed report and the CSV rows."""
    mm = _MM
    lines = [f"Paper 000, Table 1 geometry: 5 robots, the ball in 50 mm steps from (3000, 3200) "
             f"to (4500, 1200) mm, {s.trials} noise draws per position. Mean error of the "
             "fused ball position [mm].", "",
             "| noise model | equal weights | 1/L | 1/L^2 | best single robot | 4 robots "
             "(1/L, all subsets) | 1/L over equal | 4 robots over best single |",
             "|---|---|---|---|---|---|---|---|"]
    rows = []
    for label, res in ((f"head camera ({s.pixel_sigma:g} px, sway "
                        f"{math.degrees(s.sway_sigma):g} deg, pose {s.pose_sigma * mm:g} mm / "
                        f"{math.degrees(s.heading_sigma):g} deg)", cam),
                       ("paper's reading (192 mm on each estimate)", paper)):
        m = res["mean_m"]
        four = res["by_count_m"][4]
        lines.append(f"| {label} | {m['equal'] * mm:.0f} | {m['inverse'] * mm:.0f} | "
                     f"{m['inverse_square'] * mm:.0f} | {res['best_single_m'] * mm:.0f} | "
                     f"{four * mm:.0f} | {m['inverse'] / m['equal']:.2f} | "
                     f"{1 - four / res['best_single_m']:.0%} better |")
        rows.append({"model": label, **{f"{k}_mm": v * mm for k, v in m.items()},
                     "best_single_mm": res["best_single_m"] * mm,
                     **{f"robots_{k}_mm": v * mm for k, v in res["by_count_m"].items()}})
    ratio = PAPER["weighted_mm"] / PAPER["equal_mm"]
    lines += ["", f"Paper 000: equal weights {PAPER['equal_mm']:.0f} mm, weighted "
              f"{PAPER['weighted_mm']:.0f} mm (ratio {ratio:.2f}) in simulation; on hardware "
              f"a single robot {PAPER['hardware_single_mm']:.0f} mm, "
              f"weighted cooperation {PAPER['hardware_fused_mm']:.0f} mm (about 48 % better); "
              "accuracy nearly flat from 3 to 5 robots.", "",
              "Error against the number of robots (1/L weights, mean over all subsets; one "
              "robot: its own estimate) [mm]:", "",
              "| noise model | " + " | ".join(str(k) for k in range(1, 6)) + " |",
              "|---|" + "---|" * 5]
    for label, res in (("head camera", cam), ("paper's reading", paper)):
        lines.append(f"| {label} | " + " | ".join(
            f"{res['by_count_m'][k] * mm:.0f}" for k in range(1, 6)) + " |")
    return "\n".join(lines), rows


def _plot(s: Settings, cam: dict[str, Any], paper: dict[str, Any]) -> str:
    """The mean error against the number of robots, both noise models."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    ks = list(range(1, 6))
    for label, res in (("head camera", cam), ("paper's reading", paper)):
        ax.plot(ks, [res["by_count_m"][k] * _MM for k in ks], "o-", label=label)
    ax.set(xlabel="robots", ylabel="mean error [mm]", title="Hough fusion, paper 000 Table 1")
    ax.legend()
    return save_figure(fig, s.out / "paper_hough.png")
