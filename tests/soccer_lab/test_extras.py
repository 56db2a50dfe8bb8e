"""What a command needs beyond the base install: the table matches pyproject.toml's extras,
and a command whose extra is missing ends with one line naming it (exit status 2), before any
work and without a traceback."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import pytest

from soccer_lab import extras
from soccer_lab.cli import COMMANDS, main
from soccer_lab.papers import PAPERS

ROOT = Path(__file__).resolve().parents[2]

#: The distribution that installs each module of the table, as pyproject.toml names it.
DISTRIBUTION = {"matplotlib": "matplotlib", "pygame": "pygame", "imageio": "imageio",
                "cv2": "opencv-python-headless", "stable_baselines3": "stable-baselines3",
                "sb3_contrib": "sb3-contrib", "torch": "torch", "tensorboard": "tensorboard",
                "tqdm": "tqdm", "rich": "rich", "ray": "ray",
                "ssl_protocol": "soccer-env-ssl-protocol", "google.protobuf": "protobuf"}


def _requirement_names(specs: list[str]) -> set[str]:
    """``"ray[rllib]>=2.60,<2.61"`` -> ``"ray"``."""
    import re

    return {re.split(r"[\[<>=!~; ]", spec, maxsplit=1)[0].lower() for spec in specs}


def test_every_command_and_paper_has_an_entry():
    for name in COMMANDS:
        assert name in extras.REQUIREMENTS or name == "paper", name  # paper: per paper
    for name in PAPERS:
        assert f"paper {name}" in extras.REQUIREMENTS, name


def test_each_module_is_installed_by_the_extra_the_table_names():
    tomllib = pytest.importorskip("tomllib")
    optional = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"]
    for key, needs in extras.REQUIREMENTS.items():
        for need in needs:
            assert need.extra in optional, (key, need.extra)
            names = _requirement_names(optional[need.extra])
            for module in need.modules:
                assert DISTRIBUTION[module] in names, (key, module, need.extra)


def test_image_papers_need_opencv_and_the_others_only_matplotlib():
    for name in PAPERS:
        modules = {m for need in extras.REQUIREMENTS[f"paper {name}"] for m in need.modules}
        assert modules == ({"matplotlib", "cv2"} if name in ("meanshift", "following")
                           else {"matplotlib"}), name


def _missing(monkeypatch, *modules: str) -> None:
    """``importlib.util.find_spec`` reports ``modules`` as not installed."""
    real = importlib.util.find_spec

    def find_spec(name, *args, **kwargs):
        if name.split(".")[0] in modules:
            return None
        return real(name, *args, **kwargs)

    monkeypatch.setattr(importlib.util, "find_spec", find_spec)


@pytest.mark.parametrize("argv, module, line", [
    (["train"], "stable_baselines3",
     "soccer-env train needs the train extra: pip install 'soccer-env[train]' "
     "(missing: stable_baselines3)"),
    (["train", "--algo", "recurrent-ppo"], "sb3_contrib",
     "soccer-env train --algo recurrent-ppo needs the train extra: "
     "pip install 'soccer-env[train]' (missing: sb3_contrib)"),
    (["train"], "tqdm",
     "soccer-env train needs the train extra: pip install 'soccer-env[train]' "
     "(missing: tqdm); or train without the progress bar: --no-progress"),
    (["train", "--backend", "rllib"], "ray",
     "soccer-env train --backend rllib needs the rllib extra: "
     "pip install 'soccer-env[rllib]' (missing: ray)"),
    (["demo", "--no-video"], "matplotlib",
     "soccer-env demo needs the render extra: pip install 'soccer-env[render]' "
     "(missing: matplotlib)"),
    (["paper", "meanshift"], "cv2",
     "soccer-env paper meanshift needs the pixels extra: pip install 'soccer-env[pixels]' "
     "(missing: cv2)"),
    (["paper", "following", "--episodes", "1"], "cv2",
     "soccer-env paper following needs the pixels extra: pip install 'soccer-env[pixels]' "
     "(missing: cv2)"),
    (["paper", "ekf"], "matplotlib",
     "soccer-env paper ekf needs the render extra: pip install 'soccer-env[render]' "
     "(missing: matplotlib)"),
    (["ablation"], "matplotlib",
     "soccer-env ablation needs the render extra: pip install 'soccer-env[render]' "
     "(missing: matplotlib)"),
    (["ablation", "--robot", "humanoid"], "cv2",
     "soccer-env ablation with configuration pixels needs the pixels extra: "
     "pip install 'soccer-env[pixels]' (missing: cv2); or choose --configs without it"),
    (["eval", "--policy", "model.zip"], "stable_baselines3",
     "soccer-env eval --policy model.zip needs the train extra: "
     "pip install 'soccer-env[train]' (missing: stable_baselines3)"),
    (["bench", "--frames"], "cv2",
     "soccer-env bench --frames needs the pixels extra: pip install 'soccer-env[pixels]' "
     "(missing: cv2)"),
    (["bench", "--batch", "8"], "stable_baselines3",
     "soccer-env bench --batch 8 needs the train extra: pip install 'soccer-env[train]' "
     "(missing: stable_baselines3)"),
    (["play"], "pygame",
     "soccer-env play needs the render extra: pip install 'soccer-env[render]' "
     "(missing: pygame)"),
])
def test_a_missing_extra_ends_the_command_with_one_line(argv, module, line, monkeypatch,
                                                        capsys, tmp_path):
    _missing(monkeypatch, module)
    out = [] if argv[0] in ("bench", "play") else ["--out", str(tmp_path / "out")]
    with pytest.raises(SystemExit) as exc:
        main([*argv, *out])
    assert exc.value.code == 2
    captured = capsys.readouterr()
    assert captured.err == line + "\n"
    assert captured.out == ""
    assert not (tmp_path / "out").exists()


def test_two_missing_extras_are_named_together(monkeypatch):
    _missing(monkeypatch, "matplotlib", "cv2")
    assert extras.message("paper meanshift") == (
        "soccer-env paper meanshift needs the render and pixels extras: "
        "pip install 'soccer-env[render,pixels]' (missing: matplotlib, cv2)")
    assert extras.unavailable("video") is None
    _missing(monkeypatch, "pygame", "imageio")
    assert extras.unavailable("video") == ("pygame and imageio are not installed "
                                           "(pip install 'soccer-env[render]')")
    with pytest.raises(KeyError, match="no requirements listed for 'fly'"):
        extras.missing("fly")


def test_help_needs_no_extra(monkeypatch, capsys):
    _missing(monkeypatch, *{m for needs in extras.REQUIREMENTS.values() for need in needs
                            for m in need.modules})
    for command in ("demo", "bench", "train", "eval", "ablation", "list", "paper"):
        with pytest.raises(SystemExit) as exc:
            main([command, "--help"])
        assert exc.value.code == 0, command
    assert "--no-video" in capsys.readouterr().out


def test_the_process_exits_with_status_2_and_no_traceback():
    """As a user runs it: a fresh interpreter in which OpenCV cannot be imported."""
    code = ("import sys\n"
            "class Block:\n"
            "    def find_spec(self, name, path=None, target=None):\n"
            "        if name.split('.')[0] == 'cv2':\n"
            "            raise ModuleNotFoundError(name)\n"
            "sys.meta_path.insert(0, Block())\n"
            "from soccer_lab.cli import main\n"
            "sys.exit(main(['paper', 'meanshift', '--episodes', '1']))\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, timeout=120)
    assert res.returncode == 2
    assert res.stderr == ("soccer-env paper meanshift needs the pixels extra: "
                          "pip install 'soccer-env[pixels]' (missing: cv2)\n")
    assert res.stdout == ""


def test_eval_without_pygame_writes_its_result_and_says_why_there_is_no_video(
        tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "pygame", None)  # not installed: importing it fails
    out = tmp_path / "ev"
    assert main(["eval", "--episodes", "2", "--workers", "1", "--video", "2", "--out",
                 str(out)]) == 0
    captured = capsys.readouterr()
    assert captured.err == ("no video: pygame is not installed "
                            "(pip install 'soccer-env[render]')\n")
    record = json.loads((out / "eval.json").read_text())
    assert record["episodes"] == 2 and "video" not in record
    assert sorted(p.name for p in out.iterdir()) == ["eval.json"]
    assert "save rate" in captured.out


def test_demo_without_pygame_writes_the_figures(tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "pygame", None)
    assert main(["demo", "--out", str(tmp_path), "--episodes", "1"]) == 0
    captured = capsys.readouterr()
    assert captured.err == ("no video: pygame is not installed "
                            "(pip install 'soccer-env[render]')\n")
    for folder in (tmp_path, tmp_path / "humanoid"):
        summary = json.loads((folder / "summary.json").read_text())
        assert set(summary["files"]) == {"trajectories", "ball_speed", "estimate_error"}
        assert not list(folder.glob("*.mp4")) and not list(folder.glob("*.gif"))
