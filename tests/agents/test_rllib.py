"""RLlib: the registered environments, the match's policy mappings, signed checkpoints, and
training on a simulated two-node Ray cluster (both nodes sample; checkpoints restore and
training continues). Skipped without Ray (the main suite); ``make test-rllib`` runs it."""

from __future__ import annotations

import json
import time

import numpy as np
import pytest

ray = pytest.importorskip("ray")
pytest.importorskip("ray.rllib")

import torch  # noqa: E402

from agents.policies.files import UnsafeFileError  # noqa: E402
from agents.runs.rllib import (  # noqa: E402
    DEFAULT_HYPERPARAMS,
    KEEPER_INFOS,
    MATCH_INFOS,
    POLICY_MAPPINGS,
    SelfPlayCallback,
    apply_hyperparams,
    copy_module_weights,
    keeper_env,
    match_env,
    match_policies,
    ppo_config,
    self_play_callback,
)
from agents.runs.rllib_runs import (  # noqa: E402
    CHECKPOINT_INFO,
    SIGNATURE_FILE,
    RllibTrainConfig,
    check_checkpoint,
    checkpoint_key_path,
    load_checkpoint,
    save_checkpoint,
    sign_checkpoint,
)
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID  # noqa: E402

#: A match small and short enough for a few training iterations in seconds.
TINY_MATCH = {"blue": 1, "yellow": 1, "max_cycles": 40, "formation_jitter": 0.0}
#: PPO at its smallest: 64-step batches of 2 env runners x 1 environment x 32 steps.
TINY_PPO = {"train_batch_size_per_learner": 64, "minibatch_size": 32, "num_epochs": 1,
            "model_config": {"fcnet_hiddens": [8]}}


@pytest.fixture(autouse=True)
def _own_key(tmp_path_factory, monkeypatch):
    """Checkpoints are signed with a key of this test session, not the user's."""
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path_factory.getbasetemp() / "config"))


# ------------------------------------------------------------------------------------------
# Environments and mappings (no Ray running)
# ------------------------------------------------------------------------------------------

def test_keeper_env_has_the_learner_wrappers_and_small_infos():
    env = keeper_env({"actions": "guard", "frame_stack": 2, "obs_mode": "truth"})
    obs, info = env.reset(seed=0)
    single = keeper_env({}).observation_space.shape[0]
    assert obs.shape == (2 * single,)
    assert env.action_space.shape == (1,)  # a point on the guard line
    _, _, _, _, info = env.step(env.action_space.sample())
    assert set(info) <= set(KEEPER_INFOS) and "outcome" in info
    with pytest.raises(ValueError, match="actions must be one of"):
        keeper_env({"actions": "teleport"})
    with pytest.raises(TypeError, match="unexpected keyword argument"):
        keeper_env({"no_such_option": 1})


def test_match_env_fixes_the_pettingzoo_wrapper():
    from ray.rllib.env.wrappers.pettingzoo_env import ParallelPettingZooEnv

    env = match_env({"blue": 2, "yellow": 2, "max_cycles": 3})
    order = ["blue_0", "blue_1", "yellow_0", "yellow_1"]
    assert env.possible_agents == order and env.agents == order
    obs, infos = env.reset(seed=1)
    assert list(obs) == order and all(set(i) <= set(MATCH_INFOS) for i in infos.values())
    for _ in range(3):
        obs, rewards, terms, truncs, infos = env.step(
            {a: env.action_space[a].sample() for a in obs})
    assert truncs["__all__"] and env.agents == []  # the match is over
    assert all(set(i) == set(MATCH_INFOS) for i in infos.values())
    # render() calls the PettingZoo environment's render() without arguments...
    env.par_env.env.render = lambda: "frame"
    assert env.render() == "frame"
    # ...where RLlib's wrapper passes one, which PettingZoo's render takes no more.
    with pytest.raises(TypeError):
        ParallelPettingZooEnv.render(env)


def test_policy_mappings():
    config = {"blue": 2, "yellow": 2}
    shared = match_policies(config, "shared")
    assert shared.modules == ("shared",) and shared.trained == ("shared",)
    assert {shared(a) for a in ("blue_0", "yellow_1")} == {"shared"}
    per_team = match_policies(config, "per-team")
    assert set(per_team.modules) == set(per_team.trained) == {"blue", "yellow"}
    assert per_team("blue_1") == "blue" and per_team("yellow_0") == "yellow"
    selfplay = match_policies(config, "self-play", learner="yellow")
    assert selfplay.modules == ("main", "opponent") and selfplay.trained == ("main",)
    assert selfplay("yellow_1") == "main" and selfplay("blue_0") == "opponent"
    assert list(POLICY_MAPPINGS) == ["shared", "per-team", "self-play", "fixed-opponent"]
    # One network for both teams needs teams alike; per-team takes any.
    with pytest.raises(ValueError, match="equal size"):
        match_policies({"blue": 2, "yellow": 1}, "shared")
    with pytest.raises(ValueError, match="equal size"):
        match_policies({"blue": 1, "yellow": 1, "robot": {"blue": "ssl",
                                                          "yellow": "humanoid-2012"}},
                       "self-play")
    assert match_policies({"blue": 2, "yellow": 1}, "per-team").modules == ("blue", "yellow")
    assert match_policies({"blue": 1, "yellow": 0}, "per-team").modules == ("blue",)
    with pytest.raises(ValueError, match="both teams"):
        match_policies({"blue": 1, "yellow": 0}, "self-play")
    with pytest.raises(ValueError, match="policy mapping must be one of"):
        match_policies(config, "league")


def test_hyperparameters():
    from ray.rllib.algorithms.ppo import PPOConfig

    config = apply_hyperparams(PPOConfig(), {"lr": 1e-4, "model_config": {"fcnet_hiddens": [32]},
                                             "num_cpus_per_env_runner": 2})
    assert config.lr == 1e-4 and config.num_epochs == DEFAULT_HYPERPARAMS["num_epochs"]
    assert config.model_config["fcnet_hiddens"] == [32]
    assert config.model_config["fcnet_activation"] == "tanh"  # merged with the defaults
    assert config.num_cpus_per_env_runner == 2
    with pytest.raises(ValueError, match="unknown RLlib PPO hyperparameter.*learning_rate"):
        apply_hyperparams(PPOConfig(), {"learning_rate": 1e-4})
    with pytest.raises(ValueError, match="num_env_runners \\(set by num_env_runners\\)"):
        apply_hyperparams(PPOConfig(), {"num_env_runners": 4})
    with pytest.raises(ValueError, match="policy_mapping is for"):
        ppo_config(GOALKEEPER_ID, policy_mapping="per-team")
    with pytest.raises(ValueError, match="unknown RLlib PPO hyperparameter"):
        RllibTrainConfig(hyperparams={"n_steps": 128})
    with pytest.raises(ValueError, match="actions and frame_stack are for"):
        RllibTrainConfig(env_id=MATCH_ID, actions="guard")


def test_the_default_run_and_its_hyperparameters_lie_within_the_resume_limits():
    from pathlib import Path

    from agents.runs.limits import check_saved_settings, resume_options

    saved = {**RllibTrainConfig().to_dict(), "hyperparams": dict(DEFAULT_HYPERPARAMS)}
    check_saved_settings(saved, Path("config.json"))
    assert resume_options(saved) == []


def test_self_play_copies_when_the_steps_pass_a_multiple():
    class Group:
        def __init__(self):
            self.copies = 0

        def get_state(self, components, inference_only=False):
            module = components.rsplit("/", 1)[1]
            return {"learner": {"rl_module": {module: {"w": 1}}}}

        def set_state(self, state):
            assert state == {"learner": {"rl_module": {"opponent": {"w": 1}}}}
            self.copies += 1

        def foreach_env_runner(self, func, local_env_runner):
            pass

    class Algorithm:
        learner_group = env_runner_group = Group()

        @property
        def copies(self):
            return self.learner_group.copies

    callback = self_play_callback(100)()
    assert issubclass(type(callback), SelfPlayCallback) and callback.update_every == 100
    algo = Algorithm()
    callback.on_algorithm_init(algorithm=algo)
    copies = []
    for steps in range(40, 400, 40):  # iterations of 40 steps
        result = {"num_env_steps_sampled_lifetime": steps,
                  "env_runners": {"num_env_steps_sampled": 40}}
        callback.on_train_result(algorithm=algo, result=result)
        copies.append(algo.copies)
    # At the start, then after 120 (passing 100), 200, 320 (passing 300) steps.
    assert copies == [1, 1, 2, 2, 3, 3, 3, 4, 4]
    assert result["self_play_updates"] == 4
    with pytest.raises(ValueError, match="self_play_every must be"):
        self_play_callback(0)


def _fake_checkpoint(folder):
    folder.mkdir(parents=True)
    (folder / "rllib_checkpoint.json").write_text("{}")
    (folder / "learner_group").mkdir()
    (folder / "learner_group" / "state.pkl").write_bytes(b"not really a pickle")
    (folder / CHECKPOINT_INFO).write_text(json.dumps({"steps": 128}))
    return folder


def test_only_own_unchanged_checkpoints_load_without_trust(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "mine"))
    ckpt = _fake_checkpoint(tmp_path / "ckpt")
    with pytest.raises(UnsafeFileError, match="not signed.*--trust"):
        check_checkpoint(ckpt)
    sign_checkpoint(ckpt)
    assert checkpoint_key_path().stat().st_mode & 0o077 == 0  # the key is the user's alone
    assert check_checkpoint(ckpt)["steps"] == 128
    (ckpt / "learner_group" / "state.pkl").write_bytes(b"something else")
    with pytest.raises(UnsafeFileError, match="does not match"):
        check_checkpoint(ckpt)
    assert check_checkpoint(ckpt, trust=True)["steps"] == 128
    sign_checkpoint(ckpt)
    (ckpt / "extra.pkl").write_bytes(b"planted")  # a file added since
    with pytest.raises(UnsafeFileError, match="does not match"):
        check_checkpoint(ckpt)
    (ckpt / "extra.pkl").unlink()
    check_checkpoint(ckpt)
    (ckpt / "linked.pkl").symlink_to(tmp_path / "mine")  # a link could point anywhere
    with pytest.raises(ValueError, match="holds a link, linked.pkl"):
        check_checkpoint(ckpt)
    (ckpt / "linked.pkl").unlink()
    # Someone else's key (another account or machine): refused.
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "theirs"))
    with pytest.raises(UnsafeFileError, match="no signing key"):
        check_checkpoint(ckpt)
    sign_checkpoint(_fake_checkpoint(tmp_path / "other"))  # creates their key
    with pytest.raises(UnsafeFileError, match="another key"):
        check_checkpoint(ckpt)
    with pytest.raises(ValueError, match="not an RLlib checkpoint"):
        check_checkpoint(tmp_path)


# ------------------------------------------------------------------------------------------
# A two-node cluster
# ------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def cluster():
    """A Ray cluster of a head and a worker node of 1 CPU each, in this machine's processes
    (``ray.cluster_utils.Cluster``), with this process connected as its driver."""
    from ray.cluster_utils import Cluster

    torch.set_num_threads(1)
    nodes = Cluster(initialize_head=True, head_node_args={
        "num_cpus": 1, "include_dashboard": False, "object_store_memory": 80 * 2**20})
    nodes.add_node(num_cpus=1, object_store_memory=80 * 2**20)
    ray.init(address=nodes.address, logging_level="WARNING")
    nodes.wait_for_nodes()
    yield nodes
    ray.shutdown()
    nodes.shutdown()


def _weights(algo, module_id):
    """The learner's weights of module ``module_id`` (numpy arrays by parameter name)."""
    state = algo.learner_group.get_state(components=f"learner/rl_module/{module_id}")
    return state["learner"]["rl_module"][module_id]


def _same(a, b):
    """Whether the weights ``b`` (all of a module, or those of its inference part) are those
    in ``a``."""
    return set(b) <= set(a) and all(np.array_equal(a[k], np.asarray(b[k])) for k in b)


def _actions(algo, module_id, obs):
    """The module's deterministic action for ``obs`` (the mean of its Gaussian)."""
    module = algo.get_module(module_id)
    with torch.no_grad():
        out = module.forward_inference({"obs": torch.as_tensor(obs)})
    return out["action_dist_inputs"][:, : out["action_dist_inputs"].shape[1] // 2].numpy()


def test_two_nodes_sample_self_play_and_the_checkpoint_restores(cluster, tmp_path):
    node_ids = {n["NodeID"] for n in ray.nodes() if n["Alive"]}
    assert len(node_ids) == 2
    config = ppo_config(MATCH_ID, TINY_MATCH, policy_mapping="self-play", num_env_runners=2,
                        hyperparams=TINY_PPO, self_play_every=10**9)
    algo = config.build_algo()
    try:
        # Each env runner takes the one CPU of a node: one runs on each.
        runner_nodes = algo.env_runner_group.foreach_env_runner(
            lambda runner: ray.get_runtime_context().get_node_id(), local_env_runner=False)
        assert sorted(runner_nodes) == sorted(node_ids)
        # Self-play: the frozen opponent starts as a copy of the learner and stays as it is
        # while the learner trains (its next copy is due after 10**9 steps).
        start = _weights(algo, "main")
        assert _same(start, _weights(algo, "opponent"))
        times = []
        for _ in range(2):
            t0 = time.perf_counter()
            result = algo.train()
            times.append(time.perf_counter() - t0)
        by_node = result["env_runners"]["steps_by_node"]
        assert set(by_node) == node_ids  # both nodes stepped environments...
        assert all(n > 0 for n in by_node.values())
        assert sum(by_node.values()) == result["num_env_steps_sampled_lifetime"] == 128
        print(f"two-node cluster: iterations of {', '.join(f'{t:.2f}' for t in times)} s, "
              f"steps by node {by_node}")
        assert not _same(start, _weights(algo, "main"))  # ...and the learner learned
        assert _same(start, _weights(algo, "opponent"))
        assert result["self_play_updates"] == 1
        # The env runners play the opponent with the frozen weights too.
        for weights in algo.env_runner_group.foreach_env_runner(
                lambda runner: runner.module["opponent"].get_state(), local_env_runner=False):
            assert _same(start, weights)
        # A copy (what the callback does when one is due) reaches the learner's opponent and
        # every env runner's.
        copy_module_weights(algo, "main", "opponent")
        trained = _weights(algo, "main")
        assert _same(trained, _weights(algo, "opponent"))
        for weights in algo.env_runner_group.foreach_env_runner(
                lambda runner: runner.module["opponent"].get_state(), local_env_runner=False):
            assert _same(trained, weights)

        ckpt = save_checkpoint(algo, tmp_path / "ckpt", {"steps": 128})
        assert (ckpt / SIGNATURE_FILE).is_file()
        size = match_env(TINY_MATCH).observation_space["blue_0"].shape[0]
        obs = np.random.default_rng(0).normal(size=(5, size)).astype(np.float32)
        expected = {m: _actions(algo, m, obs) for m in ("main", "opponent")}
        weights = {m: _weights(algo, m) for m in ("main", "opponent")}
    finally:
        algo.stop()

    restored = load_checkpoint(ckpt)
    try:
        for m in ("main", "opponent"):
            assert _same(weights[m], _weights(restored, m))
            np.testing.assert_array_equal(_actions(restored, m, obs), expected[m])
        # Training continues where the checkpoint stopped, on both nodes.
        result = restored.train()
        assert result["num_env_steps_sampled_lifetime"] == 192
        assert result["training_iteration"] == 3
        assert len(result["env_runners"]["steps_by_node"]) == 2
    finally:
        restored.stop()
