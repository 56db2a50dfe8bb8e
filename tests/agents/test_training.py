"""The training configuration: validated, round-trips through a dict."""

from __future__ import annotations

import pytest

pytest.importorskip("stable_baselines3")

from agents.training import TrainConfig  # noqa: E402


def test_config_round_trip():
    cfg = TrainConfig(env_kwargs={"obs_mode": "raw"}, hyperparams={"gamma": 0.98})
    assert TrainConfig.from_dict(cfg.to_dict()) == cfg
    with pytest.raises(ValueError, match="unknown training config key"):
        TrainConfig.from_dict({"steps": 5})
    with pytest.raises(ValueError, match="algorithm must be one of"):
        TrainConfig(algorithm="DQN")
    with pytest.raises(ValueError, match="actions must be one of"):
        TrainConfig(actions="wheels")
