"""The estimator ablation's settings: the estimator configurations, one
:class:`~estimators.registry.Registry` per robot kind (:data:`ROBOT_KINDS`:
:data:`ESTIMATOR_CONFIGS` for SSL robots, :data:`HUMANOID_CONFIGS` for humanoids), their sensor
presets, and the defaults of a run. A new estimator (with its own perception options) is one
more :class:`EstimatorConfig` given to :func:`register_config`. The keeper's ablation
(:mod:`agents.studies.ablation`) and the match ablation (:mod:`agents.studies.match_ablation`)
both read them.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from estimators.registry import Registry
from soccer_env.perception.base import OBS_MODES, PerceptionConfig
from soccer_env.perception.options import BALL_FILTERS
from soccer_env.presets.sensors import HEAD_CAMERAS, VISION
from soccer_env.validation import check_fields

__all__ = ["EstimatorConfig", "ESTIMATOR_CONFIGS", "HUMANOID_CONFIGS", "DEFAULT_HUMANOID",
           "ROBOT_KINDS", "RobotKind", "robot_kind", "register_config", "parse_names",
           "default_presets", "DEFAULT_CHUNK_SIZE", "DEFAULT_EPISODES"]

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
        _humanoid_config("fusion-kick", "the team's sighting lines, each at its capture time, "
                         "tracked by the kick-aware Kalman tracker (no fusion step)",
                         source="ours", fusion="inverse", ball_tracker="kick"),
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
