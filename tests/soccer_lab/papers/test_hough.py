"""``soccer-env paper hough``: exact without noise, reproducible, outputs written."""

from __future__ import annotations

import pytest
from saved_figures import saved_figures

from soccer_lab.cli import main
from soccer_lab.papers import hough

pytestmark = pytest.mark.slow


def test_without_camera_noise_every_estimate_is_exact(tmp_path):
    res = hough.run(tmp_path, trials=1, pixel_sigma=0.0, pose_sigma=0.0, heading_sigma=0.0,
                    sway_sigma=0.0)
    cam = res["camera"]
    assert max(cam["mean_m"].values()) < 1e-6
    assert max(cam["single_m"]) < 1e-6
    assert (tmp_path / "paper_hough.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_reproducible_and_fusion_beats_the_average_robot(tmp_path):
    a = hough.run(tmp_path / "a", trials=2, seed=4)
    b = hough.run(tmp_path / "b", trials=2, seed=4)
    assert a["text"] == b["text"]
    cam = a["camera"]
    # Five robots' bearings fused beat what one robot alone knows, on average.
    assert cam["by_count_m"][5] < cam["by_count_m"][1]
    assert "Xu et al. (2012)" in a["text"]


def test_command_line_and_bad_arguments(tmp_path, capsys):
    assert main(["paper", "hough", "--trials", "1", "--out", str(tmp_path)]) == 0
    assert "| head camera" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        main(["paper", "hough", "--trials", "0", "--out", str(tmp_path)])
    with pytest.raises(ValueError, match="sway_sigma"):
        hough.run(tmp_path, trials=1, sway_sigma=-1.0)


def test_noise_models_bound_the_claim_and_leave_the_first_table_alone(tmp_path):
    """The noise-model table: inverse variance is equal weights under isotropic noise (so 1/L
    cannot help there) and 1/L^2 under bearing noise; it draws from its own generators, so
    the first table's results are those of the seed's own stream, bit for bit; the report
    prints the paper's figures, both readings of its 8.6 cm, and the answer for a team."""
    import numpy as np

    from soccer_lab.papers.hough.simulation import evaluate

    res = hough.run(tmp_path, trials=1, seed=3, seeds=2)
    models = res["noise_models"]
    assert set(hough.NOISE_MODELS) <= set(models)
    for key in ("isotropic", "isotropic_rms"):
        m = models[key]["mean_m"]
        assert abs(m["inverse_variance"] - m["equal"]) < 1e-12
        assert models[key]["best_weighting"] == "equal"
    assert models["bearing"]["sigmas"]["position_m"] == 0.0
    cam = models["camera"]
    assert cam["seeds"] == 2 and len(cam["single_m"]) == 5
    assert cam["best_single_m"] <= min(cam["single_m"])  # the mean of each seed's best
    assert models["recommendation"]["weighting"] in hough.MODEL_WEIGHTINGS
    rng = np.random.default_rng(3)
    first = evaluate("camera", 1, rng, pixel_sigma=2.0, pose_sigma=0.03,
                     heading_sigma=np.radians(1.0), sway_sigma=np.radians(2.0))
    assert first == res["camera"]
    text = res["text"]
    for needed in ("| 118 | 87 |", "0.74", "0.52", "8.6 cm", "one robot alone",
                   "equal-weight cooperation", "**For a team with our head camera**"):
        assert needed in text, needed
    assert text.rstrip().splitlines()[-1].startswith("**For a team with our head camera**")


def test_noise_model_settings_are_checked(tmp_path):
    with pytest.raises(ValueError, match=r"seeds must be an integer in \[1, 100\]"):
        hough.Settings(tmp_path, seeds=0)
    with pytest.raises(ValueError, match="robot must be a humanoid robot preset"):
        hough.Settings(tmp_path, robot="ssl")


def test_figure_legend_covers_no_data_and_the_title_names_the_geometry(tmp_path, monkeypatch):
    from soccer_env.render.plots import legend_overlaps, legends

    figures = saved_figures(monkeypatch, hough.report)
    hough.run(tmp_path, trials=1, seeds=2)
    (fig,) = figures
    assert len(legends(fig)) == 1 and legend_overlaps(fig) == []
    title = fig.axes[0].get_title()
    assert "Table 1" in title and "6 m x 4 m" in title
    assert [t.get_text() for t in fig.axes[0].get_xticklabels()] == ["1", "2", "3", "4", "5"]
