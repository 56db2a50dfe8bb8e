"""The settings a resumed run takes from its ``config.json`` are bounded
(:mod:`agents.runs.limits`): a received run folder cannot make a resume write a checkpoint
every step or allocate a buffer of a billion transitions, unless the user gives the setting
on the command line or trusts the file; the resume command a stopped run prints restates the
settings its own folder could not set."""

from __future__ import annotations

import json
import shlex
from pathlib import Path

import pytest

from agents.runs.limits import (
    HYPERPARAMETER_LIMITS,
    MIN_SAVE_INTERVAL,
    RUN_SETTING_LIMITS,
    SETTING_OPTIONS,
    check_saved_settings,
    resume_options,
)
from agents.runs.training.config import TrainConfig
from soccer_lab.cli_args import key_values
from soccer_lab.commands.train_options import TRAIN_OPTIONS, given_fields, parser

CONFIG = Path("received/config.json")


def test_the_default_configuration_lies_within_the_limits():
    check_saved_settings(TrainConfig().to_dict(), CONFIG)
    assert resume_options(TrainConfig().to_dict()) == []


def test_each_limited_setting_has_the_option_that_sets_it():
    flags = {o.field: o.flag for o in TRAIN_OPTIONS if o.field is not None}
    for name, option in SETTING_OPTIONS.items():
        assert flags[name] == option
    assert set(SETTING_OPTIONS) <= set(RUN_SETTING_LIMITS)


@pytest.mark.parametrize("saved,message", [
    ({"checkpoint_every": 1}, r"checkpoint_every 1 is below 10,000.*give --checkpoint-every "
                              r"to choose it \(--checkpoint-every 1 keeps it\), or --trust"),
    ({"eval_every": 5}, r"eval_every 5 is below 10,000.*--eval-every"),
    ({"eval_episodes": 10**9}, r"eval_episodes 1,000,000,000 is above 10,000.*--eval-episodes"),
    ({"n_envs": 100_000}, r"n_envs 100,000 is above 256.*--n-envs"),
    ({"n_workers": 500}, r"n_workers 500 is above 32.*--workers"),
    ({"self_play_every": 1}, r"self_play_every 1 is below.*lift it with --trust"),
    ({"torch_threads": 4096}, r"torch_threads 4,096 is above 64.*lift it with --trust"),
    ({"worker_timeout": 1e9}, r"worker_timeout 1,000,000,000.0 s is above 600 s.*"
                              r"--worker-timeout"),
    ({"worker_timeout": 0.01}, r"worker_timeout 0.01 s is below 1 s.*--worker-timeout"),
    ({"hyperparams": {"buffer_size": 10**9}},
     r"hyperparameter buffer_size 1,000,000,000 is above 1,000,000.*--hp buffer_size=\.\.\."),
    ({"hyperparams": {"n_steps": 2**30}}, r"hyperparameter n_steps .* is above 262,144"),
    ({"hyperparams": {"model_config": {"fcnet_hiddens": [8192, 8192]}}},
     r"fcnet_hiddens \[8192, 8192\] has 67,117,056 weights.*above the 4,194,304"),
])
def test_a_setting_beyond_its_limit_is_refused_naming_the_file_the_limit_and_the_flag(
        saved, message):
    with pytest.raises(ValueError, match=message) as err:
        check_saved_settings(saved, CONFIG)
    assert str(err.value).startswith(f"{CONFIG}: ")
    check_saved_settings(saved, CONFIG, trust=True)  # --trust lifts every limit


def test_a_setting_given_on_the_command_line_is_the_users_own_choice():
    check_saved_settings({"checkpoint_every": 1, "hyperparams": {"buffer_size": 10**9}},
                         CONFIG, given={"checkpoint_every"}, given_hyperparams={"buffer_size"})
    # Off (0) is always allowed for checkpoints and evaluations; types are the config's check.
    check_saved_settings({"checkpoint_every": 0, "eval_every": 0, "n_envs": "many"}, CONFIG)
    with pytest.raises(ValueError, match="fcnet_hiddens must be a list of layer sizes"):
        check_saved_settings({"hyperparams": {"model_config": {"fcnet_hiddens": "big"}}},
                             CONFIG)


def test_the_printed_resume_command_restates_what_the_file_cannot_set():
    """A run of the user's own with small intervals: the command it prints on a stop gives
    them as options, so that resuming it is not refused, and its configuration is the same."""
    cfg = TrainConfig(algorithm="sac", checkpoint_every=128, eval_every=256, n_envs=2,
                      n_workers=0, hyperparams={"buffer_size": 2 * 10**6})
    saved = json.loads(json.dumps(cfg.to_dict()))  # as the run's config.json holds it
    options = resume_options(saved)
    assert options == ["--checkpoint-every", "128", "--eval-every", "256",
                       "--hp", "buffer_size=2000000"]
    args = parser().parse_args(shlex.split(shlex.join(["--resume", "x.zip", *options])))
    given, hyper = given_fields(args, "sb3"), key_values(args.hp, "--hp")
    check_saved_settings(saved, CONFIG, given, hyper)
    assert given["checkpoint_every"] == 128 and hyper == {"buffer_size": 2 * 10**6}
    with pytest.raises(ValueError, match="checkpoint_every 128"):
        check_saved_settings(saved, CONFIG)


def test_rllib_runs_are_bounded_the_same_way():
    saved = {"backend": "rllib", "checkpoint_every": 100, "num_env_runners": 64, "n_envs": 8,
             "hyperparams": {"model_config": {"fcnet_hiddens": [4096, 4096]}}}
    with pytest.raises(ValueError, match="checkpoint_every 100"):
        check_saved_settings(saved, CONFIG)
    options = resume_options(saved)
    assert options[:4] == ["--checkpoint-every", "100", "--num-env-runners", "64"]
    assert options[4:] == ["--hp", 'model_config={"fcnet_hiddens":[4096,4096]}']
    assert MIN_SAVE_INTERVAL == RUN_SETTING_LIMITS["checkpoint_every"][0]
    assert "num_learners" in HYPERPARAMETER_LIMITS


def test_a_received_run_asking_for_a_checkpoint_every_step_writes_nothing(tmp_path, capsys):
    """``train --resume`` of a run folder whose config.json says ``checkpoint_every: 1`` (a
    2,048-step resume used to write 173 MB): refused before anything is built or written."""
    pytest.importorskip("stable_baselines3")
    from soccer_lab.cli import main

    run = tmp_path / "received"
    (run / "checkpoints").mkdir(parents=True)
    model = run / "checkpoints" / "model_128_steps.zip"
    model.write_bytes(b"PK\x05\x06" + bytes(18))  # never opened: the config is refused first
    (run / "config.json").write_text(json.dumps({**TrainConfig().to_dict(),
                                                 "checkpoint_every": 1}))
    before = sorted(p.name for p in run.rglob("*"))
    with pytest.raises(SystemExit):
        main(["train", "--resume", str(model), "--steps", "2176", "--no-progress"])
    err = capsys.readouterr().err
    assert f"--resume: {run / 'config.json'}: checkpoint_every 1 is below 10,000" in err
    assert sorted(p.name for p in run.rglob("*")) == before
