"""The examples of examples/ run at their tiny size (``--tiny``), each in its own process; an
example whose client library is not installed is skipped. The RL Zoo's run must train with
the shipped hyperparameters of hyperparams/ppo.yml."""

import importlib.util
import json
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
ZOO_HYPERPARAMS = ROOT / "hyperparams" / "ppo.yml"


def _needs(*modules: str) -> None:
    """Skip unless every one of ``modules`` is installed (without importing them here)."""
    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if missing:
        pytest.skip(f"not installed: {', '.join(missing)} (pip install -e '.[clients]')")


def _run(script: str, *args: str, timeout: float = 300) -> str:
    env = {**os.environ, "SOCCER_EXAMPLES_TINY": "1", "OMP_NUM_THREADS": "1",
           "RL_WARNINGS": "0"}
    # The examples import the package as an installed user would; from a checkout that is
    # not installed, the repository root stands in.
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
    proc = subprocess.run([sys.executable, str(EXAMPLES / script), "--tiny", *args],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout)
    assert proc.returncode == 0, f"{script} failed:\n{proc.stdout[-3000:]}\n{proc.stderr[-5000:]}"
    return proc.stdout


def test_every_example_is_tested():
    tested = {"torchrl_envs.py", "supersuit_match_ppo.py", "recurrent_ppo_keeper.py",
              "rl_zoo3_keeper.py", "batched_self_play.py", "train_ssl_team.py",
              "rllib_match.py",  # tests/examples/test_rllib_example.py, in make test-rllib
              # tests/examples/test_benchmarl_example.py, in make test-benchmarl
              "benchmarl_match.py",
              # tests/examples/test_tianshou_example.py, in make test-tianshou
              "tianshou_keeper.py", "pufferlib_envs.py"}
    assert {p.name for p in EXAMPLES.glob("*.py")} == tested


def test_torchrl_example():
    _needs("torchrl", "tensordict")
    out = _run("torchrl_envs.py")
    assert "keeper episode 0:" in out and "outcome" in out
    assert "groups: {'blue': ['blue_0', 'blue_1'], 'yellow': ['yellow_0', 'yellow_1']}" in out
    assert "match: 20 steps" in out


def test_pufferlib_example():
    _needs("pufferlib")
    out = _run("pufferlib_envs.py", "--check-stock")
    # Each environment through both backends, reset twice (the Multiprocessing one with the
    # example's fix of PufferLib's reset), the keeper's 20-step time limit and the match's 20
    # cycles ending episodes along the way.
    for backend in ("Serial", "Multiprocessing"):
        assert f"keeper, {backend}: 4 rows, 2 resets x 30 steps, 8 agent episode ends" in out
        assert f"match, {backend}: 16 rows, 2 resets x 30 steps, 32 agent episode ends" in out
    # PufferLib's own backend still hangs on the second reset: when a release fixes it, the
    # example's ResettableMultiprocessing (and docs/guide/rl-libraries.md's note) can go.
    assert "stock Multiprocessing, keeper: second reset still waiting" in out


def test_supersuit_example():
    _needs("supersuit", "stable_baselines3")
    out = _run("supersuit_match_ppo.py")
    assert "8 learners (agents x matches)" in out
    assert "trained 256 agent steps" in out and "score:" in out


def test_recurrent_ppo_example():
    _needs("sb3_contrib")
    out = _run("recurrent_ppo_keeper.py")
    assert "RecurrentPPO keeper, 128 steps:" in out


def _model_data(path: Path) -> dict:
    """The JSON part of a stable-baselines3 model file (nothing unpickled)."""
    with zipfile.ZipFile(path) as archive:
        return json.loads(archive.read("data"))


@pytest.mark.slow
def test_rl_zoo3_example_trains_with_the_shipped_hyperparameters(tmp_path):
    _needs("rl_zoo3", "yaml")
    import yaml

    _run("rl_zoo3_keeper.py", "--log-folder", str(tmp_path))
    shipped = yaml.safe_load(ZOO_HYPERPARAMS.read_text())["soccer_env/Goalkeeper-v0"]
    name = "soccer_env-Goalkeeper-v0"
    for stage, ent_coef, obs_mode in (("truth", 0.0, "truth"), ("perceived", 0.005, "perceived")):
        run = tmp_path / stage / "ppo" / f"{name}_1"
        # The hyperparameters the Zoo saved are the file's (a new -params entry replaces one).
        saved = yaml.load((run / name / "config.yml").read_text(), Loader=yaml.UnsafeLoader)
        expected = {**shipped, "ent_coef": ent_coef} if stage == "perceived" else shipped
        assert {k: v for k, v in saved.items() if k != "env_kwargs"} == \
            {k: v for k, v in expected.items() if k != "env_kwargs"}
        assert saved["env_kwargs"]["obs_mode"] == obs_mode
        assert (run / name / "vecnormalize.pkl").is_file()  # normalize: norm_obs
        # ... and the model trained with them: the file's values, not the Zoo's defaults.
        data = _model_data(run / f"{name}.zip")
        for key in ("n_steps", "batch_size", "n_epochs", "gamma", "gae_lambda"):
            assert data[key] == shipped[key], key
        assert data["n_envs"] == shipped["n_envs"] == 16
        assert data["ent_coef"] == ent_coef
        assert data["policy_kwargs"] == {"log_std_init": -0.5}
        assert data["learning_rate"]["val"] == shipped["learning_rate"]
        assert data["action_space"]["_shape"] == [1]  # agents.policies.wrappers.GuardActions


def test_zoo_hyperparameters_are_the_shipped_keepers():
    """hyperparams/ppo.yml holds the recipe the shipped keeper's first stage was trained with
    (soccer-env train's PPO defaults and the baseline's recorded arguments)."""
    _needs("yaml")
    import yaml

    from agents.baselines import load_baseline
    from agents.runs.training import TrainConfig
    from agents.sb3.algorithms import DEFAULT_HYPERPARAMS

    zoo = yaml.safe_load(ZOO_HYPERPARAMS.read_text())["soccer_env/Goalkeeper-v0"]
    meta = load_baseline("keeper-ppo-ssl2012").meta
    cfg = TrainConfig()
    for key, value in DEFAULT_HYPERPARAMS["PPO"].items():
        assert zoo[key] == value, key
    assert zoo["n_envs"] == cfg.n_envs
    assert zoo["normalize"] == f"{{'norm_obs': {cfg.normalize_obs}, " \
                               f"'norm_reward': {cfg.normalize_reward}}}"
    assert meta["actions"] == "guard"
    assert zoo["env_wrapper"] == "agents.policies.wrappers.GuardActions"
    assert zoo["policy_kwargs"] == "dict(log_std_init={})".format(
        meta["hyperparams"]["policy_kwargs"]["log_std_init"])
    stage1 = {k: v for k, v in meta["env_kwargs"].items()}
    stage1["obs_mode"] = "truth"  # the first stage's; the second continues on perceived ones
    assert zoo["env_kwargs"] == stage1
    assert "--steps 1000000" in meta["commands"][0] and zoo["n_timesteps"] == 1e6


def test_batched_self_play_example():
    _needs("stable_baselines3")
    out = _run("batched_self_play.py")
    assert "16 learners (8 matches x 2 blue robots)" in out
    assert "trained 512 agent steps" in out and "score:" in out


def test_train_ssl_team_example(tmp_path):
    _needs("stable_baselines3")
    out = _run("train_ssl_team.py", "--out", str(tmp_path / "run"))
    assert "trained 512 agent steps" in out and "3 copies" in out
    lines = [json.loads(x) for x in (tmp_path / "run" / "progress.jsonl").read_text().split("\n")
             if x]
    assert [x["checkpoint"] for x in lines] == [f"team_{x['steps']}.npz" for x in lines]
    assert all(x["wins"] + x["draws"] + x["losses"] == 2 for x in lines)
    from agents.policies import NumpyPolicy

    team = NumpyPolicy.load(tmp_path / "run" / "final_team.npz")
    assert team.action_map["kind"] == "team-residual" and team.normalize is not None
    assert team.meta["steps"] == 512 and team.meta["train_kwargs"]["blue"] == 2


def test_train_ssl_team_example_under_perception_and_the_game_flow(tmp_path):
    """The perceived game-flow training, started from the truth-trained team (``--init``), its
    observation statistics held (``--hold-statistics``)."""
    _needs("stable_baselines3")
    out = _run("train_ssl_team.py", "--setting", "perceived-game", "--init",
               "agents/baselines/ssl_team_2v2.npz", "--hold-statistics",
               "--out", str(tmp_path / "r"))
    assert "trained 512 agent steps" in out
    from agents.policies import NumpyPolicy

    team = NumpyPolicy.load(tmp_path / "r" / "final_team.npz")
    train = team.meta["train_kwargs"]
    assert train["obs_mode"] == "perceived" and train["game"] is True
    assert team.meta["eval_kwargs"]["game"] is True
    assert team.meta["ppo"]["normalize_advantage"] is False  # restarts kept out of the update
    assert "rules" in team.action_map["params"]
    assert any(n == "game.mate0.on_field" for n in team.action_map["params"]["names"])
    start = NumpyPolicy.load(ROOT / "agents" / "baselines" / "ssl_team_2v2.npz")
    team = NumpyPolicy.load(tmp_path / "r" / "checkpoints" / "team_248.npz")
    assert team.obs_size > start.obs_size  # the game block's entries added
    # The actor was held while the critic learned: the first copy has the network it started
    # from, the game block's added entries weighing nothing.
    (_, w0, b0), *rest = [layer for layer in team.layers if layer[0] == "linear"]
    (_, v0, c0), *theirs = [layer for layer in start.layers if layer[0] == "linear"]
    np.testing.assert_array_equal(w0[:, :start.obs_size], v0)
    assert not w0[:, start.obs_size:].any()
    for mine, other in zip([b0, *(a for layer in rest for a in layer[1:])],
                           [c0, *(a for layer in theirs for a in layer[1:])]):
        np.testing.assert_array_equal(mine, other)
    n = start.obs_size
    np.testing.assert_allclose(team.normalize[0][:n], start.normalize[0])
    np.testing.assert_allclose(team.normalize[1][:n], start.normalize[1])
    assert not np.allclose(team.normalize[1][n:], 1.0)  # the added entries' follow the game
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.run([sys.executable, str(EXAMPLES / "train_ssl_team.py"), "--tiny",
                           "--init", "agents/baselines/keeper_ppo_truth.npz", "--out",
                           str(tmp_path / "k")], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode != 0 and "--init must be a team-residual team file" in proc.stderr


def test_train_ssl_team_example_trains_humanoids_on_their_cameras(tmp_path):
    _needs("stable_baselines3")
    out = _run("train_ssl_team.py", "--setting", "humanoid-game", "--out", str(tmp_path / "r"))
    assert "trained 512 agent steps" in out
    from agents.policies import NumpyPolicy

    team = NumpyPolicy.load(tmp_path / "r" / "final_team.npz")
    train, evaluation = team.meta["train_kwargs"], team.meta["eval_kwargs"]
    assert train["robot"] == evaluation["robot"] == "humanoid-2012"
    assert train["perception"] == {"camera": "kidsize-2012"} and evaluation["game"] is True
    assert team.action_map["params"]["kind"] == "humanoid"
