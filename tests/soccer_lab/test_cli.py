"""The command line a user runs: version, usage, list, bench, demo and the play command."""

import importlib.metadata
import json
import shutil
import subprocess
import sys
import types
from pathlib import Path

import pytest

from soccer_env import presets
from soccer_env.perception import options
from soccer_lab.cli import COMMANDS, main


@pytest.mark.parametrize("flag", ["--version", "-V"])
def test_version(flag, capsys):
    assert main([flag]) == 0
    assert capsys.readouterr().out == f"soccer-env {importlib.metadata.version('soccer-env')}\n"
    assert importlib.metadata.version("soccer-env") == "0.1.0"


def test_usage_lists_every_command(capsys):
    assert main(["--help"]) == 0
    text = capsys.readouterr().out
    for name, (_, summary) in COMMANDS.items():
        assert f"  {name:8s}  {summary}" in text
    assert "-V, --version" in text
    assert COMMANDS["play"][1] == "drive a robot with the keyboard against the scripted team"


def test_play_runs_the_play_command_module(monkeypatch):
    calls = []
    fake = types.ModuleType("soccer_lab.commands.play")
    fake.main = lambda argv: calls.append(argv) or 0
    monkeypatch.setitem(sys.modules, "soccer_lab.commands.play", fake)
    assert main(["play", "--robot", "ssl"]) == 0
    assert calls == [["--robot", "ssl"]]


def test_list(capsys):
    assert main(["list", "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert "soccer_env/Goalkeeper-v0" in info["gymnasium"]
    assert set(info["fields"]) == {"ssl-2012", "ssl-div-b", "ssl-div-a", "humanoid-2012",
                                   "humanoid-kid"}
    assert info["vision"] == presets.VISION.descriptions()
    assert info["ball_filters"] == options.BALL_FILTERS.descriptions()


def test_list_groups_every_name_under_a_heading(capsys):
    assert main(["list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    headings = [line for line in lines if line and not line.startswith(" ")]
    assert headings == ["Environments", "World presets (environment arguments)",
                        "Sensor presets",
                        "Perception options (perception={\"OPTION\": NAME, ...})"]
    names = {line.split()[0] for line in lines if line.startswith("    ") and
             not line.startswith("     ")}
    for family in (presets.FIELDS, presets.ROBOTS, presets.VISION, presets.HEAD_CAMERAS,
                   options.BALL_FILTERS, options.FUSIONS, options.DETECTORS):
        assert set(family) <= names


def test_unknown_command(capsys):
    assert main(["fly"]) == 2
    assert "unknown command 'fly'" in capsys.readouterr().err
    assert main(["evl"]) == 2
    assert "unknown command 'evl' (did you mean 'eval'?)" in capsys.readouterr().err


def test_bench_json(capsys):
    assert main(["bench", "--json", "--steps", "300", "--match-steps", "30",
                 "--repeats", "1"]) == 0
    res = json.loads(capsys.readouterr().out)
    for key in ("goalkeeper", "match_6v6_div_b"):
        assert res[key]["steps_per_s"] > 0 and res[key]["bare_pymunk_steps_per_s"] > 0
        assert res[key]["rsoccer_steps_per_s"] in (1700, 470)


def test_bench_rejects_bad_counts():
    with pytest.raises(SystemExit):
        main(["bench", "--steps", "0"])


def test_demo_writes_video_and_figures(tmp_path: Path, capsys):
    assert main(["demo", "--out", str(tmp_path), "--episodes", "1"]) == 0
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["episodes"][0]["outcome"] in ("goal", "stopped", "cleared", "out",
                                                  "time limit")
    for path in summary["files"].values():
        assert Path(path).stat().st_size > 1000
    assert (tmp_path / "trajectories.png").exists() and (tmp_path / "ball_speed.png").exists()
    humanoid = json.loads((tmp_path / "humanoid" / "summary.json").read_text())
    assert humanoid["robot"] == "humanoid-2012"
    for path in humanoid["files"].values():
        assert Path(path).stat().st_size > 1000
    assert Path(humanoid["files"]["video"]).stem == "humanoid_goalkeeper"
    # The humanoid field's frames have an odd height: the video still encodes as the SSL one.
    assert Path(humanoid["files"]["video"]).suffix == Path(summary["files"]["video"]).suffix


def test_console_script_installed():
    exe = shutil.which("soccer-env") or str(Path(sys.executable).parent / "soccer-env")
    out = subprocess.run([exe, "--help"], capture_output=True, text=True, check=True)
    assert "demo" in out.stdout and "bench" in out.stdout
    out = subprocess.run([exe, "--version"], capture_output=True, text=True, check=True)
    assert out.stdout == "soccer-env 0.1.0\n"


def test_ruff_clean():
    ruff = shutil.which("ruff") or str(Path(sys.executable).parent / "ruff")
    if not Path(ruff).exists():
        pytest.skip("ruff not installed")
    root = Path(__file__).resolve().parents[2]
    res = subprocess.run([ruff, "check", "soccer_env", "estimators", "agents", "soccer_lab",
                          "tests", "benchmarks"], cwd=root, capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr


def test_the_command_line_page_documents_every_command():
    page = (Path(__file__).resolve().parents[2] / "docs" / "guide" / "command-line.md").read_text()
    for name in COMMANDS:
        assert f"`soccer-env {name}" in page, name
