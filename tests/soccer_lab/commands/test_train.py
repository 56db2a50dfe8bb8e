"""Training end to end: ``soccer-env train`` writes a usable run, resumes, refuses bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from agents.policies import NumpyPolicy  # noqa: E402
from agents.runs.resolve import load_sb3, make_policy  # noqa: E402
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
                 "final_vecnormalize.npz", "best_vecnormalize.npz"):
        assert (run / name).is_file(), name
    assert any((run / "tb").rglob("events.out.tfevents.*"))
    checkpoints = sorted((run / "checkpoints").glob("model_*_steps.zip"))
    assert [c.name for c in checkpoints] == ["model_1024_steps.zip", "model_2048_steps.zip"]
    assert (run / "checkpoints" / "model_vecnormalize_1024_steps.npz").is_file()
    assert not list(run.rglob("*.pkl"))  # nothing that loading would have to unpickle
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
    # run's own. Its save intervals are below what a run's config.json may set by itself, so
    # they are given again (as the resume command a stopped run prints gives them).
    assert main(["train", "--resume", str(checkpoints[0]), "--steps", "3072",
                 "--checkpoint-every", "1024", "--eval-every", "1024", "--no-progress"]) == 0
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
                 "--checkpoint-every", "0", "--eval-every", "0", "--no-progress"]) == 0
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
    (["--env", "soccer_env/Tennis-v0"], "invalid choice: 'soccer_env/Tennis-v0'"),
    (["--hp", "n_steps"], "--hp must be key=value"),
    (["--resume", "nowhere.zip"], "no checkpoint"),
    (["--frame-stack", "0"], "frame_stack must be an integer >= 1"),
    (["--algo", "dqn"], "invalid choice: 'dqn'"),
    (["--algo", "recurrent-ppo", "--frame-stack", "2"], "RecurrentPPO's LSTM carries"),
    (["--algo", "recurrent-ppo", "--hp", "buffer_size=10"], "unknown RECURRENTPPO hyperpar"),
])
def test_bad_input_is_refused_before_training(tmp_path, capsys, args, message):
    with pytest.raises(SystemExit):
        main(["train", "--out", str(tmp_path / "x"), *args])
    assert message in capsys.readouterr().err
    assert not (tmp_path / "x").exists()


def _episode_actions(policy, env, seed):
    """The actions ``policy`` takes over one episode of ``env`` (reset first)."""
    from agents.policies import reset_policy

    reset_policy(policy)
    obs, _ = env.reset(seed=seed)
    actions = []
    while True:
        actions.append(policy(obs))
        obs, _, term, trunc, _ = env.step(actions[-1])
        if term or trunc:
            return np.array(actions)


def test_recurrent_ppo_run_resumes_and_refuses_a_resume_with_nothing_to_train(tmp_path, capsys):
    """--algo recurrent-ppo trains RecurrentPPO, evaluates and exports the LSTM in numpy (the
    .npz and the .zip act alike over episodes); a resume must ask for more steps than the
    checkpoint has."""
    pytest.importorskip("sb3_contrib")
    import gymnasium as gym

    from agents.policies import NumpyRecurrentPolicy
    from agents.runs.training import TrainConfig, train

    run = tmp_path / "lstm"
    assert main(["train", "--algo", "recurrent-ppo", "--steps", "256", "--n-envs", "2",
                 "--workers", "0", "--hp", "n_steps=64", "--hp",
                 "policy_kwargs={\"lstm_hidden_size\": 8}", "--eval-every", "256",
                 "--eval-episodes", "2", "--checkpoint-every", "0", "--out", str(run),
                 "--no-progress"]) == 0
    config = json.loads((run / "config.json").read_text())
    assert config["algorithm"] == "RECURRENTPPO" and "sb3_contrib" in config["versions"]
    model = load_sb3(run / "final_model.zip")
    assert type(model).__name__ == "RecurrentPPO"
    assert model.policy.lstm_actor.hidden_size == 8
    policy = NumpyPolicy.load(run / "final_policy.npz")
    assert isinstance(policy, NumpyRecurrentPolicy)
    assert policy.meta["algorithm"] == "RECURRENTPPO" and policy.meta["frame_stack"] == 1
    assert policy.meta["evaluation"]["steps"] == 256
    env = gym.make("soccer_env/Goalkeeper-v0")
    from_zip = make_policy(run / "final_model.zip", env)
    np.testing.assert_allclose(_episode_actions(from_zip, env, 0),
                               _episode_actions(policy, env, 0), atol=1e-5)

    # --steps is the total: at or below the checkpoint's 256 steps nothing would be trained.
    capsys.readouterr()
    for steps in (["--steps", "256"], ["--steps", "100"], []):
        with pytest.raises(SystemExit):
            main(["train", "--resume", str(run / "final_model.zip"), *steps, "--eval-every",
                  "256", "--no-progress"])
        err = capsys.readouterr().err
        assert "leaves nothing to train" in err and "already trained 256 steps" in err, err
    assert "from its config.json" in err  # without --steps: the run's own total
    with pytest.raises(ValueError, match="leaves nothing to train"):
        train(TrainConfig(algorithm="recurrent-ppo", total_steps=256, out=str(tmp_path / "x")),
              resume=run / "final_model.zip")
    assert not (tmp_path / "x").exists()
    assert main(["train", "--resume", str(run / "final_model.zip"), "--steps", "384",
                 "--eval-every", "0", "--no-progress"]) == 0
    summary = json.loads((run / "summary.json").read_text())
    assert summary["steps"] == 384 and summary["trained_steps"] == 128


def test_frame_stack_run_exports_a_policy_that_keeps_the_stack(tmp_path):
    """--frame-stack 3 with the guard map: the learner sees 57 numbers, the exported policy
    takes the plain 19 and acts as the model does on the stacked environment."""
    import gymnasium as gym

    run = tmp_path / "stack"
    assert main(["train", "--frame-stack", "3", "--actions", "guard", "--steps", "256",
                 "--n-envs", "2", "--workers", "0", "--hp", "n_steps=64", "--eval-every",
                 "256", "--eval-episodes", "2", "--checkpoint-every", "0", "--out", str(run),
                 "--no-progress"]) == 0
    config = json.loads((run / "config.json").read_text())
    assert config["frame_stack"] == 3
    model = load_sb3(run / "final_model.zip")
    assert model.observation_space.shape == (57,)
    policy = NumpyPolicy.load(run / "final_policy.npz")
    assert policy.frame_stack == 3 and policy.obs_size == 19 and policy.meta["frame_stack"] == 3
    env = gym.make("soccer_env/Goalkeeper-v0")
    actions = _episode_actions(policy, env, 1)
    np.testing.assert_allclose(_episode_actions(make_policy(run / "final_model.zip", env),
                                                env, 1), actions, atol=1e-5)
    # Against the model itself on its training environment (stacked, behind the guard map
    # and VecNormalize): the same commands, step by step.
    from stable_baselines3.common.vec_env import DummyVecEnv

    from agents.policies.action_maps import action_to_command
    from agents.sb3.normalization import read_vecnormalize, vecnormalize_on
    from agents.vec.factories import goalkeeper_env_fn

    make = goalkeeper_env_fn({}, "guard", 3)
    norm = vecnormalize_on(read_vecnormalize(run / "final_vecnormalize.npz"),
                           DummyVecEnv([make]))
    stacked = make()
    policy.reset()
    obs, _ = stacked.reset(seed=2)
    plain, _ = env.reset(seed=2)
    steps, done = 0, False
    while not done:
        guard = model.predict(norm.normalize_obs(obs), deterministic=True)[0]
        command = policy(plain)
        np.testing.assert_allclose(command, action_to_command(
            "guard", plain, guard, policy.action_map["params"]), atol=1e-5)
        obs, _, term, trunc, _ = stacked.step(guard)
        plain, *_ = env.step(command)
        steps, done = steps + 1, term or trunc
    assert steps > 20 and len(actions) > 20


def test_batched_training_steps_the_keepers_as_one_batch(tmp_path, capsys):
    """--batched: the Goalkeeper's environments in one batch (BatchedVecEnv), evaluated and
    exported as any run; what the batch cannot run is refused, naming the option."""
    run = tmp_path / "batched"
    assert main(["train", "--batched", "--n-envs", "32", "--steps", "2048", "--hp",
                 "n_steps=64", "--eval-every", "2048", "--eval-episodes", "2",
                 "--checkpoint-every", "0", "--out", str(run), "--no-progress"]) == 0
    config = json.loads((run / "config.json").read_text())
    assert config["batched"] is True and config["n_workers"] == 0
    assert json.loads((run / "summary.json").read_text())["steps"] >= 2048
    assert (run / "final_policy.npz").is_file()
    for extra, message in ((["--actions", "guard"], "actions='guard'"),
                           (["--workers", "2"], "n_workers=2"),
                           (["--env-kwarg", "render_mode=rgb_array"], "does not render")):
        with pytest.raises(SystemExit):
            main(["train", "--batched", *extra, "--steps", "64", "--out",
                  str(tmp_path / "no"), "--no-progress"])
        assert message in capsys.readouterr().err


def test_batched_match_training_with_workers(tmp_path, capsys):
    """--batched on Match-v0: each worker steps its matches as one batch; self-play and the
    saved policy work as in any match run; what the batch cannot run is refused."""
    run = tmp_path / "batched_match"
    assert main(["train", "--env", "soccer_env/Match-v0", "--batched", "--workers", "2",
                 "--n-envs", "8", "--steps", "1024", "--hp", "n_steps=64",
                 "--env-kwarg", "blue=2", "--env-kwarg", "yellow=2",
                 "--env-kwarg", "match_duration=0.5", "--opponent", "self",
                 "--hp", "learning_rate=0.001", "--eval-every", "0", "--checkpoint-every", "0",
                 "--out", str(run), "--no-progress"]) == 0
    config = json.loads((run / "config.json").read_text())
    assert config["batched"] is True and config["n_workers"] == 2
    assert (run / "final_policy.npz").is_file()
    with pytest.raises(SystemExit):
        main(["train", "--env", "soccer_env/Match-v0", "--batched", "--env-kwarg",
              "render_mode=rgb_array", "--steps", "64", "--out", str(tmp_path / "no"),
              "--no-progress"])
    assert "does not render" in capsys.readouterr().err
