"""The estimator ablation: one keeper policy, the same seeded shots, every estimator
configuration under every sensor preset (``soccer-env ablation``).

Each cell of the table is an :func:`agents.runs.evaluation.evaluate` run of Goalkeeper-v0 on
the fixed shot suite (seeds ``start_seed .. start_seed + episodes - 1``) with the
configuration's observation mode and perception options and the preset's vision: save rate
with Wilson's 95 % interval, ball estimation RMSE (believed against true ball position over all
steps) and the estimator's compute per step. The same seed gives the same shot in every cell,
so the cells differ only in what the policy perceives.

Estimator configurations live in one :class:`~estimators.registry.Registry` per robot kind
(:mod:`agents.studies.ablation_settings`, whose names this module also offers):
:data:`ESTIMATOR_CONFIGS` for SSL robots and :data:`HUMANOID_CONFIGS` for humanoids
(``robot="humanoid"``: the keeper and its team-mates with head cameras, localization, team
fusion and ball tracking); a new estimator (with its own perception options) is one more
:class:`EstimatorConfig` given to :func:`register_config`. Sensor presets are the names of
:data:`soccer_env.presets.VISION` (SSL) or :data:`soccer_env.presets.HEAD_CAMERAS`
(humanoids).

The work is split into jobs of (configuration, preset, chunk of ``chunk_size`` consecutive
seeds) spread over processes. Chunks do not depend on the number of workers and are merged in
seed order, so every number except the timings (estimator us/step, seconds) is identical for
any ``workers``.

Outputs (:func:`write_outputs`, :mod:`agents.studies.ablation_report`): ``ablation.md``
(tables, the policy and the command), ``ablation.csv`` (one row per cell), ``ablation.json``
(settings, configurations and all numbers, including which seeds were saved in each cell) and
``ablation.png`` (save rates with their intervals, RMSE and compute per preset and
configuration).
"""

from __future__ import annotations

import math
import os
import time
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from agents.common.processes import map_jobs, resolve_workers
from agents.common.stats import wilson
from agents.policies.base import describe_policy
from agents.runs.evaluation import EvalResult, evaluate
from agents.runs.resolve import policy_for_jobs
from agents.studies.ablation_report import AblationResult, write_outputs
from agents.studies.ablation_settings import (
    DEFAULT_CHUNK_SIZE,
    DEFAULT_EPISODES,
    DEFAULT_HUMANOID,
    ESTIMATOR_CONFIGS,
    HUMANOID_CONFIGS,
    ROBOT_KINDS,
    EstimatorConfig,
    RobotKind,
    default_presets,
    parse_names,
    register_config,
    robot_kind,
)
from soccer_env.envs.registration import GOALKEEPER_ID

__all__ = ["run_ablation", "AblationResult", "write_outputs", "EstimatorConfig",
           "ESTIMATOR_CONFIGS", "HUMANOID_CONFIGS", "DEFAULT_HUMANOID", "ROBOT_KINDS",
           "RobotKind", "robot_kind", "register_config", "parse_names", "default_presets",
           "DEFAULT_CHUNK_SIZE", "DEFAULT_EPISODES"]


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


def run_ablation(policy: str | os.PathLike | Callable = "scripted",
                 episodes: int = DEFAULT_EPISODES,
                 presets: str | Sequence[str] | None = None,
                 configs: str | Sequence[str] | None = None, start_seed: int = 0,
                 workers: int | None = None, chunk_size: int = DEFAULT_CHUNK_SIZE,
                 env_kwargs: Mapping[str, Any] | None = None, env_id: str = GOALKEEPER_ID,
                 progress: Callable[[int, int], None] | None = None,
                 robot: str = "ssl", trust: bool = False) -> AblationResult:
    """Evaluate ``policy`` on the same seeded shots for every configuration and preset.

    Args:
        policy: a policy reference of :func:`~agents.runs.resolve.make_policy` (``"scripted"``,
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
        trust: load a stable-baselines3 file's pickled entries (see
            :mod:`agents.sb3.model_files`; only for files from a source you trust).

    Raises:
        ValueError: unknown preset or configuration names, ``episodes``, ``workers`` or
            ``chunk_size`` below 1, or a policy reference that cannot be resolved.
    """
    episodes, chunk_size, workers = _check_counts(episodes, chunk_size, workers)
    kind = robot_kind(robot)
    preset_names = parse_names(presets, kind.presets, "sensor preset(s)")
    config_names = parse_names(configs, kind.configs, "estimator configuration(s)")
    specs = {n: kind.configs[n] for n in config_names}
    base = dict(env_kwargs or {})
    cell_keys = sorted({"obs_mode", "perception"} & set(base))
    if cell_keys:
        raise ValueError(f"env_kwargs: {cell_keys} are set by each cell's configuration and "
                         "preset")
    start_seed = int(start_seed)
    job_policy = policy_for_jobs(policy, env_id,
                                 specs[config_names[0]].make_env_kwargs(preset_names[0], base),
                                 trust)

    t0 = time.perf_counter()
    keys, jobs = [], []
    # Seed chunks outermost: every configuration runs throughout, so that a change in the
    # machine's load during the run biases no configuration's timing.
    for s in range(start_seed, start_seed + episodes, chunk_size):
        for name in config_names:
            for preset in preset_names:
                keys.append((preset, name))
                jobs.append((job_policy, env_id, specs[name].make_env_kwargs(preset, base), s,
                             min(chunk_size, start_seed + episodes - s)))
    parts: dict[tuple[str, str], list[EvalResult]] = {}
    # The jobs carry their environment's keyword arguments, so configurations registered at
    # run time need not exist in the workers.
    for key, out in zip(keys, map_jobs(_run_job, jobs, workers, progress)):
        parts.setdefault(key, []).append(out)
    label = describe_policy(policy)
    cells = {(p, c): _merge(parts[(p, c)], label) for p in preset_names for c in config_names}
    return AblationResult(policy=label, episodes=episodes, start_seed=start_seed,
                          presets=preset_names, configs=config_names, cells=cells,
                          config_specs=specs, env_id=env_id, env_kwargs=base, workers=workers,
                          chunk_size=chunk_size, seconds=time.perf_counter() - t0, robot=robot)


def _check_counts(episodes: Any, chunk_size: Any, workers: Any) -> tuple[int, int, int]:
    """``episodes``, ``chunk_size`` and ``workers`` (None: every core) as integers >= 1, else
    ``ValueError``."""
    if isinstance(episodes, bool) or int(episodes) != episodes or episodes < 1:
        raise ValueError(f"episodes must be an integer >= 1, got {episodes!r}")
    if int(chunk_size) < 1:
        raise ValueError(f"chunk_size must be >= 1, got {chunk_size!r}")
    return int(episodes), int(chunk_size), resolve_workers(workers)
