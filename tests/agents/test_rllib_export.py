"""RLlib runs beyond self-play: fixed opponents played by the environment (scripted, idle, a
numpy policy), checkpoints that restore in a fresh process without registering anything, and
the numpy policy a run writes (``final_policy.npz``), whose actions are the RLlib module's and
which ``soccer-env eval`` and the matches read. Skipped without Ray (the main suite);
``make test-rllib`` runs it."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

ray = pytest.importorskip("ray")
pytest.importorskip("ray.rllib")

from agents.policies.files import UnsafeFileError  # noqa: E402
from agents.policies.numpy_policy import NumpyPolicy  # noqa: E402
from agents.runs.rllib import MatchEnv, match_policies, ppo_config  # noqa: E402
from agents.runs.rllib_export import (  # noqa: E402
    FINAL_POLICY,
    export_numpy,
    observation_statistics,
)
from agents.runs.rllib_runs import RllibTrainConfig, train  # noqa: E402
from agents.scripted import scripted_team  # noqa: E402
from soccer_env.envs.registration import MATCH_ID  # noqa: E402
from soccer_lab.cli import main  # noqa: E402

#: A 2 v 2 match of 40 steps.
TINY_MATCH = {"blue": 2, "yellow": 2, "max_cycles": 40, "formation_jitter": 0.0}
#: PPO at its smallest: batches of 64 steps sampled in this process, a tiny network.
TINY_PPO = {"train_batch_size_per_learner": 64, "minibatch_size": 32, "num_epochs": 1,
            "model_config": {"fcnet_hiddens": [8]}}
#: TINY_PPO as options of the command line.
CLI_PPO = ["--num-env-runners", "0", "--n-envs", "1", "--checkpoint-every", "0",
           "--hp", "train_batch_size_per_learner=64", "--hp", "minibatch_size=32",
           "--hp", "num_epochs=1", "--hp", 'model_config={"fcnet_hiddens": [8]}']
#: The keeper through the command line: 2 iterations of 64 steps in this process.
KEEPER = ["train", "--backend", "rllib", "--actions", "guard", *CLI_PPO, "--steps", "128",
          "--no-progress"]

#: Restores checkpoints in a fresh process with RLlib alone (no package import first) and
#: writes each module's deterministic actions for a batch of observations, computed by RLlib:
#: its MeanStdFilter statistics (the keeper's, under None; a match module's, under its id),
#: the module and the Gaussian's mean, mapped onto the action box as its env runners map it.
RESTORE = """
import json, sys
import numpy as np, torch
from ray.rllib.algorithms.algorithm import Algorithm
from ray.rllib.utils.filter import MeanStdFilter, RunningStat
from ray.rllib.utils.spaces.space_utils import unsquash_action

assert "agents.runs.rllib_envs" not in sys.modules
out = {}
for ckpt, module_id, key, obs_file in json.loads(sys.argv[1]):
    algo = Algorithm.from_checkpoint(ckpt)
    state = algo.env_runner.get_state()["env_to_module_connector"]["MeanStdFilter"][key]
    f = MeanStdFilter(tuple(state["shape"]), demean=state["de_mean_to_zero"],
                      destd=state["de_std_to_one"], clip=state["clip_by_value"])
    f.running_stats = RunningStat.from_state(state["running_stats"][0])
    module = algo.get_module(module_id)
    with torch.no_grad():
        x = torch.as_tensor(f(np.load(obs_file), update=False))
        logits = module.forward_inference({"obs": x})["action_dist_inputs"]
    mean = module.get_inference_action_dist_cls().from_logits(logits).to_deterministic()
    actions = [unsquash_action(a, module.action_space) for a in mean.sample().numpy()]
    out[ckpt] = {"actions": np.stack(actions).tolist(), "env_class": algo.config.env.__name__}
    algo.stop()
out["imported"] = "agents.runs.rllib_envs" in sys.modules
print("RESULT " + json.dumps(out))
"""


@pytest.fixture(autouse=True)
def _own_key(tmp_path_factory, monkeypatch):
    """Checkpoints are signed with a key of this test session, not the user's."""
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path_factory.getbasetemp() / "config"))


# ------------------------------------------------------------------------------------------
# Fixed opponents and observation statistics (no Ray running)
# ------------------------------------------------------------------------------------------

def _random_team_policy(obs_size: int, frame_stack: int = 1) -> NumpyPolicy:
    rng = np.random.default_rng(7)
    layers = [("linear", rng.normal(size=(8, obs_size * frame_stack)), rng.normal(size=8)),
              ("tanh",), ("linear", rng.normal(size=(6, 8)), rng.normal(size=6))]
    return NumpyPolicy(layers, "clip", -np.ones(6), np.ones(6), frame_stack=frame_stack)


@pytest.mark.parametrize("opponent, learner", [("scripted", "blue"), ("idle", "yellow"),
                                               ("numpy", "blue")])
def test_a_fixed_opponent_plays_the_other_team_inside_the_environment(opponent, learner):
    """The environment's agents are the learner's robots; the opponent's act as the fixed
    policy says, step by step the same match as the bare one given those actions."""
    import soccer_env

    kwargs = {"blue": 2, "yellow": 2, "max_cycles": 6}
    bare = soccer_env.parallel_env(**kwargs)
    other = "yellow" if learner == "blue" else "blue"
    size = bare.observation_space(f"{other}_0").shape[0]
    policy = _random_team_policy(size) if opponent == "numpy" else opponent
    env = MatchEnv({**kwargs, "opponent": policy, "learner": learner})
    assert env.possible_agents == env.agents == [f"{learner}_0", f"{learner}_1"]
    if opponent == "scripted":
        fixed = scripted_team(bare, other)
    elif opponent == "idle":
        def fixed(obs):
            return {a: np.zeros(6, np.float32) for a in obs if a.startswith(other)}
    else:
        def fixed(obs):
            mine = [a for a in obs if a.startswith(other)]
            return dict(zip(mine, policy(np.stack([obs[a] for a in mine]))))
    obs, infos = env.reset(seed=4)
    full, _ = bare.reset(seed=4)
    rng = np.random.default_rng(1)
    while env.agents:
        assert set(obs) == set(env.agents) and set(infos) == set(env.agents)
        for a in obs:
            np.testing.assert_array_equal(obs[a], full[a])
        actions = {a: rng.uniform(-1, 1, 6).astype(np.float32) for a in env.agents}
        obs, rewards, terms, truncs, infos = env.step(actions)
        full, full_rewards, *_ = bare.step({**actions, **fixed(full)})
        assert set(rewards) == set(actions)
        assert all(rewards[a] == full_rewards[a] for a in rewards)
    assert truncs["__all__"] and set(truncs) == {f"{learner}_0", f"{learner}_1", "__all__"}


def test_fixed_opponents_that_cannot_play_are_refused(tmp_path):
    with pytest.raises(ValueError, match="memory"):
        MatchEnv({**TINY_MATCH, "opponent": _random_team_policy(5, frame_stack=2)})
    with pytest.raises(ValueError, match="observations of size 5"):
        MatchEnv({**TINY_MATCH, "opponent": _random_team_policy(5)})
    with pytest.raises(ValueError, match="opponent must be one of"):
        MatchEnv({**TINY_MATCH, "opponent": "league"})
    with pytest.raises(ValueError, match="'learner' is the team against a fixed"):
        MatchEnv({**TINY_MATCH, "learner": "blue"})
    with pytest.raises(ValueError, match="opponent is for policy mapping 'fixed-opponent'"):
        RllibTrainConfig(env_id=MATCH_ID, opponent="scripted")
    with pytest.raises(ValueError, match="no such file"):
        RllibTrainConfig(env_id=MATCH_ID, policy_mapping="fixed-opponent",
                         opponent=str(tmp_path / "none.npz"))
    with pytest.raises(SystemExit):  # the command line refuses it before Ray starts
        main(["train", "--backend", "rllib", "--env", MATCH_ID, "--opponent",
              str(tmp_path / "none.npz"), "--out", str(tmp_path / "run")])
    assert not (tmp_path / "run").exists()


def test_the_fixed_opponent_configuration_carries_the_policy(tmp_path):
    """A numpy opponent's file is read where the configuration is made: the env runners of
    other machines get the policy in ``env_config``. The environment is named by its class."""
    size = MatchEnv(TINY_MATCH).observation_space["blue_0"].shape[0]
    file = _random_team_policy(size).save(tmp_path / "team.npz")
    config = ppo_config(MATCH_ID, TINY_MATCH, policy_mapping="fixed-opponent", learner="yellow",
                        opponent=str(file))
    assert config.env is MatchEnv
    assert isinstance(config.env_config["opponent"], NumpyPolicy)
    assert config.env_config["learner"] == "yellow"
    assert set(config.policies) == {"main"}
    policies = match_policies(config.env_config, "fixed-opponent", "yellow")
    assert policies.agent_module == {"yellow_0": "main", "yellow_1": "main"}
    with pytest.raises(ValueError, match="needs an opponent"):
        ppo_config(MATCH_ID, TINY_MATCH, policy_mapping="fixed-opponent", opponent="league")
    with pytest.raises(ValueError, match="opponent is for policy mapping"):
        ppo_config(MATCH_ID, TINY_MATCH, policy_mapping="self-play", opponent="idle")


def test_pooled_observation_statistics_are_those_of_all_the_robots():
    from ray.rllib.utils.filter import RunningStat
    from ray.rllib.utils.numpy import SMALL_NUMBER

    rng = np.random.default_rng(3)
    data = {"blue_0": rng.normal(1.0, 2.0, (50, 3)), "blue_1": rng.normal(-1.0, 0.5, (30, 3))}
    state = {}
    for agent, rows in data.items():
        stat = RunningStat((3,))
        for row in rows:
            stat.push(row)
        state[agent] = {"shape": (3,), "de_mean_to_zero": True, "de_std_to_one": True,
                        "clip_by_value": 10.0, "running_stats": [stat.to_state()]}
    one = observation_statistics(state, ["blue_1"])
    np.testing.assert_allclose(one[0], data["blue_1"].mean(0))
    np.testing.assert_allclose(np.sqrt(one[1]), data["blue_1"].std(0, ddof=1) + SMALL_NUMBER,
                               rtol=1e-6)
    both = observation_statistics(state, ["blue_0", "blue_1"])
    rows = np.concatenate(list(data.values()))
    np.testing.assert_allclose(both[0], rows.mean(0))
    np.testing.assert_allclose(np.sqrt(both[1]), rows.std(0, ddof=1) + SMALL_NUMBER, rtol=1e-6)
    assert both[2:] == (10.0, 0.0)


def test_the_match_filter_keeps_one_set_of_statistics_per_module():
    """The match's MeanStdFilter keys its state by module; a state by robot (version 0.1.0)
    is pooled per module as it is set, and env runners' states merge by module."""
    import gymnasium as gym
    from ray.rllib.utils.filter import RunningStat

    from agents.runs.rllib_filters import MeanStdFilter

    agents = {"blue_0": "main", "blue_1": "main", "yellow_0": "opponent"}
    box = gym.spaces.Box(-5, 5, (3,))
    spaces = gym.spaces.Dict(dict.fromkeys(agents, box))
    actions = gym.spaces.Dict(dict.fromkeys(agents, gym.spaces.Box(-1, 1, (6,))))

    def made():
        conn = MeanStdFilter(agent_module=agents)  # the spaces come later, as in a pipeline
        conn.input_action_space = actions
        conn.input_observation_space = spaces
        return conn

    conn = made()
    assert set(conn.get_state()) == {"main", "opponent"}
    rng = np.random.default_rng(5)
    old = {}
    for agent in agents:
        stat = RunningStat((3,))
        for row in rng.normal(size=(20, 3)):
            stat.push(row)
        old[agent] = {"shape": (3,), "de_mean_to_zero": True, "de_std_to_one": True,
                      "clip_by_value": 10.0, "running_stats": [stat.to_state()]}
    conn.set_state(old)
    state = conn.get_state()
    main = RunningStat.from_state(state["main"]["running_stats"][0])
    assert main.n == 40
    np.testing.assert_allclose(main.mean, observation_statistics(old, ["blue_0", "blue_1"])[0])
    assert RunningStat.from_state(state["opponent"]["running_stats"][0]).n == 20
    other = made()
    other.set_state(state)
    assert set(other.merge_states([state])) == {"main", "opponent"}


# ------------------------------------------------------------------------------------------
# Runs on Ray on this machine
# ------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def local_ray():
    """Ray on this machine for the module's runs (each run reuses it)."""
    import torch

    torch.set_num_threads(1)
    ray.init(num_cpus=2, include_dashboard=False, object_store_memory=80 * 2**20,
             logging_level="WARNING")
    yield
    ray.shutdown()


@pytest.fixture(scope="module")
def runs(local_ray, tmp_path_factory):
    """A keeper run through the command line, and two match runs against fixed opponents:
    the scripted team, then (through the command line) the first run's numpy policy."""
    base = tmp_path_factory.mktemp("runs")
    env = pytest.MonkeyPatch()
    env.setenv("XDG_CONFIG_HOME", str(tmp_path_factory.getbasetemp() / "config"))
    assert main([*KEEPER, "--out", str(base / "keeper")]) == 0
    common = {"env_id": MATCH_ID, "env_kwargs": TINY_MATCH, "num_env_runners": 0, "n_envs": 1,
              "hyperparams": TINY_PPO, "checkpoint_every": 0, "progress": False,
              "policy_mapping": "fixed-opponent"}
    scripted = train(RllibTrainConfig(**common, total_steps=128, opponent="scripted",
                                      out=str(base / "scripted")))
    match = [a for k, v in TINY_MATCH.items() for a in ("--env-kwarg", f"{k}={v}")]
    assert main(["train", "--backend", "rllib", "--env", MATCH_ID, *match, *CLI_PPO,
                 "--steps", "64", "--no-progress", "--learner", "yellow", "--opponent",
                 scripted["final_policy"], "--out", str(base / "npz")]) == 0
    versus = json.loads((base / "npz" / "summary.json").read_text())
    yield {"keeper": base / "keeper", "scripted": base / "scripted", "npz": base / "npz",
           "summaries": (scripted, versus)}
    env.undo()


def test_runs_against_fixed_opponents_write_numpy_policies(runs):
    scripted, versus = runs["summaries"]
    assert scripted["steps"] == 128 and versus["steps"] == 64
    for name in ("keeper", "scripted", "npz"):
        assert (runs[name] / FINAL_POLICY).is_file(), name
    config = json.loads((runs["npz"] / "config.json").read_text())
    assert config["policy_mapping"] == "fixed-opponent" and config["learner"] == "yellow"
    assert config["opponent"] == scripted["final_policy"]
    lines = [json.loads(line) for line in (runs["scripted"] / "results.jsonl").read_text()
             .splitlines()]
    assert [r["steps"] for r in lines] == [64, 128]
    info = json.loads((runs["scripted"] / "final_checkpoint" / "soccer_env_checkpoint.json")
                      .read_text())
    assert info["opponent"] == "scripted" and info["policy_mapping"] == "fixed-opponent"
    policy = NumpyPolicy.load(runs["npz"] / FINAL_POLICY)
    assert policy.meta["module"] == "main" and policy.meta["learner"] == "yellow"
    assert policy.meta["statistics_of"] == ["main"]
    # Both learning robots fed the module's one set of statistics (128 steps each and the
    # first observations).
    from ray.rllib.connectors.connector_pipeline_v2 import ConnectorPipelineV2
    from ray.rllib.utils.filter import RunningStat

    pipeline = ConnectorPipelineV2.from_checkpoint(
        str(runs["scripted"] / "final_checkpoint" / "env_runner" / "env_to_module_connector"))
    state = pipeline.get_state()["MeanStdFilter"]
    assert list(state) == ["main"]
    assert RunningStat.from_state(state["main"]["running_stats"][0]).n >= 2 * 128


def test_a_fresh_process_restores_and_the_numpy_policy_acts_as_the_module(runs, tmp_path):
    """The checkpoints restore with ``Algorithm.from_checkpoint`` alone in a new process (the
    environment's class is imported as the checkpoint is read), and the numpy policies act as
    the restored modules do, deterministically, within 1e-5."""
    from agents.runs.rllib import KeeperEnv

    cases = {"keeper": ("default_policy", None), "scripted": ("main", "main")}
    sizes = {"keeper": KeeperEnv({"actions": "guard"}).observation_space.shape[0],
             "scripted": MatchEnv(TINY_MATCH).observation_space["blue_0"].shape[0]}
    rng = np.random.default_rng(0)
    jobs, batches = [], {}
    for name, (module_id, key) in cases.items():
        batches[name] = (rng.normal(size=(64, sizes[name])) * 2).astype(np.float32)
        np.save(tmp_path / f"{name}.npy", batches[name])
        jobs.append([str(runs[name] / "final_checkpoint"), module_id, key,
                     str(tmp_path / f"{name}.npy")])
    proc = subprocess.run([sys.executable, "-c", RESTORE, json.dumps(jobs)], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    result = json.loads(proc.stdout.split("RESULT ", 1)[1])
    assert result["imported"]
    for (name, (_, key)), job in zip(cases.items(), jobs):
        expected = np.asarray(result[job[0]]["actions"], dtype=np.float32)
        assert result[job[0]]["env_class"] == ("KeeperEnv" if key is None else "MatchEnv")
        for policy in (NumpyPolicy.load(runs[name] / FINAL_POLICY),
                       export_numpy(job[0])):
            got = policy.network_action(batches[name])
            difference = float(np.abs(got - expected).max())
            print(f"{name}: numpy policy vs RLlib module, max |difference| {difference:.2e}")
            assert difference <= 1e-5
    keeper = NumpyPolicy.load(runs["keeper"] / FINAL_POLICY)
    assert keeper.action_map["kind"] == "guard" and keeper.meta["statistics_of"] == [None]


def test_export_refuses_what_it_cannot_copy_safely(runs, tmp_path, monkeypatch):
    with pytest.raises(ValueError, match="has no module 'opponent'"):
        export_numpy(runs["scripted"], module_id="opponent")
    with pytest.raises(ValueError, match="not an RLlib checkpoint"):
        export_numpy(tmp_path)
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "someone_else"))
    with pytest.raises(UnsafeFileError, match="not a checkpoint of your own runs"):
        export_numpy(runs["scripted"])
    assert export_numpy(runs["scripted"], trust=True).meta["opponent"] == "scripted"


def test_eval_and_the_matches_read_rllib_runs(runs, tmp_path, capsys):
    from agents.studies.matches import Side, play_match

    out = tmp_path / "eval"
    assert main(["eval", "--policy", str(runs["keeper"]), "--episodes", "4", "--video", "0",
                 "--workers", "1", "--out", str(out), "--json"]) == 0
    result = json.loads((out / "eval.json").read_text())
    assert result["episodes"] == 4
    match = play_match(TINY_MATCH, Side(str(runs["scripted"] / FINAL_POLICY), "truth"),
                       Side("scripted", "truth"), seed=0)
    assert match["steps"] == TINY_MATCH["max_cycles"]
    capsys.readouterr()
