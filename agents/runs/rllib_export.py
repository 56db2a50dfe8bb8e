"""RLlib policies as numpy policies: :func:`export_numpy` copies a module of a run's checkpoint
(:mod:`agents.runs.rllib_runs`) into the package's numpy format
(:class:`~agents.policies.numpy_policy.NumpyPolicy`), which ``soccer-env eval``, the matches
and the ratings read; every run writes its learning module so as ``final_policy.npz``.

What is copied is the deterministic action of RLlib's default PPO module (``model_config``'s
``fcnet_hiddens`` and activation, tanh or relu, with a separate or shared critic): the actor's
layers (its encoder, then the ``pi`` head), the mean of its Gaussian (the first half of the
head's outputs), mapped onto the action box as RLlib's env runners map it (``normalize_actions``,
RLlib's default: ``low + (mean + 1) (high - low) / 2``, folded into the last layer) and clipped
into the box. The observations pass first through the statistics of RLlib's ``MeanStdFilter``
(``normalize_obs``): ``clip((x - mean) / (std + 1e-6), -10, 10)``, which the numpy policy's
``normalize`` computes with the variance ``(std + 1e-6)**2`` and epsilon 0.

The match's runs keep one set of observation statistics per module
(:class:`agents.runs.rllib_filters.MeanStdFilter`), so every module is copied exactly, as is
the keeper. Checkpoints of version 0.1.0 kept one set per robot: a module that played several
robots there is copied with its robots' statistics pooled (their counts, means and spreads,
:func:`~agents.runs.rllib_filters.pooled_statistics`), which normalises each robot's
observation as RLlib did only as far as the robots' statistics agree. The meta records whose
statistics the policy has (``"statistics_of"``: the module, or the robots pooled).

A checkpoint is a pickle: :func:`export_numpy` loads only checkpoints that
:func:`~agents.runs.rllib_checkpoints.check_checkpoint` finds safe (the user's own runs) unless
``trust``. Nothing here starts Ray.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from agents.policies.numpy_policy import NumpyPolicy
from agents.policies.wrappers import wrap_actions
from agents.runs.folders import read_run_config, run_folder
from agents.runs.rllib import POLICY_MAPPINGS, learner_module
from agents.runs.rllib_checkpoints import (
    FINAL_CHECKPOINT,
    check_checkpoint,
    is_rllib_checkpoint,
)
from agents.runs.rllib_filters import pooled_statistics
from agents.scripted import TEAMS
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID

__all__ = ["FINAL_POLICY", "KEEPER_MODULE", "export_numpy", "module_policy",
           "observation_statistics", "module_agents"]

#: The numpy policy a run writes into its folder.
FINAL_POLICY = "final_policy.npz"
#: The keeper's module (RLlib's default module id).
KEEPER_MODULE = "default_policy"
#: RLlib's ``MeanStdFilter`` connector, by its name in a checkpoint.
_FILTER = "MeanStdFilter"
#: A stand-in for "no clipping" where RLlib's filter has none (a numpy policy clips).
_NO_CLIP = float(np.finfo(np.float32).max)


def _leaves(module: Any) -> list[Any]:
    """The layers of a torch module (its modules without children), in order."""
    return [m for m in module.modules() if not list(m.children())]


def module_policy(module: Any, normalize: tuple | None = None,
                  meta: dict[str, Any] | None = None, action_map: dict[str, Any] | None = None,
                  frame_stack: int = 1) -> NumpyPolicy:
    """The deterministic actor of RLlib PPO module ``module`` (see the module docstring) as
    a :class:`~agents.policies.numpy_policy.NumpyPolicy`, with ``normalize`` (from
    :func:`observation_statistics`), ``meta``, the keeper's ``action_map`` and
    ``frame_stack`` (as :class:`~agents.policies.numpy_policy.NumpyPolicy` takes them).

    ``ValueError`` for a module other than a PPO default module of an MLP on a flat ``Box``
    observation with a bounded ``Box`` action (layers other than linear, tanh and relu, a
    recurrent or attention network, ...)."""
    from torch import nn

    space = getattr(module, "action_space", None)
    if not isinstance(space, gym.spaces.Box) or len(space.shape) != 1 \
            or not (np.all(np.isfinite(space.low)) and np.all(np.isfinite(space.high))):
        raise ValueError(f"a module with a bounded Box action is needed, got {space}")
    encoder = getattr(module, "encoder", None)
    actor = getattr(encoder, "actor_encoder", None)
    if actor is None:  # a critic that shares the actor's layers (vf_share_layers)
        actor = getattr(encoder, "encoder", None)
    head = getattr(module, "pi", None)
    if actor is None or head is None:
        raise ValueError(f"cannot copy a {type(module).__name__} into numpy: not RLlib's "
                         "default PPO module (an encoder and a 'pi' head)")
    layers: list[tuple] = []
    for m in _leaves(actor) + _leaves(head):
        if isinstance(m, nn.Linear):
            layers.append(("linear", m.weight.detach().cpu().numpy().astype(np.float64),
                           m.bias.detach().cpu().numpy().astype(np.float64)))
        elif isinstance(m, (nn.Tanh, nn.ReLU)):
            layers.append((type(m).__name__.lower(),))
        elif not isinstance(m, nn.Identity):
            raise ValueError(f"cannot copy a {type(m).__name__} layer of "
                             f"{type(module).__name__} into numpy (linear, tanh and relu only)")
    if not layers or layers[-1][0] != "linear":
        raise ValueError("the actor's head does not end in a linear layer")
    n = space.shape[0]
    _, w, b = layers[-1]
    if w.shape[0] not in (n, 2 * n):
        raise ValueError(f"the head gives {w.shape[0]} outputs for {n} actions (expected the "
                         f"Gaussian's {2 * n}: mean and log-std, or the mean alone)")
    # The mean, mapped from [-1, 1] onto the box as RLlib's env runners do.
    scale = (space.high.astype(np.float64) - space.low) / 2.0
    shift = (space.high.astype(np.float64) + space.low) / 2.0
    layers[-1] = ("linear", w[:n] * scale[:, None], b[:n] * scale + shift)
    return NumpyPolicy(layers, "clip", space.low, space.high, meta, normalize, action_map,
                       frame_stack)


def observation_statistics(filter_state: dict[Any, dict[str, Any]], keys: list[Any]
                           ) -> tuple[np.ndarray, np.ndarray, float, float]:
    """The ``normalize`` of a numpy policy (``(mean, var, clip, epsilon)``) that normalises
    as RLlib's ``MeanStdFilter`` of state ``filter_state`` does with the statistics under
    ``keys`` (a module id, the keeper's None, or agent ids whose statistics are pooled, see
    the module docstring)."""
    from ray.rllib.utils.numpy import SMALL_NUMBER

    missing = [k for k in keys if k not in filter_state]
    if missing or not keys:
        raise ValueError(f"the observation statistics hold {list(filter_state)}, not "
                         f"{missing or keys}")
    states = [filter_state[k] for k in keys]
    first = states[0]
    stats = pooled_statistics(states)
    mean = np.asarray(stats.mean, dtype=np.float64)
    if not first["de_mean_to_zero"]:
        mean = np.zeros_like(mean)
    # RLlib divides by (std + SMALL_NUMBER) in float32: its square is the variance whose
    # square root (epsilon 0) a numpy policy divides by.
    std = np.asarray(stats.std + SMALL_NUMBER, dtype=np.float64)
    var = std ** 2 if first["de_std_to_one"] else np.ones_like(mean)
    clip = first["clip_by_value"]
    return mean, var, float(clip) if clip else _NO_CLIP, 0.0


def module_agents(settings: dict[str, Any], module_id: str, agents: list[str]) -> list[str]:
    """The match's ``agents`` (of the observation statistics) that module ``module_id``
    plays under the run's policy mapping (``settings``: its ``config.json``)."""
    teams = {t: [a for a in agents if a.split("_")[0] == t] for t in TEAMS}
    policies = POLICY_MAPPINGS[settings.get("policy_mapping", "shared")](
        teams, settings.get("learner", "blue"))
    return [a for a in agents if policies.agent_module.get(a) == module_id]


def _run_settings(checkpoint: Path) -> dict[str, Any]:
    """The ``config.json`` of the RLlib run of ``checkpoint``."""
    config = run_folder(checkpoint) / "config.json"
    try:
        settings = read_run_config(config)
    except (OSError, ValueError) as err:
        raise ValueError(f"{checkpoint}: no readable config.json of its run in "
                         f"{config.parent} ({err}): not a checkpoint of soccer-env train "
                         "--backend rllib") from None
    if settings.get("backend") != "rllib" or settings.get("env_id") not in (GOALKEEPER_ID,
                                                                            MATCH_ID):
        raise ValueError(f"{config} is not the configuration of an RLlib run")
    return settings


def _action_map(settings: dict[str, Any]) -> dict[str, Any] | None:
    """The keeper learner's action map as a numpy policy stores it (None: native)."""
    actions = settings.get("actions", "native")
    if settings["env_id"] != GOALKEEPER_ID or actions == "native":
        return None
    env = wrap_actions(gym.make(GOALKEEPER_ID, **settings.get("env_kwargs", {})), actions)
    params = getattr(env, "params", None)
    env.close()
    return {"kind": actions, "params": params or {}}


def _filter_state(checkpoint: Path) -> dict[Any, dict[str, Any]] | None:
    """The state of the checkpoint's ``MeanStdFilter`` (None without one)."""
    from ray.rllib.connectors.connector_pipeline_v2 import ConnectorPipelineV2

    folder = checkpoint / "env_runner" / "env_to_module_connector"
    if not folder.is_dir():
        return None
    return ConnectorPipelineV2.from_checkpoint(str(folder)).get_state().get(_FILTER)


def export_numpy(source: str | os.PathLike, path: str | os.PathLike | None = None, *,
                 module_id: str | None = None, trust: bool = False) -> NumpyPolicy:
    """The numpy policy of module ``module_id`` of an RLlib checkpoint of a run (``source``:
    the checkpoint folder, or the run folder for its ``final_checkpoint``), saved to ``path``
    if given (``.npz``). The module defaults to the learner's: the keeper's, ``"shared"``,
    ``"main"`` (self-play, fixed opponent) or the ``learner`` team's (per-team).

    The checkpoint is loaded only if :func:`~agents.runs.rllib_checkpoints.check_checkpoint`
    finds it safe, or ``trust``. ``ValueError`` for a folder that is no checkpoint of an
    RLlib run, an unknown module, or a network that numpy cannot copy
    (:func:`module_policy`)."""
    from ray.rllib.core.rl_module.rl_module import RLModule

    folder = Path(source)
    if not is_rllib_checkpoint(folder) and is_rllib_checkpoint(folder / FINAL_CHECKPOINT):
        folder = folder / FINAL_CHECKPOINT
    info = check_checkpoint(folder, trust)
    settings = _run_settings(folder)
    keeper = settings["env_id"] == GOALKEEPER_ID
    if module_id is None:
        module_id = KEEPER_MODULE if keeper else learner_module(
            settings.get("policy_mapping", "shared"), settings.get("learner", "blue"))
    modules = folder / "learner_group" / "learner" / "rl_module"
    known = sorted(p.name for p in modules.iterdir() if p.is_dir()) if modules.is_dir() else []
    if module_id not in known:
        raise ValueError(f"{folder} has no module {module_id!r} (it has {known})")
    module = RLModule.from_checkpoint(str(modules / module_id))
    state = _filter_state(folder) if settings.get("normalize_obs", True) else None
    keys = None
    if state is not None:  # the keeper's; the module's; its agents' (version 0.1.0)
        keys = [None] if keeper else [module_id] if module_id in state else module_agents(
            settings, module_id, sorted(state))
    meta = {"backend": "rllib", "algorithm": "PPO", "module": module_id,
            "steps": info.get("steps"), "statistics_of": keys,
            **{k: settings.get(k) for k in ("env_id", "env_kwargs", "actions", "frame_stack",
                                            "policy_mapping", "learner", "opponent",
                                            "hyperparams", "seed", "total_steps")}}
    normalize = None if state is None else observation_statistics(state, keys)
    policy = module_policy(module, normalize, meta, _action_map(settings),
                           int(settings.get("frame_stack", 1)))
    if path is not None:
        policy.save(path)
    return policy
