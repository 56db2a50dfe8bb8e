"""``soccer-env paper meanshift``: fast-manoeuvring robots of two teams filmed by the MiroSot
overhead camera, each tracked by Li et al.'s (2010) mean-shift PF (20 particles, identity check by
the player dots) and by the plain PF with 20 and 200 particles: outputs written, every tracker
kind measured with consistent figures, the identity check tells team-mates apart, the figures
do not depend on the workers, bad arguments rejected."""

from __future__ import annotations

import csv
import json
import math

import cv2
import numpy as np
import pytest
from saved_figures import saved_figures

from soccer_env import presets
from soccer_env.sensors.images.overhead import OverheadRenderer
from soccer_env.sensors.images.patterns import PATTERN, PATTERN_IDS
from soccer_env.sim.world import World
from soccer_lab.papers import meanshift
from soccer_lab.papers.meanshift.scene import IdentityCheck

pytestmark = pytest.mark.slow

#: Figures that do not depend on timing.
FIGURES = ("median_px", "p90_px", "rmse_px", "median_mm", "rmse_mm", "lost_share",
           "off_target_share", "on_teammate_share")


@pytest.fixture(scope="module")
def short_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("meanshift")
    return out, meanshift.run(out, seed=3, workers=2, episodes=2, duration=2.0)


def test_outputs_written(short_run):
    out, res = short_run
    names = {p.rsplit("/", 1)[-1] for p in res["files"]}
    assert names == {f"paper_meanshift.{e}" for e in ("md", "csv", "json", "png")}
    assert (out / "paper_meanshift.md").read_text().strip() == res["text"].strip()
    assert (out / "paper_meanshift.png").stat().st_size > 0
    data = json.loads((out / "paper_meanshift.json").read_text())
    assert set(data["summary"]) == set(meanshift.KINDS)
    assert data["episodes"] == 2 and data["frame"] == meanshift.FRAME
    with (out / "paper_meanshift.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    # One pooled row and one row per episode for every tracker kind.
    assert sorted((r["episode"], r["tracker"]) for r in rows) == sorted(
        (ep, k) for k in meanshift.KINDS for ep in ("all", "3", "4"))
    assert res["seconds"] > 0.0


def test_every_tracker_kind_measured_consistently(short_run):
    _, res = short_run
    summary = res["summary"]
    assert set(summary) == {"ms-pf-20", "ms-pf-20-paper", "pf-20", "pf-200"}
    data = json.loads((short_run[0] / "paper_meanshift.json").read_text())
    mm_per_px = 1e3 * data["metres_per_pixel"]
    for kind, s in summary.items():
        for key in ("median_px", "p90_px", "rmse_px", "median_mm", "rmse_mm"):
            assert math.isfinite(s[key]) and s[key] >= 0.0, (kind, key)
        assert s["median_px"] <= s["p90_px"]
        assert s["median_mm"] == pytest.approx(s["median_px"] * mm_per_px)
        assert s["rmse_mm"] == pytest.approx(s["rmse_px"] * mm_per_px)
        for key in ("off_target_share", "on_teammate_share"):
            assert 0.0 <= s[key] <= 1.0
        # An estimate on a team-mate is off its own robot.
        assert s["on_teammate_share"] <= s["off_target_share"]
        assert s["ms_per_update"] > 0.0
        cdf = np.asarray(s["error_cdf"])
        assert np.all(np.diff(cdf) >= 0.0) and 0.0 <= cdf[0] and cdf[-1] <= 1.0
        assert kind in res["text"]
    # Only the mean-shift PF reports lost tracks.
    assert 0.0 <= summary["ms-pf-20"]["lost_share"] <= 1.0
    assert summary["pf-20"]["lost_share"] is None and summary["pf-200"]["lost_share"] is None
    # The mean-shift PF tracks: finite errors, well within a robot radius at the median.
    ms = summary["ms-pf-20"]
    assert ms["median_px"] < data["robot_radius_px"]
    assert ms["off_target_share"] < 0.5
    diag = data["ms_pf_diagnostics"]
    for key in ("true_area_fail_share", "true_id_fail_share", "lost_while_passable_share"):
        assert 0.0 <= diag[key] <= 1.0
    assert res["cycle_ms"] > res["prep_ms_per_frame"] > 0.0
    # The paper's claims and the aims are printed, with a verdict.
    assert meanshift.PAPER["text"] in res["text"] and meanshift.AIMS["text"] in res["text"]
    assert res["text"].count("met (") + res["text"].count("not met (") >= 2
    assert isinstance(res["aims"]["accurate"], bool)
    assert isinstance(res["aims"]["under_5_ms"], bool)


def test_figures_do_not_depend_on_workers(short_run, tmp_path):
    _, res = short_run
    again = meanshift.run(tmp_path, seed=3, workers=1, episodes=2, duration=2.0)
    for kind in meanshift.KINDS:
        for key in FIGURES:
            assert again["summary"][kind][key] == res["summary"][kind][key], (kind, key)


def test_identity_check_tells_team_mates_apart():
    robot = presets.robot(meanshift.ROBOT)
    rend = OverheadRenderer("clean", meanshift.FIELD, robot, presets.ball("ssl"), [0, 0, 0])
    world = World(meanshift.FIELD, presets.ball("ssl"), robot, 3, 0)
    world.reset(np.array([[-0.6, 0.3, 0.4], [0.0, -0.2, 2.0], [0.6, 0.4, -1.3]]), (0.0, 0.6))
    state = world.snapshot()
    frame = rend.render(state)
    table = rend.colour_table()
    pink = cv2.blur(table.probability(frame, "pink"), (meanshift.DOT_BOX,) * 2)
    green = cv2.blur(table.probability(frame, "green"), (meanshift.DOT_BOX,) * 2)
    mpp = rend.metres_per_pixel
    dots = np.array(PATTERN.dot_positions) / mpp
    u, v = rend.to_pixel(state.robots[:, 0], state.robots[:, 1])
    windows = np.column_stack([np.rint(u - 0.5 - 6), np.rint(v - 0.5 - 6),
                               np.full(3, 13), np.full(3, 13)]).astype(int)
    for own in range(3):
        check = IdentityCheck(own, [0, 1, 2], dots,
                              {j: PATTERN_IDS[j] for j in range(3)})
        check.set_images(pink, green)
        assert check(windows, None).tolist() == [j == own for j in range(3)]


@pytest.mark.parametrize("kwargs, name", [
    ({"seed": -1}, "seed"),
    ({"seed": 1.5}, "seed"),
    ({"episodes": 0}, "episodes"),
    ({"episodes": True}, "episodes"),
    ({"duration": 0.0}, "duration"),
    ({"duration": float("nan")}, "duration"),
    ({"duration": "10"}, "duration"),
    ({"workers": 0}, "workers"),
    ({"robots_per_team": 0}, "robots_per_team"),
    ({"robots_per_team": 7}, "robots_per_team"),
])
def test_bad_arguments(tmp_path, kwargs, name):
    with pytest.raises(ValueError, match=name):
        meanshift.run(tmp_path, **kwargs)


def test_figure_legends_cover_no_data_and_the_title_names_the_scene(tmp_path, monkeypatch):
    from soccer_env.render.plots import legend_overlaps, legends
    from soccer_lab.papers.meanshift import report

    figures = saved_figures(monkeypatch, report)
    meanshift.run(tmp_path, seed=3, workers=1, episodes=1, duration=1.0)
    (fig,) = figures
    labels = {t.get_text() for leg in legends(fig) for t in leg.get_texts()}
    assert set(meanshift.KINDS) <= labels and legend_overlaps(fig) == []
    assert "mirosot-middle field (2.2 m x 1.8 m)" in fig.get_suptitle()
