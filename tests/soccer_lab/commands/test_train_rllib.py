"""``soccer-env train --backend rllib`` end to end on Ray on this machine: a run folder with
signed checkpoints, the resume command it prints, and the checkpoints of others refused.
Skipped without Ray (the main suite); ``make test-rllib`` runs it."""

from __future__ import annotations

import json

import pytest

pytest.importorskip("ray.rllib")

from soccer_lab.cli import main  # noqa: E402

#: A short keeper run: 2 iterations of 100 steps on one env runner, a tiny network.
TINY = ["--backend", "rllib", "--actions", "guard", "--num-env-runners", "1", "--n-envs", "1",
        "--hp", "train_batch_size_per_learner=100", "--hp", "minibatch_size=50",
        "--hp", "num_epochs=1", "--hp", 'model_config={"fcnet_hiddens": [8]}',
        "--checkpoint-every", "100", "--seed", "2"]


def test_train_resume_and_refuse_others_checkpoints(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    run = tmp_path / "run"
    assert main(["train", *TINY, "--steps", "200", "--out", str(run)]) == 0
    out = capsys.readouterr().out
    assert "iteration 2: 200 steps" in out and "1 node(s) sampled" in out
    final = run / "final_checkpoint"
    assert f"continue with: soccer-env train --backend rllib --resume {final} --steps 400" in out
    config = json.loads((run / "config.json").read_text())
    assert config["backend"] == "rllib" and config["actions"] == "guard"
    assert config["num_env_runners"] == 1 and config["hyperparams"]["num_epochs"] == 1
    assert "ray" in config["versions"]
    lines = [json.loads(line) for line in (run / "results.jsonl").read_text().splitlines()]
    assert [r["steps"] for r in lines] == [100, 200]
    assert all(len(r["steps_by_node"]) == 1 for r in lines)
    summary = json.loads((run / "summary.json").read_text())
    assert summary["steps"] == 200 and len(summary["cluster_nodes"]) == 1
    assert list(summary["steps_by_node"].values()) == [200]
    assert (run / "checkpoints" / "checkpoint_100_steps" / "soccer_env_signature.json").is_file()
    assert (final / "soccer_env_signature.json").is_file()

    # --resume continues the run in its folder (and picks the rllib backend by itself). The
    # run's checkpoint interval is below what its config.json may set: given again, as the
    # printed command does.
    assert "--steps 400 --checkpoint-every 100" in out
    again = ["--checkpoint-every", "100"]
    assert main(["train", "--resume", str(run / "checkpoints" / "checkpoint_100_steps"),
                 "--steps", "300", *again, "--no-progress"]) == 0
    assert "trained 200 steps" in capsys.readouterr().out
    lines = [json.loads(line) for line in (run / "results.jsonl").read_text().splitlines()]
    assert [r["steps"] for r in lines] == [100, 200, 200, 300]
    assert json.loads((run / "summary.json").read_text())["steps"] == 300

    # Nothing left to train; a checkpoint of another account (another signing key).
    with pytest.raises(SystemExit):
        main(["train", "--resume", str(final), "--steps", "300", *again])
    assert "leaves nothing to train" in capsys.readouterr().err
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "someone_else"))
    with pytest.raises(SystemExit):
        main(["train", "--resume", str(final), "--steps", "400", *again])
    err = capsys.readouterr().err
    assert "not a checkpoint of your own runs" in err and "--trust" in err


def test_an_address_where_no_cluster_answers(tmp_path, capsys):
    # Port 1 of the loopback interface: refused at once (Ray would retry for minutes).
    with pytest.raises(SystemExit):
        main(["train", *TINY, "--address", "127.0.0.1:1", "--out", str(tmp_path / "run")])
    err = capsys.readouterr().err
    assert "no Ray cluster answers at 127.0.0.1:1" in err and "ray start --head" in err
    assert not (tmp_path / "run").exists()


def test_the_options_rllib_takes_are_fields_of_its_configuration():
    import dataclasses

    from agents.runs.rllib_runs import RllibTrainConfig
    from soccer_lab.commands.train_options import TRAIN_OPTIONS

    fields = {f.name for f in dataclasses.fields(RllibTrainConfig)}
    for option in TRAIN_OPTIONS:
        if option.field is not None and "rllib" in option.backends:
            assert option.field in fields, option.flag
