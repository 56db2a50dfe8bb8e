"""``soccer-env imitate``: a tiny run through the command line, bad input refused."""

from __future__ import annotations

import json

import pytest

from soccer_lab.cli import main

pytest.importorskip("torch")

_ENV = ["--robot", "humanoid-2012", "--obs-mode", "perceived", "--env-kwarg",
        'perception={"camera": "kidsize-2012", "ball_tracker": "kick"}']


def test_imitate_trains_a_run_the_evaluation_reads(tmp_path, capsys):
    run = tmp_path / "run"
    assert main(["imitate", *_ENV, "--rounds", "1", "--episodes", "2", "--frame-stack", "2",
                 "--hidden", "8", "--epochs", "1", "--eval-episodes", "2", "--workers", "1",
                 "--out", str(run)]) == 0
    text = capsys.readouterr().out
    assert "round 0:" in text and "held-out save rate" in text and "steps/s" in text
    config = json.loads((run / "config.json").read_text())
    assert config["command"][:2] == ["soccer-env", "imitate"] and config["frame_stack"] == 2
    assert main(["eval", "--policy", str(run), *_ENV, "--episodes", "1", "--workers", "1",
                 "--video", "0", "--out", str(tmp_path / "ev")]) == 0
    with pytest.raises(SystemExit):  # the folder holds a run
        main(["imitate", *_ENV, "--out", str(run)])
    assert "already holds a run" in capsys.readouterr().err


def test_imitate_refuses_bad_options(tmp_path, capsys):
    with pytest.raises(SystemExit):
        main(["imitate", "--out", str(tmp_path / "a")])  # truth observations
    assert "obs_mode='truth'" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["imitate", *_ENV, "--rounds", "0", "--out", str(tmp_path / "b")])
    assert "rounds must be an integer >= 1" in capsys.readouterr().err
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()
