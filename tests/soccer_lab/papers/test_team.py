"""``soccer-env paper team``: humanoid matches and keeper under each ball estimation."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from saved_figures import saved_figures

from soccer_lab.papers import team
from soccer_lab.papers.common import lock_on

pytestmark = pytest.mark.slow


def test_team_benchmark_measures_every_configuration_and_writes_its_outputs(tmp_path: Path):
    res = team.run(tmp_path, matches=1, duration=3.0, shots=2, workers=1)
    table = res["matches"]["configs"]
    assert list(table) == list(team.MATCH_CONFIGS)
    for r in table.values():
        assert r["mean_m"] > 0.0 and r["median_m"] > 0.0  # perceived, never exact
        assert 0.0 <= r["good_share"] <= 1.0
        assert r["localization_median_m"] < 0.5  # the robots know where they are
        assert 0.0 < r["steady_rmse_m"] and r["mean_m"] <= r["rmse_m"]
    assert list(res["keeper"]["configs"]) == list(team.KEEPER_CONFIGS)
    assert res["keeper"]["configs"]["truth"]["ball_rmse_m"] == 0.0
    for suffix in ("md", "csv", "json", "png"):
        assert (tmp_path / f"paper_team.{suffix}").stat().st_size > 0
    data = json.loads((tmp_path / "paper_team.json").read_text())
    assert data["paper"]["gain"] == 0.48
    assert "Xu et al. 2012, hardware: 48%" in res["text"]


def test_kicks_and_collisions_are_told_apart_and_lock_on_is_counted():
    dt = 1.0 / 60.0
    v = np.zeros((120, 2))
    v[10:60] = (3.0, 0.0) - np.arange(50)[:, None] * (0.5 * dt, 0.0)  # kicked, then rolling
    v[60:] = (-1.0, 0.5)  # off a post: slower, another direction
    steps, kicked = team.ball_events(v)
    assert steps.tolist() == [10, 60] and kicked.tolist() == [True, False]
    err = np.ones(30)
    err[12:] = 0.5
    err[14] = 2.0  # one step off: the run starts again
    assert lock_on(err, 10, 30, 1.0, 3) == 5
    assert lock_on(err, 10, 16, 1.0, 3) is None


def test_team_benchmark_rejects_bad_arguments(tmp_path: Path):
    with pytest.raises(ValueError, match="matches must be an integer >= 1"):
        team.run(tmp_path, matches=0)
    with pytest.raises(ValueError, match=r"duration must be in \[1, 3600\]"):
        team.run(tmp_path, duration=0.1)


def test_figure_legends_cover_no_data_and_the_title_names_the_robots(tmp_path, monkeypatch):
    from soccer_env.render.plots import legend_overlaps, legends

    figures = saved_figures(monkeypatch, team)
    team.run(tmp_path, matches=1, duration=1.0, workers=1, keeper=False)
    (fig,) = figures
    labels = {t.get_text() for leg in legends(fig) for t in leg.get_texts()}
    assert set(team.MATCH_CONFIGS) <= labels and legend_overlaps(fig) == []
    title = fig.axes[0].get_title()
    assert "humanoid-2012 humanoids on the humanoid-2012 field" in title
    assert "kidsize-2012" in title
    # The cumulative share starts at 0 error and is 1 where the axis ends.
    for line in fig.axes[0].lines[:len(team.MATCH_CONFIGS)]:
        x, y = line.get_data()
        assert x[0] == 0.0 and y[0] == 0.0 and y[-1] == pytest.approx(1.0)
