"""The Zhao et al. (2012) benchmark: its claims as testable orderings, and its command line."""

import json
from pathlib import Path

import pytest
from saved_figures import saved_figures

from soccer_lab.cli import main
from soccer_lab.papers import ekf

pytestmark = pytest.mark.slow


def test_open_loop_orderings():
    res = ekf.open_loop(episodes=12, seed=1)["estimators"]
    steady = {k: v["position_rmse_steady_m"] for k, v in res.items()}
    # Latency compensation is what matters between collisions...
    assert steady["kf-comp"] < 0.6 * steady["kf"]
    assert steady["ekf"] < 0.5 * steady["raw"]
    # ...and the friction model helps a little on top of it.
    assert steady["ekf"] <= steady["kf-comp"] * 1.05
    for r in res.values():
        assert r["position_rmse_now_m"] > 0 and r["lock_on_after_shot_cycles"] >= 0


def test_closed_loop_structure():
    res = ekf.closed_loop(shots=4, workers=1, presets_=("realistic",))
    row = res["presets"]["realistic"]
    assert set(row) == set(ekf.CLOSED_LOOP_MODES)
    for cell in row.values():
        assert cell["shots"] == 4 and 0 <= cell["ci_low"] <= cell["save_rate"] <= cell["ci_high"]


def test_wilson_interval():
    # The closed loop's intervals come from agents.common.stats.
    from agents.common.stats import wilson

    lo, hi = wilson(90, 100)
    assert lo == pytest.approx(0.8256, abs=1e-3) and hi == pytest.approx(0.9448, abs=1e-3)


def test_paper_command_writes_tables_and_plots(tmp_path: Path, capsys):
    assert main(["paper", "ekf", "--out", str(tmp_path), "--episodes", "4", "--shots", "2",
                 "--workers", "1"]) == 0
    out = capsys.readouterr().out
    assert "Zhao et al. (2012) reports" in out and "| sensor preset |" in out
    for name in ("paper_ekf_open_loop.md", "paper_ekf_open_loop.csv",
                 "paper_ekf_closed_loop.md", "paper_ekf_closed_loop.csv",
                 "paper_ekf_trace.png", "paper_ekf_save_rates.png"):
        assert (tmp_path / name).stat().st_size > 100, name
    summary = json.loads((tmp_path / "paper_ekf_summary.json").read_text())
    assert summary["closed_loop"]["shots"] == 2
    with pytest.raises(SystemExit):
        main(["paper", "ekf", "--shots", "0"])


def test_the_floor_is_what_the_filter_gets_when_the_ball_moves_as_its_model_says():
    """A ball whose velocity wanders by N(0, delta_R^2) per 40 ms cycle, seen every cycle with
    25 mm noise: our constant-velocity Kalman filter with the paper's noise figures reaches
    the steady-state floor (within the Monte Carlo error of 3,000 cycles), at capture time and
    predicted 80 ms ahead."""
    import math

    import numpy as np

    from estimators import BallFilterConfig, BallTracker

    floor = ekf.steady_state_floor(ahead=(0.0, 0.08))
    rng = np.random.default_rng(0)
    tracker = BallTracker(BallFilterConfig(deceleration=0.0, collision_noise=False, gate=None,
                                           reset_after=None, maneuver_radius=None))
    x, v = np.zeros(2), np.array([0.3, -0.2])
    err_now, err_ahead, truth = [], [], []
    for k in range(3200):
        t = k * ekf.CYCLE
        truth.append(x.copy())
        tracker.update(t, [tuple(x + rng.normal(0.0, ekf.SIGMA, 2))], [])
        if k >= 200:  # past the start-up transient
            err_now.append(np.hypot(*(tracker.estimate(t)[:2] - x)))
            err_ahead.append(tracker.estimate(t + 0.08)[:2])
        x = x + ekf.CYCLE * v
        v = v + rng.normal(0.0, 0.1, 2)
    rms_now = math.sqrt(np.mean(np.square(err_now)))
    ahead = np.array(err_ahead[:-2]) - np.array(truth[202:])
    rms_ahead = math.sqrt(np.mean(np.sum(ahead**2, axis=1)))
    assert rms_now == pytest.approx(floor[0.0], rel=0.08)
    assert rms_ahead == pytest.approx(floor[0.08], rel=0.08)
    with pytest.raises(ValueError, match="sigma_xy"):
        ekf.steady_state_floor(sigma_xy=0.0)


def test_figures_legends_cover_no_data_and_titles_name_the_setting(tmp_path, monkeypatch):
    from soccer_env.render.plots import legend_overlaps, legends

    figures = saved_figures(monkeypatch, ekf)
    ekf.run(tmp_path, episodes=2, shots=1, workers=1)
    trace, rates = figures
    for fig in figures:
        assert legends(fig) and legend_overlaps(fig) == []
    labels = {t.get_text() for leg in legends(trace) for t in leg.get_texts()}
    assert {"raw", "ekf", "ls", "collision (wall or robot)"} <= labels
    assert "ssl-2012 field (6.1 m x 4.7 m)" in trace.axes[0].get_title()
    labels = {t.get_text() for leg in legends(rates) for t in leg.get_texts()}
    assert set(ekf.CLOSED_LOOP_MODES) | {"95 % Wilson interval"} <= labels
    assert "ssl-div-b field (9 m x 6 m)" in rates.axes[0].get_title()
