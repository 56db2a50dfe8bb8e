"""The estimator ablation in matches (agents.studies.match_ablation): each team perceives
through its own configuration under the cell's preset, the outputs parse and agree with the
matches, the command reruns it, and bad input is refused before any match."""

import csv
import json
from pathlib import Path

import pytest

from agents.studies.match_ablation import (
    DEFAULT_PAIRS,
    parse_pairs,
    run_match_ablation,
    write_outputs,
)


@pytest.fixture(scope="module")
def result():
    """Truth against raw detections under two presets, two short 2 vs 2 matches each."""
    return run_match_ablation("truth:raw", "ideal,realistic", matches=2, team_size=2,
                              duration=3.0, start_seed=4, workers=1)


def test_each_team_perceives_through_its_own_configuration(result):
    for preset in ("ideal", "realistic"):
        h = result.cell(preset, "truth", "raw")
        assert h.matches == 2 and [r.seed for r in h.records] == [4, 4]
        assert h.a.obs_mode == "truth" and h.b.obs_mode == "raw"
        assert h.a.perception == {"vision": preset} == h.b.perception
        assert h.ball_error(0) == (0.0, 0.0)
        assert h.ball_error(1)[0] > 0.0
    # Noisier vision, larger error of the raw detections.
    assert (result.cell("realistic", "truth", "raw").ball_error(1)[0]
            > result.cell("ideal", "truth", "raw").ball_error(1)[0])


def test_outputs_are_written_and_agree_with_the_matches(result, tmp_path: Path):
    files = write_outputs(result, tmp_path / "out")
    assert {p.name for p in files.values()} == {f"match_ablation.{k}"
                                               for k in ("md", "csv", "json", "png")}
    md = files["md"].read_text()
    assert "| ideal | truth | raw |" in md and "| realistic | truth | raw |" in md
    assert "soccer-env ablation --env soccer_env/Match-v0 --pairs truth:raw --presets " \
           "ideal,realistic --matches 2 --team-size 2 --duration 3 --start-seed 4" in md
    with files["csv"].open() as fh:
        rows = list(csv.DictReader(fh))
    assert [(r["preset"], r["a"], r["b"]) for r in rows] == [("ideal", "truth", "raw"),
                                                             ("realistic", "truth", "raw")]
    for row in rows:
        h = result.cell(row["preset"], "truth", "raw")
        assert int(row["wins"]) + int(row["draws"]) + int(row["losses"]) == 2
        assert int(row["goals_for"]) == h.goals_for
        assert float(row["b_ball_error_mean_mm"]) == pytest.approx(1000 * h.ball_error(1)[0])
    data = json.loads(files["json"].read_text())
    assert data["settings"]["pairs"] == [["truth", "raw"]] and data["settings"]["team_size"] == 2
    assert [c["pair"] for c in data["cells"]] == ["truth:raw", "truth:raw"]
    assert [r["a_blue"] for r in data["cells"][0]["records"]] == [True, False]
    assert set(data["configs"]) == {"truth", "raw"}
    assert files["png"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plot_legends_cover_no_data_and_the_title_names_the_setting(result):
    from agents.studies.match_ablation import figure
    from soccer_env.render.plots import legend_overlaps, legends, pyplot

    fig = figure(result)
    try:
        assert legend_overlaps(fig) == []
        labels = {t.get_text() for leg in legends(fig) for t in leg.get_texts()}
        assert {"A wins", "draws", "B wins", "no difference"} <= labels
        # One seed per cell (two matches, one from each side): no interval, said so.
        assert "mean (one seed: no interval)" in labels
        title = fig.get_suptitle()
        assert "Match-v0" in title and "teams of 2, 3 s matches, 2 per row" in title
        assert "SSL robots on the ssl-div-b field" in title
        # Rows top to bottom in table order.
        rows = sorted(fig.axes[0].get_yticklabels(), key=lambda t: -t.get_position()[1])
        assert [t.get_text() for t in rows] == ["A truth vs B raw\npreset ideal",
                                                "A truth vs B raw\npreset realistic"]
    finally:
        pyplot().close(fig)


def test_humanoid_teams_run_their_own_fusion_and_tracking():
    res = run_match_ablation(None, None, matches=1, robot="humanoid", team_size=2,
                             duration=2.0, workers=1)
    assert res.pairs == list(DEFAULT_PAIRS["humanoid"]) == [("fusion-mfbpf", "own")]
    h = res.cell("kidsize-2012", "fusion-mfbpf", "own")
    assert h.a.perception == {"camera": "kidsize-2012", "fusion": "inverse",
                              "ball_tracker": "mfbpf"}
    assert h.b.perception == {"camera": "kidsize-2012", "fusion": "own", "ball_tracker": "none"}
    assert res.env_kwargs == {"robot": "humanoid-2012"}
    # One belief per humanoid: two per team per step.
    r = h.records[0]
    assert r.err_count == (2 * r.steps, 2 * r.steps)
    assert all(e > 0 for e in r.err_sum)
    assert "--robot humanoid" in res.command() and "--env-kwarg" not in res.command()


def test_pairs_parse():
    allowed = ["ekf", "raw", "kf"]
    assert parse_pairs("ekf:raw, ekf:kf", allowed) == [("ekf", "raw"), ("ekf", "kf")]
    assert parse_pairs([("kf", "ekf"), "raw:raw"], allowed) == [("kf", "ekf"), ("raw", "raw")]
    assert parse_pairs(None, allowed) == list(DEFAULT_PAIRS["ssl"])


@pytest.mark.parametrize("kwargs, match", [
    ({"pairs": "ekf-raw"}, "a configuration pair is written A:B, got 'ekf-raw'"),
    ({"pairs": "ekf:nope"}, "unknown estimator configuration 'nope' in pair 'ekf:nope'; "
                            "allowed: truth,raw"),
    ({"pairs": "ekf:raw,ekf:raw"}, "pair.* given more than once: ekf:raw"),
    ({"pairs": ","}, "no configuration pair given"),
    ({"presets": "foggy"}, "unknown sensor preset"),
    ({"presets": "kidsize"}, "unknown sensor preset"),  # a head camera, not a vision preset
    ({"team_size": 0}, "team_size must be an integer in 1..11, got 0"),
    ({"duration": -1.0}, "duration must be a positive number of seconds"),
    ({"matches": 0}, "matches must be an integer >= 1, got 0"),
    ({"env_kwargs": {"blue": 2}}, r"must not set \['blue'\]: the ablation sets the team sizes"),
    ({"env_kwargs": {"field": "nowhere"}}, "field"),
    ({"policy": "champion"}, "policy must be 'scripted', 'idle'"),
])
def test_bad_input_is_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        run_match_ablation(**{"pairs": "ekf:raw", "matches": 2, "workers": 1,
                              "duration": 1.0, **kwargs})
