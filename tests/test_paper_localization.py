"""``soccer-env paper localization``: KLD-sampling localizes a walking robot from a global
start and tracks it with few particles; outputs written; reproducible."""

from __future__ import annotations

import pytest

from soccer_env.cli import main
from soccer_env.papers import localization


def test_kld_localizes_and_tracks_with_few_particles(tmp_path):
    res = localization.run(tmp_path, duration=20.0, fixed_sizes=(200,))
    kld = res["results"]["KLD-sampling (50-5000)"]
    assert kld["median_pos_m"] < 0.15  # issue aim while walking
    assert kld["global_particles"] >= 3 * kld["tracking_particles"]  # at least 3x fewer
    again = localization.run(tmp_path / "again", duration=20.0, fixed_sizes=(200,))
    for name, r in res["results"].items():  # the same run, timings aside
        for key in ("median_pos_m", "median_head_deg", "tracking_particles"):
            assert again["results"][name][key] == r[key]
    assert (tmp_path / "paper_localization.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_command_line_and_bad_arguments(tmp_path, capsys):
    assert main(["paper", "localization", "--out", str(tmp_path)]) == 0
    assert "KLD-sampling" in capsys.readouterr().out
    with pytest.raises(ValueError, match="duration"):
        localization.run(tmp_path, duration=1.0)
