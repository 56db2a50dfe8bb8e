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

from soccer_env.envs.registration import GOALKEEPER_ID
from soccer_env.render.plots import (
    EPISODE_COLOURS,
    LABEL_SIZE,
    TICK_SIZE,
    TITLE_SIZE,
    colour_key,
    draw_field,
    field_window,
    legend_beside,
    pyplot,
    save_figure,
    style_key,
)
from soccer_env.render.video import hold_last, write_video

__all__ = ["run_demo"]


def run_demo(out: str | Path = "demo_output", episodes: int = 3, seed: int = 0,
             obs_mode: str = "perceived", perception: str | None = "realistic",
             video: bool = True, robot: str = "ssl") -> dict[str, Any]:
    """Run ``episodes`` Goalkeeper-v0 episodes with the scripted keeper; write the files
    (``perception=None``: the robot's default; a humanoid's files are prefixed
    ``humanoid_``). In the video each episode opens with its title card and its last frame,
    with the outcome banner, stays a second before the next one."""
    from agents import ScriptedGoalkeeper

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    env = gym.make(GOALKEEPER_ID, obs_mode=obs_mode, robot=robot,
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
        if video:  # the outcome banner stays a second before the next episode's title card
            hold_last(frames, env.unwrapped.metadata["render_fps"])
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
    files.update(_figures(records, env.unwrapped.field, out, robot=robot, obs_mode=obs_mode,
                          perception=perception))
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


#: Line widths [pt] and opacities of the trajectory figure: the keeper's path is a broad
#: translucent band under the ball's, the true ball a lighter line under the dashed belief.
_KEEPER_LW, _KEEPER_ALPHA, _TRUE_ALPHA = 6.0, 0.35, 0.55


def _figures(records: list[dict[str, Any]], field, out: Path, *, robot: str = "ssl",
             obs_mode: str = "perceived", perception: Any = "realistic") -> dict[str, str]:
    """Write ``trajectories.png``, ``ball_speed.png`` and ``estimate_error.png`` of
    ``records`` (each with its ``track``, rows of :func:`_row`) into ``out``; the titles name
    the keeper's robot, ``field`` and what the keeper observes (``robot``, ``obs_mode`` and
    ``perception`` as :func:`run_demo` takes them). Returns the paths by name."""
    setting = _setting(field, robot, obs_mode, perception)
    return {"trajectories": save_figure(_trajectory_figure(records, field, setting),
                                        out / "trajectories.png"),
            "ball_speed": save_figure(_speed_figure(records, setting), out / "ball_speed.png"),
            "estimate_error": save_figure(_error_figure(records, setting,
                                                        seen_late=obs_mode != "truth"),
                                          out / "estimate_error.png")}


def _setting(field, robot: str, obs_mode: str, perception: Any) -> tuple[str, str]:
    """The keeper (``"SSL keeper"``, ``"humanoid keeper (humanoid-2012)"``) and a line naming
    the field and what the keeper observes, for the figures' titles."""
    from soccer_env import presets

    spec = presets.robot(robot)
    who = "SSL keeper" if spec.kind == "ssl" else f"humanoid keeper ({spec.name})"
    if obs_mode == "truth":
        sees = "true observations"
    elif spec.kind == "humanoid":
        camera = perception if isinstance(perception, str) else spec.camera
        sees = f"{obs_mode} observations, head camera {camera}"
    else:
        vision = perception if isinstance(perception, str) else (
            "realistic" if perception is None else "custom")
        sees = f"{obs_mode} observations, {vision} vision"
    return who, f"field {field.name} ({field.length:g} m x {field.width:g} m), {sees}"


def _colour(k: int) -> str:
    """Episode ``k``'s colour (one that stands out on the grass)."""
    return EPISODE_COLOURS[k % len(EPISODE_COLOURS)]


def _kick_time(track: np.ndarray) -> float | None:
    """The first time [s] the ball moves faster than 0.1 m/s (the kick), None if never."""
    moving = np.flatnonzero(np.hypot(track[:, 4], track[:, 5]) > 0.1)
    return float(track[moving[0], 0]) if len(moving) else None


def _trajectory_figure(records: list[dict[str, Any]], field, setting: tuple[str, str]):
    """The true and believed ball paths and the keeper's path of every episode, on the part of
    the field where they are (with the keeper's goal)."""
    plt = pyplot()
    tracks = [r["track"] for r in records]
    xs = np.concatenate([np.concatenate([t[:, 1], t[:, 6], t[:, 8]]) for t in tracks])
    ys = np.concatenate([np.concatenate([t[:, 2], t[:, 7], t[:, 9]]) for t in tracks])
    side = -1.0 if np.median(np.concatenate([t[:, 6] for t in tracks])) < 0 else 1.0
    goal_x = side * (field.half_length + field.goal_depth)
    xs = np.append(xs, [goal_x, goal_x])
    ys = np.append(ys, [-field.goal_width / 2, field.goal_width / 2])
    x0, x1, y0, y1 = field_window(xs, ys, field, margin=0.35)
    width = 6.0
    fig, ax = plt.subplots(figsize=(width + 2.6, max(2.8, width * (y1 - y0) / (x1 - x0)) + 0.9))
    draw_field(ax, field)
    for k, tr in enumerate(tracks):
        c = _colour(k)
        ax.plot(tr[:, 6], tr[:, 7], color=c, lw=_KEEPER_LW, alpha=_KEEPER_ALPHA, zorder=2,
                solid_capstyle="round")
        ax.plot(tr[:, 1], tr[:, 2], color=c, lw=2.2, alpha=_TRUE_ALPHA, zorder=3)
        ax.plot(tr[:, 8], tr[:, 9], color=c, lw=1.3, ls="--", zorder=4)
        ax.plot(tr[0, 1], tr[0, 2], "o", color=c, ms=7, mec="white", mew=1.0, zorder=5)
        ax.plot(tr[-1, 1], tr[-1, 2], "X", color=c, ms=8, mec="white", mew=1.0, zorder=5)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_xlabel("x [m]", fontsize=LABEL_SIZE)
    ax.set_ylabel("y [m]", fontsize=LABEL_SIZE)
    ax.tick_params(labelsize=TICK_SIZE)
    ax.set_title(f"Ball and keeper paths, {setting[0]}\n{setting[1]}", fontsize=TITLE_SIZE)
    keys = [style_key("true ball", lw=2.2, alpha=_TRUE_ALPHA),
            style_key("believed ball", ls="--", lw=1.3),
            style_key("keeper", lw=_KEEPER_LW, alpha=_KEEPER_ALPHA),
            style_key("ball at the start", ls="None", marker="o", ms=7),
            style_key("ball at the end", ls="None", marker="X", ms=8)]
    episodes = [colour_key(f"seed {r['seed']}: {r['outcome']}", _colour(k))
                for k, r in enumerate(records)]
    first = legend_beside(ax, keys, title="line style", handlelength=2.6)
    legend_beside(ax, episodes, title="episode (seed: outcome)", below=first)
    return fig


def _speed_figure(records: list[dict[str, Any]], setting: tuple[str, str]):
    """Ball speed against time, every episode."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(9.0, 4.2))
    for k, r in enumerate(records):
        tr = r["track"]
        ax.plot(tr[:, 0], np.hypot(tr[:, 4], tr[:, 5]), color=_colour(k), lw=1.6,
                label=f"seed {r['seed']}: {'chip' if r['shot']['chip'] else 'flat'} shot, "
                      f"{r['outcome']}")
    _time_axes(ax, records, "ball speed [m/s]",
               f"Ball speed, {setting[0]}: sliding, then rolling, until the episode "
               f"ends\n{setting[1]}")
    return fig


def _error_figure(records: list[dict[str, Any]], setting: tuple[str, str], *,
                  seen_late: bool = True):
    """Distance between the believed and the true ball against time, every episode (drawn
    at 0.001 mm at least, on a log scale); ``seen_late``: the keeper sees through a sensor
    (the title says why the error peaks after the kick)."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(9.0, 4.2))
    for k, r in enumerate(records):
        tr = r["track"]
        err = np.hypot(tr[:, 8] - tr[:, 1], tr[:, 9] - tr[:, 2]) * 1000
        ax.plot(tr[:, 0], np.maximum(err, 1e-3), color=_colour(k), lw=1.4,
                label=f"seed {r['seed']}: {r['outcome']}")
    ax.set_yscale("log")
    why = ": large right after the kick (the ball is seen late)" if seen_late else ""
    _time_axes(ax, records, "|believed - true ball position| [mm]\n(0.001 mm at least)",
               f"Ball estimation error, {setting[0]}{why}\n{setting[1]}")
    return fig


def _time_axes(ax, records: list[dict[str, Any]], ylabel: str, title: str) -> None:
    """Labels, grid, every episode's kick as a dotted line and the legend beside the axes."""
    for k, r in enumerate(records):
        t = _kick_time(r["track"])
        if t is not None:
            ax.axvline(t, color=_colour(k), ls=":", lw=1.2)
    ax.set_xlabel("time since the episode's start [s]", fontsize=LABEL_SIZE)
    ax.set_ylabel(ylabel, fontsize=LABEL_SIZE)
    ax.set_title(title, fontsize=TITLE_SIZE)
    ax.tick_params(labelsize=TICK_SIZE)
    ax.grid(alpha=0.3)
    first = legend_beside(ax, title="episode")
    legend_beside(ax, [style_key("kick (first step the ball\nmoves faster than 0.1 m/s)",
                                 ls=":", lw=1.2)], title="line style", below=first)
