"""``soccer-env eval``: the result and the video written, bad input refused."""

from __future__ import annotations

import json
import math

import pytest

from soccer_lab.cli import main


def test_eval_command_writes_result_and_video(tmp_path, capsys):
    out = tmp_path / "ev"
    assert main(["eval", "--policy", "scripted", "--obs-mode", "perceived", "--perception",
                 "ssl-2012", "--episodes", "6", "--workers", "1", "--video", "1", "--out",
                 str(out)]) == 0
    text = capsys.readouterr().out
    assert "save rate" in text
    record = json.loads((out / "eval.json").read_text())
    assert record["episodes"] == 6 and len(record["saved"]) == 6
    assert math.isfinite(record["ball_rmse_m"])
    video = out / record["video"].split("/")[-1]
    assert video.exists() and video.stat().st_size > 1000


def test_eval_command_rejects_bad_input(tmp_path, capsys):
    with pytest.raises(SystemExit):
        main(["eval", "--episodes", "0"])
    with pytest.raises(SystemExit):
        main(["eval", "--policy", "nowhere.zip", "--out", str(tmp_path)])
    assert "no model at" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["eval", "--perception", "foggy", "--out", str(tmp_path)])


def test_eval_versus_compares_two_policies_shot_by_shot(tmp_path, capsys):
    out = tmp_path / "ev"
    assert main(["eval", "--policy", "scripted", "--versus", "idle", "--episodes", "8",
                 "--workers", "1", "--video", "0", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    record = json.loads((out / "eval.json").read_text())
    v = record["versus"]
    ours, theirs = record["saved"], v["saved"]
    assert v["a_only"] == sum(a and not b for a, b in zip(ours, theirs))
    assert v["b_only"] == sum(b and not a for a, b in zip(ours, theirs))
    assert v["difference"] == pytest.approx(record["save_rate"] - v["save_rate"])
    assert 0.0 < v["sign_test_p"] <= 1.0
    assert "versus idle" in text and "sign test p = " in text
    with pytest.raises(SystemExit):
        main(["eval", "--versus", "nowhere.npz", "--out", str(tmp_path)])
    assert "nowhere.npz" in capsys.readouterr().err
