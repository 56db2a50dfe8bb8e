"""The benchmarks behind ``benchmarks/*.py``: the keepers' save rates and the rollout rates'
report."""

from __future__ import annotations

import pytest

from soccer_lab import bench


def test_keeper_save_rates_evaluate_each_keeper_on_the_same_shots():
    res = bench.keeper_save_rates(episodes=4, workers=1)
    assert list(res) == ["scripted", "idle"]
    for r in res.values():
        assert r.episodes == 4 and sum(r.outcomes.values()) == 4
    lines = bench.format_save_rates(res).splitlines()
    assert [line.split()[0] for line in lines] == ["scripted", "idle"]
    assert all("over 4 shots" in line for line in lines)


def test_rollout_rates_report_medians_and_ratios():
    rates = {"worker-16x2": [900.0, 1000.0, 1100.0], "subproc-2": [400.0, 500.0, 600.0],
             "dummy-2": [200.0, 250.0, 300.0]}
    text = bench.format_rollout_rates(rates, {"obs_mode": "truth"})
    assert text.splitlines()[0] == ("Goalkeeper-v0 {'obs_mode': 'truth'}, PPO rollouts, "
                                    "median of 3:")
    assert "x4.00 vs dummy-2" in text and "(900-1,100)" in text
    assert list(rates) == list(bench.ROLLOUT_CONFIGS)


def test_the_bench_command_runs_in_a_fresh_interpreter():
    """``soccer-env bench`` at a tiny size, in a process of its own (as a user runs it: nothing
    imported beforehand registers the environments for it)."""
    import json
    import subprocess
    import sys

    code = ("import sys; from soccer_lab.cli import main; sys.exit(main(['bench', '--json', "
            "'--steps', '200', '--match-steps', '100', '--repeats', '1']))")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=300)
    assert res.returncode == 0, res.stderr
    out = json.loads(res.stdout)
    assert out["goalkeeper"]["steps_per_s"] > 0 and out["match_6v6_div_b"]["steps_per_s"] > 0
    assert set(out["perceived"]) == set(bench.PERCEIVED_PRESETS)


def test_bench_times_the_batched_environments_against_single_ones(capsys):
    """``soccer-env bench --batch N``: the batched Goalkeeper and 2 vs 2 match VecEnv beside
    their single counterparts, in the table and the JSON; a bad --batch is refused."""
    import json

    from soccer_lab.cli import main

    assert main(["bench", "--batch", "4", "--steps", "100", "--match-steps", "40",
                 "--repeats", "1", "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    batched = res["batched"]
    assert batched["batch"] == 4
    for key in ("goalkeeper", "match_2v2_scripted"):
        r = batched[key]
        assert r["single_env_steps_per_s"] > 0 and r["batched_env_steps_per_s"] > 0
        assert r["ratio"] > 0
    assert "batched (4 environments" in bench.format_table(res)
    with pytest.raises(SystemExit):
        main(["bench", "--batch", "-1"])
    assert "--batch must be in 0..65536" in capsys.readouterr().err


def test_bench_profiles_a_perceived_step(capsys):
    """``soccer-env bench --profile CASE``: the top functions of a perceived step by their own
    time per step, as a table and as JSON; the estimators' and sensors' functions show up."""
    import json

    from soccer_lab.cli import main

    assert main(["bench", "--profile", "goalkeeper", "--steps", "120", "--top", "40"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("goalkeeper, perceived (ssl-2012):")
    assert "own us/step" in text and "sensors/overhead.py" in text
    assert main(["bench", "--profile", "humanoid-match", "--match-steps", "30", "--top", "5",
                 "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    assert res["perception"] == "kidsize-2012" and len(res["functions"]) == 5
    own = [f["own_us_per_step"] for f in res["functions"]]
    assert own == sorted(own, reverse=True) and res["steps_per_s"] > 0
    with pytest.raises(SystemExit):
        main(["bench", "--profile", "goalkeeper", "--top", "0"])
    assert "--top must be >= 1" in capsys.readouterr().err


def test_bench_compile_times_cold_and_warm_kernel_caches():
    """``soccer-env bench --compile``'s measure on its cheapest case: a fresh interpreter
    compiles with an empty kernel cache, and the next one loads what it saved."""
    name = "Goalkeeper-v0, truth"
    res = bench.bench_compile([name], steps=20)
    cold, warm = res[name]["cold"], res[name]["warm"]
    times = ("import_s", "first_step_s", "steps_per_s")
    assert min(cold[k] for k in times) > 0 and min(warm[k] for k in times) > 0
    # The cold interpreter compiled its kernels and saved them; the warm one compiled none.
    assert cold["compiled"] > 0 and cold["loaded"] == 0
    assert warm["compiled"] == 0 and warm["loaded"] == cold["compiled"]
    assert name in bench.format_compile(res)
    with pytest.raises(ValueError, match="case must be one of"):
        bench.bench_compile(["no such case"])


def test_bench_pixels_times_the_pixels_detector_against_truth(capsys):
    """``soccer-env bench --pixels`` at a tiny size: both environments, a rate and a cost."""
    pytest.importorskip("cv2", reason="the pixels detector needs the 'pixels' extra (OpenCV)")
    from soccer_lab.cli import main

    assert main(["bench", "--pixels", "--json", "--steps", "30", "--match-steps", "50",
                 "--repeats", "1"]) == 0
    import json

    res = json.loads(capsys.readouterr().out)
    assert list(res) == list(bench.PIXELS_CASES)
    for r in res.values():
        assert r["steps_per_s"] > 0 and r["cost_vs_truth"] > 0
