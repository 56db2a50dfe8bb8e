"""Paper 001's adaptive localization: KLD-sampling against fixed-size particle filters on a
walking episode.

``soccer-env paper localization``: a humanoid walks for ``duration`` seconds on paper 000's
6 m x 4 m field (0.2 m/s, turning now and then, more at the edges), scanning with its head
(pan sweeping +-90 degrees at 1 rad/s, a 51-degree field of view). It sees the landmarks inside
its view and within 4 m (goal posts, field corners, centre-line ends; paper 001 ignores
farther ones): range with 5 % noise (stereo or ground-projection error grows with distance) and
bearing with 1 degree. Odometry has slip noise, larger while turning. Localization starts
global (no prior) at 10 Hz.

Reports for :class:`estimators.KLDLocalizer` (KLD-sampling) and for the same filter with a
fixed particle count: median position and heading error after the first 5 s, particles while
globally localizing and while tracking, time per update; the paper's claims beside.
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import numpy as np

from estimators.localization import KLDConfig, KLDLocalizer

from ..plots import pyplot, save_figure
from ._io import write_report

__all__ = ["run", "LANDMARKS", "PAPER"]

#: Goal posts, field corners and centre-line ends of a 6 m x 4 m field [m].
LANDMARKS = np.array([[3, 0.7], [3, -0.7], [-3, 0.7], [-3, -0.7], [3, 2], [3, -2], [-3, 2],
                      [-3, -2], [0, 2], [0, -2]], dtype=float)
BOUNDS = (-3.0, 3.0, -2.0, 2.0)
PAPER = ("Paper 001: KLD-sampling keeps many particles while uncertain and few once converged; "
         "errors are larger in turns (wheel slip); robot speed <= 0.5 m/s.")
DT = 0.1
FOV = math.radians(51.0)
MAX_RANGE = 4.0


def _episode(duration: float, rng: np.random.Generator) -> list[dict[str, Any]]:
    """The walk: true poses, noisy odometry and sightings per update."""
    pose = np.array([-1.5, 0.5, 0.2])
    steps = []
    for k in range(int(round(duration / DT))):
        t = k * DT
        v = 0.2 * DT
        w = (0.4 if (k // 60) % 2 else -0.1) * DT
        if abs(pose[0]) > 2.3 or abs(pose[1]) > 1.4:  # turn back towards the centre
            w = 0.8 * DT
        c, s = math.cos(pose[2] + 0.5 * w), math.sin(pose[2] + 0.5 * w)
        pose = pose + np.array([c * v, s * v, w])
        slip = np.array([0.02 * v + 0.01 * abs(w), 0.02 * v + 0.01 * abs(w),
                         0.05 * abs(w) + 0.02 * v])
        odo = np.array([v, 0.0, w]) + rng.normal(0.0, 1.0, 3) * slip * 5.0
        pan = 0.5 * math.pi * math.sin(1.0 * t / (0.5 * math.pi))  # head scan
        rel = LANDMARKS - pose[:2]
        dist = np.hypot(rel[:, 0], rel[:, 1])
        bearing = np.arctan2(rel[:, 1], rel[:, 0]) - pose[2]
        off = np.remainder(bearing - pan + math.pi, 2 * math.pi) - math.pi
        seen = (dist < MAX_RANGE) & (np.abs(off) < 0.5 * FOV)
        ranges = dist[seen] * (1.0 + rng.normal(0.0, 0.05, seen.sum()))
        bearings = bearing[seen] + rng.normal(0.0, math.radians(1.0), seen.sum())
        steps.append({"pose": pose.copy(), "odometry": odo, "landmarks": LANDMARKS[seen],
                      "ranges": ranges, "bearings": bearings})
    return steps


def _run_filter(steps: list[dict[str, Any]], config: KLDConfig, seed: int) -> dict[str, Any]:
    loc = KLDLocalizer(BOUNDS, np.random.default_rng(seed), config)
    pos_err, head_err, counts = [], [], []
    t0 = time.perf_counter()
    for st in steps:
        loc.predict(st["odometry"])
        loc.update(st["landmarks"], st["ranges"], st["bearings"])
        est = loc.estimate()
        pos_err.append(float(np.hypot(*(est[:2] - st["pose"][:2]))))
        head_err.append(abs(math.remainder(est[2] - st["pose"][2], 2 * math.pi)))
        counts.append(loc.n)
    seconds = time.perf_counter() - t0
    settle = int(round(5.0 / DT))
    return {"pos_err": pos_err, "head_err": head_err, "counts": counts,
            "median_pos_m": float(np.median(pos_err[settle:])),
            "median_head_deg": float(np.degrees(np.median(head_err[settle:]))),
            "global_particles": int(counts[0]) if counts else 0,
            "tracking_particles": float(np.mean(counts[settle:])),
            "ms_per_update": seconds / len(steps) * 1e3}


def run(out: str | Path = "paper_output", duration: float = 60.0, seed: int = 0,
        fixed_sizes: tuple[int, ...] = (100, 300, 1000, 3000)) -> dict[str, Any]:
    """Run the episode with KLD-sampling and with fixed sizes; write ``paper_localization``
    ``.md``, ``.csv``, ``.json`` and ``.png`` into ``out``."""
    if not (math.isfinite(duration) and 6.0 <= duration <= 3600.0):
        raise ValueError(f"duration must be in [6, 3600] s, got {duration!r}")
    t0 = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    steps = _episode(duration, np.random.default_rng(seed))
    results = {"KLD-sampling (50-5000)": _run_filter(steps, KLDConfig(), seed + 1)}
    for n in fixed_sizes:
        cfg = KLDConfig(min_particles=n, max_particles=n)
        results[f"fixed {n}"] = _run_filter(steps, cfg, seed + 1)
    kld = results["KLD-sampling (50-5000)"]
    lines = [f"Walking episode, {duration:g} s at 0.2 m/s on a 6 m x 4 m field, head scanning, "
             "landmarks within 4 m and the 51-degree view, global start; errors after the "
             "first 5 s.", "",
             "| filter | median position error [m] | median heading error [deg] | particles "
             "at the start | mean particles while tracking | ms per update |",
             "|---|---|---|---|---|---|"]
    summary = {name: {k: v for k, v in r.items() if not isinstance(v, list)}
               for name, r in results.items()}
    for name, r in results.items():
        lines.append(f"| {name} | {r['median_pos_m']:.3f} | {r['median_head_deg']:.1f} | "
                     f"{r['global_particles']} | {r['tracking_particles']:.0f} | "
                     f"{r['ms_per_update']:.2f} |")
    ratio = kld["global_particles"] / max(kld["tracking_particles"], 1.0)
    lines += ["", f"KLD-sampling: {ratio:.0f} times fewer particles while tracking than while "
              f"globally localizing; median error {kld['median_pos_m']:.3f} m while walking.",
              "", PAPER]
    text = "\n".join(lines)
    rows = [{"filter": name, **r} for name, r in summary.items()]
    files = write_report(out, "paper_localization", text, rows,
                         {"duration": duration, "seed": seed, "results": results})
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    t = np.arange(len(steps)) * DT
    for name, r in results.items():
        ax1.plot(t, r["pos_err"], lw=1, label=name)
    ax1.set(ylabel="position error [m]", yscale="log")
    ax1.legend(fontsize=7)
    ax2.plot(t, kld["counts"], "k-")
    ax2.set(xlabel="time [s]", ylabel="particles (KLD)", yscale="log")
    files.append(save_figure(fig, out / "paper_localization.png"))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "results": summary}
