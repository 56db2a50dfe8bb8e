"""The policy mappings, callbacks and PPO configuration of the RLlib backend (Ray's
reinforcement-learning library), which samples on any number of machines of a Ray cluster.

The environments are those of :mod:`agents.runs.rllib_envs` (their names are importable from
here too): :class:`~agents.runs.rllib_envs.KeeperEnv` for ``"soccer_env/Goalkeeper-v0"`` and
:class:`~agents.runs.rllib_envs.MatchEnv` for ``"soccer_env/Match-v0"``. A configuration names
the class, so its checkpoints restore in a fresh process without registering anything.

The match's agents map to RLlib modules (networks) in one of :data:`POLICY_MAPPINGS`:

* ``"shared"``: one module, ``"shared"``, plays every robot of both teams (parameter sharing;
  the observations are in each team's own frame, so one policy can play either side);
* ``"per-team"``: modules ``"blue"`` and ``"yellow"``, each playing its team's robots and both
  learning;
* ``"self-play"``: module ``"main"`` learns and plays the ``learner`` team; the other team is
  played by ``"opponent"``, a frozen copy of ``"main"`` (not trained) whose weights
  :class:`SelfPlayCallback` copies from the learner when training starts and every
  ``self_play_every`` environment steps, after RLlib's own self-play example
  (``rllib/examples/multi_agent/self_play_*``; :func:`copy_module_weights` says where it
  differs);
* ``"fixed-opponent"``: module ``"main"`` learns and plays the ``learner`` team; the
  environment itself plays the other team with a fixed policy, ``opponent`` (the scripted
  team, idle robots or a numpy policy, see :func:`~agents.runs.rllib_envs.opponent_team`),
  and RLlib sees the learner's robots only.

:func:`ppo_config` puts it together (RLlib's new API stack)::

    from agents.runs.rllib import ppo_config

    config = ppo_config(MATCH_ID, {"blue": 2, "yellow": 2, "max_cycles": 600},
                        policy_mapping="self-play", num_env_runners=4)
    algo = config.build_algo()
    for _ in range(100):
        result = algo.train()
    algo.save_to_path("/path/to/checkpoint")

:mod:`agents.runs.rllib_runs` trains into a run folder (``soccer-env train --backend rllib``).

Every env runner also reports how many environment steps it sampled under the id of the Ray
node it runs on (:class:`NodeStepsCallback`: ``result["env_runners"]["steps_by_node"]``), and
the keeper's save rate or the match's goals (:class:`SoccerMetricsCallback`).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from typing import Any

from ray.rllib.algorithms.ppo import PPOConfig
from ray.rllib.callbacks.callbacks import RLlibCallback
from ray.rllib.connectors.env_to_module.mean_std_filter import (
    MeanStdFilter as RLlibMeanStdFilter,
)

from agents.policies.numpy_policy import NumpyPolicy
from agents.runs.rllib_envs import (
    ENV_CLASSES,
    ENV_IDS,
    KEEPER_INFOS,
    MATCH_INFOS,
    OPPONENT_NAMES,
    KeeperEnv,
    MatchEnv,
    MatchMultiAgentEnv,
    keeper_env,
    match_env,
    match_kwargs,
    register_envs,
)
from agents.runs.rllib_filters import MeanStdFilter
from agents.scripted import TEAMS
from estimators.registry import Registry
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID

__all__ = ["ENV_IDS", "ENV_CLASSES", "KEEPER_INFOS", "MATCH_INFOS",
           "POLICY_MAPPINGS", "DEFAULT_HYPERPARAMS", "register_envs", "keeper_env", "match_env",
           "KeeperEnv", "MatchEnv", "MatchMultiAgentEnv", "MatchPolicies", "match_policies",
           "ppo_config", "fixed_opponent_config", "learner_module", "OPPONENT_NAMES",
           "MeanStdFilter",
           "apply_hyperparams", "hyperparameter_names", "SelfPlayCallback", "self_play_callback",
           "NodeStepsCallback", "SoccerMetricsCallback", "copy_module_weights"]

#: PPO settings over RLlib's defaults, chosen as stable-baselines3's PPO defaults that
#: :mod:`agents.runs.training` uses (16 environments x 256 steps per update, minibatches of 512,
#: 10 epochs, two hidden layers of 64 tanh units, separate actor and critic networks).
#: ``model_config`` entries merge key by key with given ones.
DEFAULT_HYPERPARAMS: dict[str, Any] = {
    "lr": 3e-4, "gamma": 0.99, "lambda_": 0.95, "clip_param": 0.2, "num_epochs": 10,
    "minibatch_size": 512, "train_batch_size_per_learner": 4096, "entropy_coeff": 0.0,
    "model_config": {"fcnet_hiddens": [64, 64], "fcnet_activation": "tanh",
                     "vf_share_layers": False},
}

#: The options that the configuration's other arguments set, refused as hyperparameters.
_RESERVED = {"env": "env_id", "env_config": "env_config", "policies": "policy_mapping",
             "policy_mapping_fn": "policy_mapping", "policies_to_train": "policy_mapping",
             "num_env_runners": "num_env_runners", "num_rollout_workers": "num_env_runners",
             "num_envs_per_env_runner": "n_envs", "num_envs_per_worker": "n_envs",
             "seed": "seed", "callbacks_class": "the callbacks of agents.runs.rllib",
             "env_to_module_connector": "normalize_obs"}
#: The configuration methods whose keyword arguments are hyperparameters.
_HP_METHODS = ("training", "env_runners", "learners", "reporting", "fault_tolerance",
               "resources")


# ------------------------------------------------------------------------------------------
# Policy mappings
# ------------------------------------------------------------------------------------------

class MatchPolicies:
    """The modules of a policy mapping and which agent each plays (see
    :func:`match_policies`).

    Attributes:
        mapping: the mapping's name (:data:`POLICY_MAPPINGS`).
        modules: the module ids.
        trained: the ids of the modules that learn.
        agent_module: module id of each agent of the match.
    """

    def __init__(self, mapping: str, modules: tuple[str, ...], trained: tuple[str, ...],
                 agent_module: dict[str, str]) -> None:
        self.mapping = mapping
        self.modules = modules
        self.trained = trained
        self.agent_module = agent_module

    def __call__(self, agent_id: str, episode: Any = None, **kwargs: Any) -> str:
        """RLlib's ``policy_mapping_fn``: the module that plays ``agent_id``."""
        return self.agent_module[agent_id]

    def __repr__(self) -> str:
        return (f"MatchPolicies({self.mapping!r}, modules={list(self.modules)}, "
                f"trained={list(self.trained)})")


def _shared(teams: dict[str, list[str]], learner: str) -> MatchPolicies:
    agents = [a for team in TEAMS for a in teams[team]]
    return MatchPolicies("shared", ("shared",), ("shared",), dict.fromkeys(agents, "shared"))


def _per_team(teams: dict[str, list[str]], learner: str) -> MatchPolicies:
    present = tuple(t for t in TEAMS if teams[t])
    return MatchPolicies("per-team", present, present,
                         {a: t for t in present for a in teams[t]})


def _self_play(teams: dict[str, list[str]], learner: str) -> MatchPolicies:
    other = TEAMS[1 - TEAMS.index(learner)]
    if not teams[learner] or not teams[other]:
        raise ValueError(f"self-play needs robots in both teams, got blue={len(teams['blue'])}, "
                         f"yellow={len(teams['yellow'])}")
    agent_module = {a: ("main" if t == learner else "opponent") for t in TEAMS for a in teams[t]}
    return MatchPolicies("self-play", ("main", "opponent"), ("main",), agent_module)


def _fixed_opponent(teams: dict[str, list[str]], learner: str) -> MatchPolicies:
    if not teams[learner]:
        raise ValueError(f"the learner team {learner!r} has no robots")
    return MatchPolicies("fixed-opponent", ("main",), ("main",),
                         dict.fromkeys(teams[learner], "main"))


#: The match's policy mappings (name -> factory of its :class:`MatchPolicies`).
POLICY_MAPPINGS: Registry[Callable[[dict[str, list[str]], str], MatchPolicies]] = Registry(
    "policy mapping", [
        ("shared", _shared, "one module, 'shared', plays every robot of both teams and learns "
                            "from all of them (parameter sharing)"),
        ("per-team", _per_team, "modules 'blue' and 'yellow' play their teams' robots; both "
                                "learn"),
        ("self-play", _self_play, "module 'main' learns and plays the learner team; "
                                  "'opponent', a frozen copy of 'main' refreshed every "
                                  "self_play_every steps, plays the other team"),
        ("fixed-opponent", _fixed_opponent, "module 'main' learns and plays the learner team; "
                                            "the environment plays the other team with a "
                                            "fixed policy (scripted, idle or a numpy policy)"),
    ])


def learner_module(mapping: str, learner: str = "blue") -> str:
    """The module of policy mapping ``mapping`` that plays team ``learner`` (and learns):
    ``"shared"``, the team's own under ``"per-team"``, else ``"main"``."""
    POLICY_MAPPINGS.check(mapping)
    if mapping == "shared":
        return "shared"
    return learner if mapping == "per-team" else "main"


def match_policies(env_config: Mapping[str, Any] | None = None, mapping: str = "shared",
                   learner: str = "blue") -> MatchPolicies:
    """The modules of policy mapping ``mapping`` (:data:`POLICY_MAPPINGS`) for the match of
    ``env_config`` (keyword arguments of :func:`soccer_env.parallel_env`; the fixed opponent's
    entries, :data:`~agents.runs.rllib_envs.MATCH_OPTIONS`, are left aside), ``learner`` being
    the team that the learning module of ``"self-play"`` and ``"fixed-opponent"`` plays.

    A module that plays both teams (``"shared"``, and ``"self-play"`` whose copy plays the
    other team) needs teams of the same size and robots (``ValueError`` otherwise): an
    observation entry must mean the same for every robot it reads."""
    import soccer_env

    POLICY_MAPPINGS.check(mapping)
    if learner not in TEAMS:
        raise ValueError(f"learner must be 'blue' or 'yellow', got {learner!r}")
    env = soccer_env.parallel_env(**match_kwargs(env_config))
    try:
        teams = {t: [a for a in env.possible_agents if a.split("_")[0] == t] for t in TEAMS}
        if mapping in ("shared", "self-play") and teams["blue"] and teams["yellow"]:
            blue, yellow = teams["blue"][0], teams["yellow"][0]
            kinds = [type(spec).__name__ for spec in env.team_specs]
            same = (len(teams["blue"]) == len(teams["yellow"]) and kinds[0] == kinds[1]
                    and env.observation_space(blue) == env.observation_space(yellow)
                    and env.action_space(blue) == env.action_space(yellow))
            if not same:
                raise ValueError(
                    f"policy mapping {mapping!r} has one network play both teams, which needs "
                    f"teams of equal size and robots, got blue={len(teams['blue'])} "
                    f"({kinds[0]}), yellow={len(teams['yellow'])} ({kinds[1]}) with "
                    f"observations of {env.observation_space(blue).shape} and "
                    f"{env.observation_space(yellow).shape}; use 'per-team'")
    finally:
        env.close()
    return POLICY_MAPPINGS[mapping](teams, learner)


# ------------------------------------------------------------------------------------------
# Callbacks
# ------------------------------------------------------------------------------------------

def _module_state(algorithm: Any, module_id: str, inference_only: bool = False) -> Any:
    state = algorithm.learner_group.get_state(components=f"learner/rl_module/{module_id}",
                                              inference_only=inference_only)
    return state["learner"]["rl_module"][module_id]


def copy_module_weights(algorithm: Any, source: str, target: str) -> None:
    """Copy module ``source``'s weights into module ``target`` in the learners and on every
    env runner, before this returns.

    RLlib's self-play example copies with ``Algorithm.set_state``, whose weight sync the env
    runners ignore here (Ray 2.60): an env runner takes weights only with a newer
    ``weights_seq_no`` than its own, and a copy does not advance the learner's, so the runners
    would play the old opponent until the next training step's sync. The copy is therefore
    set on every env runner directly (their inference-only part)."""
    weights = _module_state(algorithm, source)
    algorithm.learner_group.set_state({"learner": {"rl_module": {target: weights}}})
    inference = _module_state(algorithm, target, inference_only=True)

    def put(runner: Any) -> None:
        runner.module[target].set_state(inference)

    for group in (algorithm.env_runner_group, getattr(algorithm, "eval_env_runner_group", None)):
        if group is not None:
            group.foreach_env_runner(put, local_env_runner=True)


class SelfPlayCallback(RLlibCallback):
    """Self-play: copy the learning module ``"main"`` into the frozen ``"opponent"`` when
    training starts and whenever the sampled environment steps pass a multiple of
    :attr:`update_every` (:func:`self_play_callback` makes the class with its period).

    ``result["self_play_updates"]`` counts the copies of this run (since the algorithm was
    built)."""

    #: Environment steps between copies.
    update_every: int = 100_000

    def __init__(self) -> None:
        super().__init__()
        self.updates = 0

    def on_algorithm_init(self, *, algorithm: Any, metrics_logger: Any = None,
                          **kwargs: Any) -> None:
        copy_module_weights(algorithm, "main", "opponent")
        self.updates += 1

    def on_train_result(self, *, algorithm: Any, metrics_logger: Any = None, result: dict,
                        **kwargs: Any) -> None:
        steps = int(result.get("num_env_steps_sampled_lifetime", 0))
        new = int(result.get("env_runners", {}).get("num_env_steps_sampled", 0))
        if steps // self.update_every > (steps - new) // self.update_every:
            copy_module_weights(algorithm, "main", "opponent")
            self.updates += 1
        result["self_play_updates"] = self.updates


def self_play_callback(update_every: int) -> type[SelfPlayCallback]:
    """:class:`SelfPlayCallback` copying every ``update_every`` environment steps (RLlib
    builds callbacks from their class, without arguments)."""
    if isinstance(update_every, bool) or not isinstance(update_every, int) or update_every < 1:
        raise ValueError(f"self_play_every must be an integer >= 1, got {update_every!r}")
    return type("SelfPlayCallback", (SelfPlayCallback,), {"update_every": update_every,
                                                          "__module__": __name__})


class NodeStepsCallback(RLlibCallback):
    """Each env runner logs the environment steps it sampled under the id of the Ray node it
    runs on: ``result["env_runners"]["steps_by_node"]`` maps node ids (hex, as
    ``ray.nodes()`` and ``ray.get_runtime_context().get_node_id()`` give them) to the steps
    sampled there so far, summed over the runners of a node. The sums are part of the
    algorithm's metrics, so a restored checkpoint carries those of the nodes of its run
    (node ids are new with every Ray session)."""

    def on_sample_end(self, *, env_runner: Any = None, metrics_logger: Any = None,
                      samples: Any = None, **kwargs: Any) -> None:
        import ray

        if metrics_logger is None or not samples:
            return
        steps = sum(len(episode) for episode in samples)
        node = ray.get_runtime_context().get_node_id()
        metrics_logger.log_value(("steps_by_node", node), steps, reduce="lifetime_sum")


class SoccerMetricsCallback(RLlibCallback):
    """Episode metrics in ``result["env_runners"]``: for the keeper ``save_rate`` (the share of
    the last 100 episodes that ended saved; a time limit counts as not saved, as
    :func:`~agents.runs.evaluation.evaluate` counts it); for the match ``blue_goals`` and
    ``yellow_goals`` (mean over the last 100 matches)."""

    def on_episode_end(self, *, episode: Any, metrics_logger: Any = None, **kwargs: Any
                       ) -> None:
        if metrics_logger is None:
            return
        info = episode.get_infos(-1)
        if "outcome" in info:  # the keeper
            saved = bool(episode.is_terminated) and info["outcome"] not in (None, "goal")
            metrics_logger.log_value("save_rate", float(saved), reduce="mean", window=100)
            return
        scores = [i["score"] for i in info.values() if isinstance(i, Mapping) and "score" in i]
        if scores:
            for team in TEAMS:
                metrics_logger.log_value(f"{team}_goals", float(scores[0][team]),
                                         reduce="mean", window=100)


# ------------------------------------------------------------------------------------------
# Configuration
# ------------------------------------------------------------------------------------------

def hyperparameter_names() -> dict[str, str]:
    """The names :func:`apply_hyperparams` takes, each with the ``PPOConfig`` method that
    sets it (``"training"``, ``"env_runners"``, ...; ``"rl_module"`` for ``model_config``)."""
    import inspect

    names: dict[str, str] = {}
    for method in _HP_METHODS:
        # PPOConfig.training takes its own arguments and passes the rest (**kwargs) on to
        # AlgorithmConfig.training: every class's signature counts.
        for cls in PPOConfig.__mro__:
            if method not in vars(cls):
                continue
            for name, param in inspect.signature(vars(cls)[method]).parameters.items():
                if (name not in _RESERVED and not name.startswith("_") and name != "self"
                        and param.kind is not param.VAR_KEYWORD):
                    names.setdefault(name, method)
    names["model_config"] = "rl_module"
    return names


def _merged(hyperparams: Mapping[str, Any] | None) -> dict[str, Any]:
    given = dict(hyperparams or {})
    merged = {**DEFAULT_HYPERPARAMS, **given}
    if "model_config" in given:
        if not isinstance(given["model_config"], Mapping):
            raise ValueError(f"model_config must be a mapping of RLlib's DefaultModelConfig "
                             f"fields, got {given['model_config']!r}")
        merged["model_config"] = {**DEFAULT_HYPERPARAMS["model_config"],
                                  **given["model_config"]}
    return merged


def apply_hyperparams(config: PPOConfig, hyperparams: Mapping[str, Any] | None) -> PPOConfig:
    """Set ``hyperparams`` over :data:`DEFAULT_HYPERPARAMS` on ``config``, each through the
    ``PPOConfig`` method that takes it (:func:`hyperparameter_names`: ``lr``, ``gamma``,
    ``train_batch_size_per_learner``, ``minibatch_size``, ``num_epochs``,
    ``rollout_fragment_length``, ``num_learners``, ``num_cpus_per_env_runner``, ...;
    ``model_config`` a mapping of RLlib's ``DefaultModelConfig`` fields). Names that another
    argument of :func:`ppo_config` sets, and unknown names, raise ``ValueError``."""
    given = dict(hyperparams or {})
    reserved = sorted(set(given) & set(_RESERVED))
    if reserved:
        raise ValueError("hyperparameter(s) " + ", ".join(
            f"{k} (set by {_RESERVED[k]})" for k in reserved) + " cannot be set directly")
    names = hyperparameter_names()
    unknown = sorted(set(given) - set(names))
    if unknown:
        raise ValueError(f"unknown RLlib PPO hyperparameter(s) {unknown}: they must be "
                         f"arguments of PPOConfig.{'(), .'.join(_HP_METHODS)}() or "
                         "model_config, e.g. lr, gamma, train_batch_size_per_learner, "
                         "minibatch_size, num_epochs, entropy_coeff, num_learners")
    by_method: dict[str, dict[str, Any]] = {}
    for name, value in _merged(given).items():
        by_method.setdefault(names[name], {})[name] = value
    for method, kwargs in by_method.items():
        getattr(config, method)(**kwargs)
    return config


def _normalizer(policies: MatchPolicies | None) -> Callable[..., Any]:
    """The env-to-module connector factory of ``normalize_obs``: RLlib's ``MeanStdFilter``
    for the keeper, :class:`MeanStdFilter` (statistics per module) for the match."""
    agent_module = None if policies is None else dict(policies.agent_module)

    def make(env: Any = None, spaces: Any = None, device: Any = None) -> Any:
        if agent_module is None:
            return RLlibMeanStdFilter(multi_agent=False)
        return MeanStdFilter(agent_module=agent_module)

    return make


def fixed_opponent_config(env_config: Mapping[str, Any] | None, learner: str,
                          opponent: Any) -> dict[str, Any]:
    """The match's ``env_config`` with the fixed ``opponent`` playing the team other than
    ``learner`` (:class:`~agents.runs.rllib_envs.MatchEnv`): ``"scripted"``, ``"idle"``, a
    numpy policy, or the path of its file (``.npz``), which is read here, so that the env
    runners on other machines need no copy of it (the policy travels in ``env_config``).
    ``ValueError`` for any other opponent or a file that is no numpy policy."""
    if isinstance(opponent, (str, os.PathLike)) and os.fspath(opponent).endswith(".npz"):
        opponent = NumpyPolicy.load(opponent)
    elif not (isinstance(opponent, NumpyPolicy) or opponent in OPPONENT_NAMES):
        raise ValueError(f"policy mapping 'fixed-opponent' needs an opponent: one of "
                         f"{list(OPPONENT_NAMES)}, a numpy policy or the path of its file "
                         f"(.npz), got {opponent!r}")
    return {**match_kwargs(env_config), "opponent": opponent, "learner": learner}


def ppo_config(env_id: str = GOALKEEPER_ID, env_config: Mapping[str, Any] | None = None, *,
               policy_mapping: str = "shared", learner: str = "blue", opponent: Any = None,
               num_env_runners: int = 0, n_envs: int = 1, seed: int | None = 0,
               hyperparams: Mapping[str, Any] | None = None, normalize_obs: bool = True,
               self_play_every: int = 100_000) -> PPOConfig:
    """RLlib's PPO (new API stack) on ``env_id`` (:data:`ENV_IDS`), the environment named by
    its class (:data:`~agents.runs.rllib_envs.ENV_CLASSES`).

    Args:
        env_id: ``"soccer_env/Goalkeeper-v0"`` or ``"soccer_env/Match-v0"``.
        env_config: the environment's keyword arguments (see :func:`keeper_env`,
            :class:`MatchEnv`).
        policy_mapping: the match: which module plays which robots
            (:data:`POLICY_MAPPINGS`: ``"shared"``, ``"per-team"``, ``"self-play"``,
            ``"fixed-opponent"``).
        learner: the match under ``"self-play"`` and ``"fixed-opponent"``: the team that the
            learning module plays.
        opponent: the match under ``"fixed-opponent"``: the policy the environment plays
            the other team with (:func:`fixed_opponent_config`).
        num_env_runners: env runners (Ray actors, 1 CPU each by default, placed on any node
            of the cluster); 0 samples in the driver.
        n_envs: environments per env runner.
        seed: seeds the environments, the networks and the sampling (None: unseeded).
        hyperparams: :func:`apply_hyperparams`'s (over :data:`DEFAULT_HYPERPARAMS`).
        normalize_obs: observations pass through RLlib's ``MeanStdFilter`` (running mean and
            standard deviation, merged over the env runners and saved in checkpoints; for the
            match one set per module, :class:`MeanStdFilter`).
        self_play_every: environment steps between copies of ``"main"`` into the frozen
            ``"opponent"`` under ``"self-play"``.

    Every configuration reports the steps by node (:class:`NodeStepsCallback`) and the
    episode metrics of :class:`SoccerMetricsCallback`. ``ValueError`` for a bad argument.
    """
    if env_id not in ENV_IDS:
        raise ValueError(f"env_id must be one of {list(ENV_IDS)}, got {env_id!r}")
    for name, value, low in (("num_env_runners", num_env_runners, 0), ("n_envs", n_envs, 1)):
        if isinstance(value, bool) or not isinstance(value, int) or value < low:
            raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    if (opponent is not None) != (policy_mapping == "fixed-opponent"):
        raise ValueError(f"opponent is for policy mapping 'fixed-opponent' (and needed there), "
                         f"got opponent={opponent!r} with {policy_mapping!r}")
    multi_agent = env_id == MATCH_ID
    env_config = dict(env_config or {})
    if opponent is not None and multi_agent:
        env_config = fixed_opponent_config(env_config, learner, opponent)
    callbacks: list[type[RLlibCallback]] = [NodeStepsCallback, SoccerMetricsCallback]
    policies = match_policies(env_config, policy_mapping, learner) if multi_agent else None
    config = (PPOConfig()
              .environment(ENV_CLASSES[env_id], env_config=env_config)
              .env_runners(num_env_runners=num_env_runners, num_envs_per_env_runner=n_envs,
                           env_to_module_connector=_normalizer(policies)
                           if normalize_obs else None)
              .debugging(seed=seed))
    if policies is not None:
        config.multi_agent(policies=set(policies.modules), policy_mapping_fn=policies,
                           policies_to_train=list(policies.trained))
        if policies.mapping == "self-play":
            callbacks.append(self_play_callback(self_play_every))
    elif policy_mapping != "shared":
        raise ValueError(f"policy_mapping is for {MATCH_ID} (Goalkeeper-v0 has one agent), "
                         f"got {policy_mapping!r}")
    config.callbacks(callbacks_class=callbacks)
    return apply_hyperparams(config, hyperparams)
