"""The estimator ablation's report (:func:`write_outputs`): the tables of ``ablation.md``, one
row per cell in ``ablation.csv``, settings and every number in ``ablation.json`` and the bars
of ``ablation.png`` (save rates with their intervals, ball RMSE and estimator compute per
preset and configuration), from an :class:`AblationResult`, the outcome of
:func:`~agents.studies.ablation.run_ablation`."""

from __future__ import annotations

import csv
import json
import os
import shlex
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from agents.runs.evaluation import EvalResult
from agents.studies.ablation_settings import (
    DEFAULT_CHUNK_SIZE,
    DEFAULT_HUMANOID,
    EstimatorConfig,
    robot_kind,
)
from soccer_env.envs.registration import GOALKEEPER_ID

__all__ = ["AblationResult", "write_outputs", "write_files", "markdown", "rows", "data", "plot",
           "figure", "rate_text"]


@dataclass
class AblationResult:
    """The outcome of :func:`run_ablation`.

    Attributes:
        policy: the policy reference.
        episodes, start_seed: the shot suite (seeds ``start_seed .. start_seed + episodes -
            1``).
        presets, configs: the sensor presets and configuration names, in table order.
        cells: ``(preset, config) -> EvalResult``.
        config_specs: the configurations as they were run.
        env_id, env_kwargs: the environment and the keyword arguments shared by all cells.
        workers, chunk_size: how the work was split (the numbers do not depend on them).
        seconds: wall time [s].
        robot: the robot kind (``"ssl"`` or ``"humanoid"``).
    """

    policy: str
    episodes: int
    start_seed: int
    presets: list[str]
    configs: list[str]
    cells: dict[tuple[str, str], EvalResult]
    config_specs: dict[str, EstimatorConfig]
    env_id: str
    env_kwargs: dict[str, Any]
    workers: int
    chunk_size: int
    seconds: float
    robot: str = "ssl"

    @property
    def preset_table(self) -> Mapping[str, Any]:
        """The sensor presets of the robot kind (their specs have a ``source``)."""
        return robot_kind(self.robot).presets

    @property
    def preset_table_name(self) -> str:
        """Where the robot kind's sensor presets live (``soccer_env.presets.VISION`` or
        ``soccer_env.presets.HEAD_CAMERAS``)."""
        return robot_kind(self.robot).presets_name

    def cell(self, preset: str, config: str) -> EvalResult:
        """The evaluation of ``config`` under ``preset``."""
        return self.cells[(preset, config)]

    def command(self) -> str:
        """A ``soccer-env ablation`` command line that reruns this ablation."""
        args = ["soccer-env", "ablation"] + (["--robot", self.robot] if self.robot != "ssl"
                                             else []) + ["--policy", self.policy, "--episodes",
                str(self.episodes), "--start-seed", str(self.start_seed), "--presets",
                ",".join(self.presets), "--configs", ",".join(self.configs), "--workers",
                str(self.workers)]
        if self.chunk_size != DEFAULT_CHUNK_SIZE:
            args += ["--chunk-size", str(self.chunk_size)]
        for key, value in self.env_kwargs.items():
            args += ["--env-kwarg", f"{key}={json.dumps(value)}"]
        text = shlex.join(args)
        if self.env_id != GOALKEEPER_ID:
            text += f"  (API only: env_id={self.env_id!r})"
        return text

    def rows(self) -> list[dict[str, Any]]:
        """One flat row per cell (preset-major), as in ``ablation.csv``."""
        return rows(self)

    def to_dict(self) -> dict[str, Any]:
        """Settings, configurations and every number (``ablation.json``)."""
        return data(self)

    def markdown(self) -> str:
        """The tables of ``ablation.md``."""
        return markdown(self)


def markdown(res: AblationResult) -> str:
    """The tables of ``ablation.md``."""
    lines = [
        "# Estimator ablation",
        "",
        f"Policy `{res.policy}` on `{res.env_id}`, {res.episodes} seeded shots per cell "
        f"(seeds {res.start_seed}-{res.start_seed + res.episodes - 1}, the same shots "
        "in every cell). Save: the episode ends without a goal; Wilson 95 % interval. "
        "RMSE: believed against true ball position over all steps. Compute: time in the "
        "perception's filters per environment step (sensor simulation excluded).",
        "",
        f"Command: `{res.command()}` ({res.seconds:.0f} s wall time).",
        "",
        "Save rate [%] (95 % CI):",
        "",
        "| sensor preset | " + " | ".join(res.configs) + " |",
        "|---|" + "---|" * len(res.configs),
    ]
    for preset in res.presets:
        cells = [rate_text(res.cell(preset, c)) for c in res.configs]
        lines.append(f"| {preset} | " + " | ".join(cells) + " |")
    lines += ["", "| sensor preset | estimator | save rate [%] (95 % CI) | saves "
              "| ball RMSE [mm] | estimator [us/step] |", "|---|---|---|---|---|---|"]
    for preset in res.presets:
        for c in res.configs:
            r = res.cell(preset, c)
            us = ("-" if r.estimator_us_per_step is None
                  else f"{r.estimator_us_per_step:.1f}")
            lines.append(f"| {preset} | {c} | {rate_text(r)} | {r.saves}/{r.episodes} | "
                         f"{1000 * r.ball_rmse_m:.1f} | {us} |")
    lines += ["", "Estimator configurations:", ""]
    for c in res.configs:
        spec = res.config_specs[c]
        src = f" Source: {spec.source}." if spec.source else ""
        lines.append(f"- `{c}` ({spec.obs_mode}): {spec.description}.{src}")
    lines += ["", f"Sensor presets (`{res.preset_table_name}`):", ""]
    for p in res.presets:
        src = f": {res.preset_table[p].source}" if p in res.preset_table else ""
        lines.append(f"- `{p}`{src}.")
    return "\n".join(lines)


def rate_text(r: EvalResult) -> str:
    """A save rate and its interval in percent: ``"97.0 (93.2-98.7)"``."""
    return f"{100 * r.save_rate:.1f} ({100 * r.ci_low:.1f}-{100 * r.ci_high:.1f})"


def rows(res: AblationResult) -> list[dict[str, Any]]:
    """One flat row per cell (preset-major), as in ``ablation.csv``."""
    keys = sorted({k for r in res.cells.values() for k in r.outcomes})
    rows = []
    for preset in res.presets:
        for name in res.configs:
            r, spec = res.cell(preset, name), res.config_specs[name]
            rows.append({
                "preset": preset, "config": name, "obs_mode": spec.obs_mode,
                "ball_filter": spec.ball_filter or "", "episodes": r.episodes,
                "saves": r.saves, "save_rate": r.save_rate, "ci_low": r.ci_low,
                "ci_high": r.ci_high, "ball_rmse_mm": 1000 * r.ball_rmse_m,
                "estimator_us_per_step": r.estimator_us_per_step,
                "steps": r.steps, "mean_steps": r.mean_steps, "seconds": r.seconds,
                **{f"outcome_{k.replace(' ', '_')}": r.outcomes.get(k, 0) for k in keys},
            })
    return rows


def data(res: AblationResult) -> dict[str, Any]:
    """Settings, configurations and every number (``ablation.json``)."""
    cells = []
    for preset in res.presets:
        for name in res.configs:
            r = res.cell(preset, name)
            d = r.to_dict()
            d["saved"] = [int(s) for s in d["saved"]]
            cells.append({"preset": preset, "config": name, **d})
    return {
        "settings": {
            "policy": res.policy, "episodes": res.episodes,
            "start_seed": res.start_seed,
            "seeds": [res.start_seed, res.start_seed + res.episodes - 1],
            "presets": res.presets, "configs": res.configs, "env_id": res.env_id,
            "env_kwargs": res.env_kwargs, "workers": res.workers,
            "chunk_size": res.chunk_size, "command": res.command(),
            "save": "episode terminated without a goal (time limit: not saved)",
            "interval": "Wilson score interval, 95 %",
        },
        "configs": {n: res.config_specs[n].to_dict() for n in res.configs},
        "presets": {p: {"source": res.preset_table[p].source}
                    if p in res.preset_table else {} for p in res.presets},
        "cells": cells,
        "seconds": res.seconds,
    }


def plot(res: AblationResult, path: Path) -> str:
    """Write :func:`figure` of ``res`` to ``path`` (PNG); return the path."""
    from soccer_env.render.plots import save_figure

    return save_figure(figure(res), path)


def figure(res: AblationResult) -> Any:
    """Grouped bars per preset: save rate with its interval, ball RMSE, compute per step; the
    legend of the configurations beside the bars, the title naming the environment, the robots,
    the field and the policy.

    Returns:
        The :class:`matplotlib.figure.Figure` (not yet laid out; :func:`plot` saves it).
    """
    import numpy as np

    from soccer_env.render.plots import (
        LABEL_SIZE,
        TITLE_SIZE,
        describe_world,
        interval_key,
        legend_beside,
        pyplot,
    )

    plt = pyplot()
    n_p, n_c = len(res.presets), len(res.configs)
    fig, axes = plt.subplots(3, 1, figsize=(max(7.0, 1.6 + 0.32 * n_p * n_c) + 2.4, 9.8),
                             sharex=True)
    width = 0.8 / n_c
    x = np.arange(n_p)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    if len(res.configs) > len(colors):  # more estimators than the cycle's colours: no repeats
        colors = [plt.get_cmap("tab20")((2 * k) % 20 + (2 * k) // 20) for k in range(n_c)]
    for j, name in enumerate(res.configs):
        cells = [res.cell(p, name) for p in res.presets]
        pos = x + (j - (n_c - 1) / 2) * width
        color = colors[j % len(colors)]
        rate = np.array([c.save_rate for c in cells]) * 100
        err = np.array([[c.save_rate - c.ci_low, c.ci_high - c.save_rate] for c in cells]).T
        axes[0].bar(pos, rate, width, yerr=err * 100, capsize=2, color=color, label=name)
        rmse = np.array([c.ball_rmse_m for c in cells]) * 1000
        axes[1].bar(pos, np.where(rmse > 0, rmse, np.nan), width, color=color)
        us = np.array([c.estimator_us_per_step or 0.0 for c in cells])
        axes[2].bar(pos, us, width, color=color)
    axes[0].set_ylabel("save rate [%]", fontsize=LABEL_SIZE)
    axes[0].set_ylim(0, 105)
    kwargs = dict(res.env_kwargs)
    robot = kwargs.get("robot", DEFAULT_HUMANOID if res.robot == "humanoid" else "ssl")
    env = res.env_id.split("/")[-1]
    fig.suptitle(f"Estimator ablation on {env}: policy {res.policy}, {res.episodes} shots per "
                 f"bar\n{describe_world(robot, kwargs.get('field'))}", fontsize=TITLE_SIZE)
    axes[0].set_title("Save rate", fontsize=LABEL_SIZE)
    axes[1].set_ylabel("ball RMSE [mm]", fontsize=LABEL_SIZE)
    errors_mm = [1000 * res.cell(p, c).ball_rmse_m for p in res.presets for c in res.configs]
    errors_mm = [e for e in errors_mm if e > 0 and np.isfinite(e)]
    if errors_mm:
        from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

        axes[1].set_yscale("log")
        # Ticks at 1, 2 and 5 per decade: a range within one decade still gets labels; the
        # axis runs from the tick below the smallest bar to the tick above the largest.
        axes[1].yaxis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
        axes[1].yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        axes[1].yaxis.set_minor_formatter(NullFormatter())
        ticks = [m * 10.0 ** k for k in range(-3, 9) for m in (1.0, 2.0, 5.0)]
        low = max([v for v in ticks if v <= min(errors_mm) / 1.1], default=ticks[0])
        high = min([v for v in ticks if v >= max(errors_mm) * 1.1], default=ticks[-1])
        axes[1].set_ylim(low, high)
    axes[1].set_title("Ball estimation error, believed against true position over all steps "
                      "(truth: 0, not drawn)", fontsize=LABEL_SIZE)
    axes[2].set_ylabel("estimator [us/step]", fontsize=LABEL_SIZE)
    axes[2].set_title("Estimator compute per environment step", fontsize=LABEL_SIZE)
    axes[2].set_xticks(x, res.presets)
    axes[2].set_xlabel("head-camera preset" if res.robot == "humanoid"
                       else "sensor preset (overhead vision)", fontsize=LABEL_SIZE)
    for ax in axes:
        ax.grid(axis="y", alpha=0.3)
    first = legend_beside(axes[0], title="ball estimate")
    legend_beside(axes[0], [interval_key("95 % Wilson interval", color="k")], below=first)
    return fig


def write_outputs(res: AblationResult, out: str | os.PathLike) -> dict[str, Path]:
    """Write ``ablation.md``, ``.csv``, ``.json`` and ``.png`` to ``out``; return their
    paths by kind."""
    return write_files(out, "ablation", markdown(res), rows(res), data(res),
                       lambda path: plot(res, path))


def write_files(out: str | os.PathLike, stem: str, text: str, table: list[dict[str, Any]],
                numbers: dict[str, Any], draw: Callable[[Path], Any]) -> dict[str, Path]:
    """Write ``out/stem.md`` (``text``), ``.csv`` (``table``, one row per dict, the first
    row's keys as the header), ``.json`` (``numbers``) and ``.png`` (``draw(path)``);
    return their paths by kind."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    files = {k: out / f"{stem}.{k}" for k in ("md", "csv", "json", "png")}
    files["md"].write_text(text + "\n")
    with files["csv"].open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(table[0]))
        writer.writeheader()
        writer.writerows(table)
    files["json"].write_text(json.dumps(numbers, indent=1) + "\n")
    draw(files["png"])
    return files
