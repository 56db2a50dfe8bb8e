"""The estimator ablation: one keeper policy, the same seeded shots, every estimator
configuration under every sensor preset (``soccer-env ablation``).

Each cell of the table is an :func:`agents.evaluation.evaluate` run of Goalkeeper-v0 on the
fixed shot suite (seeds ``start_seed .. start_seed + episodes - 1``) with the configuration's
observation mode and perception options and the preset's vision: save rate with Wilson's 95 %
interval, ball estimation RMSE (believed against true ball position over all steps) and the
estimator's compute per step. The same seed gives the same shot in every cell, so the cells
differ only in what the policy perceives.

Estimator configurations live in one :class:`~estimators.registry.Registry` per robot kind
(:data:`ROBOT_KINDS`): :data:`ESTIMATOR_CONFIGS` for SSL robots and :data:`HUMANOID_CONFIGS`
for humanoids (``robot="humanoid"``: the keeper and its team-mates with head cameras,
localization, team fusion and ball tracking); a new estimator (with its own perception
options) is one more :class:`EstimatorConfig` given to :func:`register_config`. Sensor presets
are the names of :data:`soccer_env.presets.VISION` (SSL) or
:data:`soccer_env.presets.HEAD_CAMERAS` (humanoids).

The work is split into jobs of (configuration, preset, chunk of ``chunk_size`` consecutive
seeds) spread over processes. Chunks do not depend on the number of workers and are merged in
seed order, so every number except the timings (estimator us/step, seconds) is identical for
any ``workers``.

Outputs (:func:`write_outputs`, :mod:`agents.ablation_report`): ``ablation.md`` (tables, the
policy and the command), ``ablation.csv`` (one row per cell), ``ablation.json`` (settings,
configurations and all numbers, including which seeds were saved in each cell) and
``ablation.png`` (save rates with their intervals, RMSE and compute per preset and
configuration).
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import shlex
import time
from collections import Counter
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from agents import ablation_report
from agents.ablation_report import write_outputs
from agents.evaluation import (
    EvalResult,
    describe_policy,
    evaluate,
    map_jobs,
    resolve_workers,
    wilson,
)
from estimators.registry import Registry
from soccer_env.envs.registration import GOALKEEPER_ID
from soccer_env.perception.base import OBS_MODES, PerceptionConfig
from soccer_env.perception.options import BALL_FILTERS
from soccer_env.presets.sensors import HEAD_CAMERAS, VISION
from soccer_env.validation import check_fields

__all__ = ["EstimatorConfig", "ESTIMATOR_CONFIGS", "HUMANOID_CONFIGS", "ROBOT_KINDS",
           "RobotKind", "robot_kind", "register_config", "AblationResult", "run_ablation",
           "write_outputs", "parse_names", "default_presets", "DEFAULT_CHUNK_SIZE",
           "DEFAULT_EPISODES"]

#: Shots per cell.
DEFAULT_EPISODES = 1000
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
        # The vision is the preset, not a configuration's.
        check_fields(PerceptionConfig, self.perception, "perception", exclude=("vision",),
                     where=f" in configuration {self.name!r} (its vision is the preset)")
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
    :data:`~soccer_env.perception.options.BALL_FILTERS`)."""
    return EstimatorConfig(name, "perceived", BALL_FILTERS.description(name), source,
                           perception={"ball_filter": name})


def _registry(family: str, configs: Iterable[EstimatorConfig]) -> Registry[EstimatorConfig]:
    """A registry of ``configs`` by name, each described by its description."""
    return Registry(family, [(c.name, c, c.description) for c in configs])


#: The estimator configurations of SSL robots, by name, in table order.
ESTIMATOR_CONFIGS: Registry[EstimatorConfig] = _registry(
    "estimator configuration", (
        EstimatorConfig("truth", "truth", "oracle: the true state (the preset's actuation "
                        "latency and command loss still apply)", "upper bound"),
        EstimatorConfig("raw", "raw", "latest delayed detections, unfiltered (velocity from "
                        "the last two sightings)", "lower bound"),
        _filter_config("kf", "Zhao et al. (2012) (baseline without latency compensation)"),
        _filter_config("kf-comp", "Zhao et al. (2012) (latency compensation without friction "
                       "model)"),
        _filter_config("ekf", "Zhao et al. (2012)"),
        _filter_config("ekf-improved", "Zhao et al. (2012) (improved EKF)"),
        _filter_config("ekf-2phase", "soccer_env (Zhao et al.'s 2012 EKF with a two-phase ball)"),
        _filter_config("ls", "Zhao et al. (2012) (least-squares baseline)"),
        _filter_config("kick", "soccer_env (kick-aware smoother over the two-phase ball)"),
        _filter_config("imm", "soccer_env (interacting multiple model: rest, rolling, "
                       "maneuver)"),
    ))


def _humanoid_config(name: str, description: str, obs_mode: str = "perceived",
                     source: str = "Xu et al. (2012)", **perception: str) -> EstimatorConfig:
    return EstimatorConfig(name, obs_mode, description, source, perception=perception,
                           robot="humanoid")


#: The humanoid robot of the humanoid ablation unless ``robot`` is given: Xu et al.'s (2012).
DEFAULT_HUMANOID = "humanoid-2012"

#: The humanoid estimator configurations, by name, in table order: what the keeper believes
#: about the ball (its own pose from KLD-sampling localization in all perceived ones).
HUMANOID_CONFIGS: Registry[EstimatorConfig] = _registry(
    "estimator configuration", (
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
        _humanoid_config("fusion-ivar-mfbpf", "Hough fusion weighted by the inverse variance "
                         "of each line's offset, MFBPF tracking", source="Xu et al. (2012); the "
                         "weighting ours", fusion="inverse_variance", ball_tracker="mfbpf"),
        _humanoid_config("pixels", "fusion-mfbpf with every robot finding the ball in its "
                         "rendered head-camera images (Kalman-started mean shift)",
                         source="Xu et al. (2012) and Yu et al. (2010)", fusion="inverse",
                         ball_tracker="mfbpf",
                         detector="pixels"),
    ))


@dataclass(frozen=True)
class RobotKind:
    """The keepers of one robot kind in the ablation.

    Attributes:
        configs: its estimator configurations.
        presets: its sensor presets (specs with a ``source``), by name.
        presets_name: where the presets live, for the tables.
    """

    configs: Registry[EstimatorConfig]
    presets: Mapping[str, Any]
    presets_name: str


#: Robot kinds of the ablation: their configuration registries and sensor presets.
ROBOT_KINDS: Registry[RobotKind] = Registry("robot", [
    ("ssl", RobotKind(ESTIMATOR_CONFIGS, VISION, "soccer_env.presets.VISION"),
     "SSL keepers: overhead vision and its ball filters"),
    ("humanoid", RobotKind(HUMANOID_CONFIGS, HEAD_CAMERAS, "soccer_env.presets.HEAD_CAMERAS"),
     "humanoid keepers with three team-mates: head cameras, localization, team fusion and "
     "ball tracking"),
])


def robot_kind(robot: str) -> RobotKind:
    """The configurations and sensor presets of robot kind ``robot`` (looked up in
    :data:`ROBOT_KINDS` when called); ``ValueError`` for an unknown kind."""
    return ROBOT_KINDS[ROBOT_KINDS.check(robot, "robot")]


def register_config(config: EstimatorConfig, replace: bool = False) -> EstimatorConfig:
    """Add ``config`` to the registry of its robot kind (:data:`ESTIMATOR_CONFIGS` or
    :data:`HUMANOID_CONFIGS`, after the existing ones; its description is the registry's). A
    name already registered raises ``ValueError`` unless ``replace``."""
    if not isinstance(config, EstimatorConfig):
        raise TypeError(f"config must be an EstimatorConfig, got {type(config).__name__}")
    return robot_kind(config.robot).configs.register(config.name, config, config.description,
                                                     replace=replace)


def default_presets(robot: str = "ssl") -> list[str]:
    """All sensor presets of the robot kind: :data:`soccer_env.presets.VISION` for SSL
    robots, :data:`soccer_env.presets.HEAD_CAMERAS` for humanoids."""
    return list(robot_kind(robot).presets)


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
        return ablation_report.rows(self)

    def to_dict(self) -> dict[str, Any]:
        """Settings, configurations and every number (``ablation.json``)."""
        return ablation_report.data(self)

    def markdown(self) -> str:
        """The tables of ``ablation.md``."""
        return ablation_report.markdown(self)


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


def _resolve_policy(policy: Any, env_id: str, env_kwargs: Mapping[str, Any],
                    trust: bool = False) -> Any:
    """Resolve the policy once here, so that a bad reference fails before any work starts.
    Returns what the jobs get: the reference itself, or for a saved stable-baselines3 model
    (``.zip`` or run folder) the loaded policy (its numpy copy pickles cheaply, where loading
    the model in every job would import torch in every worker)."""
    import gymnasium as gym

    from agents.policies import make_policy

    env = gym.make(env_id, **env_kwargs)
    try:
        resolved = make_policy(policy, env, trust=trust)
    finally:
        env.close()
    if isinstance(policy, (str, os.PathLike)) and (
            os.fspath(policy).endswith(".zip") or Path(policy).is_dir()):
        return resolved
    return policy


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
        trust: load a stable-baselines3 file's pickled entries (see
            :mod:`agents.model_files`; only for files from a source you trust).

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
    job_policy = _resolve_policy(policy, env_id,
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
