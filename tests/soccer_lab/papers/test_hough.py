"""``soccer-env paper hough``: exact without noise, reproducible, outputs written."""

from __future__ import annotations

import pytest

from soccer_lab.cli import main
from soccer_lab.papers import hough

pytestmark = pytest.mark.slow


def test_without_camera_noise_every_estimate_is_exact(tmp_path):
    res = hough.run(tmp_path, trials=1, pixel_sigma=0.0, pose_sigma=0.0, heading_sigma=0.0,
                    sway_sigma=0.0)
    cam = res["camera"]
    assert max(cam["mean_m"].values()) < 1e-6
    assert max(cam["single_m"]) < 1e-6
    assert (tmp_path / "paper_hough.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_reproducible_and_fusion_beats_the_average_robot(tmp_path):
    a = hough.run(tmp_path / "a", trials=2, seed=4)
    b = hough.run(tmp_path / "b", trials=2, seed=4)
    assert a["text"] == b["text"]
    cam = a["camera"]
    # Five robots' bearings fused beat what one robot alone knows, on average.
    assert cam["by_count_m"][5] < cam["by_count_m"][1]
    assert "Paper 000" in a["text"]


def test_command_line_and_bad_arguments(tmp_path, capsys):
    assert main(["paper", "hough", "--trials", "1", "--out", str(tmp_path)]) == 0
    assert "| head camera" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        main(["paper", "hough", "--trials", "0", "--out", str(tmp_path)])
    with pytest.raises(ValueError, match="sway_sigma"):
        hough.run(tmp_path, trials=1, sway_sigma=-1.0)
