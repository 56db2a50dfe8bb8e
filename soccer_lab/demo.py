"""The ``make demo`` episode: the scripted keeper against seeded shots, as video and figures.

Writes to the output folder:

* ``goalkeeper.mp4`` (or ``goalkeeper.gif`` if no ffmpeg is available): the rendered episodes,
  the team's belief drawn in cyan over the truth;
* ``trajectories.png``: true ball paths, the believed ball paths and the keeper's paths;
* ``ball_speed.png``: ball speed against time, showing the sliding and rolling phases;
* ``estimate_error.png``: distance between the believed and the true ball over time;
* ``summary.json``: each episode's shot, outcome, length and estimation error.

The keeper plays from perceived observations: the overhead vision's late, noisy frames
filtered by the ball EKF (``obs_mode="perceived"``, ``perception="realistic"``). With
``robot="humanoid-2012"`` (what ``soccer-env demo`` runs second, into ``humanoid/``) it is paper
000's humanoid keeper with three watching team-mates, localizing from its head camera and
diving on the team's fused and tracked estimate of the ball (files ``humanoid_goalkeeper.mp4``
and the same figures).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from soccer_env.render.plots import pyplot, save_figure
from soccer_env.render.video import write_video

__all__ = ["run_demo"]


def run_demo(out: str | Path = "demo_output", episodes: int = 3, seed: int = 0,
             obs_mode: str = "perceived", perception: str | None = "realistic",
             video: bool = True, robot: str = "ssl") -> dict[str, Any]:
    """Run ``episodes`` Goalkeeper-v0 episodes with the scripted keeper; write the files
    (``perception=None``: the robot's default; a humanoid's files are prefixed
    ``humanoid_``)."""
    from agents import ScriptedGoalkeeper

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    env = gym.make("soccer_env/Goalkeeper-v0", obs_mode=obs_mode, robot=robot,
                   perception=None if obs_mode == "truth" else perception,
                   render_mode="rgb_array" if video else None, render_width=640)
    policy = ScriptedGoalkeeper.for_env(env)
    frames: list[np.ndarray] = []
    records = []
    for ep in range(episodes):
        obs, info = env.reset(seed=seed + ep)
        track = [_row(info)]
        if video:
            frames.append(env.render())
        while True:
            obs, reward, term, trunc, info = env.step(policy(obs))
            track.append(_row(info))
            if video:
                frames.append(env.render())
            if term or trunc:
                break
        track = np.array(track)
        err = np.hypot(track[:, 8] - track[:, 1], track[:, 9] - track[:, 2])
        records.append({"seed": seed + ep, "shot": info["shot"],
                        "outcome": info["outcome"] if term else "time limit",
                        "reward": reward, "steps": len(track) - 1,
                        "ball_error_median_m": float(np.median(err)),
                        "ball_error_max_m": float(np.max(err)), "track": track})
    env.close()

    files = {}
    if video:
        stem = "humanoid_goalkeeper" if robot.startswith("humanoid") else "goalkeeper"
        files["video"] = str(write_video(frames, out / f"{stem}.mp4",
                                         env.unwrapped.metadata["render_fps"]))
    files.update(_figures(records, env.unwrapped.field, out))
    summary = {
        "robot": robot,
        "obs_mode": obs_mode,
        "perception": None if obs_mode == "truth" else perception,
        "episodes": [{k: v for k, v in r.items() if k != "track"} for r in records],
        "files": files,
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary


def _row(info: dict[str, Any]) -> list[float]:
    """time, true ball x y z vx vy, keeper x y, believed ball x y."""
    t = info["truth"]
    kx, ky, _ = t["robot_pose"]["blue_0"]
    bx, by = t["ball_position"]
    vx, vy = t["ball_velocity"]
    ex, ey = info["estimate"]["ball_position"]
    return [t["time"], bx, by, t["ball_height"], vx, vy, kx, ky, ex, ey]


def _figures(records: list[dict[str, Any]], field, out: Path) -> dict[str, str]:
    plt = pyplot()

    hx, hy = field.half_length, field.half_width
    fig, ax = plt.subplots(figsize=(9, 6.5))
    ax.add_patch(plt.Rectangle((-hx, -hy), 2 * hx, 2 * hy, fill=True, color="#1e7a34", lw=0))
    ax.plot([0, 0], [-hy, hy], color="w", lw=1)
    gw, gd = field.goal_width / 2, field.goal_depth
    for s in (-1, 1):
        ax.plot([s * hx, s * (hx + gd), s * (hx + gd), s * hx], [gw, gw, -gw, -gw], color="k")
        dd, dw = field.defense_depth, field.defense_width / 2
        ax.plot([s * hx, s * (hx - dd), s * (hx - dd), s * hx], [dw, dw, -dw, -dw], color="w",
                lw=1)
    for k, r in enumerate(records):
        tr = r["track"]
        colour = f"C{k % 10}"
        ax.plot(tr[:, 1], tr[:, 2], color=colour, lw=1.5,
                label=f"seed {r['seed']}: {r['outcome']}")
        ax.plot(tr[:, 8], tr[:, 9], color=colour, lw=1, ls="--")
        ax.plot(tr[0, 1], tr[0, 2], "o", color=colour)
        ax.plot(tr[:, 6], tr[:, 7], color=colour, lw=3, alpha=0.6)
    ax.set_aspect("equal")
    ax.set_xlim(-hx - field.boundary, hx + field.boundary)
    ax.set_ylim(-hy - field.boundary, hy + field.boundary)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("Goalkeeper-v0: true ball (solid), believed ball (dashed), keeper (thick)")
    ax.legend(loc="upper right", fontsize=8)
    traj = save_figure(fig, out / "trajectories.png")

    fig, ax = plt.subplots(figsize=(7, 4))
    for k, r in enumerate(records):
        tr = r["track"]
        ax.plot(tr[:, 0], np.hypot(tr[:, 4], tr[:, 5]), color=f"C{k % 10}",
                label=f"seed {r['seed']} ({'chip' if r['shot']['chip'] else 'flat'})")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("ball speed [m/s]")
    ax.set_title("Ball speed: sliding, then rolling, until saved or scored")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    speed = save_figure(fig, out / "ball_speed.png")

    fig, ax = plt.subplots(figsize=(7, 4))
    for k, r in enumerate(records):
        tr = r["track"]
        err = np.hypot(tr[:, 8] - tr[:, 1], tr[:, 9] - tr[:, 2]) * 1000
        ax.plot(tr[:, 0], np.maximum(err, 1e-3), color=f"C{k % 10}", label=f"seed {r['seed']}")
    ax.set_yscale("log")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("believed - true ball position [mm]")
    ax.set_title("Estimation error (large right after the kick: it is seen late)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    error = save_figure(fig, out / "estimate_error.png")
    return {"trajectories": traj, "ball_speed": speed, "estimate_error": error}
