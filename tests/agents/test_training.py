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
