"""The training configuration: validated, round-trips through a dict."""

from __future__ import annotations

import pytest

pytest.importorskip("stable_baselines3")

from agents.runs.training import TrainConfig  # noqa: E402


def test_config_round_trip():
    cfg = TrainConfig(env_kwargs={"obs_mode": "raw"}, hyperparams={"gamma": 0.98})
    assert TrainConfig.from_dict(cfg.to_dict()) == cfg
    with pytest.raises(ValueError, match="unknown training config key"):
        TrainConfig.from_dict({"steps": 5})
    with pytest.raises(ValueError, match="algorithm must be one of"):
        TrainConfig(algorithm="DQN")
    with pytest.raises(ValueError, match="actions must be one of"):
        TrainConfig(actions="wheels")


def test_recurrent_ppo_and_frame_stack_are_validated():
    pytest.importorskip("sb3_contrib")
    for spelling in ("recurrent-ppo", "RecurrentPPO", "RECURRENTPPO", "recurrent_ppo"):
        assert TrainConfig(algorithm=spelling).algorithm == "RECURRENTPPO"
    cfg = TrainConfig(algorithm="recurrent-ppo", hyperparams={"n_steps": 128})
    assert TrainConfig.from_dict(cfg.to_dict()) == cfg
    # RecurrentPPO's own signature: PPO's arguments, no replay buffer.
    with pytest.raises(ValueError, match=r"unknown RECURRENTPPO hyperparameter\(s\) "
                                         r"\['buffer_size'\]"):
        TrainConfig(algorithm="recurrent-ppo", hyperparams={"buffer_size": 10})
    assert TrainConfig(frame_stack=4).frame_stack == 4
    with pytest.raises(ValueError, match="frame_stack must be an integer >= 1"):
        TrainConfig(frame_stack=0)
    with pytest.raises(ValueError, match="RecurrentPPO's LSTM carries the memory"):
        TrainConfig(algorithm="recurrent-ppo", frame_stack=2)
    with pytest.raises(ValueError, match="frame_stack is for soccer_env/Goalkeeper-v0 only"):
        TrainConfig(env_id="soccer_env/Match-v0", frame_stack=2)
    with pytest.raises(ValueError, match="opponent 'self'"):
        TrainConfig(env_id="soccer_env/Match-v0", algorithm="recurrent-ppo", opponent="self")


def test_default_policy_kwargs_merge_with_the_configuration():
    pytest.importorskip("sb3_contrib")
    from agents.runs.training.environments import training_env

    cfg = TrainConfig(algorithm="recurrent-ppo", n_envs=1, n_workers=0, normalize_obs=False,
                      hyperparams={"policy_kwargs": {"net_arch": [16]}, "n_steps": 64})
    venv, params = training_env(cfg, None)
    venv.close()
    assert params["policy_kwargs"] == {"lstm_hidden_size": 64, "net_arch": [16]}
    assert params["n_steps"] == 64 and params["batch_size"] == 64  # one rollout at most


def test_checkpoint_steps_reads_the_model_file_without_loading_it(tmp_path):
    from agents.baselines import baseline_path
    from agents.runs.training import checkpoint_steps

    assert checkpoint_steps(baseline_path("keeper-ppo-truth", "zip")) == 1_000_000
    (tmp_path / "bad.zip").write_text("not a zip")
    with pytest.raises(ValueError, match="not a stable-baselines3 model file"):
        checkpoint_steps(tmp_path / "bad.zip")


def test_checkpoint_steps_reads_within_the_file_budget(tmp_path, monkeypatch):
    """A model file whose JSON unpacks to more than the budget is refused before it is read."""
    import zipfile

    from agents.policies import files
    from agents.policies.files import UnsafeFileError
    from agents.runs.training import checkpoint_steps

    path = tmp_path / "big.zip"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("data", '{"num_timesteps": 5, "pad": "' + "x" * 4000 + '"}')
    assert checkpoint_steps(path) == 5
    monkeypatch.setattr(files, "MAX_FILE_BYTES", 1000)
    with pytest.raises(UnsafeFileError, match="unpacks to"):
        checkpoint_steps(path)


def test_worker_timeout_is_validated_and_an_older_config_without_it_resumes():
    assert TrainConfig().worker_timeout == 60.0
    cfg = TrainConfig(worker_timeout=5)
    assert cfg.worker_timeout == 5.0 and TrainConfig.from_dict(cfg.to_dict()) == cfg
    for bad in (0, -1.0, float("inf"), float("nan"), "30", True, None):
        with pytest.raises(ValueError, match="worker_timeout must be a finite number of "
                                             "seconds > 0"):
            TrainConfig(worker_timeout=bad)
    older = TrainConfig().to_dict()
    del older["worker_timeout"]  # a config.json written before the setting existed
    assert TrainConfig.from_dict(older).worker_timeout == 60.0


@pytest.mark.slow
def test_a_stopped_worker_ends_training_with_a_checkpoint(tmp_path, monkeypatch, no_hang):
    """An environment that stops its own worker (SIGSTOP) mid-run: training ends within the
    worker timeout as for a worker that died, naming the worker; the model of the last
    completed update is saved and the message says how to resume."""
    import time

    from faulty_envs import HangingAfter

    import agents.vec.factories as factories
    from agents.runs.folders import TrainingStopped
    from agents.runs.training import train

    real = factories.goalkeeper_env_fn
    monkeypatch.setattr(factories, "goalkeeper_env_fn",
                        lambda *a, **k: HangingAfter(real(*a, **k), after=200, how="stop"))
    cfg = TrainConfig(total_steps=10_000, n_envs=2, n_workers=2, worker_timeout=1.0,
                      out=str(tmp_path / "run"), hyperparams={"n_steps": 64}, eval_every=0,
                      checkpoint_every=0, progress_bar=False)
    t0 = time.monotonic()
    with pytest.raises(TrainingStopped) as err:
        train(cfg)
    assert time.monotonic() - t0 < 60.0
    stopped = err.value
    assert stopped.reason == "worker failed"
    text = str(stopped)
    assert "rollout worker 0" in text and "stopped answering: no reply within 1 s" in text
    # As for an environment that raises at the same step: each environment's 201st step
    # falls in the 4th rollout of 2 x 64 steps, so the checkpoint has 3 updates, 384 steps.
    assert stopped.steps == 384
    assert stopped.checkpoint == tmp_path / "run" / "checkpoints" / "model_384_steps.zip"
    assert stopped.checkpoint.is_file()
    assert f"--resume {stopped.checkpoint} --steps 10000" in text
