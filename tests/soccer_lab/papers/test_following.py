"""``soccer-env paper following``: Yu et al.'s (2010) Kalman-started mean shift against plain mean
shift on a turning humanoid's head-camera frames."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from saved_figures import saved_figures

from estimators import HeadCamera
from soccer_lab.papers import following
from soccer_lab.papers.following.episode import view

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def short_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("following")
    return out, following.run(out, episodes=1, duration=1.0, seed=3, workers=1)


def test_the_run_writes_its_outputs(short_run):
    out, res = short_run
    names = sorted(p.rsplit("/", 1)[-1] for p in res["files"])
    assert names == ["paper_following.csv", "paper_following.json", "paper_following.md",
                     "paper_following.png"]
    assert (out / "paper_following.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (out / "paper_following.md").read_text().strip() == res["text"]
    data = json.loads((out / "paper_following.json").read_text())
    assert data["robot"] == "humanoid-2012" and data["episodes"] == 1
    assert len(data["episode_list"]) == len(following.VARIANTS)
    csv = (out / "paper_following.csv").read_text().splitlines()
    assert csv[0].startswith("table,variant") and len(csv) > 10
    assert "Yu et al. (2010)" in res["text"] and following.AIM in res["text"]
    assert res["seconds"] > 0.0


def test_both_trackers_are_measured_with_consistent_figures(short_run):
    _, res = short_run
    labels = [f"{tr} x{sc:g}" for sc in (1.0, 2.0) for tr in following.TRACKERS]
    for variant in (*following.VARIANTS, "all"):
        s = res["summary"][variant]
        assert s["frames"] > 0 and 0.0 <= s["out_of_view_rate"] <= 1.0
        assert set(s["trackers"]) == set(labels)
        for lab, r in s["trackers"].items():
            for key in ("lost_rate", "off_target_rate", "loss_hazard"):
                assert 0.0 <= r[key] <= 1.0, (variant, lab, key)
            assert r["frames"] == s["frames"]
            assert math.isfinite(r["median_error_px"]) and r["median_error_px"] >= 0.0
            assert math.isfinite(r["ms_per_frame"]) and r["ms_per_frame"] > 0.0
            assert 0 <= r["recoveries"] <= r["losses"]
            if r["off_target_rate"] < 1.0:
                assert math.isfinite(r["rmse_on_target_px"])
            if r["depth_frames"]:
                assert 0.0 <= r["depth_median_rel"] < 1.0  # the size gives the distance
        for row in res["turn_bins"][variant]:
            for lab in labels:
                v = row[f"{lab} off_target_rate"]
                assert math.isnan(v) if row["frames"] == 0 else 0.0 <= v <= 1.0
        assert sum(r["frames"] for r in res["turn_bins"][variant]) == s["frames"]
    assert sum(r["frames"] for r in res["jump_bins"]) == res["summary"]["all"]["frames"]
    for key, vd in res["verdicts"].items():
        assert vd["off_target"] in ("met", "not met") or vd["off_target"].startswith(
            "not testable"), key
        assert f"window {key}" in res["text"]
    for lab in labels:
        assert f"| turn | {lab} |" in res["text"]


def test_truth_pixel_matches_the_camera_model():
    cam = HeadCamera(0.56, math.radians(51.0), 320, 240)
    robot = np.array([0.3, -0.2, 0.4])
    ball = np.array([2.0, 0.5, 0.0])
    u, v, depth = view(robot, ball, 0.03, 0.3, cam.height, 0.033, cam.focal_px,
                       cam.centre)
    dx, dy = ball[0] - robot[0], ball[1] - robot[1]
    c, s = math.cos(robot[2]), math.sin(robot[2])
    (pu, pv), = cam.project(np.array([[c * dx + s * dy, -s * dx + c * dy, 0.033]]), 0.03,
                            0.3)[0]
    assert (u, v) == pytest.approx((pu, pv))
    assert 0.9 * math.hypot(dx, dy, cam.height - 0.033) < depth <= math.hypot(
        dx, dy, cam.height - 0.033)  # the depth along the axis, at most the range


def test_same_seed_same_figures(tmp_path):
    a = following.run(tmp_path / "a", episodes=1, duration=0.4, seed=5, workers=1,
                      window_scales=(1.0,))
    b = following.run(tmp_path / "b", episodes=1, duration=0.4, seed=5, workers=1,
                      window_scales=(1.0,))
    strip = ("ms_per_frame", "bp_ms_per_frame")
    for v in ("turn", "follow"):
        ra = {k: x for k, x in a["summary"][v]["trackers"]["kalman x1"].items()
              if k not in strip}
        rb = {k: x for k, x in b["summary"][v]["trackers"]["kalman x1"].items()
              if k not in strip}
        assert ra == rb


@pytest.mark.parametrize("kwargs, name", [
    ({"episodes": 0}, "episodes"),
    ({"episodes": 1.5}, "episodes"),
    ({"duration": 0.0}, "duration"),
    ({"duration": float("nan")}, "duration"),
    ({"seed": -1}, "seed"),
    ({"workers": 0}, "workers"),
    ({"robot": "ssl"}, "robot"),
    ({"size": (320,)}, "size"),
    ({"size": (10, 240)}, "size"),
    ({"appearance": "foggy"}, "appearance"),
    ({"window_scales": ()}, "window_scales"),
    ({"window_scales": (1.0, 1.0)}, "window_scales"),
    ({"window_scales": ("x",)}, "window_scales"),
])
def test_bad_arguments_name_the_argument(tmp_path, kwargs, name):
    with pytest.raises(ValueError, match=name):
        following.run(tmp_path, **kwargs)


def test_figure_legends_cover_no_data_and_the_title_names_the_robot(tmp_path, monkeypatch):
    from soccer_env.render.plots import legend_overlaps, legends
    from soccer_lab.papers.following import report

    figures = saved_figures(monkeypatch, report)
    following.run(tmp_path, episodes=1, duration=0.4, seed=5, workers=1)
    (fig,) = figures
    labels = {t.get_text() for leg in legends(fig) for t in leg.get_texts()}
    assert {"kalman x1", "plain x2", "turn rate (right axis)"} <= labels
    assert legend_overlaps(fig) == []
    title = fig.get_suptitle()
    assert "humanoid-2012 humanoid on the humanoid-2012 field" in title
    assert "kidsize-2012" in title
