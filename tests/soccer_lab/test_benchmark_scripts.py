"""The learning-study scripts under ``benchmarks/``: every recipe's commands are valid
``soccer-env`` command lines, and the first-frame oracle hides the kick as documented."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import soccer_env  # noqa: F401

ROOT = Path(__file__).resolve().parents[2]


def _script(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "benchmarks" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("preset", ["ssl-2012", "realistic"])
def test_every_recipe_is_a_valid_command(preset, tmp_path):
    pytest.importorskip("stable_baselines3")
    from soccer_lab.commands import evaluate as evaluate_cmd
    from soccer_lab.commands import train as train_cmd

    recipes = _script("learning_recipes")
    for name in recipes.RECIPES:
        train, evaluate = recipes.commands(preset, name, 1000, tmp_path)
        assert train[:2] == ["soccer-env", "train"]
        p = train_cmd.parser()
        cfg = train_cmd.train_config(p.parse_args(train[2:]), {})
        assert cfg.total_steps == 1000 and cfg.seed == 0
        # The suite evaluation runs on the plain preset, with the recipe's observation.
        eargs = evaluate_cmd.parser().parse_args(evaluate[2:])
        assert eargs.perception == preset and eargs.episodes == 1000
        eval_kwargs = cfg.eval_env_kwargs or cfg.env_kwargs
        assert eval_kwargs.get("perception") == preset
        assert ("belief_features=true" in evaluate) == bool(
            cfg.env_kwargs.get("belief_features"))


def test_oracle_hides_the_kick_until_the_first_frame():
    bounds = _script("keeper_bounds")
    env = bounds.oracle_env(perception="ssl-2012", control_dt=0.04)
    truth = gym.make("soccer_env/Goalkeeper-v0", obs_mode="truth", perception="ssl-2012",
                     control_dt=0.04)
    obs, info = env.reset(seed=3)
    tobs, _ = truth.reset(seed=3)
    kick, blind = info["shot"]["delay"], env.blind
    assert blind == pytest.approx(0.5 / 25 + 0.08)
    for _ in range(40):
        t = env.unwrapped.world.time
        ball_velocity = obs[9:11]
        if t < kick + blind:
            assert np.all(ball_velocity == 0.0)
        else:
            np.testing.assert_allclose(obs, tobs, atol=1e-6)
        obs, _, term, *_ = env.step(np.zeros(6, np.float32))
        tobs, *_ = truth.step(np.zeros(6, np.float32))
        if term:
            break


def test_true_velocity_keeps_the_belief_but_the_ball_velocity():
    """The humanoid bound's observation: the perceived one with the true ball velocity in the
    believed body frame (the keeper's pose and the ball's position stay believed)."""
    bounds = _script("keeper_bounds")
    kwargs = {"robot": "humanoid-2012", "perception": "kidsize-2012"}
    env = bounds.true_velocity_env(**kwargs)
    plain = gym.make("soccer_env/Goalkeeper-v0", obs_mode="perceived", **kwargs)
    obs, _ = env.reset(seed=5)
    pobs, _ = plain.reset(seed=5)
    oracle = bounds.oracle_env(**kwargs)
    assert oracle.blind == pytest.approx(0.5 / 25 + 0.04)  # the head camera's figures
    fastest = 0.0
    for _ in range(100):
        others = [i for i in range(len(obs)) if i not in (9, 10)]
        np.testing.assert_array_equal(obs[others], pobs[others])
        c, s = obs[2], -obs[3]
        v = env.unwrapped.world.snapshot().ball[3:5]
        np.testing.assert_allclose(obs[9:11], [c * v[0] + s * v[1], -s * v[0] + c * v[1]],
                                   atol=1e-5)
        fastest = max(fastest, float(np.hypot(*v)))
        obs, _, term, trunc, _ = env.step(np.zeros(6, np.float32))
        pobs, *_ = plain.step(np.zeros(6, np.float32))
        if term or trunc:
            break
    assert fastest > 1.0  # the shot was checked in flight


def test_kick_tracker_parts_table_has_every_variant_and_leaves_the_registry(capsys):
    from soccer_env.perception import BALL_TRACKERS

    parts = _script("kick_tracker_parts")
    before = list(BALL_TRACKERS)
    assert parts.main(["--episodes", "2"]) == 0
    out = capsys.readouterr().out
    assert all(f"| {name} | " in out for name in parts.VARIANTS)
    assert list(BALL_TRACKERS) == before
    with pytest.raises(SystemExit):
        parts.main(["--variants", "kick,faster"])


def test_keeper_lock_on_counts_frames_from_the_shot(capsys):
    bench = _script("keeper_lock_on")
    assert bench.main(["--episodes", "2", "--trackers", "kick"]) == 0
    row = [line for line in capsys.readouterr().out.splitlines() if line.startswith("| kick")]
    assert len(row) == 1
    frames = bench.shot_lock_on("kick", 0)
    assert frames is None or 1.0 <= frames < 20.0  # the first frame after the kick comes late


def test_soak_reports_memory_growth_per_million_steps(capsys):
    """The soak benchmark at a tiny size: it samples RSS and the Python heap and reports
    their slopes; a least-squares slope of a straight line is its gradient."""
    soak = _script("soak")
    assert soak.slope_per_million([0, 500_000, 1_000_000], [10.0, 12.0, 14.0]) == \
        pytest.approx(4.0)
    assert soak.main(["--env", "goalkeeper", "--steps", "300", "--every", "100",
                      "--warmup", "0", "--tracemalloc", "--json"]) == 0
    import json

    result = json.loads(capsys.readouterr().out)
    assert [s["steps"] for s in result["samples"]] == [100, 200, 300]
    assert result["rss_final_mb"] > 0 and np.isfinite(result["rss_mb_per_million_steps"])
    assert result["heap_mb_per_million_steps"] is not None


def test_match_workers_benchmark_reports_each_worker_count(tmp_path, capsys):
    pytest.importorskip("stable_baselines3")
    bench = _script("match_workers")
    out = tmp_path / "figures.json"
    assert bench.main(["--matches", "2", "--steps", "5", "--rounds", "2", "--sizes", "1",
                       "--workers", "0", "2", "--json", str(out)]) == 0
    import json

    figures = json.loads(out.read_text())["1v1"]
    assert set(figures) == {"0", "2"}
    assert figures["0"]["ratio_to_baseline"] == 1.0
    assert all(len(f["env_steps_per_s"]) == 2 and f["median"] > 0 for f in figures.values())
    assert "2 workers" in capsys.readouterr().out


def test_batched_physics_layouts_agree_until_the_patches_round_differently(capsys):
    """The design measurement of the batched simulation: both layouts step the same worlds;
    the shared space differs from separate spaces only in rounding (coordinates offset by
    each environment's patch), not in behaviour."""
    bench = _script("batched_physics")
    t_sep, s_sep = bench.measure(bench.Spaces, 4, 1, 20)
    t_sh, s_sh = bench.measure(bench.Shared, 4, 1, 20)
    assert t_sep > 0 and t_sh > 0 and s_sep.shape == s_sh.shape == (8, 6)
    np.testing.assert_allclose(s_sh, s_sep, atol=1e-9)
    assert bench.main(["--sizes", "1", "2", "--steps", "3"]) == 0
    assert "shared" in capsys.readouterr().out


def test_batched_keeper_benchmark_reports_rates_and_memory(tmp_path, capsys):
    bench = _script("batched_keeper")
    out = tmp_path / "figures.json"
    assert bench.main(["--sizes", "2", "--steps", "3", "--rounds", "1", "--memory", "3",
                       "--json", str(out)]) == 0
    import json

    figures = json.loads(out.read_text())
    assert figures["single"]["median"] > 0 and figures["batch 2"]["ratio_to_single"] > 0
    # Chipmunk's share of the same run bounds the batch's rate from above.
    batch = figures["batch 2"]
    assert batch["physics_ceiling"] > batch["median"]
    assert np.isfinite(figures["bytes_per_env"])  # (a few worlds may fit in freed memory)
    assert "bytes per environment" in capsys.readouterr().out


def test_batched_match_benchmark_reports_the_table_and_memory(tmp_path, capsys):
    """One round of the batched-match benchmark at tiny sizes (no VMAS): both process counts
    for every batch size, the unbatched rate and the memory per match."""
    pytest.importorskip("stable_baselines3")
    bench = _script("batched_match")
    out = tmp_path / "figures.json"
    assert bench.main(["--batches", "1", "3", "--rounds", "1", "--target", "40",
                       "--memory", "3", "--json", str(out)]) == 0
    import json

    figures = json.loads(out.read_text())
    assert set(figures["rates"]) == {"ours:1:1", "ours:1:3", "ours:2:1", "ours:2:3"}
    assert all(v[0] > 0 for v in figures["rates"].values()) and figures["unbatched_1"][0] > 0
    assert np.isfinite(figures["bytes_per_match"])
    text = capsys.readouterr().out
    assert "ours 2 proc" in text and "bytes per match" in text


def test_known_kick_tells_the_filter_the_true_kick_time():
    """The kick-time bound's environment: the kick-aware filter's motion after the shot
    starts at the shot's true kick time; a filter without ``kick()`` is refused."""
    bounds = _script("ball_filter_bounds")
    env = bounds.known_kick_env(obs_mode="perceived",
                                perception={"vision": "ssl-2012", "ball_filter": "kick"})
    _, info = env.reset(seed=3)
    tracker = env.unwrapped.pipelines[0].ball_tracker
    kick = info["shot"]["delay"]
    for _ in range(int(kick / 0.04) + 12):  # past the kick and the vision's latency
        env.step(np.zeros(6, np.float32))
    assert tracker.kick_time == pytest.approx(kick, abs=1e-9)
    ekf = bounds.known_kick_env(obs_mode="perceived", perception="ssl-2012")
    with pytest.raises(ValueError, match="kick"):
        ekf.reset(seed=3)


def test_true_velocity_once_moving_waits_for_the_belief_to_move():
    """The lag bound's observation: the perceived one until the believed ball moves faster
    than the threshold, the true ball velocity from then on (also when the belief slows)."""
    bounds = _script("keeper_bounds")
    kwargs = {"robot": "humanoid-2012", "perception": "kidsize-2012"}
    env = bounds.TrueVelocityOnceMoving(
        gym.make("soccer_env/Goalkeeper-v0", obs_mode="perceived", **kwargs), threshold=0.3)
    plain = gym.make("soccer_env/Goalkeeper-v0", obs_mode="perceived", **kwargs)
    obs, _ = env.reset(seed=5)
    pobs, _ = plain.reset(seed=5)
    moving, switched = False, 0
    for _ in range(150):
        moving = moving or float(np.hypot(*pobs[9:11])) > 0.3
        if moving:
            c, s = obs[2], -obs[3]
            v = env.unwrapped.world.snapshot().ball[3:5]
            np.testing.assert_allclose(obs[9:11], [c * v[0] + s * v[1], -s * v[0] + c * v[1]],
                                       atol=1e-5)
            switched += 1
        else:
            np.testing.assert_array_equal(obs, pobs)
        obs, _, term, trunc, _ = env.step(np.zeros(6, np.float32))
        pobs, *_ = plain.step(np.zeros(6, np.float32))
        if term or trunc:
            break
    assert switched > 0  # the belief saw the shot
    obs, _ = env.reset(seed=6)  # each episode starts on the belief again
    np.testing.assert_array_equal(obs, plain.reset(seed=6)[0])


def test_game_flow_counts_a_matchs_time_and_events(capsys):
    flow = _script("game_flow")
    row = flow.play("ssl", 1, 2.0, seed=0)
    assert row["playing_seconds"] == 2.0
    assert row["match_seconds"] >= 2.0  # the clock stops while nobody may play the ball
    assert row["finished"] == (row["match_seconds"] < flow.MAX_RATIO * 2.0)
    assert all(isinstance(v, int) and v > 0 for v in row["events"].values())
    flow.report([row, {**row, "match_seconds": 2 * row["match_seconds"]}])
    text = capsys.readouterr().out
    ratio = 1.5 * row["match_seconds"] / 2.0
    assert f"| match time / playing time | {ratio:.2f} (" in text
    assert "| matches not over after 10 times their playing time | " in text
    with pytest.raises(SystemExit):
        flow.main(["--matches", "0"])
    with pytest.raises(SystemExit):
        flow.main(["--team", "missing.npz"])


def test_game_flow_counts_each_teams_fouls_with_a_team_file(capsys, tmp_path):
    """A team that never slows down at a stop fouls; every foul is put on the team that
    committed it, the file's team on either colour."""
    from agents.policies import NumpyPolicy

    flow = _script("game_flow")
    env = soccer_env.parallel_env(blue=1, yellow=1, game=True)
    n = env.observation_space("blue_0").shape[0]
    env.close()
    reckless = NumpyPolicy([("linear", np.zeros((6, n)), np.array([1.0, 0, 0, 0, 0, 0]))],
                           "clip", -np.ones(6), np.ones(6))
    path = str(reckless.save(tmp_path / "reckless.npz"))
    rows = [flow.play("ssl", 1, 4.0, seed=1, team_file=path, team_blue=blue)
            for blue in (True, False)]
    for row in rows:
        assert sum(row["by_team"].values()) == sum(
            v for k, v in row["events"].items() if k in flow.FOULS)
        assert any(k.startswith("team:") and v > 0 for k, v in row["by_team"].items())
    flow.report(rows)
    assert "| fouls, team | " in capsys.readouterr().out


def test_ssl_serve_measures_the_stepped_rate_and_the_cameras_in_real_time():
    pytest.importorskip("ssl_protocol")
    serve = _script("ssl_serve")
    s = serve.stepped(1, "ssl-2012", 60)
    assert s["steps"] == 60 and s["frames"] > 0 and s["dropped"] == 0
    r = serve.realtime(1, "ssl-2012", 0.6)
    assert r["cameras"] == 4 and all(v == pytest.approx(25.0, rel=0.01)
                                     for v in r["rate_per_camera"].values())
    assert r["delay_ms"][0] == pytest.approx(80.0, abs=0.1)  # ssl-2012: 80 ms, no jitter


def test_ssl_closed_loop_compares_the_served_keeper_with_the_keeper_in_process():
    pytest.importorskip("ssl_protocol")
    out = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "ssl_closed_loop.py"),
                          "--policy", "scripted", "--env-kwarg", "control_dt=0.04",
                          "--env-kwarg", "obs_mode=\"perceived\"",
                          "--env-kwarg", "perception=\"ssl-2012\"", "--shots", "12",
                          "--realtime-seconds", "1.5", "--matches", "2", "--match-seconds", "3"],
                         capture_output=True, text=True, timeout=300, check=True).stdout
    assert "in process:          " in out and "% of 12 (95 %:" in out
    assert "through the sockets: " in out and "0 steps missed" in out
    assert "real time, 1.5 s: " in out and "actions/s" in out
    assert "ssl-team-2v2 (blue) against the scripted team, 2 matches" in out
    assert "served: 180 steps in " in out
