"""The noise models that bound Xu et al.'s (2012) claim: four models on the Table 1
geometry, each fused with every weighting (the inverse variance of a line's offset
included), over independent seeds; the spread of their ratios and the weighting a team with
our head camera should use (see :mod:`soccer_lab.papers.hough`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from estimators import HeadCamera, fusion_weights, hough_fuse
from soccer_env.presets import HEAD_CAMERAS, ROBOTS, HumanoidRobotSpec
from soccer_lab.papers.hough.sightings import (
    MM,
    PAPER_SIGMA,
    ROBOTS_MM,
    WEIGHTINGS,
    ball_path,
    sightings_walking,
)

__all__ = ["MODEL_WEIGHTINGS", "NOISE_MODELS", "Model", "mean_distance", "noise_models", "draw",
           "fuse_all", "evaluate_model", "simulate_models", "spread", "summarise", "recommend"]

#: The weightings of the noise-model table: :data:`WEIGHTINGS` and the inverse variance of
#: each line's offset (the optimal weighting of each model, given its sigmas).
MODEL_WEIGHTINGS = (*WEIGHTINGS, "inverse_variance")
#: The noise models of the second table (see :mod:`soccer_lab.papers.hough`), by key: label.
NOISE_MODELS = {
    "isotropic": "(a) isotropic, 192 mm per axis on each estimate",
    "isotropic_rms": "(a') isotropic, 192 mm as the 2-D RMS (136 mm per axis)",
    "bearing": "(b) bearing only, {bearing_deg:.1f} deg",
    "bearing_pose": "(c) bearing {bearing_deg:.1f} deg + position 192 mm",
    "camera": "(d) our head camera walking ({robot}: pan/tilt sway {pan_deg:g}/{tilt_deg:g} "
              "deg, {pixel_sigma:g} px, pose {pose_mm:g} mm / {heading_deg:g} deg)",
}


@dataclass(frozen=True)
class Model:
    """One noise model of the second table: how it draws sightings, and the sigmas of its
    lines' offsets (``bearing`` [rad], ``position`` [m] per axis, ``heading`` [rad]) that
    the inverse-variance weighting takes."""

    key: str
    label: str
    bearing: float
    position: float
    heading: float
    params: dict[str, Any]


def mean_distance() -> float:
    """The mean distance [m] from the robots to the ball along the path (2.59 m)."""
    path, robots = ball_path() / 1000.0, ROBOTS_MM / 1000.0
    return float(np.mean(np.hypot(path[:, None, 0] - robots[None, :, 0],
                                  path[:, None, 1] - robots[None, :, 1])))


def noise_models(s: Any) -> list[Model]:
    """The noise models of :mod:`soccer_lab.papers.hough`'s docstring, their sigmas from the
    paper, the presets and the settings ``s`` (:class:`~soccer_lab.papers.hough.Settings`)."""
    robot = ROBOTS[s.robot]
    assert isinstance(robot, HumanoidRobotSpec)  # checked by Settings
    cam = HEAD_CAMERAS[robot.camera]
    f = 0.5 * cam.width / math.tan(0.5 * cam.hfov)  # focal length [px]
    sigma_b = PAPER_SIGMA / mean_distance()  # the paper's 192 mm as a bearing [rad]
    cam_b = math.sqrt(0.5 * robot.sway_pan ** 2 + (cam.pixel_sigma / f) ** 2)
    fmt = {"bearing_deg": math.degrees(sigma_b), "robot": robot.name,
           "pan_deg": round(math.degrees(robot.sway_pan), 2),
           "tilt_deg": round(math.degrees(robot.sway_tilt), 2),
           "pixel_sigma": cam.pixel_sigma, "pose_mm": s.pose_sigma * MM,
           "heading_deg": round(math.degrees(s.heading_sigma), 2)}
    rms = PAPER_SIGMA / math.sqrt(2.0)
    spec = {"isotropic": (0.0, PAPER_SIGMA, 0.0, {"sigma": PAPER_SIGMA}),
            "isotropic_rms": (0.0, rms, 0.0, {"sigma": rms}),
            "bearing": (sigma_b, 0.0, 0.0, {"bearing": sigma_b, "position": 0.0}),
            "bearing_pose": (sigma_b, PAPER_SIGMA, 0.0,
                             {"bearing": sigma_b, "position": PAPER_SIGMA}),
            "camera": (cam_b, s.pose_sigma, s.heading_sigma,
                       {"camera": HeadCamera(cam.height, cam.hfov, cam.width, cam.height_px),
                        "pixel_sigma": cam.pixel_sigma, "sway_pan": robot.sway_pan,
                        "sway_tilt": robot.sway_tilt, "pose_sigma": s.pose_sigma,
                        "heading_sigma": s.heading_sigma})}
    return [Model(k, NOISE_MODELS[k].format(**fmt), *spec[k]) for k in NOISE_MODELS]


def draw(model: Model, ball: np.ndarray, robots: np.ndarray, rng: np.random.Generator
         ) -> tuple[np.ndarray, np.ndarray]:
    """One draw of ``model``: per robot its believed position and its estimate of the ball
    (field frame, m)."""
    k = model.params
    if "sigma" in k:  # (a): isotropic noise on the estimate, true positions
        return robots.copy(), ball + rng.normal(0.0, k["sigma"], robots.shape)
    if "bearing" in k:  # (b), (c): bearing noise, position noise, exact range
        pos = robots + rng.normal(0.0, k["position"], robots.shape) if k["position"] > 0.0 \
            else robots.copy()
        rel = ball - robots
        dist = np.hypot(rel[:, 0], rel[:, 1])
        psi = np.arctan2(rel[:, 1], rel[:, 0]) + rng.normal(0.0, k["bearing"], len(robots))
        return pos, pos + dist[:, None] * np.column_stack([np.cos(psi), np.sin(psi)])
    return sightings_walking(ball, robots, rng, **k)


def fuse_all(model: Model, pos: np.ndarray, est: np.ndarray) -> dict[str, np.ndarray]:
    """The fused point of every weighting of :data:`MODEL_WEIGHTINGS`; ``L`` the robots' own
    ranges, and for ``"inverse_variance"`` the distances ``D`` to the ``1/L`` point."""
    dirs = est - pos
    L = np.hypot(dirs[:, 0], dirs[:, 1])
    out = {w: hough_fuse(pos, dirs, weights=fusion_weights(L, w)) for w in WEIGHTINGS}
    first = out["inverse"]
    D = np.maximum(np.hypot(first[0] - pos[:, 0], first[1] - pos[:, 1]), 1e-6)
    out["inverse_variance"] = hough_fuse(pos, dirs, weights=fusion_weights(
        D, "inverse_variance", bearing_sigma=model.bearing, position_sigma=model.position,
        heading_sigma=model.heading))
    return out


def evaluate_model(model: Model, trials: int, rng: np.random.Generator) -> dict[str, Any]:
    """One seed of ``model``: each robot's and each weighting's mean error [m] over the path
    (``trials`` draws per ball position)."""
    robots = ROBOTS_MM / 1000.0
    single, nearest, fused = [], [], {w: [] for w in MODEL_WEIGHTINGS}
    for ball in ball_path() / 1000.0:
        for _ in range(trials):
            pos, est = draw(model, ball, robots, rng)
            e = np.hypot(est[:, 0] - ball[0], est[:, 1] - ball[1])
            single.append(e)
            nearest.append(e[np.argmin(np.hypot(*(est - pos).T))])  # by its own range
            for w, x in fuse_all(model, pos, est).items():
                fused[w].append(math.hypot(x[0] - ball[0], x[1] - ball[1]))
    singles = np.mean(single, axis=0)
    return {"single_m": singles.tolist(), "best_single_m": float(singles.min()),
            "nearest_m": float(np.mean(nearest)),
            "mean_m": {w: float(np.mean(v)) for w, v in fused.items()}}


def simulate_models(s: Any) -> dict[str, Any]:
    """Every noise model over ``s.seeds`` seeds: seed ``j`` of model ``m`` draws from the
    generator of ``SeedSequence(s.seed).spawn(seeds)[j].spawn(models)[m]`` (independent of the
    first table's stream and of the other models)."""
    models = noise_models(s)
    per_seed = [child.spawn(len(models))
                for child in np.random.SeedSequence(s.seed).spawn(int(s.seeds))]
    out: dict[str, Any] = {}
    for m_idx, model in enumerate(models):
        runs = [evaluate_model(model, int(s.trials), np.random.default_rng(seqs[m_idx]))
                for seqs in per_seed]
        out[model.key] = summarise(model, runs)
    out["recommendation"] = recommend(out["camera"])
    return out


def spread(values: list[float]) -> dict[str, float]:
    """Mean, sample standard deviation (0 for one value), min and max of ``values``."""
    v = np.asarray(values, dtype=float)
    return {"mean": float(v.mean()), "sd": float(v.std(ddof=1)) if len(v) > 1 else 0.0,
            "min": float(v.min()), "max": float(v.max())}


def summarise(model: Model, runs: list[dict[str, Any]]) -> dict[str, Any]:
    """The seeds' mean errors and the per-seed ratios of a model."""
    mean = {w: float(np.mean([r["mean_m"][w] for r in runs])) for w in MODEL_WEIGHTINGS}
    # The smallest mean error; of weightings equal to it up to rounding (inverse variance is
    # equal weights under isotropic noise), the first named.
    low = min(mean.values())
    best_w = next(w for w in MODEL_WEIGHTINGS if mean[w] <= low * (1.0 + 1e-9))
    return {
        "label": model.label,
        "sigmas": {"bearing_rad": model.bearing, "position_m": model.position,
                   "heading_rad": model.heading},
        "single_m": np.mean([r["single_m"] for r in runs], axis=0).tolist(),
        "best_single_m": float(np.mean([r["best_single_m"] for r in runs])),
        "nearest_m": float(np.mean([r["nearest_m"] for r in runs])),
        "mean_m": mean,
        "best_weighting": best_w,
        "inverse_over_equal": spread([r["mean_m"]["inverse"] / r["mean_m"]["equal"]
                                      for r in runs]),
        "inverse_variance_over_inverse": spread(
            [r["mean_m"]["inverse_variance"] / r["mean_m"]["inverse"] for r in runs]),
        "best_over_equal": spread([r["mean_m"][best_w] / r["mean_m"]["equal"] for r in runs]),
        "fused_over_best_single": {w: spread([r["mean_m"][w] / r["best_single_m"]
                                              for r in runs]) for w in MODEL_WEIGHTINGS},
        "fused_over_nearest": {w: spread([r["mean_m"][w] / r["nearest_m"] for r in runs])
                               for w in MODEL_WEIGHTINGS},
        "over_best": {w: spread([r["mean_m"][w] / r["mean_m"][best_w] for r in runs])
                      for w in MODEL_WEIGHTINGS},
        "seeds": len(runs),
    }


def recommend(cam: dict[str, Any]) -> dict[str, Any]:
    """For the head camera (d): the weighting with the smallest mean error, the weightings
    not distinguishable from it (their per-seed error ratio to it has a mean within two
    standard errors of 1), and team fusion over the best single robot and over the robot
    that believes itself nearest the ball."""
    best = cam["best_weighting"]
    n = cam["seeds"]
    tied = [w for w in MODEL_WEIGHTINGS if w != best and
            cam["over_best"][w]["mean"] - 2.0 * cam["over_best"][w]["sd"] / math.sqrt(n) <= 1.0]
    return {"weighting": best, "equivalent": tied,
            "fused_over_best_single": cam["fused_over_best_single"][best],
            "fused_over_nearest": cam["fused_over_nearest"][best]}
