"""The demo's figures read on their own: legends that say what each line style means and
cover no data, axes on the part of the field where the action is, titles naming the robot."""

from __future__ import annotations

import pytest

from soccer_env import presets
from soccer_env.render.plots import field_window, legend_overlaps, legends, pyplot
from soccer_lab import demo


def _demo_figures(tmp_path, monkeypatch, robot, perception):
    """Run two demo episodes without video; every figure it saves, by file name."""
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    saved = {}
    original = demo.save_figure

    def keep(fig, path):
        out = original(fig, path)
        saved[path.name] = fig
        return out

    monkeypatch.setattr(demo, "save_figure", keep)
    summary = demo.run_demo(tmp_path, episodes=2, video=False, robot=robot,
                            perception=perception)
    assert set(saved) == {"trajectories.png", "ball_speed.png", "estimate_error.png"}
    return saved, summary


def _title(fig) -> str:
    return " ".join([fig.get_suptitle()] + [ax.get_title() for ax in fig.axes])


def _entries(fig) -> dict:
    """Every legend entry of ``fig``: label -> handle."""
    out = {}
    for leg in legends(fig):
        for handle, text in zip(leg.legend_handles, leg.get_texts()):
            out[text.get_text()] = handle
    return out


@pytest.fixture(scope="module")
def ssl(tmp_path_factory):
    with pytest.MonkeyPatch.context() as mp:
        return _demo_figures(tmp_path_factory.mktemp("ssl"), mp, "ssl", "realistic")


@pytest.fixture(scope="module")
def humanoid(tmp_path_factory):
    with pytest.MonkeyPatch.context() as mp:
        return _demo_figures(tmp_path_factory.mktemp("humanoid"), mp, "humanoid-2012", None)


def test_trajectory_legend_explains_the_line_styles(ssl):
    figs, summary = ssl
    entries = _entries(figs["trajectories.png"])
    true, believed, keeper = (entries[k] for k in ("true ball", "believed ball", "keeper"))
    assert true.get_linestyle() == "-" and believed.get_linestyle() == "--"
    assert keeper.get_linestyle() == "-" and keeper.get_linewidth() > 2 * true.get_linewidth()
    # Neutral keys for styles, one coloured entry per episode with its outcome.
    assert true.get_color() == believed.get_color() == keeper.get_color()
    for ep in summary["episodes"]:
        assert f"seed {ep['seed']}: {ep['outcome']}" in entries


@pytest.mark.parametrize("name", ["trajectories.png", "ball_speed.png", "estimate_error.png"])
def test_no_legend_covers_data(ssl, humanoid, name):
    for figs, _ in (ssl, humanoid):
        fig = figs[name]
        assert legends(fig), name
        assert legend_overlaps(fig) == [], name


def test_trajectory_axes_show_where_the_action_is(ssl):
    fig = ssl[0]["trajectories.png"]
    ax = fig.axes[0]
    field = presets.field("ssl-div-b")
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    xw, yw = field.half_length + field.boundary, field.half_width + field.boundary
    # Inside the walls and smaller than the whole walled area (the shots are at one goal)...
    assert -xw <= x0 < x1 <= xw and -yw <= y0 < y1 <= yw
    assert (x1 - x0) * (y1 - y0) < 0.8 * (2 * xw) * (2 * yw)
    # ...holding every plotted path, with equal aspect and the field drawn underneath.
    for line in ax.lines:
        if line.get_gid() != "background":
            x, y = line.get_xdata(), line.get_ydata()
            assert x.min() >= x0 and x.max() <= x1 and y.min() >= y0 and y.max() <= y1
    assert ax.get_aspect() == 1.0
    assert any(p.get_gid() == "background" for p in ax.patches)


def test_titles_name_the_robot_the_field_and_the_sensors(ssl, humanoid):
    for name in ("trajectories.png", "ball_speed.png", "estimate_error.png"):
        ssl_title, hum_title = _title(ssl[0][name]), _title(humanoid[0][name])
        assert "SSL" in ssl_title and "ssl-div-b" in ssl_title and "realistic" in ssl_title
        assert "humanoid" not in ssl_title
        assert "humanoid" in hum_title and "humanoid-2012" in hum_title
        assert "kidsize-2012" in hum_title and "SSL" not in hum_title


def test_the_overlap_check_finds_a_legend_over_data():
    # Guards the tests above: a legend drawn over a line is reported.
    plt = pyplot()
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], label="diagonal")
    ax.plot([0, 1], [0.95, 0.95], label="top")
    ax.legend(loc="upper left")
    try:
        assert [a.get_label() for _, a in legend_overlaps(fig)] == ["top"]
    finally:
        plt.close(fig)


def test_field_window():
    field = presets.field("ssl-div-b")  # 9 m x 6 m, 0.3 m to the walls
    x0, x1, y0, y1 = field_window([-4.4, -3.0], [-0.5, 0.4], field, margin=0.2)
    assert x0 == pytest.approx(-4.6) and x1 == pytest.approx(-2.8)
    assert y0 <= -0.7 and y1 >= 0.6 and 0.45 <= (y1 - y0) / (x1 - x0) <= 1.2
    # Data beyond the walls are clipped, the window shifted inwards.
    x0, x1, y0, y1 = field_window([-10.0, 10.0], [-0.1, 0.1], field)
    assert (x0, x1) == (-4.8, 4.8) and -3.3 <= y0 < y1 <= 3.3
    # A point gets the least span; no finite point: the whole walled area.
    x0, x1, _, _ = field_window([1.0], [1.0], field, margin=0.0, min_span=1.0)
    assert x1 - x0 == pytest.approx(1.0)
    assert field_window([float("nan")], [0.0], field) == (-4.8, 4.8, -3.3, 3.3)
    with pytest.raises(ValueError, match="margin must be a finite number of metres >= 0"):
        field_window([0.0], [0.0], field, margin=-1.0)
    with pytest.raises(ValueError, match="aspect must be"):
        field_window([0.0], [0.0], field, aspect=(1.0, 0.5))
