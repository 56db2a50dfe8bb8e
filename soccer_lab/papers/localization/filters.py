"""The filters of Guo and Li's (2013) reproduction on a recorded walk: each replayed as the
robot's brain feeds its localization (KLD-sampling, with Fox's binning and with the
triangulation recovery seed, and fixed-size filters), and triangulation alone (Xu et al. 2012);
see :mod:`soccer_lab.papers.localization`."""

from __future__ import annotations

import dataclasses
import time
from collections import deque
from collections.abc import Callable
from typing import Any

import numpy as np

from estimators import KLDConfig, KLDLocalizer, SightingMemory, seed_poses
from soccer_env.perception.brain import Brain
from soccer_lab.papers.localization.episode import record_walk
from soccer_lab.papers.localization.measures import (
    GLOBAL_WINDOW,
    MIRROR_M,
    SETTLE,
    TRI_OUTCOMES,
    WRONG_M,
    deg,
    localized_after,
    median,
    pose_errors,
)

__all__ = ["SEED_MEMORY", "SEEDED", "FOX", "TRIANGULATIONS", "BrainReplay", "replay",
           "run_filter", "TriangulationOnly", "run_triangulation", "kld_config", "filter_name",
           "episode_results"]

#: The recovery seed's memory: the sightings of this many updates (frames with landmarks;
#: one to two seconds of the scanning head).
SEED_MEMORY = 25
#: The name of KLD-sampling with the triangulation recovery seed: the KLD row's plus this.
SEEDED = " + triangulation seed"
#: The suffix of KLD-sampling with Fox's binning of the predicted samples
#: (``KLDConfig(binning="predicted")``).
FOX = ", bins of the predicted samples (Fox)"
#: Triangulation alone (Xu et al. 2012, no filter): name -> the frames with landmarks whose
#: sightings it uses (this frame's only, or the seed's memory moved by the odometry).
TRIANGULATIONS = {"triangulation, this frame": 1,
                  f"triangulation, last {SEED_MEMORY} frames": SEED_MEMORY}


class BrainReplay:
    """A filter fed as :class:`~soccer_env.perception.humanoid`'s robot brain feeds its
    localization: the brain's own odometry bookkeeping (kept with time stamps, composed up to
    a frame's capture time, turned into the filter's mid-step convention) on this filter."""

    kind = "kld"
    odometry = Brain.odometry
    odometry_until = Brain.odometry_until
    move_localization = Brain.move_localization

    def __init__(self, loc: KLDLocalizer) -> None:
        self.loc = loc
        self.odo: deque[tuple[float, tuple[float, float, float]]] = deque()
        self.loc_estimate = loc.estimate()


def replay(ep: dict[str, Any], rep: BrainReplay,
           frame: Callable[[tuple, np.ndarray, np.ndarray], Any]) -> tuple[list[Any], float]:
    """Feed the recorded episode to ``rep``: the odometry as it came, and at every frame the
    localization moved to the frame's capture time, then ``frame(kinds, ranges, bearings)``.
    Returns each frame's result and the seconds spent moving and in ``frame``."""
    out, seconds = [], 0.0
    for ev in ep["events"]:
        if ev[0] == "odo":
            rep.odometry(ev[1], ev[2], None)
            continue
        _, t_cap, kinds, ranges, bearings = ev
        t0 = time.perf_counter()
        rep.move_localization(rep.odometry_until(t_cap))
        res = frame(kinds, ranges, bearings)
        seconds += time.perf_counter() - t0
        out.append(res)
    return out, seconds


def run_filter(ep: dict[str, Any], config: KLDConfig, seed: int,
               recovery: str = "uniform") -> dict[str, Any]:
    """Replay the episode into a filter of ``config`` (with the ``recovery`` draws of
    :class:`~estimators.KLDLocalizer`) started global; its errors per frame (at the frame's
    capture time) and the summary figures."""
    team = ep["team"]
    table = team.landmark_table
    rep = BrainReplay(KLDLocalizer(team.bounds, np.random.default_rng(seed), config,
                                   recovery=recovery, seed_memory=SEED_MEMORY))
    loc = rep.loc
    initial = loc.n

    def frame(kinds: tuple, ranges: np.ndarray, bearings: np.ndarray) -> tuple[np.ndarray, int]:
        if kinds:
            loc.update_kinds(kinds, ranges, bearings, table)
        rep.loc_estimate = loc.estimate()
        return rep.loc_estimate, loc.n

    per_frame, seconds = replay(ep, rep, frame)
    counts = [c for _, c in per_frame]
    t, truth = ep["frame_t"], ep["frame_truth"]
    e = np.array([est for est, _ in per_frame])
    err, herr, mirror = pose_errors(e, truth, MIRROR_M)
    n = np.array(counts)
    tk = ep["kidnap_time"]
    end = float(ep["times"][-1]) + 1.0
    tracking = t >= SETTLE
    if tk is not None:
        tracking &= ~((t >= tk) & (t < tk + SETTLE))
    return {"pos_err": np.round(err, 4).tolist(), "head_err": np.round(herr, 4).tolist(),
            "counts": counts, "estimate": np.round(e, 3).tolist(),
            "median_pos_m": float(np.median(err[tracking])),
            "median_head_deg": float(np.degrees(np.median(herr[tracking]))),
            "median_pos_turning_m": median(err[tracking & ep["frame_turning"]]),
            "median_pos_straight_m": median(err[tracking & ~ep["frame_turning"]]),
            "initial_particles": int(initial),
            "first_second_particles": float(np.mean(n[t < GLOBAL_WINDOW])),
            "tracking_particles": float(np.mean(n[tracking])),
            "tracking_particles_median": float(np.median(n[tracking])),
            "ms_per_update": seconds / max(len(t), 1) * 1e3,
            "mirror_pct": float(100.0 * np.mean(mirror)),
            "localized_s": localized_after(t, err, float(t[0]), tk if tk is not None else end),
            "recovery_s": None if tk is None else localized_after(t, err, tk, end)}


class TriangulationOnly:
    """No filter: the remembered sightings, moved by the odometry as the brain moves its
    localization (:class:`BrainReplay` calls :meth:`predict` and :meth:`estimate`)."""

    def __init__(self, frames: int) -> None:
        self.memory = SightingMemory(frames)

    def predict(self, odometry: tuple[float, float, float]) -> None:
        self.memory.move(odometry)

    def estimate(self) -> np.ndarray:
        return np.full(3, np.nan)


def run_triangulation(ep: dict[str, Any], frames: int, config: KLDConfig) -> dict[str, Any]:
    """Xu et al.'s (2012) triangulation alone, at every frame, from the sightings of the last
    ``frames`` frames with landmarks (moved by the odometry), with the perception's noise
    model ``config`` (range and bearing sigmas): each frame's outcome (:data:`TRI_OUTCOMES`),
    the errors of its best pose, and the summary figures (shares of the frames [%], median
    errors of the poses found and of the correct ones)."""
    team = ep["team"]
    table = team.landmark_table
    tri = TriangulationOnly(frames)
    rep = BrainReplay.__new__(BrainReplay)  # the brain's odometry bookkeeping, no filter
    rep.loc, rep.odo, rep.loc_estimate = tri, deque(), tri.estimate()

    def frame(kinds: tuple, ranges: np.ndarray, bearings: np.ndarray) -> Any:
        if kinds:
            tri.memory.add(kinds, ranges, bearings)
        k, pts = tri.memory.sightings()
        return None if len(k) < 3 else seed_poses(k, pts, table, config, team.bounds)

    hyps, seconds = replay(ep, rep, frame)
    poses = np.array([hyp.poses[0] if hyp is not None and hyp.ok else np.full(3, np.nan)
                      for hyp in hyps]).reshape(-1, 3)
    e, h, mirror = pose_errors(poses, ep["frame_truth"][:len(hyps)], WRONG_M)
    found = np.isfinite(e)
    outcome = [("correct" if err <= WRONG_M else "wrong") if ok
               else ("too_few" if hyp is None else hyp.reason)
               for hyp, err, ok in zip(hyps, e.tolist(), found.tolist())]
    out = np.array(outcome)
    right = out == "correct"
    n = max(len(out), 1)
    res: dict[str, Any] = {f"{o}_pct": float(100.0 * np.mean(out == o)) for o in TRI_OUTCOMES}
    res.update({
        "outcome": outcome, "pos_err": np.round(np.where(found, e, -1.0), 4).tolist(),
        "fix_pct": float(100.0 * np.mean(found)),
        "mirror_pct": float(100.0 * np.sum(mirror) / n),
        "median_pos_m": median(e[found]), "median_head_deg": deg(median(h[found])),
        "median_pos_correct_m": median(e[right]),
        "median_head_correct_deg": deg(median(h[right])),
        "ms_per_frame": seconds / n * 1e3})
    return res


def kld_config(base: KLDConfig) -> KLDConfig:
    """The perception's KLD noise model with the default particle bounds."""
    default = KLDConfig()
    return dataclasses.replace(base, min_particles=default.min_particles,
                               max_particles=default.max_particles)


def filter_name(cfg: KLDConfig) -> str:
    """The table's name of KLD-sampling with the particle bounds of ``cfg``."""
    return f"KLD-sampling ({cfg.min_particles}-{cfg.max_particles})"


def episode_results(job: tuple[int, float, bool, tuple[int, ...]]) -> dict[str, Any]:
    """One episode (seed, duration, kidnapping, fixed sizes): recorded once and replayed into
    KLD-sampling and every fixed-size filter (module level, for a process pool)."""
    seed, duration, kidnap, sizes = job
    ep = record_walk(duration, seed, kidnap)
    base = ep["team"].kld_config  # the camera's noise model, as the perception uses it
    kld_cfg = kld_config(base)
    kld_name = filter_name(kld_cfg)
    results = {kld_name: run_filter(ep, kld_cfg, seed + 1),
               kld_name + FOX: run_filter(ep, dataclasses.replace(kld_cfg, binning="predicted"),
                                          seed + 1),
               kld_name + SEEDED: run_filter(ep, kld_cfg, seed + 1, "triangulate")}
    for n in sizes:
        cfg = dataclasses.replace(base, min_particles=int(n), max_particles=int(n))
        results[f"fixed {int(n)}"] = run_filter(ep, cfg, seed + 1)
    counts = np.array(results[kld_name]["counts"])
    tk = ep["kidnap_time"]
    return {"seed": seed, "kld_name": kld_name, "kld_config": dataclasses.asdict(kld_cfg),
            "frames": len(ep["frame_t"]),
            "frames_seen": sum(1 for ev in ep["events"] if ev[0] == "frame" and ev[2]),
            "kld_at_min_pct": float(100.0 * np.mean(counts <= kld_cfg.min_particles)),
            "kidnap_time": tk, "kidnap_to": None if tk is None else ep["kidnap_to"].tolist(),
            "falls": int(ep["falls"]), "frame_t": np.round(ep["frame_t"], 4).tolist(),
            "truth_t": np.round(ep["times"][::6], 4).tolist(),
            "truth_pose": np.round(ep["poses"][::6], 4).tolist(), "results": results,
            "triangulation": {name: run_triangulation(ep, frames, base)
                              for name, frames in TRIANGULATIONS.items()}}
