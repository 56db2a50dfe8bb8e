"""``soccer-env paper localization``: walking humanoids (walk engine, scanning head camera,
landmarks by kind) localized from a global start by KLD-sampling and by fixed-size filters,
each seeded episode recorded once and replayed into every filter, with a kidnapping; figures
reported as medians over the episodes beside each episode's position error: KLD adapts its
particle count, tracks with small errors and recovers the kidnapped robot; outputs written;
reproducible whatever the workers; bad arguments rejected."""

from __future__ import annotations

import csv
import functools
import json
import math

import numpy as np
import pytest

from estimators import KLDConfig
from soccer_env.perception.brain import Brain
from soccer_lab.cli import main
from soccer_lab.papers import localization

pytestmark = pytest.mark.slow

KLD = "KLD-sampling (50-5000)"
SEEDED = KLD + " + triangulation seed"
FOX = KLD + ", bins of the predicted samples (Fox)"
TRI = list(localization.TRIANGULATIONS)
SEEDS = [4, 5]
#: Figures that do not depend on timing.
FIGURES = ("median_pos_m", "median_head_deg", "initial_particles", "first_second_particles",
           "tracking_particles", "tracking_particles_median", "mirror_pct", "localized_s",
           "recovery_s")


@pytest.fixture(scope="module")
def short_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("loc")
    return out, localization.run(out, duration=24.0, seed=SEEDS[0], fixed_sizes=(1000,),
                                 episodes=len(SEEDS), workers=2)


def test_kld_adapts_tracks_and_recovers(short_run):
    out, res = short_run
    assert list(res["results"]) == [KLD, FOX, SEEDED, "fixed 1000"]
    kld = res["results"][KLD]
    assert kld["episodes"] == len(SEEDS)
    # Many particles at the global start, few while tracking (our criterion: 3 times fewer).
    assert kld["initial_particles"] == KLDConfig().max_particles
    assert kld["initial_particles"] >= 3 * kld["tracking_particles"]
    assert kld["tracking_particles_median"] <= 2 * KLDConfig().min_particles
    # Small errors once converged (our criterion while walking), in every episode here.
    assert kld["median_pos_m"] < 0.15 and kld["pos_aim_episodes"] == len(SEEDS)
    assert kld["median_head_deg"] < 5.0
    # Localized from the global start in every episode, and found again after the
    # kidnapping in at least one.
    assert kld["localized_never"] == 0 and kld["localized_s"] < 16.0
    recoveries = [ep["results"][KLD]["recovery_s"] for ep in res["episodes"]]
    assert kld["recovery_never"] == sum(r is None for r in recoveries) < len(SEEDS)
    assert min(r for r in recoveries if r is not None) < 8.0 - 1.0
    fixed = res["results"]["fixed 1000"]
    assert fixed["initial_particles"] == fixed["tracking_particles"] == 1000
    assert kld["ms_per_update"] > 0.0 and fixed["ms_per_update"] > 0.0
    assert "KLD-sampling" in res["text"] and localization.AIMS in res["text"]
    assert localization.PAPER in res["text"] and "kidnapped at 16.0 s" in res["text"]
    assert (f"under 0.15 m in {len(SEEDS)} of {len(SEEDS)} episode(s): criteria met"
            in res["text"])


def test_medians_over_episodes_and_per_episode_table(short_run):
    _, res = short_run
    assert [ep["seed"] for ep in res["episodes"]] == SEEDS
    for name, r in res["results"].items():
        per = [ep["results"][name] for ep in res["episodes"]]
        for key in localization.MEDIAN_KEYS:
            vals = [p[key] for p in per if p[key] is not None]
            assert r[key] == pytest.approx(float(np.median(vals)))
        for key in ("localized_s", "recovery_s"):  # "never" counts as infinitely late
            never = [p[key] is None for p in per]
            assert r[key.replace("_s", "_never")] == sum(never)
            if sum(never) >= len(per) / 2:
                assert r[key] is None
            else:
                assert r[key] == pytest.approx(float(np.median(
                    [math.inf if p[key] is None else p[key] for p in per])))
        assert r["median_pos_m_per_episode"] == [p["median_pos_m"] for p in per]
        assert r["pos_aim_episodes"] == sum(p["median_pos_m"] < 0.15 for p in per)
    # The episodes differ (their own seeds), so the medians are not one episode's figures.
    kld = [ep["results"][KLD]["median_pos_m"] for ep in res["episodes"]]
    assert kld[0] != kld[1]
    assert res["results"][KLD]["median_pos_m"] == pytest.approx(np.mean(kld))  # two: the mean
    # The per-episode table: filters x seeds of the median position errors.
    text = res["text"]
    assert "| filter | seed 4 | seed 5 |" in text
    for name, r in res["results"].items():
        row = f"| {name} | " + " | ".join(f"{v:.3f}" for v in r["median_pos_m_per_episode"])
        assert row + " |" in text
    assert "medians over the 2 episode(s)" in text and "seeds 4-5" in text


def test_same_episode_for_every_filter_and_outputs(short_run):
    out, res = short_run
    data = json.loads((out / "paper_localization.json").read_text())
    assert data["seeds"] == SEEDS and data["episodes"] == len(SEEDS)
    assert len(data["per_episode"]) == len(SEEDS)
    for ep in data["per_episode"]:
        t = np.array(ep["frame_t"])
        assert len(t) > 0.9 * 25 * 24  # the 25 Hz camera over the episode
        for r in ep["results"].values():  # one series per frame, the same frames for all
            assert len(r["pos_err"]) == len(r["counts"]) == len(r["estimate"]) == len(t)
        assert ep["kidnap_time"] == pytest.approx(16.0, abs=0.05)
        truth = np.array(ep["truth_pose"])
        jump = np.hypot(*np.diff(truth[:, :2], axis=0).T)
        assert jump.max() >= 2.0 - 0.2  # the teleport (truth subsampled every 0.1 s)
        assert np.abs(truth[:, 0]).max() < 3.0 and np.abs(truth[:, 1]).max() < 2.0  # inside
        counts = np.array(ep["results"][KLD]["counts"])
        assert counts.max() > 10 * counts.min()  # adapts both ways (recovery grows it again)
    # Different seeds, different walks.
    a, b = (np.array(ep["truth_pose"]) for ep in data["per_episode"])
    assert not np.allclose(a, b)
    for name, r in data["summary"].items():
        assert r["median_pos_m"] == pytest.approx(res["results"][name]["median_pos_m"])
    with (out / "paper_localization.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    assert [(r["filter"], r["episode"]) for r in rows] == [
        (KLD, "median"), (FOX, "median"), (SEEDED, "median"), ("fixed 1000", "median"),
        (KLD, "4"), (FOX, "4"), (SEEDED, "4"), ("fixed 1000", "4"),
        (KLD, "5"), (FOX, "5"), (SEEDED, "5"), ("fixed 1000", "5"),
        (TRI[0], "median"), (TRI[1], "median"), (TRI[0], "4"), (TRI[1], "4"),
        (TRI[0], "5"), (TRI[1], "5")]
    assert float(rows[0]["median_pos_m"]) == pytest.approx(res["results"][KLD]["median_pos_m"])
    md = (out / "paper_localization.md").read_text()
    assert "| filter |" in md and "recovered after the kidnapping" in md
    assert "| filter | seed 4 | seed 5 |" in md
    assert (out / "paper_localization.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # The filters are fed by the robot brain's own odometry code.
    assert localization.BrainReplay.odometry_until is Brain.odometry_until
    assert localization.BrainReplay.move_localization is Brain.move_localization


def test_triangulation_alone_and_as_the_recovery_seed(short_run):
    out, res = short_run
    tri = res["triangulation"]
    assert list(tri) == TRI == ["triangulation, this frame", "triangulation, last 25 frames"]
    for name, r in tri.items():
        per = [ep["triangulation"][name] for ep in res["episodes"]]
        for p in per:  # every frame has one outcome
            assert sum(p[f"{o}_pct"] for o in localization.TRI_OUTCOMES) == pytest.approx(100.0)
            assert p["fix_pct"] == pytest.approx(p["correct_pct"] + p["wrong_pct"])
            assert p["mirror_pct"] <= p["wrong_pct"]
        for key in localization.TRI_KEYS:
            vals = [p[key] for p in per if p[key] is not None]
            assert r[key] == pytest.approx(float(np.median(vals)))
    one, many = tri[TRI[0]], tri[TRI[1]]
    # One 51-degree frame rarely holds three landmarks; the head scan's last frames do.
    assert one["too_few_pct"] > 50.0 > many["too_few_pct"]
    assert many["correct_pct"] > 3 * one["correct_pct"]
    # A correct assignment is accurate (bearings of 2 degrees); wrong ones are the field's
    # ambiguity (mostly its mirror image).
    assert many["median_pos_correct_m"] < 0.15 and many["median_head_correct_deg"] < 5.0
    assert many["wrong_pct"] > 0.0
    # Per frame: outcomes, and errors where there is a pose (-1 where none).
    data = json.loads((out / "paper_localization.json").read_text())
    ep = data["per_episode"][0]
    frames = len(ep["frame_t"])
    for name in TRI:
        outcome, err = ep["triangulation"][name]["outcome"], ep["triangulation"][name]["pos_err"]
        assert len(outcome) == len(err) == frames
        assert set(outcome) <= set(localization.TRI_OUTCOMES)
        assert all((e > localization.WRONG_M) == (o == "wrong") for o, e in zip(outcome, err)
                   if o in ("correct", "wrong"))
        assert all(e == -1.0 for o, e in zip(outcome, err) if o not in ("correct", "wrong"))
    assert data["triangulation"][TRI[1]]["correct_pct"] == pytest.approx(many["correct_pct"])
    # The seeded filter is the same filter and walk; the text compares the two.
    seeded = res["results"][SEEDED]
    assert seeded["initial_particles"] == res["results"][KLD]["initial_particles"]
    assert "Recovery seed (Xu et al.'s 2012 triangulation" in res["text"]
    assert "| triangulation, last 25 frames |" in res["text"]
    assert "fewer than three landmarks [%]" in res["text"]


def test_reproducible_whatever_the_workers_and_without_kidnapping(tmp_path, short_run):
    _, res = short_run
    # The same run inline (the fixture used two processes), timings aside.
    again = localization.run(tmp_path / "again", duration=24.0, seed=SEEDS[0],
                             fixed_sizes=(1000,), episodes=len(SEEDS), workers=1)
    for name, r in res["results"].items():
        for key in FIGURES + ("median_pos_m_per_episode",):
            assert again["results"][name][key] == r[key]
    for name, r in res["triangulation"].items():
        for key in localization.TRI_KEYS[:-1]:  # the timing aside
            assert again["triangulation"][name][key] == r[key]
    # One episode alone is the same as that seed's episode among several.
    alone = localization.run(tmp_path / "alone", duration=24.0, seed=SEEDS[1],
                             fixed_sizes=(1000,), episodes=1, workers=1)
    for name, r in alone["episodes"][0]["results"].items():
        for key in FIGURES:
            assert res["episodes"][1]["results"][name][key] == r[key]
            assert alone["results"][name][key] == r[key]  # the median of one
    assert "| filter | seed 5 |" in alone["text"] and "seed 5;" in alone["text"]
    calm = localization.run(tmp_path / "calm", duration=15.0, seed=1, fixed_sizes=(),
                            kidnap=False, episodes=2, workers=1)
    kld = calm["results"][KLD]
    assert kld["recovery_s"] is None and kld["recovery_never"] == 0
    assert "no kidnapping" in calm["text"] and "Kidnapped to" not in calm["text"]
    assert all(ep["kidnap_time"] is None for ep in calm["episodes"])
    assert math.isfinite(kld["median_pos_m"])


def test_command_line_and_bad_arguments(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(localization, "run", functools.partial(
        localization.run, duration=15.0, fixed_sizes=(100,)))
    assert main(["paper", "localization", "--out", str(tmp_path), "--walks", "2",
                 "--workers", "1"]) == 0
    printed = capsys.readouterr().out
    assert "KLD-sampling" in printed and "2 episode(s)" in printed
    assert "| filter | seed 0 | seed 1 |" in printed
    assert (tmp_path / "paper_localization.png").exists()
    monkeypatch.undo()
    with pytest.raises(SystemExit):
        main(["paper", "localization", "--out", str(tmp_path), "--walks", "0"])
    assert "--walks must be >= 1" in capsys.readouterr().err
    for duration in (1.0, 14.0, math.nan, math.inf, 4000.0):
        with pytest.raises(ValueError, match="duration"):
            localization.run(tmp_path, duration=duration)
    for sizes in ((0,), (1.5,), (True,), (-3,)):
        with pytest.raises(ValueError, match="fixed_sizes"):
            localization.run(tmp_path, duration=15.0, fixed_sizes=sizes)
    with pytest.raises(ValueError, match="seed"):
        localization.run(tmp_path, duration=15.0, seed=-1)
    for episodes in (0, -1, 1.5, True, None):
        with pytest.raises(ValueError, match="episodes"):
            localization.run(tmp_path, duration=15.0, episodes=episodes)
    for workers in (0, 2.0, False):
        with pytest.raises(ValueError, match="workers"):
            localization.run(tmp_path, duration=15.0, workers=workers)
