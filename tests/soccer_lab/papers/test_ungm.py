"""``soccer-env paper ungm``: outputs, reproducibility, and the filters' shared bookkeeping."""

from __future__ import annotations

import json

import numpy as np
import pytest
from saved_figures import saved_figures

from soccer_lab.cli import main
from soccer_lab.papers import ungm

pytestmark = pytest.mark.slow


def test_tables_plot_and_reproducibility(tmp_path):
    a = ungm.run(tmp_path / "a", runs=12, seed=3)
    b = ungm.run(tmp_path / "b", runs=12, seed=3)
    assert a["rmse"] == b["rmse"]
    data = json.loads((tmp_path / "a" / "paper_ungm.json").read_text())
    per_run = {k: np.array(v) for k, v in data["rmse_per_run"].items()}
    # MFBPF with FBPF's test runs FBPF's algorithm with resampling below the threshold: the
    # same numbers, run by run.
    np.testing.assert_allclose(per_run["mfbpf-below"], per_run["fbpf-threshold"])
    assert set(data["paired"]) == {f"{a} - {b}" for a, b, _ in ungm.PAIRS}
    # Every filter tracks the state far better than its spread (UNGM's |x| reaches ~20).
    assert all(2.0 < v < 8.0 for v in a["rmse"].values())
    assert (tmp_path / "a" / "paper_ungm.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "Xu et al. (2012)" in (tmp_path / "a" / "paper_ungm.md").read_text()


def test_command_line_and_bad_arguments(tmp_path, capsys):
    assert main(["paper", "ungm", "--runs", "3", "--out", str(tmp_path)]) == 0
    assert "| mfbpf:" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        main(["paper", "ungm", "--particles", "1", "--out", str(tmp_path)])
    with pytest.raises(ValueError, match="runs"):
        ungm.run(tmp_path, runs=0)


def test_figure_legends_cover_no_data_and_the_title_names_the_benchmark(tmp_path, monkeypatch):
    from soccer_env.render.plots import legend_overlaps, legends

    figures = saved_figures(monkeypatch, ungm)
    ungm.run(tmp_path, runs=3, seed=1)
    (fig,) = figures
    labels = {t.get_text() for leg in legends(fig) for t in leg.get_texts()}
    assert {"true state", *ungm.FILTERS, "median"} <= labels
    assert legend_overlaps(fig) == []
    assert "UNGM" in fig.get_suptitle() and "3 runs, 100 particles" in fig.axes[1].get_title()
