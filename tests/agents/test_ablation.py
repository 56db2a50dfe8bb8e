"""The estimator ablation (agents.studies.ablation): numbers that do not depend on how the work is
split, outputs that parse, the oracle's zero error and cost, an extensible registry, and clear
errors for bad input."""

import csv
import dataclasses
import json
from pathlib import Path

import pytest

from agents.studies import ablation_settings as ablation
from agents.studies.ablation import (
    ESTIMATOR_CONFIGS,
    HUMANOID_CONFIGS,
    EstimatorConfig,
    parse_names,
    register_config,
    run_ablation,
    write_outputs,
)
from estimators.registry import Registry
from soccer_env.presets.sensors import VISION

PRESETS = ["ideal", "realistic"]
CONFIGS = ["truth", "ekf"]
EPISODES = 10


@pytest.fixture(scope="module")
def runs():
    """The same tiny ablation on 1 and 2 workers, with seed chunks of 4 (3 jobs per cell)."""
    return {w: run_ablation("scripted", EPISODES, PRESETS, CONFIGS, start_seed=3, workers=w,
                            chunk_size=4) for w in (1, 2)}


def _numbers(res):
    return {k: (r.saved, r.outcomes, r.steps, r.ball_rmse_m, r.saves, r.ci_low, r.ci_high)
            for k, r in res.cells.items()}


def test_workers_do_not_change_the_numbers(runs):
    one, two = runs[1], runs[2]
    assert one.workers == 1 and two.workers == 2
    assert _numbers(one) == _numbers(two)
    assert set(one.cells) == {(p, c) for p in PRESETS for c in CONFIGS}
    for r in one.cells.values():
        assert r.episodes == EPISODES and len(r.saved) == EPISODES
        assert r.saves == sum(r.saved) and sum(r.outcomes.values()) == EPISODES
        assert 0 <= r.ci_low <= r.save_rate <= r.ci_high <= 1


def test_chunking_only_splits_the_work(runs):
    whole = run_ablation("scripted", EPISODES, ["realistic"], ["ekf"], start_seed=3,
                         workers=1, chunk_size=EPISODES)
    a, b = whole.cell("realistic", "ekf"), runs[1].cell("realistic", "ekf")
    assert a.saved == b.saved and a.outcomes == b.outcomes and a.steps == b.steps
    assert a.ball_rmse_m == pytest.approx(b.ball_rmse_m, rel=1e-12)


def test_same_shots_in_every_cell(runs):
    # Truth observations with ideal vision are the plain evaluation of the scripted keeper.
    from agents.runs.evaluation import evaluate

    ref = evaluate("scripted", {"obs_mode": "truth", "perception": {"vision": "ideal"}},
                   episodes=EPISODES, start_seed=3)
    cell = runs[1].cell("ideal", "truth")
    assert cell.saved == ref.saved and cell.steps == ref.steps


def test_truth_is_free_and_exact_perception_is_not(runs):
    res = runs[1]
    for preset in PRESETS:
        truth = res.cell(preset, "truth")
        assert truth.ball_rmse_m == 0.0 and truth.estimator_us_per_step == 0.0
        ekf = res.cell(preset, "ekf")
        assert ekf.estimator_us_per_step > 0
        assert ekf.env_kwargs == {"obs_mode": "perceived",
                                  "perception": {"vision": preset, "ball_filter": "ekf"}}
    assert res.cell("realistic", "ekf").ball_rmse_m > 1e-3  # millimetre noise, 45 ms latency


def test_outputs_are_written_and_parse(runs, tmp_path: Path):
    res = runs[2]
    files = write_outputs(res, tmp_path / "out")
    assert {p.name for p in files.values()} == {"ablation.md", "ablation.csv", "ablation.json",
                                               "ablation.png"}
    md = files["md"].read_text()
    assert "Policy `scripted`" in md and "soccer-env ablation --policy scripted" in md
    assert "| sensor preset | truth | ekf |" in md and "| realistic | ekf |" in md
    with files["csv"].open() as fh:
        rows = list(csv.DictReader(fh))
    assert [(r["preset"], r["config"]) for r in rows] == [(p, c) for p in PRESETS
                                                          for c in CONFIGS]
    for row in rows:
        cell = res.cell(row["preset"], row["config"])
        assert int(row["saves"]) == cell.saves and int(row["episodes"]) == EPISODES
        assert float(row["ball_rmse_mm"]) == pytest.approx(1000 * cell.ball_rmse_m)
        assert sum(int(v) for k, v in row.items() if k.startswith("outcome_")) == EPISODES
    data = json.loads(files["json"].read_text())
    assert data["settings"]["policy"] == "scripted" and data["settings"]["episodes"] == EPISODES
    assert data["settings"]["seeds"] == [3, 3 + EPISODES - 1]
    assert set(data["configs"]) == set(CONFIGS) and data["configs"]["ekf"]["ball_filter"] == "ekf"
    assert len(data["cells"]) == len(PRESETS) * len(CONFIGS)
    for cell in data["cells"]:
        assert cell["saved"] == [int(s) for s in res.cell(cell["preset"], cell["config"]).saved]
    png = files["png"].read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000


def test_plot_legend_covers_no_bar_and_the_title_names_the_setting(runs):
    from agents.studies.ablation_report import figure
    from soccer_env.render.plots import legend_overlaps, legends, pyplot

    fig = figure(runs[1])
    try:
        fig.tight_layout()  # as plot() lays it out before saving
        bars = [p for ax in fig.axes for p in ax.patches]
        assert len(bars) == 3 * len(PRESETS) * len(CONFIGS)
        assert legend_overlaps(fig) == []
        labels = [t.get_text() for leg in legends(fig) for t in leg.get_texts()]
        assert labels == CONFIGS + ["95 % Wilson interval"]
        title = fig.get_suptitle()
        assert "Goalkeeper-v0" in title and f"{EPISODES} shots per bar" in title
        assert "SSL robots on the ssl-div-b field" in title
        assert fig.axes[-1].get_xlabel() == "sensor preset (overhead vision)"
    finally:
        pyplot().close(fig)


def test_registry_holds_the_required_configurations():
    for name in ("truth", "raw", "kf", "ekf", "ekf-improved"):
        assert ESTIMATOR_CONFIGS[name].name == name
    assert ESTIMATOR_CONFIGS["truth"].obs_mode == "truth"
    assert ESTIMATOR_CONFIGS["raw"].obs_mode == "raw"
    kf = ESTIMATOR_CONFIGS["kf"]
    assert kf.obs_mode == "perceived" and kf.ball_filter == "kf"
    assert ESTIMATOR_CONFIGS["ekf-improved"].ball_filter == "ekf-improved"
    assert ablation.default_presets() == list(VISION)
    assert parse_names(None, ESTIMATOR_CONFIGS, "configs") == list(ESTIMATOR_CONFIGS)
    # The registries' descriptions are the configurations' own.
    for registry in (ESTIMATOR_CONFIGS, HUMANOID_CONFIGS):
        for name, config in registry.items():
            assert registry.description(name) == config.description
    assert ablation.robot_kind("humanoid").configs is HUMANOID_CONFIGS
    assert list(ablation.ROBOT_KINDS) == ["ssl", "humanoid"]


def _with_copied_ssl_registry(monkeypatch) -> Registry:
    """Point the SSL robot kind at a copy of its registry (the real one stays untouched);
    return the copy."""
    copy = Registry(ESTIMATOR_CONFIGS.family, [(n, c, ESTIMATOR_CONFIGS.description(n))
                                               for n, c in ESTIMATOR_CONFIGS.items()])
    kinds = ablation.ROBOT_KINDS
    monkeypatch.setattr(ablation, "ROBOT_KINDS", Registry(kinds.family, [
        (name, dataclasses.replace(kind, configs=copy) if name == "ssl" else kind,
         kinds.description(name)) for name, kind in kinds.items()]))
    return copy


def test_a_registered_configuration_is_run(monkeypatch):
    registry = _with_copied_ssl_registry(monkeypatch)
    new = register_config(EstimatorConfig("ls-test", "perceived", "test entry", "tests",
                                          perception={"ball_filter": "ls"}))
    assert registry["ls-test"] is new and registry.description("ls-test") == "test entry"
    assert ablation.robot_kind("ssl").configs is registry
    assert "ls-test" not in ESTIMATOR_CONFIGS  # the real registry is untouched
    assert parse_names("all", registry, "configs")[-1] == "ls-test"
    with pytest.raises(ValueError, match="already registered"):
        register_config(EstimatorConfig("ls-test", "raw", "again"))
    register_config(EstimatorConfig("ls-test", "perceived", "replaced",
                                    perception={"ball_filter": "ls"}), replace=True)
    # Jobs carry their environment arguments: workers need not know the registry.
    res = run_ablation("scripted", 2, "realistic", "truth,ls-test", workers=2)
    cell = res.cell("realistic", "ls-test")
    assert cell.env_kwargs["perception"] == {"vision": "realistic", "ball_filter": "ls"}
    assert cell.episodes == 2 and cell.ball_rmse_m > 0
    assert "`ls-test` (perceived): replaced." in res.markdown()


@pytest.mark.parametrize("kwargs, match", [
    ({"configs": "truth,nope"}, r"unknown estimator configuration\(s\) 'nope'; allowed: "
                                r"truth,raw,kf,"),
    ({"presets": "foggy"}, r"unknown sensor preset\(s\) 'foggy'; allowed: ideal,ssl-2012,"),
    ({"presets": ""}, "no sensor preset"),
    ({"configs": "ekf,ekf"}, "more than once: ekf"),
    ({"episodes": 0}, "episodes must be an integer >= 1, got 0"),
    ({"episodes": 2.5}, "episodes must be an integer >= 1"),
    ({"workers": 0}, "workers must be >= 1, got 0"),
    ({"chunk_size": 0}, "chunk_size must be >= 1, got 0"),
    ({"policy": "no-such-policy"}, "policy must be one of"),
])
def test_bad_arguments_raise(kwargs, match):
    args = {"policy": "scripted", "episodes": 1, "presets": "ideal", "configs": "truth",
            "workers": 1, **kwargs}
    with pytest.raises(ValueError, match=match):
        run_ablation(**args)


@pytest.mark.parametrize("kwargs, match", [
    ({"obs_mode": "telepathy"}, r"obs_mode of configuration 'x' must be one of \['truth'"),
    ({"perception": {"vision": "harsh"}}, r"unknown perception key\(s\) \['vision'\]"),
    ({"perception": {"ball_filter": "magic"}}, "ball_filter must be one of"),
    ({"env_kwargs": {"obs_mode": "raw"}}, r"must not set \['obs_mode'\]"),
    ({"name": "a,b"}, "without commas"),
])
def test_bad_configurations_raise(kwargs, match):
    args = {"name": "x", "obs_mode": "perceived", "description": "d", **kwargs}
    with pytest.raises(ValueError, match=match):
        EstimatorConfig(**args)
    with pytest.raises(TypeError):
        register_config({"name": "x"})


def test_a_saved_policy_runs_like_the_reference(tmp_path: Path):
    import gymnasium as gym
    import numpy as np

    from agents.policies import NumpyPolicy

    env = gym.make("soccer_env/Goalkeeper-v0")
    n_obs, n_act = env.observation_space.shape[0], env.action_space.shape[0]
    low, high = env.action_space.low, env.action_space.high
    env.close()
    # A network whose output is all zeros: the idle keeper.
    zero = NumpyPolicy([("linear", np.zeros((n_act, n_obs)), np.zeros(n_act))], "clip", low,
                       high)
    path = zero.save(tmp_path / "zero.npz")
    saved = run_ablation(path, 4, "realistic", "truth,raw", workers=2)
    idle = run_ablation("idle", 4, "realistic", "truth,raw", workers=1)
    assert saved.policy == str(path) and idle.policy == "idle"
    assert _numbers(saved) == _numbers(idle)


def test_humanoid_ablation_runs_the_team_estimators_on_head_camera_presets(tmp_path: Path):
    res = run_ablation("scripted", 2, "kidsize-2012", "truth,own,fusion-mfbpf", workers=1,
                       robot="humanoid")
    cell = res.cell("kidsize-2012", "fusion-mfbpf")
    assert cell.env_kwargs["robot"] == "humanoid-2012"
    assert cell.env_kwargs["perception"] == {"camera": "kidsize-2012", "fusion": "inverse",
                                             "ball_tracker": "mfbpf"}
    assert res.cell("kidsize-2012", "truth").ball_rmse_m == 0.0
    assert cell.ball_rmse_m > 0.0 and cell.estimator_us_per_step > 0.0
    assert res.command().startswith("soccer-env ablation --robot humanoid")
    files = write_outputs(res, tmp_path)
    assert "soccer_env.presets.HEAD_CAMERAS" in files["md"].read_text()
    from agents.studies.ablation_report import figure
    from soccer_env.render.plots import pyplot

    fig = figure(res)
    assert "humanoid-2012 humanoids on the humanoid-2012 field" in fig.get_suptitle()
    assert fig.axes[-1].get_xlabel() == "head-camera preset"
    pyplot().close(fig)
    assert ablation.default_presets("humanoid") == ["ideal", "kidsize-2012", "kidsize"]
    with pytest.raises(ValueError, match="unknown sensor preset"):
        run_ablation("scripted", 1, "realistic", "own", robot="humanoid")
    with pytest.raises(ValueError, match="robot must be one of"):
        run_ablation("scripted", 1, robot="nao")
