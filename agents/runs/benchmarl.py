"""The match as a BenchMARL task: multi-agent PPO (MAPPO, IPPO) and BenchMARL's other
algorithms on :func:`soccer_env.parallel_env`, through TorchRL's ``PettingZooWrapper``.

BenchMARL (the ``benchmarl`` extra) describes an environment by a task enum, whose members
name its tasks, and a task class, which makes a TorchRL environment from a task's
configuration. :data:`SoccerTask` is the enum, with one member, ``SoccerTask.MATCH``;
:data:`SoccerMatchClass` the class. The configuration is :class:`MatchTaskConfig`, the
keyword arguments of :func:`soccer_env.parallel_env`::

    from benchmarl.algorithms import MappoConfig
    from benchmarl.experiment import Experiment, ExperimentConfig
    from benchmarl.models.mlp import MlpConfig

    from agents.runs.benchmarl import SoccerTask

    task = SoccerTask.MATCH.get_task({"blue": 2, "yellow": 2, "max_cycles": 600})
    experiment = Experiment(task=task, algorithm_config=MappoConfig.get_from_yaml(),
                            model_config=MlpConfig.get_from_yaml(), seed=0,
                            config=ExperimentConfig.get_from_yaml())
    experiment.run()

TorchRL groups the agents by team: group ``"blue"`` (``blue_0``, ``blue_1``, ...) and group
``"yellow"``, each with a policy (shared by the group's robots) and a critic of its own; both
teams learn. Every robot acts with the match's continuous actions (``Box(-1, 1, (6,))``).

The task always makes the match with ``info_mode="flat"``: TorchRL's wrapper turns every
entry of every agent's info into a tensor of the shape it had at the first reset
(``torch.as_tensor``), which the default infos refuse: ``truth``, ``estimate``, ``score`` and
``reward_terms`` are nested dicts (``Could not infer dtype of dict``) and ``event`` is a name,
not a number. The flat infos are numbers under the same keys at every step; they reach BenchMARL's
batches under ``(team, "info", key)``, and :meth:`SoccerMatchClass.log_info` logs the goals
of every collected batch from their ``event`` codes.

Importing this module needs neither BenchMARL nor torch: :data:`SoccerTask` and
:data:`SoccerMatchClass` are made on first use (they subclass BenchMARL's classes). The
experiments that BenchMARL saves pickle the task, so a checkpoint reloads
(``Experiment.reload_from_file``) wherever this module can be imported.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field, fields
from typing import Any

import soccer_env
from soccer_env.envs.flat_info import EVENT_CODES

# SoccerTask and SoccerMatchClass too, made on first use (see __getattr__); not in __all__,
# so that a star import needs no BenchMARL.
__all__ = ["MatchTaskConfig", "match_config", "match_env_kwargs"]

#: The environment's name in BenchMARL's logs and experiment names.
ENV_NAME = "soccer_env"


@dataclass
class MatchTaskConfig:
    """The configuration of ``SoccerTask.MATCH``: keyword arguments of
    :func:`soccer_env.parallel_env` (the defaults: 2 vs 2 matches of 30 s on true
    observations, shaped towards the ball and the opponent goal).

    Attributes:
        blue: blue's robots.
        yellow: yellow's robots.
        match_duration: the match's length [s].
        max_cycles: parallel steps after which the match is truncated, and the length of
            BenchMARL's evaluation rollouts (1800: 30 s at the default 60 Hz).
        obs_mode: ``"truth"``, ``"raw"`` or ``"perceived"`` (or one per team).
        perception: a vision preset's name, or its configuration (or one per team).
        shaping: ``{term: scale}`` of the match's shaping terms
            (:data:`soccer_env.envs.match.MATCH_SHAPING`).
        env_kwargs: any other keyword arguments of :func:`soccer_env.parallel_env`
            (``control_dt``, ``game``, ``robot``, ...), but ``info_mode``, which the task sets.
    """

    blue: int = 2
    yellow: int = 2
    match_duration: float = 30.0
    max_cycles: int = 1800
    obs_mode: Any = "truth"
    perception: Any = None
    shaping: dict[str, float] = field(
        default_factory=lambda: {"ball_progress": 1.0, "ball_distance": 0.1})
    env_kwargs: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.max_cycles, int) or self.max_cycles < 1:
            raise ValueError(f"max_cycles must be a whole number >= 1, got {self.max_cycles!r}"
                             " (it bounds the evaluation's rollouts)")
        if "info_mode" in self.env_kwargs:
            raise ValueError("env_kwargs: the task makes the match with info_mode='flat' "
                             "(TorchRL's wrapper needs numbers under fixed keys)")


def match_config(config: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """The full configuration (a plain dict, as BenchMARL keeps a task's) from some of
    :class:`MatchTaskConfig`'s fields, the others at their defaults.

    Raises:
        TypeError: for a key that is no field of :class:`MatchTaskConfig`.
        ValueError: for ``max_cycles`` below 1 or an ``info_mode`` in ``env_kwargs``.
    """
    config = dict(config or {})
    unknown = sorted(set(config) - {f.name for f in fields(MatchTaskConfig)})
    if unknown:
        raise TypeError(f"SoccerTask.MATCH takes no {', '.join(unknown)}: its configuration "
                        f"is {', '.join(f.name for f in fields(MatchTaskConfig))} (and "
                        "env_kwargs for any other keyword of soccer_env.parallel_env)")
    return asdict(MatchTaskConfig(**config))


def match_env_kwargs(config: Mapping[str, Any]) -> dict[str, Any]:
    """The keyword arguments of :func:`soccer_env.parallel_env` for a task's ``config``
    (``info_mode="flat"`` added)."""
    kwargs = {k: v for k, v in config.items() if k != "env_kwargs" and v is not None}
    return {**kwargs, **config.get("env_kwargs", {}), "info_mode": "flat"}


def _wrapped_match(config: Mapping[str, Any], seed: int | None, device: Any) -> Any:
    """The match of ``config`` in TorchRL's ``PettingZooWrapper`` (agents grouped by team,
    no masks: the robots play the whole match), seeded with ``seed``."""
    from torchrl.envs import PettingZooWrapper

    return PettingZooWrapper(soccer_env.parallel_env(**match_env_kwargs(config)),
                             use_mask=False, categorical_actions=True, seed=seed,
                             device=device, return_state=False)


def _match_class() -> type:
    """``SoccerMatchClass``, on BenchMARL's PettingZoo task class (whose specs and group map
    fit the wrapped match)."""
    from benchmarl.environments import PettingZooClass

    class SoccerMatchClass(PettingZooClass):
        """BenchMARL's task class of the match (``SoccerTask.MATCH.get_task()`` makes one)."""

        def get_env_fun(self, num_envs: int, continuous_actions: bool, seed: int | None,
                        device: Any) -> Any:
            """A function making the wrapped match; BenchMARL steps ``num_envs`` of them in a
            ``SerialEnv``. Each match it makes takes the next seed from ``seed`` on."""
            config, made = dict(self.config), [0]

            def make() -> Any:
                index, made[0] = made[0], made[0] + 1
                return _wrapped_match(config, None if seed is None else seed + index, device)

            return make

        def supports_continuous_actions(self) -> bool:
            """The robots' actions are continuous."""
            return True

        def supports_discrete_actions(self) -> bool:
            """No discrete actions."""
            return False

        def has_render(self, env: Any) -> bool:
            """No frames in evaluation: they need the render extra and ``render_mode``."""
            return False

        def max_steps(self, env: Any) -> int:
            """An evaluation rollout's length: ``max_cycles``."""
            return int(self.config["max_cycles"])

        @staticmethod
        def env_name() -> str:
            """``"soccer_env"``."""
            return ENV_NAME

        @staticmethod
        def log_info(batch: Any) -> dict[str, float]:
            """Goals in a collected batch, per 1000 parallel steps (``match/goals_per_1k``)."""
            event = batch.get(("next", "blue", "info", "event"), None)
            if event is None:
                event = batch.get(("next", "yellow", "info", "event"))
            steps = math.prod(event.shape[:-1])
            goals = float((event[..., 0] == EVENT_CODES["goal"]).sum())
            return {"match/goals_per_1k": 1000.0 * goals / max(steps, 1)}

    return SoccerMatchClass


def _task_enum(match_class: type) -> type:
    """``SoccerTask``, on BenchMARL's ``Task`` enum, its member's class ``match_class``."""
    from benchmarl.environments import Task

    class SoccerTask(Task):
        """BenchMARL's task enum of soccer_env: ``MATCH``, configured by
        :class:`MatchTaskConfig`."""

        MATCH = None

        @staticmethod
        def associated_class() -> type:
            """:data:`SoccerMatchClass`."""
            return match_class

        def get_task(self, config: Mapping[str, Any] | None = None) -> Any:
            """The task with ``config`` (some of :class:`MatchTaskConfig`'s fields; the rest
            at their defaults)."""
            return match_class(name=self.name, config=match_config(config))

        def get_from_yaml(self, path: str | None = None) -> Any:
            """The task with the configuration of the YAML file ``path`` (None: the
            defaults), as BenchMARL's own tasks load theirs."""
            if path is None:
                return self.get_task()
            from omegaconf import OmegaConf

            return self.get_task(OmegaConf.to_container(OmegaConf.load(path), resolve=True))

    return SoccerTask


def _task_classes() -> dict[str, type]:
    """``SoccerMatchClass`` and ``SoccerTask``, named for pickles (BenchMARL's config.pkl),
    which find a class by its module and qualified name."""
    match_class = _match_class()
    made = {"SoccerMatchClass": match_class, "SoccerTask": _task_enum(match_class)}
    for name, cls in made.items():
        cls.__qualname__ = name
    return made


def __getattr__(name: str) -> Any:
    """``SoccerTask`` and ``SoccerMatchClass``, made on first use.

    Raises:
        ModuleNotFoundError: without BenchMARL, naming the extra that installs it.
    """
    if name not in ("SoccerTask", "SoccerMatchClass"):
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    try:
        made = _task_classes()
    except ModuleNotFoundError as err:
        missing = (err.name or "benchmarl").split(".")[0]
        raise ModuleNotFoundError(
            f"agents.runs.benchmarl.{name} needs BenchMARL: pip install torch==2.13.0 && "
            f"pip install 'soccer-env[benchmarl]' (missing: {missing})", name=missing) from err
    globals().update(made)
    return made[name]
