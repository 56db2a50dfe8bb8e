"""``soccer-env train --backend``: the options each backend refuses, and the message for a
missing Ray. None of this needs Ray (or starts it)."""

from __future__ import annotations

import sys

import pytest

from soccer_lab.cli import main

MATCH = ["--env", "soccer_env/Match-v0"]


@pytest.mark.parametrize("args, message", [
    (["--workers", "4"], "--workers sets stable-baselines3's subprocesses; with --backend "
                         "rllib use --num-env-runners"),
    (["--worker-timeout", "30"], "--worker-timeout sets stable-baselines3's subprocesses"),
    (["--eval-every", "1000"], "--eval-every is stable-baselines3's periodic evaluation"),
    (["--eval-episodes", "10"], "--eval-episodes is for the periodic evaluation"),
    (["--eval-obs-mode", "raw"], "--eval-obs-mode is for the periodic evaluation"),
    (["--eval-perception", "harsh"], "--eval-perception is for the periodic evaluation"),
    (["--algo", "sac"], "--algo sac: the rllib backend trains PPO only"),
    (["--critic", "privileged"], "--critic privileged is stable-baselines3's"),
    ([*MATCH, "--opponent", "league"], "--opponent league: with --backend rllib the "
                                       "opponent is 'self'"),
    (["--opponent", "scripted"], "--opponent is for soccer_env/Match-v0"),
    ([*MATCH, "--learner", "both", "--opponent", "self"], "--opponent self with --learner "
                                                          "both"),
    (["--learner", "yellow"], "--learner is for soccer_env/Match-v0"),
    (["--resume", "runs/none"], "--resume: no RLlib checkpoint at runs/none"),
])
def test_rllib_refuses_options_it_has_no_use_for(args, message, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["train", "--backend", "rllib", *args])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


@pytest.mark.parametrize("args", [["--num-env-runners", "2"], ["--address", "auto"]])
def test_sb3_refuses_the_rllib_options(args, capsys):
    with pytest.raises(SystemExit):
        main(["train", *args])
    assert f"{args[0]} is for --backend rllib" in capsys.readouterr().err


def test_an_rllib_checkpoint_is_not_resumed_by_sb3(tmp_path, capsys):
    ckpt = tmp_path / "final_checkpoint"
    ckpt.mkdir()
    (ckpt / "rllib_checkpoint.json").write_text("{}")
    with pytest.raises(SystemExit):
        main(["train", "--backend", "sb3", "--resume", str(ckpt)])
    assert "is an RLlib checkpoint: resume it with --backend rllib" in capsys.readouterr().err


def test_missing_ray_names_the_extra(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "ray", None)  # as if Ray were not installed
    with pytest.raises(SystemExit) as exc:
        main(["train", "--backend", "rllib", "--steps", "100"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("soccer-env train --backend rllib needs the rllib extra: "
                          "pip install 'soccer-env[rllib]' (missing: ray")
    assert err.count("\n") == 1 and "Traceback" not in err


def test_the_option_table_sets_each_backends_fields():
    """Each option of the table (:mod:`soccer_lab.commands.train_options`) names known
    backends, one that sets a field for the sb3 backend names a ``TrainConfig`` field, and the
    options given set their fields for the backends that take them, and only those."""
    import dataclasses

    from agents.runs.training import TrainConfig
    from soccer_lab.commands.train_options import (
        BACKENDS,
        TRAIN_OPTIONS,
        given_fields,
        parser,
    )

    fields = {f.name for f in dataclasses.fields(TrainConfig)}
    for option in TRAIN_OPTIONS:
        assert set(option.backends) <= set(BACKENDS) and set(option.refused) <= set(BACKENDS)
        if option.field is not None and "sb3" in option.backends:
            assert option.field in fields, option.flag
    args = parser().parse_args(["--steps", "5", "--n-envs", "3", "--num-env-runners", "2",
                                "--workers", "1"])
    assert given_fields(args, "sb3") == {"total_steps": 5, "n_envs": 3, "n_workers": 1}
    assert given_fields(args, "rllib") == {"total_steps": 5, "n_envs": 3,
                                           "num_env_runners": 2}


@pytest.mark.parametrize("value", ["0", "-5", "inf", "nan"])
def test_sb3_refuses_a_worker_timeout_that_is_no_positive_number_of_seconds(tmp_path, value,
                                                                           capsys):
    pytest.importorskip("stable_baselines3")
    with pytest.raises(SystemExit) as exc:
        main(["train", "--worker-timeout", value, "--no-progress", "--out",
              str(tmp_path / "x")])
    assert exc.value.code == 2
    assert "worker_timeout must be a finite number of seconds > 0" in capsys.readouterr().err
    assert not (tmp_path / "x").exists()


def test_worker_timeout_option_sets_the_configuration():
    """--worker-timeout sets TrainConfig.worker_timeout; without it a new run, or a resumed
    run whose config.json predates the setting, gets the default."""
    pytest.importorskip("stable_baselines3")
    from soccer_lab.commands.train import train_config
    from soccer_lab.commands.train_options import given_fields, parser

    args = parser().parse_args(["--worker-timeout", "12.5"])
    assert given_fields(args, "sb3") == {"worker_timeout": 12.5}
    assert train_config(args, {}).worker_timeout == 12.5
    assert train_config(parser().parse_args([]), {"n_envs": 4}).worker_timeout == 60.0
