"""The estimator ablation: one keeper policy, the same seeded shots, every estimator
configuration under every sensor preset (``soccer-env ablation``).

Each cell of the table is an :func:`agents.evaluation.evaluate` run of Goalkeeper-v0 on the
fixed shot suite (seeds ``start_seed .. start_seed + episodes - 1``) with the configuration's
observation mode and perception options and the preset's vision: save rate with Wilson's 95 %
interval, ball estimation RMSE (believed against true ball position over all steps) and the
estimator's compute per step. The same seed gives the same shot in every cell, so the cells
differ only in what the policy perceives.

Estimator configurations live in registries, :data:`ESTIMATOR_CONFIGS` for SSL robots and
:data:`HUMANOID_CONFIGS` for humanoids (``robot="humanoid"``: the keeper and its team-mates
with head cameras, localization, team fusion and ball tracking); a new estimator (with its own
perception options) is one more :class:`EstimatorConfig` given to :func:`register_config`.
Sensor presets are the names of :data:`soccer_env.presets.VISION` (SSL) or
:data:`soccer_env.presets.HEAD_CAMERAS` (humanoids).

The work is split into jobs of (configuration, preset, chunk of ``chunk_size`` consecutive
seeds) spread over processes. Chunks do not depend on the number of workers and are merged in
seed order, so every number except the timings (estimator us/step, seconds) is identical for
any ``workers``.

Outputs (:func:`write_outputs`): ``ablation.md`` (tables, the policy and the command),
``ablation.csv`` (one row per cell), ``ablation.json`` (settings, configurations and all
numbers, including which seeds were saved in each cell) and ``ablation.png`` (save rates with
their intervals, RMSE and compute per preset and configuration).
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import json
import math
import os
import shlex
import sys
import time
from collections import Counter
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from agents.cli_args import key_values
from agents.evaluation import GOALKEEPER_ID, EvalResult, evaluate, process_context, wilson
from soccer_env.perception.base import BALL_FILTERS, OBS_MODES, PerceptionConfig
from soccer_env.presets.sensors import HEAD_CAMERAS, VISION

__all__ = ["EstimatorConfig", "ESTIMATOR_CONFIGS", "HUMANOID_CONFIGS", "ROBOT_KINDS",
           "register_config", "AblationResult", "run_ablation", "write_outputs", "parse_names",
           "default_presets", "main", "DEFAULT_CHUNK_SIZE"]

#: Consecutive seeds per job: small enough to keep every core busy to the end, large enough
#: that building the environment and the policy per job costs little.
DEFAULT_CHUNK_SIZE = 100


@dataclass(frozen=True)
class EstimatorConfig:
    """One estimator configuration of the ablation.

    The environment of a cell is ``gymnasium.make(env_id, **base_env_kwargs, **env_kwargs,
    obs_mode=obs_mode, perception={"vision": preset, **perception})`` (for a humanoid
    configuration ``{"camera": preset, ...}``, and ``robot="humanoid-2012"`` unless the base
    or the configuration names another humanoid).

    Attributes:
        name: the registry key (what ``--configs`` takes).
        obs_mode: one of :data:`soccer_env.perception.base.OBS_MODES`.
        description: one line for the tables.
        source: where the estimator comes from (paper, team).
        perception: options of :class:`~soccer_env.perception.base.PerceptionConfig` other than the
            vision preset, e.g. ``{"ball_filter": "kf"}``.
        env_kwargs: further environment keyword arguments of this configuration (not
            ``obs_mode`` or ``perception``).
        robot: ``"ssl"`` or ``"humanoid"``: which robots (and sensor presets) it is for.
    """

    name: str
    obs_mode: str
    description: str
    source: str = ""
    perception: Mapping[str, Any] = field(default_factory=dict)
    env_kwargs: Mapping[str, Any] = field(default_factory=dict)
    robot: str = "ssl"

    def __post_init__(self) -> None:
        if not self.name or "," in self.name or self.name.strip() != self.name:
            raise ValueError(f"configuration name must be non-empty without commas or "
                             f"surrounding spaces, got {self.name!r}")
        if self.obs_mode not in OBS_MODES:
            raise ValueError(f"obs_mode of configuration {self.name!r} must be one of "
                             f"{list(OBS_MODES)}, got {self.obs_mode!r}")
        allowed = {f.name for f in dataclasses.fields(PerceptionConfig)} - {"vision"}
        unknown = sorted(set(self.perception) - allowed)
        if unknown:
            raise ValueError(f"unknown perception key(s) {unknown} in configuration "
                             f"{self.name!r}; allowed: {sorted(allowed)} (the vision is the "
                             f"preset)")
        # Validates the values too (e.g. the ball filter's name).
        PerceptionConfig(vision="ideal", **self.perception)
        if self.robot not in ("ssl", "humanoid"):
            raise ValueError(f"robot of configuration {self.name!r} must be 'ssl' or "
                             f"'humanoid', got {self.robot!r}")
        clash = sorted({"obs_mode", "perception"} & set(self.env_kwargs))
        if clash:
            raise ValueError(f"env_kwargs of configuration {self.name!r} must not set {clash}")
        object.__setattr__(self, "perception", dict(self.perception))
        object.__setattr__(self, "env_kwargs", dict(self.env_kwargs))

    @property
    def ball_filter(self) -> str | None:
        """The ball filter of a ``"perceived"`` configuration (for a humanoid one, its fusion
        and tracker; None otherwise)."""
        if self.obs_mode != "perceived":
            return None
        if self.robot == "humanoid":
            return (f"{self.perception.get('fusion', PerceptionConfig.fusion)}+"
                    f"{self.perception.get('ball_tracker', PerceptionConfig.ball_tracker)}")
        return self.perception.get("ball_filter", PerceptionConfig.ball_filter)

    def make_env_kwargs(self, preset: str,
                        base: Mapping[str, Any] | None = None) -> dict[str, Any]:
        """The environment keyword arguments of this configuration under sensor ``preset``,
        over ``base`` (keyword arguments shared by all cells)."""
        kwargs = {**dict(base or {}), **self.env_kwargs, "obs_mode": self.obs_mode}
        if self.robot == "humanoid":
            kwargs.setdefault("robot", DEFAULT_HUMANOID)
            kwargs["perception"] = {"camera": preset, **self.perception}
        else:
            kwargs["perception"] = {"vision": preset, **self.perception}
        return kwargs

    def to_dict(self) -> dict[str, Any]:
        return {**dataclasses.asdict(self), "ball_filter": self.ball_filter}


def _filter_config(name: str, source: str) -> EstimatorConfig:
    """The ``"perceived"`` configuration with ball filter ``name`` (described as in
    :data:`~soccer_env.perception.base.BALL_FILTERS`)."""
    return EstimatorConfig(name, "perceived", BALL_FILTERS[name], source,
                           perception={"ball_filter": name})


#: The estimator configurations, by name, in table order.
ESTIMATOR_CONFIGS: dict[str, EstimatorConfig] = {
    c.name: c for c in (
        EstimatorConfig("truth", "truth", "oracle: the true state (the preset's actuation "
                        "latency and command loss still apply)", "upper bound"),
        EstimatorConfig("raw", "raw", "latest delayed detections, unfiltered (velocity from "
                        "the last two sightings)", "lower bound"),
        _filter_config("kf", "paper 002 (baseline without latency compensation)"),
        _filter_config("kf-comp", "paper 002 (latency compensation without friction model)"),
        _filter_config("ekf", "paper 002"),
        _filter_config("ekf-improved", "paper 002 (improved EKF)"),
        _filter_config("ekf-2phase", "soccer_env (paper 002's EKF with a two-phase ball)"),
        _filter_config("ls", "paper 002 (least-squares baseline)"),
    )
}


def _humanoid_config(name: str, description: str, obs_mode: str = "perceived",
                     source: str = "paper 000", **perception: str) -> EstimatorConfig:
    return EstimatorConfig(name, obs_mode, description, source, perception=perception,
                           robot="humanoid")


#: The humanoid robot of the humanoid ablation unless ``robot`` is given: paper 000's.
DEFAULT_HUMANOID = "humanoid-2012"

#: The humanoid estimator configurations, by name, in table order: what the keeper believes
#: about the ball (its own pose from KLD-sampling localization in all perceived ones).
HUMANOID_CONFIGS: dict[str, EstimatorConfig] = {
    c.name: c for c in (
        _humanoid_config("truth", "oracle: the true state", "truth", "upper bound"),
        _humanoid_config("raw", "dead reckoning and the keeper's own latest sighting, "
                         "unfiltered", "raw", "lower bound"),
        _humanoid_config("own", "the keeper's own sightings, no tracking (one robot alone)",
                         fusion="own", ball_tracker="none"),
        _humanoid_config("own-mfbpf", "the keeper's own sightings tracked by MFBPF",
                         fusion="own", ball_tracker="mfbpf"),
        _humanoid_config("fusion", "Hough fusion of the team's sightings (1/L weights), no "
                         "tracking", fusion="inverse", ball_tracker="none"),
        _humanoid_config("fusion-equal-mfbpf", "Hough fusion with equal weights, MFBPF "
                         "tracking", fusion="equal", ball_tracker="mfbpf"),
        _humanoid_config("fusion-bootstrap", "Hough fusion (1/L), bootstrap PF tracking",
                         fusion="inverse", ball_tracker="bootstrap"),
        _humanoid_config("fusion-fbpf", "Hough fusion (1/L), FBPF tracking",
                         fusion="inverse", ball_tracker="fbpf"),
        _humanoid_config("fusion-mfbpf", "Hough fusion (1/L), MFBPF tracking (default)",
                         fusion="inverse", ball_tracker="mfbpf"),
        _humanoid_config("pixels", "fusion-mfbpf with every robot finding the ball in its "
                         "rendered head-camera images (Kalman-started mean shift)",
                         source="papers 000 and 004", fusion="inverse", ball_tracker="mfbpf",
                         detector="pixels"),
    )
}

#: Robot kinds of the ablation: the names of their configuration registries in this module,
#: and their sensor presets.
ROBOT_KINDS = {"ssl": ("ESTIMATOR_CONFIGS", VISION),
               "humanoid": ("HUMANOID_CONFIGS", HEAD_CAMERAS)}


def _kind(robot: str) -> tuple[dict[str, EstimatorConfig], Mapping[str, Any]]:
    """The configuration registry and the sensor presets of a robot kind (the registry
    looked up when called, so that a replaced module attribute is the one used)."""
    if robot not in ROBOT_KINDS:
        raise ValueError(f"robot must be one of {list(ROBOT_KINDS)}, got {robot!r}")
    name, presets = ROBOT_KINDS[robot]
    return globals()[name], presets


def register_config(config: EstimatorConfig, replace: bool = False) -> EstimatorConfig:
    """Add ``config`` to the registry of its robot kind (:data:`ESTIMATOR_CONFIGS` or
    :data:`HUMANOID_CONFIGS`, after the existing ones). A name already registered raises
    ``ValueError`` unless ``replace``."""
    if not isinstance(config, EstimatorConfig):
        raise TypeError(f"config must be an EstimatorConfig, got {type(config).__name__}")
    registry = _kind(config.robot)[0]
    if config.name in registry and not replace:
        raise ValueError(f"estimator configuration {config.name!r} is already registered "
                         f"(pass replace=True to replace it)")
    registry[config.name] = config
    return config


def default_presets(robot: str = "ssl") -> list[str]:
    """All sensor presets of the robot kind: :data:`soccer_env.presets.VISION` for SSL
    robots, :data:`soccer_env.presets.HEAD_CAMERAS` for humanoids."""
    return list(_kind(robot)[1])


def parse_names(value: str | Iterable[str] | None, allowed: Iterable[str], what: str
                ) -> list[str]:
    """Names from a comma-separated string or a sequence, checked against ``allowed`` (all of
    them, in their order, for None or ``"all"``). Raises ``ValueError`` naming the unknown and
    the allowed names, for an empty list or for duplicates."""
    allowed = list(allowed)
    if value is None or value == "all":
        return allowed
    names = ([n.strip() for n in value.split(",") if n.strip()] if isinstance(value, str)
             else [str(n) for n in value])
    if not names:
        raise ValueError(f"no {what} given; allowed: {','.join(allowed)}")
    unknown = [n for n in names if n not in allowed]
    if unknown:
        raise ValueError(f"unknown {what} {', '.join(map(repr, unknown))}; allowed: "
                         f"{','.join(allowed)}")
    dupes = sorted({n for n in names if names.count(n) > 1})
    if dupes:
        raise ValueError(f"{what} given more than once: {', '.join(dupes)}")
    return names


# ------------------------------------------------------------------------------------------
# Running
# ------------------------------------------------------------------------------------------

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
        return _kind(self.robot)[1]

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
        keys = sorted({k for r in self.cells.values() for k in r.outcomes})
        rows = []
        for preset in self.presets:
            for name in self.configs:
                r, spec = self.cell(preset, name), self.config_specs[name]
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

    def to_dict(self) -> dict[str, Any]:
        """Settings, configurations and every number (``ablation.json``)."""
        cells = []
        for preset in self.presets:
            for name in self.configs:
                r = self.cell(preset, name)
                d = r.to_dict()
                d["saved"] = [int(s) for s in d["saved"]]
                cells.append({"preset": preset, "config": name, **d})
        return {
            "settings": {
                "policy": self.policy, "episodes": self.episodes,
                "start_seed": self.start_seed,
                "seeds": [self.start_seed, self.start_seed + self.episodes - 1],
                "presets": self.presets, "configs": self.configs, "env_id": self.env_id,
                "env_kwargs": self.env_kwargs, "workers": self.workers,
                "chunk_size": self.chunk_size, "command": self.command(),
                "save": "episode terminated without a goal (time limit: not saved)",
                "interval": "Wilson score interval, 95 %",
            },
            "configs": {n: self.config_specs[n].to_dict() for n in self.configs},
            "presets": {p: {"source": self.preset_table[p].source}
                        if p in self.preset_table else {} for p in self.presets},
            "cells": cells,
            "seconds": self.seconds,
        }

    def markdown(self) -> str:
        """The tables of ``ablation.md``."""
        lines = [
            "# Estimator ablation",
            "",
            f"Policy `{self.policy}` on `{self.env_id}`, {self.episodes} seeded shots per cell "
            f"(seeds {self.start_seed}-{self.start_seed + self.episodes - 1}, the same shots "
            "in every cell). Save: the episode ends without a goal; Wilson 95 % interval. "
            "RMSE: believed against true ball position over all steps. Compute: time in the "
            "perception's filters per environment step (sensor simulation excluded).",
            "",
            f"Command: `{self.command()}` ({self.seconds:.0f} s wall time).",
            "",
            "Save rate [%] (95 % CI):",
            "",
            "| sensor preset | " + " | ".join(self.configs) + " |",
            "|---|" + "---|" * len(self.configs),
        ]
        for preset in self.presets:
            cells = [_rate(self.cell(preset, c)) for c in self.configs]
            lines.append(f"| {preset} | " + " | ".join(cells) + " |")
        lines += ["", "| sensor preset | estimator | save rate [%] (95 % CI) | saves "
                  "| ball RMSE [mm] | estimator [us/step] |", "|---|---|---|---|---|---|"]
        for preset in self.presets:
            for c in self.configs:
                r = self.cell(preset, c)
                us = ("-" if r.estimator_us_per_step is None
                      else f"{r.estimator_us_per_step:.1f}")
                lines.append(f"| {preset} | {c} | {_rate(r)} | {r.saves}/{r.episodes} | "
                             f"{1000 * r.ball_rmse_m:.1f} | {us} |")
        lines += ["", "Estimator configurations:", ""]
        for c in self.configs:
            spec = self.config_specs[c]
            src = f" Source: {spec.source}." if spec.source else ""
            lines.append(f"- `{c}` ({spec.obs_mode}): {spec.description}.{src}")
        table = ("soccer_env.presets.HEAD_CAMERAS" if self.robot == "humanoid"
                 else "soccer_env.presets.VISION")
        lines += ["", f"Sensor presets (`{table}`):", ""]
        for p in self.presets:
            src = f": {self.preset_table[p].source}" if p in self.preset_table else ""
            lines.append(f"- `{p}`{src}.")
        return "\n".join(lines)


def _rate(r: EvalResult) -> str:
    return f"{100 * r.save_rate:.1f} ({100 * r.ci_low:.1f}-{100 * r.ci_high:.1f})"


def _describe(policy: Any) -> str:
    if isinstance(policy, (str, os.PathLike)):
        return os.fspath(policy)
    return getattr(policy, "__name__", type(policy).__name__)


def _run_job(job: tuple) -> EvalResult:
    """One job: the seeds ``[start, start + n)`` of one cell, in this process."""
    policy, env_id, env_kwargs, start, n = job
    return evaluate(policy, env_kwargs, episodes=n, start_seed=start, workers=1,
                    measure_estimator=True, env_id=env_id)


def _merge(parts: Sequence[EvalResult], policy: str) -> EvalResult:
    """One evaluation from the evaluations of consecutive seed chunks, in seed order."""
    saved = [s for p in parts for s in p.saved]
    saves, n = sum(saved), len(saved)
    steps = sum(p.steps for p in parts)
    outcomes: Counter = Counter()
    for p in parts:
        outcomes.update(p.outcomes)
    sq_err = sum(p.ball_rmse_m ** 2 * p.steps for p in parts)
    timed = [p.estimator_us_per_step for p in parts]
    lo, hi = wilson(saves, n)
    return EvalResult(
        policy=policy, env_kwargs=parts[0].env_kwargs, episodes=n, saves=saves,
        save_rate=saves / n, ci_low=lo, ci_high=hi, outcomes=dict(sorted(outcomes.items())),
        steps=steps, mean_steps=steps / n, ball_rmse_m=math.sqrt(sq_err / max(steps, 1)),
        estimator_us_per_step=(None if any(t is None for t in timed) else
                               sum(t * p.steps for t, p in zip(timed, parts)) / max(steps, 1)),
        seconds=sum(p.seconds for p in parts), saved=saved)


def _resolve_policy(policy: Any, env_id: str, env_kwargs: Mapping[str, Any]) -> Any:
    """Resolve the policy once here, so that a bad reference fails before any work starts.
    Returns what the jobs get: the reference itself, or for a saved stable-baselines3 model
    (``.zip`` or run folder) the loaded policy (its numpy copy pickles cheaply, where loading
    the model in every job would import torch in every worker)."""
    import gymnasium as gym

    from agents.policies import make_policy

    env = gym.make(env_id, **env_kwargs)
    try:
        resolved = make_policy(policy, env)
    finally:
        env.close()
    if isinstance(policy, (str, os.PathLike)) and (
            os.fspath(policy).endswith(".zip") or Path(policy).is_dir()):
        return resolved
    return policy


def run_ablation(policy: str | os.PathLike | Callable = "scripted", episodes: int = 1000,
                 presets: str | Sequence[str] | None = None,
                 configs: str | Sequence[str] | None = None, start_seed: int = 0,
                 workers: int | None = None, chunk_size: int = DEFAULT_CHUNK_SIZE,
                 env_kwargs: Mapping[str, Any] | None = None, env_id: str = GOALKEEPER_ID,
                 progress: Callable[[int, int], None] | None = None,
                 robot: str = "ssl") -> AblationResult:
    """Evaluate ``policy`` on the same seeded shots for every configuration and preset.

    Args:
        policy: a policy reference of :func:`~agents.policies.make_policy` (``"scripted"``,
            ``"idle"``, ``"baseline:NAME"``, a ``.zip``/``.npz`` path or a run folder); a
            callable must pickle when ``workers > 1``.
        episodes: shots per cell, seeds ``start_seed`` onwards (>= 1).
        presets: sensor preset names (list or comma-separated; default: all of
            :data:`soccer_env.presets.VISION`, or for humanoids of
            :data:`soccer_env.presets.HEAD_CAMERAS`).
        configs: names in :data:`ESTIMATOR_CONFIGS` (for humanoids
            :data:`HUMANOID_CONFIGS`; default: all, in registry order).
        start_seed: the first seed.
        workers: processes (default: all cores); the numbers do not depend on it.
        chunk_size: consecutive seeds per job.
        env_kwargs: environment keyword arguments shared by all cells (e.g. ``field``);
            ``obs_mode`` and ``perception`` belong to the cells and are refused.
        env_id: the environment (Goalkeeper-v0).
        progress: called as ``progress(jobs_done, jobs_total)`` after each job.
        robot: ``"ssl"`` or ``"humanoid"`` (the keeper, its configurations and presets).

    Raises:
        ValueError: unknown preset or configuration names, ``episodes``, ``workers`` or
            ``chunk_size`` below 1, or a policy reference that cannot be resolved.
    """
    if isinstance(episodes, bool) or int(episodes) != episodes or episodes < 1:
        raise ValueError(f"episodes must be an integer >= 1, got {episodes!r}")
    if int(chunk_size) < 1:
        raise ValueError(f"chunk_size must be >= 1, got {chunk_size!r}")
    workers = (os.cpu_count() or 1) if workers is None else int(workers)
    if workers < 1:
        raise ValueError(f"workers must be >= 1, got {workers!r}")
    registry, preset_table = _kind(robot)
    preset_names = parse_names(presets, preset_table, "sensor preset(s)")
    config_names = parse_names(configs, registry, "estimator configuration(s)")
    specs = {n: registry[n] for n in config_names}
    base = dict(env_kwargs or {})
    cell_keys = sorted({"obs_mode", "perception"} & set(base))
    if cell_keys:
        raise ValueError(f"env_kwargs: {cell_keys} are set by each cell's configuration and "
                         "preset")
    episodes, start_seed, chunk_size = int(episodes), int(start_seed), int(chunk_size)
    job_policy = _resolve_policy(policy, env_id,
                                 specs[config_names[0]].make_env_kwargs(preset_names[0], base))

    t0 = time.perf_counter()
    starts = list(range(start_seed, start_seed + episodes, chunk_size))
    keys, jobs = [], []
    # Seed chunks outermost: every configuration runs throughout, so that a change in the
    # machine's load during the run biases no configuration's timing.
    for s in starts:
        for name in config_names:
            for preset in preset_names:
                kwargs = specs[name].make_env_kwargs(preset, base)
                keys.append((preset, name))
                jobs.append((job_policy, env_id, kwargs, s,
                             min(chunk_size, start_seed + episodes - s)))
    outs: list[EvalResult | None] = [None] * len(jobs)
    if workers == 1 or len(jobs) == 1:
        for i, job in enumerate(jobs):
            outs[i] = _run_job(job)
            if progress:
                progress(i + 1, len(jobs))
    else:
        # forkserver (or spawn), not fork: a parent that has used torch deadlocks forked
        # children. The jobs carry their environment's keyword arguments, so configurations
        # registered at run time need not exist in the workers.
        with ProcessPoolExecutor(min(workers, len(jobs)), mp_context=process_context()) as pool:
            futures = {pool.submit(_run_job, job): i for i, job in enumerate(jobs)}
            for done, fut in enumerate(as_completed(futures), 1):
                outs[futures[fut]] = fut.result()
                if progress:
                    progress(done, len(jobs))
    parts: dict[tuple[str, str], list[EvalResult]] = {}
    for key, out in zip(keys, outs):
        parts.setdefault(key, []).append(out)
    label = _describe(policy)
    cells = {(p, c): _merge(parts[(p, c)], label) for p in preset_names for c in config_names}
    return AblationResult(policy=label, episodes=episodes, start_seed=start_seed,
                          presets=preset_names, configs=config_names, cells=cells,
                          config_specs=specs, env_id=env_id, env_kwargs=base, workers=workers,
                          chunk_size=chunk_size, seconds=time.perf_counter() - t0, robot=robot)


# ------------------------------------------------------------------------------------------
# Outputs
# ------------------------------------------------------------------------------------------

def _plot(res: AblationResult, path: Path) -> str:
    """Grouped bars per preset: save rate with its interval, ball RMSE, compute per step."""
    import numpy as np

    from soccer_env.render.plots import pyplot, save_figure

    plt = pyplot()
    n_p, n_c = len(res.presets), len(res.configs)
    fig, axes = plt.subplots(3, 1, figsize=(max(7.0, 1.6 + 0.32 * n_p * n_c), 9.5), sharex=True)
    width = 0.8 / n_c
    x = np.arange(n_p)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
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
    axes[0].set_ylabel("save rate [%]")
    axes[0].set_ylim(0, 105)
    axes[0].set_title(f"Policy {res.policy}: {res.episodes} shots per bar (95 % CI)")
    axes[0].legend(fontsize=8, ncol=min(n_c, 4), loc="lower left")
    axes[1].set_ylabel("ball RMSE [mm]")
    if any(res.cell(p, c).ball_rmse_m > 0 for p in res.presets for c in res.configs):
        from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

        axes[1].set_yscale("log")
        # Ticks at 1, 2 and 5 per decade: a range within one decade still gets labels.
        axes[1].yaxis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
        axes[1].yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        axes[1].yaxis.set_minor_formatter(NullFormatter())
    axes[1].set_title("Ball estimation error (truth: 0, not drawn)", fontsize=10)
    axes[2].set_ylabel("estimator [us/step]")
    axes[2].set_title("Estimator compute per step", fontsize=10)
    axes[2].set_xticks(x, res.presets)
    axes[2].set_xlabel("sensor preset")
    for ax in axes:
        ax.grid(axis="y", alpha=0.3)
    return save_figure(fig, path)


def write_outputs(res: AblationResult, out: str | os.PathLike) -> dict[str, Path]:
    """Write ``ablation.md``, ``.csv``, ``.json`` and ``.png`` to ``out``; return their
    paths by kind."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    files = {k: out / f"ablation.{k}" for k in ("md", "csv", "json", "png")}
    files["md"].write_text(res.markdown() + "\n")
    rows = res.rows()
    with files["csv"].open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    files["json"].write_text(json.dumps(res.to_dict(), indent=1) + "\n")
    _plot(res, files["png"])
    return files


# ------------------------------------------------------------------------------------------
# Command line
# ------------------------------------------------------------------------------------------

def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="soccer-env ablation",
        description="Evaluate one keeper policy on the same seeded shots under every estimator "
                    "configuration and sensor preset: save rate with Wilson 95 % interval, "
                    "ball estimation RMSE and estimator compute per step.")
    p.add_argument("--policy", default="scripted",
                   help="policy reference: scripted, idle, baseline:NAME, a .zip/.npz file or "
                        "a training run folder (default: scripted)")
    p.add_argument("--episodes", type=int, default=1000,
                   help="shots per cell, seeds start-seed onwards (default: 1000)")
    p.add_argument("--robot", default="ssl", choices=list(ROBOT_KINDS),
                   help="the keeper's robot kind: ssl (overhead vision) or humanoid (head "
                        "cameras, localization, team fusion; robot humanoid-2012 unless "
                        "--env-kwarg robot=... names another) (default: ssl)")
    p.add_argument("--presets", default=None,
                   help=f"comma-separated sensor presets (default: all; ssl: "
                        f"{','.join(VISION)}; humanoid: {','.join(HEAD_CAMERAS)})")
    p.add_argument("--configs", default="all",
                   help="comma-separated estimator configurations (default: all; ssl: "
                        f"{','.join(ESTIMATOR_CONFIGS)}; humanoid: "
                        f"{','.join(HUMANOID_CONFIGS)})")
    p.add_argument("--workers", type=int, default=None,
                   help="processes (default: all cores); the results do not depend on it")
    p.add_argument("--out", default="ablation_output",
                   help="output folder (default: ablation_output)")
    p.add_argument("--start-seed", type=int, default=0, help="seed of the first shot")
    p.add_argument("--chunk-size", type=int, default=DEFAULT_CHUNK_SIZE,
                   help=f"consecutive seeds per job (default: {DEFAULT_CHUNK_SIZE})")
    p.add_argument("--env-kwarg", action="append", default=[], metavar="KEY=VALUE",
                   help="environment keyword argument shared by all cells (value parsed as "
                        "JSON), repeatable, e.g. control_dt=0.04 or field=ssl-2012; obs_mode "
                        "and perception belong to the cells")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    """``soccer-env ablation``: run the ablation, write its outputs and print the table."""
    p = _parser()
    args = p.parse_args(list(sys.argv[1:] if argv is None else argv))
    for name in ("episodes", "chunk_size"):
        if getattr(args, name) < 1:
            p.error(f"--{name.replace('_', '-')} must be >= 1, got {getattr(args, name)}")
    if args.workers is not None and args.workers < 1:
        p.error(f"--workers must be >= 1, got {args.workers}")
    try:
        registry, preset_table = _kind(args.robot)
        presets = parse_names(args.presets, preset_table, "sensor preset(s)")
        configs = parse_names(args.configs, registry, "estimator configuration(s)")
        env_kwargs = key_values(args.env_kwarg, "--env-kwarg")
    except ValueError as exc:
        p.error(str(exc))
    t0 = time.perf_counter()

    def progress(done: int, total: int) -> None:
        if not args.quiet and (done == total or done % max(1, total // 20) == 0):
            print(f"ablation: {done}/{total} jobs ({time.perf_counter() - t0:.0f} s)",
                  file=sys.stderr, flush=True)

    try:
        res = run_ablation(args.policy, args.episodes, presets, configs, args.start_seed,
                           args.workers, args.chunk_size, env_kwargs=env_kwargs,
                           progress=progress, robot=args.robot)
    except (ValueError, TypeError, FileNotFoundError) as exc:
        p.error(str(exc))
    files = write_outputs(res, args.out)
    print(res.markdown())
    for path in files.values():
        print(f"wrote {path}")
    print(f"{len(res.cells)} cells x {res.episodes} shots in {res.seconds:.0f} s")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
