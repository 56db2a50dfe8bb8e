"""``soccer-env rate``: a tiny round robin, its table and JSON, and refused input."""

from __future__ import annotations

import json

import pytest

from agents.baselines import SSL_TEAM_2V2
from soccer_lab.commands.rate import main, parse_team


def test_a_tiny_round_robin_prints_the_ratings_and_writes_every_match(tmp_path, capsys):
    out = tmp_path / "r.json"
    assert main(["--team", "scripted", "--team", "idle", "--team", "ssl-team-2v2", "--matches",
                 "2", "--duration", "3", "--workers", "1", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "| side | Elo |" in text and "| scripted | 1000 |" in text
    report = json.loads(out.read_text())
    assert report["teams"] == ["scripted", "idle", "ssl-team-2v2"]
    assert len(report["head_to_head"]) == 3
    assert {r["label"] for r in report["ratings"]} == set(report["teams"])


def test_a_team_plays_on_its_own_observation_mode():
    side = parse_team("scripted@perceived", "truth", "ssl-2012")
    assert side.obs_mode == "perceived" and side.perception == {
        "vision": "ssl-2012", "ball_filter": "ekf", "robot_prediction": "constant-velocity"}
    side = parse_team("idle", "perceived", "realistic", "commands", ball_filter="kick")
    assert side.perception == {"vision": "realistic", "ball_filter": "kick",
                               "robot_prediction": "commands"}
    side = parse_team("idle", "perceived", "ssl-2012", "commands", "kidsize-2012")
    assert side.perception == {"camera": "kidsize-2012"}


def test_humanoid_teams_are_rated_on_their_cameras(tmp_path, capsys):
    out = tmp_path / "rating.json"
    assert main(["--team", "scripted", "--team", "idle", "--robot", "humanoid-2012",
                 "--obs-mode", "perceived", "--game", "--matches", "2", "--duration", "2",
                 "--workers", "1", "--json", str(out)]) == 0
    report = json.loads(out.read_text())
    assert report["env_kwargs"]["robot"] == "humanoid-2012" and report["env_kwargs"]["game"]
    assert len(report["head_to_head"]) == 1
    side = parse_team("ssl-team-2v2", "truth", "ssl-2012")
    assert side.obs_mode == "truth" and side.policy == str(SSL_TEAM_2V2)


def test_a_team_trained_without_the_game_flow_is_rated_under_it(tmp_path, capsys):
    import soccer_env
    from agents.policies import NumpyPolicy
    from agents.studies.matches import widened_team

    assert main(["--team", "scripted", "--team", "ssl-team-2v2", "--game", "--matches", "1",
                 "--duration", "2", "--workers", "1"]) == 0
    assert "| ssl-team-2v2 |" in capsys.readouterr().out
    env = soccer_env.parallel_env(blue=2, yellow=2, game=True)
    wide = widened_team(NumpyPolicy.load(SSL_TEAM_2V2), env, "blue").save(tmp_path / "g.npz")
    env.close()
    with pytest.raises(SystemExit):
        main(["--team", "scripted", "--team", str(wide)])
    assert "takes observations of 72 entries" in capsys.readouterr().err


@pytest.mark.parametrize("argv, message", [
    (["--team", "scripted"], "two or more different teams"),
    (["--team", "scripted", "--team", "scripted"], "two or more different teams"),
    (["--team", "scripted", "--team", "robots"], "must be one of"),
    (["--team", "scripted", "--team", "idle@raw"], "the mode after @"),
    (["--team", "scripted", "--team", "missing.npz"], "no such file"),
    (["--team", "scripted", "--team", "idle", "--matches", "0"], "--matches must be >= 1"),
    (["--team", "scripted", "--team", "idle", "--anchor", "other"], "--anchor must be one"),
    (["--team", "scripted", "--team", "idle", "--duration", "0"], "--duration must be"),
    (["--team", "scripted", "--team", "idle", "--robot-prediction", "smith"],
     "--robot-prediction: invalid choice"),
    (["--team", "scripted", "--team", "idle", "--ball-filter", "magic"],
     "--ball-filter: invalid choice"),
])
def test_bad_input_is_refused_naming_the_option(argv, message, capsys):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    assert message in capsys.readouterr().err
