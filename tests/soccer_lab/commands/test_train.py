"""Training end to end: ``soccer-env train`` writes a usable run, resumes, refuses bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from agents.policies import NumpyPolicy, load_sb3, make_policy  # noqa: E402
from soccer_lab.cli import main  # noqa: E402

pytestmark = pytest.mark.slow


def test_train_evaluate_checkpoint_and_resume(tmp_path, capsys):
    run = tmp_path / "run"
    args = ["train", "--obs-mode", "perceived", "--perception", "ssl-2012", "--steps", "2048",
            "--n-envs", "4", "--workers", "2", "--hp", "n_steps=128", "--eval-every", "1024",
            "--eval-episodes", "4", "--checkpoint-every", "1024", "--out", str(run),
            "--no-progress", "--seed", "3"]
    assert main(args) == 0
    assert "steps/s collecting rollouts" in capsys.readouterr().out
    config = json.loads((run / "config.json").read_text())
    assert config["env_kwargs"] == {"obs_mode": "perceived", "perception": "ssl-2012"}
    assert config["hyperparams"] == {"n_steps": 128} and config["seed"] == 3
    assert "stable_baselines3" in config["versions"]
    summary = json.loads((run / "summary.json").read_text())
    assert summary["steps"] == 2048 and summary["rollout_steps_per_s"] > 0
    evaluations = json.loads((run / "evaluations.json").read_text())
    assert [e["steps"] for e in evaluations] == [1024, 2048]
    assert all(0.0 <= e["save_rate"] <= 1.0 for e in evaluations)
    for name in ("final_model.zip", "final_policy.npz", "best_model.zip", "best_policy.npz",
                 "final_vecnormalize.pkl", "best_vecnormalize.pkl"):
        assert (run / name).is_file(), name
    assert any((run / "tb").rglob("events.out.tfevents.*"))
    checkpoints = sorted((run / "checkpoints").glob("model_*_steps.zip"))
    assert [c.name for c in checkpoints] == ["model_1024_steps.zip", "model_2048_steps.zip"]
    assert (run / "checkpoints" / "model_vecnormalize_1024_steps.pkl").is_file()
    policy = NumpyPolicy.load(run / "final_policy.npz")
    assert policy.meta["env_kwargs"]["perception"] == "ssl-2012"
    assert policy.meta["evaluation"]["steps"] == 2048
    assert policy.normalize is not None  # observations normalised as in training
    # The saved model with its statistics acts as the numpy policy.
    import gymnasium as gym

    env = gym.make("soccer_env/Goalkeeper-v0")
    obs = np.stack([env.reset(seed=s)[0] for s in range(5)])
    np.testing.assert_allclose(make_policy(run / "final_model.zip", env)(obs), policy(obs),
                               atol=1e-5)

    # Resume from the first checkpoint: the step count continues, the configuration is the
    # run's own.
    assert main(["train", "--resume", str(checkpoints[0]), "--steps", "3072",
                 "--no-progress"]) == 0
    summary = json.loads((run / "summary.json").read_text())
    assert summary["steps"] == 3072 and summary["trained_steps"] == 2048
    resumed = json.loads((run / "config.json").read_text())
    assert resumed["resumed_from"] == str(checkpoints[0])
    assert resumed["env_kwargs"] == config["env_kwargs"]
    # Evaluations continue at the next multiples of eval_every, once each.
    steps = [e["steps"] for e in json.loads((run / "evaluations.json").read_text())]
    assert steps == [2048, 3072], steps

    # Fine-tuning: resume with another observation mode and hyperparameter.
    tuned = tmp_path / "tuned"
    assert main(["train", "--resume", str(run / "final_model.zip"), "--obs-mode", "truth",
                 "--hp", "ent_coef=0.01", "--steps", "4096", "--out", str(tuned),
                 "--no-progress"]) == 0
    cfg = json.loads((tuned / "config.json").read_text())
    assert cfg["env_kwargs"]["obs_mode"] == "truth" and cfg["hyperparams"]["ent_coef"] == 0.01
    assert load_sb3(tuned / "final_model.zip").ent_coef == 0.01

    act = make_policy(run, env)(np.zeros(19, np.float32))
    assert act.shape == (6,) and np.all(np.abs(act) <= 1)


def test_target_actions_run_acts_on_the_plain_env(tmp_path):
    """A keeper trained through the target action map: its numpy policy and its model both
    give native 6-number commands, the same ones."""
    import gymnasium as gym

    run = tmp_path / "target"
    assert main(["train", "--actions", "target", "--env-kwarg", "control_dt=0.04",
                 "--steps", "512", "--n-envs", "2", "--workers", "0", "--hp", "n_steps=256",
                 "--eval-every", "0", "--checkpoint-every", "0", "--out", str(run),
                 "--no-progress"]) == 0
    config = json.loads((run / "config.json").read_text())
    assert config["actions"] == "target" and config["action_map"]["kind"] == "target"
    policy = NumpyPolicy.load(run / "final_policy.npz")
    assert policy.action_size == 2 and policy.action_map["kind"] == "target"
    env = gym.make("soccer_env/Goalkeeper-v0", control_dt=0.04)
    obs = np.stack([env.reset(seed=s)[0] for s in range(5)])
    act = policy(obs)
    assert act.shape == (5, 6)
    np.testing.assert_allclose(make_policy(run / "final_model.zip", env)(obs), act, atol=1e-5)


def test_off_policy_algorithm_in_process(tmp_path):
    assert main(["train", "--algo", "sac", "--steps", "300", "--n-envs", "1", "--workers",
                 "0", "--hp", "learning_starts=100", "--hp", "buffer_size=1000",
                 "--eval-every", "0", "--checkpoint-every", "0", "--out",
                 str(tmp_path / "sac"), "--no-progress"]) == 0
    assert NumpyPolicy.load(tmp_path / "sac" / "final_policy.npz").output == "tanh"


@pytest.mark.parametrize("args,message", [
    (["--hp", "learning_rat=0.1"], "unknown PPO hyperparameter"),
    (["--env-kwarg", "obs_mod=raw"], "obs_mod"),
    (["--perception", "foggy"], "foggy"),
    (["--steps", "0"], "total_steps must be an integer >= 1"),
    (["--env", "soccer_env/Tennis-v0"], "env_id must be"),
    (["--hp", "n_steps"], "--hp must be key=value"),
    (["--resume", "nowhere.zip"], "no checkpoint"),
])
def test_bad_input_is_refused_before_training(tmp_path, capsys, args, message):
    with pytest.raises(SystemExit):
        main(["train", "--out", str(tmp_path / "x"), *args])
    assert message in capsys.readouterr().err
    assert not (tmp_path / "x").exists()
