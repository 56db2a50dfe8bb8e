"""The package's evaluation, training and match adapter read the full infos: flat ones are
refused at once, with the argument named."""

import pytest

from agents.runs.evaluation import evaluate
from agents.runs.training import TrainConfig, check_env_kwargs
from agents.vec.match import MatchVecEnv


def test_evaluate_refuses_flat_infos():
    with pytest.raises(ValueError, match="evaluate reads the environments' full infos: "
                                         "info_mode must be 'full'"):
        evaluate("scripted", {"info_mode": "flat"}, episodes=1)


def test_training_refuses_flat_infos_before_it_starts(tmp_path):
    cfg = TrainConfig(env_kwargs={"info_mode": "flat"}, out=str(tmp_path / "run"))
    with pytest.raises(ValueError, match="info_mode must be 'full'"):
        check_env_kwargs(cfg)
    cfg = TrainConfig(eval_env_kwargs={"info_mode": "flat"}, out=str(tmp_path / "run"))
    with pytest.raises(ValueError, match="training's evaluation reads"):
        check_env_kwargs(cfg)
    check_env_kwargs(TrainConfig(env_kwargs={"info_mode": "full"}))


def test_match_vec_env_refuses_flat_infos():
    with pytest.raises(ValueError, match="MatchVecEnv reads"):
        MatchVecEnv({"blue": 1, "yellow": 1, "info_mode": "flat"})
