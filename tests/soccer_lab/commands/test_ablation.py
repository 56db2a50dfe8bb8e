"""``soccer-env ablation``: the command runs the ablation's cells, passes environment
arguments to every cell, and exits with a message for bad command lines before any work."""

import json
from pathlib import Path

import pytest

from agents.studies import ablation
from soccer_lab.cli import main as cli_main
from soccer_lab.commands.ablation import main


def test_command_line(tmp_path: Path, capsys):
    out = tmp_path / "cli"
    assert cli_main(["ablation", "--episodes", "2", "--presets", "ssl-2012", "--configs",
                     "raw,kf", "--workers", "1", "--out", str(out), "--quiet"]) == 0
    text = capsys.readouterr().out
    assert "| ssl-2012 | raw |" in text and "| ssl-2012 | kf |" in text
    data = json.loads((out / "ablation.json").read_text())
    assert data["settings"]["configs"] == ["raw", "kf"]
    assert data["settings"]["presets"] == ["ssl-2012"]


def test_command_line_env_kwargs_reach_every_cell(tmp_path: Path, capsys):
    out = tmp_path / "dt"
    assert cli_main(["ablation", "--episodes", "2", "--presets", "ssl-2012", "--configs",
                     "truth,ekf", "--workers", "1", "--env-kwarg", "control_dt=0.04",
                     "--out", str(out), "--quiet"]) == 0
    data = json.loads((out / "ablation.json").read_text())
    assert "--env-kwarg control_dt=0.04" in data["settings"]["command"]
    cells = ablation.run_ablation("scripted", 2, "ssl-2012", "truth", workers=1,
                                  env_kwargs={"control_dt": 0.04}).cells
    assert cells[("ssl-2012", "truth")].env_kwargs["control_dt"] == 0.04


@pytest.mark.parametrize("argv, message", [
    (["--configs", "truth,nope"], "unknown estimator configuration(s) 'nope'; allowed:"),
    (["--presets", "foggy"], "unknown sensor preset(s) 'foggy'; allowed:"),
    (["--episodes", "0"], "--episodes must be >= 1, got 0"),
    (["--workers", "0"], "--workers must be >= 1, got 0"),
    (["--chunk-size", "0"], "--chunk-size must be >= 1"),
    (["--env-kwarg", "obs_mode=raw"], "set by each cell's configuration"),
    (["--env-kwarg", "control_dt"], "--env-kwarg must be key=value"),
    (["--episodes", "ten"], "invalid int value"),
    (["--policy", "missing.zip", "--episodes", "1", "--presets", "ideal", "--configs",
      "truth"], "no model at missing.zip"),
])
def test_bad_command_lines_exit_with_a_message(argv, message, capsys, tmp_path: Path):
    with pytest.raises(SystemExit) as exc:
        main([*argv, "--out", str(tmp_path / "never")])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "never").exists()


def test_match_command_line(tmp_path: Path, capsys):
    out = tmp_path / "matches"
    assert cli_main(["ablation", "--env", "soccer_env/Match-v0", "--pairs", "truth:raw",
                     "--presets", "ideal", "--matches", "2", "--team-size", "1", "--duration",
                     "2", "--workers", "1", "--out", str(out), "--quiet"]) == 0
    text = capsys.readouterr().out
    assert "# Estimator ablation in matches" in text and "| ideal | truth | raw |" in text
    assert "1 cells x 2 matches" in text
    data = json.loads((out / "match_ablation.json").read_text())
    assert data["settings"]["team_size"] == 1 and data["settings"]["duration_s"] == 2.0
    assert len(data["cells"][0]["records"]) == 2
    assert not (out / "ablation.json").exists()


@pytest.mark.parametrize("argv, message", [
    (["--env", "soccer_env/Match-v0", "--episodes", "3"],
     "--episodes applies to soccer_env/Goalkeeper-v0 only, not to --env soccer_env/Match-v0"),
    (["--env", "soccer_env/Match-v0", "--configs", "ekf", "--chunk-size", "2"],
     "--configs, --chunk-size apply to soccer_env/Goalkeeper-v0 only"),
    (["--matches", "4"], "--matches applies to soccer_env/Match-v0 only"),
    (["--env", "soccer_env/Match-v0", "--pairs", "ekf:nope"],
     "unknown estimator configuration 'nope' in pair 'ekf:nope'"),
    (["--env", "soccer_env/Match-v0", "--matches", "0"], "--matches must be >= 1, got 0"),
    (["--env", "soccer_env/Match-v0", "--duration", "-3"], "--duration must be a positive"),
    (["--env", "soccer_env/Match-v0", "--team-size", "12"], "team_size must be an integer in "
                                                            "1..11, got 12"),
    (["--env", "soccer_env/Match-v0", "--env-kwarg", "match_duration=10"],
     "the ablation sets the team sizes"),
    (["--env", "soccer_env/Match-v0", "--trust"], "--trust applies to "
                                                  "soccer_env/Goalkeeper-v0 only"),
    (["--env", "soccer_env/Shootout-v0"], "invalid choice"),
])
def test_bad_match_command_lines_exit_with_a_message(argv, message, capsys, tmp_path: Path):
    with pytest.raises(SystemExit) as exc:
        main([*argv, "--out", str(tmp_path / "never")])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "never").exists()
