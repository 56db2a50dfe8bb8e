"""Xu, Xie, Wang and Ni (2012) in the closed loop: what a humanoid team knows about
the ball, alone or together.

``soccer-env paper team``:

* **Match.** Humanoid matches on Xu et al.'s (2012) 6 m x 4 m field (robot ``humanoid-2012``, head
  camera ``kidsize-2012``: 25 Hz, 51 degrees, 0.56 m, the ZigBee-like team radio): four blue
  robots (a keeper and three field players, Xu et al.'s (2012) hardware team size) against three
  yellow ones, both teams scripted (:class:`agents.scripted.humanoid.HumanoidTeam`) and acting on
  their own perception. For each blue ball-estimation configuration (the robot's own
  sightings alone, with and without particle tracking; the team's Hough fusion, with and
  without tracking), the same seeded matches are played and the blue robots' beliefs about
  the ball are compared with the truth at every step: mean and median error, the share of
  robot-steps within 0.3 m, the error while the ball rolls faster than 0.5 m/s, and the
  blue robots' median localization error. Yellow always uses the default (fusion + MFBPF).
* **Keeper.** The humanoid keeper's save rate under the same configurations (and the truth)
  on the same seeded shots: a subset of the humanoid estimator ablation
  (``soccer-env ablation --robot humanoid``).

Xu et al. (2012) reports (hardware, 300 trials): a mean error of 8.6 cm falling to 4.5 cm with
weighted cooperative localization (about 48 % better), and a particle-filtered track smoother
than the raw fused positions. Its sentence names one baseline for three methods: the 8.6 cm is
either one robot alone or equal-weight cooperation
(:data:`soccer_lab.papers.hough.HARDWARE_BASELINE_READINGS`); the report compares with the
first reading, the one this match's "own" configuration measures.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from soccer_env.render.plots import pyplot, save_figure
from soccer_lab.papers.common import lock_on, map_jobs, write_report

__all__ = ["run", "Settings", "match_errors", "keeper_saves", "ball_events", "MATCH_CONFIGS",
           "KEEPER_CONFIGS", "PAPER"]

#: Blue's ball estimation in the match: names of
#: :data:`agents.studies.ablation_settings.HUMANOID_CONFIGS`.
MATCH_CONFIGS = ("own", "own-mfbpf", "fusion", "fusion-mfbpf", "fusion-ivar-mfbpf",
                 "fusion-kick")
#: The keeper's configurations (the same plus the truth).
KEEPER_CONFIGS = ("truth", *MATCH_CONFIGS)
PAPER = {"baseline_mm": 86.0, "fused_mm": 45.0, "gain": 0.48}
ROBOT, CAMERA, FIELD = "humanoid-2012", "kidsize-2012", "humanoid-2012"
BLUE, YELLOW = 4, 3
#: Ball speed above which the ball counts as rolling [m/s].
MOVING = 0.5
#: Error below which a belief counts as good [m] (and a track as locked on).
GOOD = 0.3
#: A change of the true ball velocity in one step above this [m/s] is a kick or a collision.
EVENT_DV = 0.3
#: Events followed by this long without another are scored for lock-on, and steps this long
#: after the latest event count as steady tracking [s].
SETTLE = 0.5
#: The head camera's frame period [s] (``kidsize-2012``: 25 Hz): lock-on is counted in
#: frames.
FRAME = 0.04
#: Frames the velocity error must stay within its allowance to count as locked on.
HOLD_FRAMES = 3
#: The velocity error allowed for lock-on: this share of the true speed, at least
#: :data:`LOCK_SPEED` [m/s].
LOCK_SHARE = 0.25
LOCK_SPEED = 0.2


def _match(args: tuple[str, int, float]) -> dict[str, Any]:
    """One seeded match with blue's configuration ``name``; blue's errors."""
    from agents.scripted import HumanoidTeam
    from agents.studies.ablation_settings import HUMANOID_CONFIGS
    from soccer_env.envs.match import SoccerParallelEnv

    name, seed, duration = args
    cfg = HUMANOID_CONFIGS[name]
    env = SoccerParallelEnv(blue=BLUE, yellow=YELLOW, robot=ROBOT, field=FIELD,
                            obs_mode=cfg.obs_mode,
                            perception={"blue": {"camera": CAMERA, **cfg.perception},
                                        "yellow": {"camera": CAMERA}},
                            match_duration=duration)
    obs, infos = env.reset(seed=seed)
    teams = [HumanoidTeam.for_env(env, "blue"), HumanoidTeam.for_env(env, "yellow")]
    blue = env.possible_agents[:BLUE]
    err, moving, loc, per_step, velocity, off = [], [], [], [], [], []
    t0 = time.perf_counter()
    steps = 0
    while env.agents:
        actions = {}
        for team in teams:
            actions.update(team(obs))
        obs, _, _, _, infos = env.step(actions)
        steps += 1
        truth = infos[blue[0]]["truth"]
        tb = truth["ball_position"]
        tv = truth["ball_velocity"][0:2]
        velocity.append(tv)
        rolling = math.hypot(*tv) > MOVING
        scale = max(LOCK_SHARE * math.hypot(*tv), LOCK_SPEED)
        row, vrow = [], []
        for a in blue:
            est = infos[a]["estimate"]
            e = math.hypot(*(est["ball_position"] - tb))
            row.append(e)
            vrow.append(math.hypot(*(est["ball_velocity"][0:2] - tv)) / scale)
            if rolling:
                moving.append(e)
            loc.append(math.hypot(*(est["robot_pose"][a][0:2] - truth["robot_pose"][a][0:2])))
        err += row
        per_step.append(row)
        off.append(vrow)
    score = infos[blue[0]]["score"]
    dt = float(env.settings.control_dt)
    return {"err": err, "moving": moving, "loc": loc, "steps": steps,
            "seconds": time.perf_counter() - t0, "score": score,
            **_events(np.array(per_step), np.array(off), np.array(velocity), dt)}


def ball_events(velocity: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(steps, kicked)``: the steps at which the true ball's velocity ``(K, 2)`` [m/s] changed
    by more than :data:`EVENT_DV` from the step before (friction changes it far less), and
    whether each was a kick (the speed grew by more than :data:`EVENT_DV`) rather than a
    collision with a robot, a post or a wall."""
    dv = np.hypot(*np.diff(velocity, axis=0).T)
    steps = np.flatnonzero(dv > EVENT_DV) + 1
    speed = np.hypot(*velocity.T)
    return steps, speed[steps] - speed[steps - 1] > EVENT_DV


def _events(err: np.ndarray, off: np.ndarray, velocity: np.ndarray, dt: float
            ) -> dict[str, list[float]]:
    """Each blue robot's lock-on after every kick and collision followed by at least
    :data:`SETTLE` seconds without another (in camera frames, see :data:`FRAME`): until its
    believed velocity is within :data:`LOCK_SHARE` of the true speed (at least
    :data:`LOCK_SPEED`) for :data:`HOLD_FRAMES` frames; and the position errors of the steps
    at least :data:`SETTLE` seconds after the latest event (steady tracking). ``err``:
    ``(K, robots)`` position errors [m] per step; ``off``: the velocity errors over their
    allowance."""
    steps, kicked = ball_events(velocity)
    settle, hold = round(SETTLE / dt), round(HOLD_FRAMES * FRAME / dt)
    locks: dict[str, list[float]] = {"lock_kick": [], "lock_collision": [], "missed_kick": [],
                                     "missed_collision": []}
    bounds = list(steps) + [len(err)]
    for j, (c, kick) in enumerate(zip(steps, kicked)):
        if bounds[j + 1] - c < settle:
            continue
        kind = "kick" if kick else "collision"
        for r in range(err.shape[1]):
            k = lock_on(off[:, r], int(c), int(bounds[j + 1]), 1.0, hold)
            if k is None:
                locks["missed_" + kind].append(1.0)
            else:
                locks["lock_" + kind].append(k * dt / FRAME)
    since = np.arange(len(err)) - np.maximum.accumulate(
        np.isin(np.arange(len(err)), steps) * np.arange(len(err)))
    locks["steady"] = err[since >= settle].ravel().tolist()
    return locks


def match_errors(matches: int = 4, duration: float = 60.0, workers: int | None = None,
                 seed: int = 0, configs: tuple[str, ...] = MATCH_CONFIGS) -> dict[str, Any]:
    """Blue's ball errors over ``matches`` seeded matches of ``duration`` seconds per
    configuration (see the module docstring)."""
    jobs = [(name, seed + k, duration) for name in configs for k in range(matches)]
    outs = map_jobs(_match, jobs, workers)
    table: dict[str, dict[str, Any]] = {}
    for name in configs:
        parts = [o for j, o in zip(jobs, outs) if j[0] == name]
        err = np.concatenate([p["err"] for p in parts])
        moving = np.concatenate([p["moving"] for p in parts])
        loc = np.concatenate([p["loc"] for p in parts])
        steps = sum(p["steps"] for p in parts)
        locks = {key: np.concatenate([p[key] for p in parts]) for key in
                 ("lock_kick", "lock_collision", "missed_kick", "missed_collision", "steady")}
        table[name] = {
            "mean_m": float(err.mean()), "median_m": float(np.median(err)),
            "rmse_m": float(np.sqrt(np.mean(err ** 2))),
            "steady_rmse_m": float(np.sqrt(np.mean(locks["steady"] ** 2)))
            if len(locks["steady"]) else float("nan"),
            **{f"{key}_median_frames": float(np.median(locks[key])) if len(locks[key])
               else float("nan") for key in ("lock_kick", "lock_collision")},
            **{f"{kind}s_missed": f"{len(locks['missed_' + kind])}/"
               f"{len(locks['missed_' + kind]) + len(locks['lock_' + kind])}"
               for kind in ("kick", "collision")},
            "good_share": float(np.mean(err < GOOD)),
            "moving_mean_m": float(moving.mean()) if len(moving) else float("nan"),
            "moving_share": len(moving) / len(err),
            "localization_median_m": float(np.median(loc)),
            "ms_per_step": 1e3 * sum(p["seconds"] for p in parts) / steps,
            "goals": [[p["score"]["blue"], p["score"]["yellow"]] for p in parts],
            "error_hist": np.histogram(np.minimum(err, 3.0), bins=30, range=(0, 3))[0].tolist(),
        }
    return {"matches": matches, "duration": duration, "configs": table}


def keeper_saves(shots: int = 500, workers: int | None = None,
                 configs: tuple[str, ...] = KEEPER_CONFIGS) -> dict[str, Any]:
    """The humanoid keeper's save rates (a subset of the humanoid ablation)."""
    from agents.studies.ablation import run_ablation

    res = run_ablation("scripted", shots, [CAMERA], list(configs), workers=workers,
                       robot="humanoid", env_kwargs={"robot": ROBOT})
    return {"shots": shots, "command": res.command(), "configs": {
        c: {"save_rate": r.save_rate, "ci_low": r.ci_low, "ci_high": r.ci_high,
            "saves": r.saves, "ball_rmse_m": r.ball_rmse_m}
        for c in configs for r in [res.cell(CAMERA, c)]}}


@dataclass(frozen=True)
class Settings:
    """What one run simulates (validated on construction).

    Attributes:
        out: the output folder.
        matches: seeded matches per configuration (seeds ``seed`` onwards), >= 1.
        duration: match length [s], in [1, 3600].
        shots: the keeper's shots per configuration, >= 1.
        workers: processes (None: all cores).
        seed: the first match's seed.
        keeper: run the keeper comparison.
    """

    out: Path
    matches: int = 4
    duration: float = 60.0
    shots: int = 500
    workers: int | None = None
    seed: int = 0
    keeper: bool = True

    def __post_init__(self) -> None:
        for name, lo in (("matches", 1), ("shots", 1)):
            v = getattr(self, name)
            if isinstance(v, bool) or int(v) != v or v < lo:
                raise ValueError(f"{name} must be an integer >= {lo}, got {v!r}")
        if not (math.isfinite(self.duration) and 1.0 <= self.duration <= 3600.0):
            raise ValueError(f"duration must be in [1, 3600] s, got {self.duration!r}")


def run(out: str | Path = "paper_output", matches: int = 4, duration: float = 60.0,
        shots: int = 500, workers: int | None = None, seed: int = 0,
        keeper: bool = True) -> dict[str, Any]:
    """Run the match and keeper comparisons; write ``paper_team.md``, ``.csv``, ``.json`` and
    ``.png`` into ``out``."""
    s = Settings(Path(out), matches, duration, shots, workers, seed, keeper)
    t0 = time.perf_counter()
    s.out.mkdir(parents=True, exist_ok=True)
    m = match_errors(int(s.matches), float(s.duration), s.workers, s.seed)
    k = keeper_saves(int(s.shots), s.workers) if s.keeper else None
    text, rows = _tables(s, m, k)
    files = write_report(s.out, "paper_team", text, rows,
                         {"matches": m, "keeper": k, "paper": PAPER, "seed": s.seed})
    files.append(_plot(s, m))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "matches": m, "keeper": k}


# ------------------------------------------------------------------------------------------
# Report
# ------------------------------------------------------------------------------------------

def _tables(s: Settings, m: dict[str, Any], k: dict[str, Any] | None
            ) -> tuple[str, list[dict[str, Any]]]:
    """The printed report and the CSV rows: the matches, then the keeper."""
    lines = [f"Humanoid matches on Xu et al.'s (2012) field: {BLUE} blue ({ROBOT}, camera "
             f"{CAMERA}) against {YELLOW} yellow, {s.matches} seeded match(es) of "
             f"{s.duration:g} s per configuration of blue's ball estimation; blue robots' ball "
             "belief against the truth at every step.", "",
             "| blue's ball estimation | mean error [m] | median [m] | RMSE [m] | "
             "steady RMSE [m] | within 0.3 m | mean while rolling [m] | lock-on after a kick "
             "[frames] (never) | after a collision [frames] (never) | localization median [m] "
             "| ms per step |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    rows = []
    for name, r in m["configs"].items():
        lines.append(f"| {name} | {r['mean_m']:.3f} | {r['median_m']:.3f} | "
                     f"{r['rmse_m']:.3f} | {r['steady_rmse_m']:.3f} | "
                     f"{100 * r['good_share']:.0f} % | {r['moving_mean_m']:.3f} | "
                     f"{r['lock_kick_median_frames']:.1f} ({r['kicks_missed']}) | "
                     f"{r['lock_collision_median_frames']:.1f} ({r['collisions_missed']}) | "
                     f"{r['localization_median_m']:.3f} | {r['ms_per_step']:.2f} |")
        rows.append({"part": "match", "config": name,
                     **{kk: v for kk, v in r.items() if not isinstance(v, list)}})
    lines += ["", f"Lock-on: camera frames ({1 / FRAME:g} Hz) from a kick (the ball's speed "
              f"grew by over {EVENT_DV:g} m/s in a step) or a collision (its velocity changed "
              f"as much otherwise) until a blue robot's believed ball velocity stays within "
              f"{LOCK_SHARE:.0%} of the true speed (at least {LOCK_SPEED:g} m/s) for "
              f"{HOLD_FRAMES} frames, median over robots and events followed by at least "
              f"{SETTLE:g} s without another; (never): those that did not lock on before the "
              f"next event, of all. Steady: steps at least {SETTLE:g} s after the latest "
              "event."]
    own, fused = m["configs"]["own"]["mean_m"], m["configs"]["fusion"]["mean_m"]
    lines += ["", f"Team fusion against one robot alone (mean error): {1 - fused / own:.0%} "
              f"better (Xu et al. 2012, hardware: {PAPER['gain']:.0%}, "
              f"{PAPER['baseline_mm']:.0f} mm -> {PAPER['fused_mm']:.0f} mm, if its 86 mm is "
              "one robot alone; the sentence can also read as equal-weight cooperation -> "
              "weighted, see `soccer-env paper hough`)."]
    if k is not None:
        lines += ["", f"Humanoid keeper ({ROBOT}, 3 watching team-mates), scripted, "
                  f"{s.shots} seeded shots per configuration; `{k['command']}`:", "",
                  "| ball estimation | save rate [%] (95 % CI) | ball RMSE [mm] |",
                  "|---|---|---|"]
        for name, r in k["configs"].items():
            lines.append(f"| {name} | {100 * r['save_rate']:.1f} ({100 * r['ci_low']:.1f}-"
                         f"{100 * r['ci_high']:.1f}) | {1000 * r['ball_rmse_m']:.0f} |")
            rows.append({"part": "keeper", "config": name, **r})
    return "\n".join(lines), rows


def _plot(s: Settings, m: dict[str, Any]) -> str:
    """The distribution of blue's ball belief error per configuration (cumulative share of
    blue robot-steps below each error), up to the error that every configuration stays
    under."""
    from soccer_env.render.plots import (
        LABEL_SIZE,
        TITLE_SIZE,
        describe_world,
        legend_beside,
        style_key,
    )

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.4))
    edges = np.linspace(0, 3, 31)
    reach = 0.0
    for name, r in m["configs"].items():
        h = np.asarray(r["error_hist"], dtype=float)
        cdf = np.concatenate([[0.0], np.cumsum(h) / h.sum()])
        ax.plot(edges, cdf, lw=1.6, label=name)
        reach = max(reach, edges[np.argmax(cdf >= 0.995)])
    ax.axvline(GOOD, color="k", ls=":", lw=1.2)
    ax.set_xlim(0, min(3.0, max(0.5, reach + 0.2)))
    ax.set_ylim(0, 1.02)
    ax.set_xlabel("ball belief error [m] (errors of 3 m and more counted at 3 m)",
                  fontsize=LABEL_SIZE)
    ax.set_ylabel("share of blue robot-steps\nwith a smaller error", fontsize=LABEL_SIZE)
    ax.set_title(f"Blue's ball belief error in humanoid matches, {BLUE} vs {YELLOW}\n"
                 f"{describe_world(ROBOT, FIELD)}, head camera {CAMERA}\n"
                 f"{s.matches} match(es) of {s.duration:g} s per configuration",
                 fontsize=TITLE_SIZE)
    ax.grid(alpha=0.3)
    first = legend_beside(ax, title="blue's ball estimation")
    legend_beside(ax, [style_key(f"{GOOD:g} m: counted within", ls=":", lw=1.2, color="k")],
                  title="line style", below=first)
    return save_figure(fig, s.out / "paper_team.png")
