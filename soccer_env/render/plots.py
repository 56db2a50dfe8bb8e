"""Figure helpers shared by the demo, the paper benchmarks and the ablations (matplotlib, no
display).

Every figure the package writes goes through :func:`save_figure`. The helpers keep figures
readable on their own:

* legend keys for what a line style, marker or error bar means, drawn in a neutral grey
  beside the coloured entries (:func:`style_key`, :func:`interval_key`, :func:`colour_key`);
* legends placed beside or above the axes, where they cover no data (:func:`legend_beside`,
  :func:`legend_above`), and a check that no legend covers data (:func:`legend_overlaps`);
* field plots limited to where the action is, the field drawn underneath
  (:func:`field_window`, :func:`draw_field`), and titles naming the robots and the field
  (:func:`describe_world`).

Lengths are in metres, as in :class:`~soccer_env.presets.FieldSpec`; font sizes in points
(at :data:`DPI` 110 a point is about 1.5 pixels).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

__all__ = ["pyplot", "save_figure", "DPI", "TITLE_SIZE", "LABEL_SIZE", "TICK_SIZE",
           "LEGEND_SIZE", "KEY_GREY", "EPISODE_COLOURS", "style_key", "colour_key", "interval_key",
           "legend_beside", "legend_above", "legends", "legend_overlaps", "field_window",
           "draw_field", "describe_world"]

#: Resolution of the written PNGs [dots per inch].
DPI = 110
#: Font sizes [pt]: titles, axis labels, tick labels and legends (9 pt is 14 px at 110 dpi).
TITLE_SIZE, LABEL_SIZE, TICK_SIZE, LEGEND_SIZE = 11.0, 10.0, 9.0, 9.0
#: The neutral grey of legend keys that explain a line style or marker, not a colour.
KEY_GREY = "0.35"
#: Colours of episodes, seeds and configurations on field plots: the matplotlib cycle without
#: its green (lost on the grass) and its grey (the keys' colour).
EPISODE_COLOURS = ("C0", "C1", "C3", "C4", "C5", "C6", "C9", "C8")
#: Field drawing: grass, the run-off strip to the walls, lines, goals and walls.
_GRASS, _RUNOFF, _LINES, _GOALS, _WALLS = "#c4e3b6", "#e6f2df", "white", "0.1", "0.45"


def pyplot() -> ModuleType:
    """``matplotlib.pyplot`` on the file-only Agg backend (imported on first use: matplotlib is
    an optional dependency and slow to import)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, path: str | Path) -> str:
    """Lay out ``fig`` (tight layout, unless it has a layout engine of its own), write it to
    ``path`` as PNG at :data:`DPI` cropped to its artists (so a legend beside the axes is kept
    whole), close it and return the path."""
    if fig.get_layout_engine() is None:
        fig.tight_layout()
    fig.savefig(path, dpi=DPI, bbox_inches="tight", pad_inches=0.08)
    pyplot().close(fig)
    return str(path)


# ------------------------------------------------------------------------------------------
# Legends
# ------------------------------------------------------------------------------------------

def style_key(label: str, *, ls: str = "-", lw: float = 1.5, marker: str = "None",
              ms: float = 6.0, alpha: float = 1.0, color: str = KEY_GREY, **kwargs: Any):
    """A legend entry for a line style or marker, in a neutral grey by default.

    Args:
        label: what the style means ("believed ball").
        ls: line style (``"-"``, ``"--"``, ``":"``, ``"None"`` for a marker alone).
        lw: line width [pt].
        marker: matplotlib marker (``"o"``, ``"x"``; ``"None"`` for a line alone).
        ms: marker size [pt].
        alpha: opacity in [0, 1], as the plotted lines use it.
        color: the entry's colour.
        **kwargs: further :class:`~matplotlib.lines.Line2D` properties (``mfc="none"`` for a
            hollow marker).

    Returns:
        A :class:`matplotlib.lines.Line2D` that is drawn nowhere but in a legend.
    """
    from matplotlib.lines import Line2D

    return Line2D([], [], ls=ls, lw=lw, marker=marker, ms=ms, alpha=alpha, color=color,
                  label=label, **kwargs)


def colour_key(label: str, color: str, alpha: float = 1.0):
    """A legend entry for a colour alone (a filled square), e.g. one episode's colour.

    Returns:
        A :class:`matplotlib.patches.Patch` that is drawn nowhere but in a legend.
    """
    from matplotlib.patches import Patch

    return Patch(facecolor=color, edgecolor="none", alpha=alpha, label=label)


def interval_key(label: str, *, marker: str = "None", horizontal: bool = False,
                 color: str = KEY_GREY):
    """A legend entry for an error bar (an interval, with caps), in a neutral grey by default.

    Args:
        label: what the bar shows ("95 % Wilson interval").
        marker: the marker at the estimate (``"o"``), ``"None"`` for a bar alone.
        horizontal: a horizontal bar (``xerr``) instead of a vertical one.
        color: the entry's colour.

    Returns:
        A :class:`matplotlib.container.ErrorbarContainer` that is drawn nowhere but in a
        legend.
    """
    from matplotlib.collections import LineCollection
    from matplotlib.container import ErrorbarContainer
    from matplotlib.lines import Line2D

    data = Line2D([], [], ls="None", marker=marker, color=color)
    cap = Line2D([], [], ls="None", marker="|" if horizontal else "_", ms=6, color=color)
    return ErrorbarContainer((data, (cap, cap), (LineCollection([], colors=color),)),
                             has_xerr=horizontal, has_yerr=not horizontal, label=label)


def legend_beside(ax, handles: Sequence[Any] | None = None, *, title: str | None = None,
                  below: Any = None, fontsize: float = LEGEND_SIZE, **kwargs: Any):
    """A legend to the right of ``ax``, outside the axes (so it covers none of their data;
    :func:`save_figure` keeps it in the PNG): its top level with the axes' top, or 0.1 inch
    under the legend ``below`` (an earlier legend beside the same axes, which is kept).

    Legends are sized in points, so the stacked legend's offset under ``below`` is fixed in
    inches and stays right when the layout resizes the axes.

    Args:
        ax: the axes.
        handles: the entries (default: the axes' labelled artists).
        title: the legend's title.
        below: a legend made by this function for ``ax``, to stack this one under.
        fontsize: font size [pt].
        **kwargs: further :meth:`matplotlib.axes.Axes.legend` arguments.

    Returns:
        The :class:`matplotlib.legend.Legend`.
    """
    kw: dict[str, Any] = {"loc": "upper left", "bbox_to_anchor": (1.02, 1.0),
                          "borderaxespad": 0.0, "fontsize": fontsize,
                          "title_fontsize": fontsize, "title": title, **kwargs}
    if below is not None:
        from matplotlib.transforms import ScaledTranslation

        fig = ax.figure
        height = below.get_window_extent(_renderer(fig)).height / fig.dpi
        kw["bbox_transform"] = ax.transAxes + ScaledTranslation(0.0, -(height + 0.1),
                                                                fig.dpi_scale_trans)
        if below not in ax.artists:
            ax.add_artist(below)  # a new ax.legend() replaces ax.legend_
    return ax.legend(handles=handles, **kw) if handles is not None else ax.legend(**kw)


def legend_above(ax, handles: Sequence[Any] | None = None, *, ncol: int | None = None,
                 fontsize: float = LEGEND_SIZE, **kwargs: Any):
    """A legend in a row above ``ax`` (between its title, if any, and the axes: give the
    title with ``pad``), outside the axes.

    Args:
        ax: the axes.
        handles: the entries (default: the axes' labelled artists).
        ncol: columns (default: all entries in one row, at most 5 a row).
        fontsize: font size [pt].
        **kwargs: further :meth:`matplotlib.axes.Axes.legend` arguments.

    Returns:
        The :class:`matplotlib.legend.Legend`.
    """
    n = len(handles) if handles is not None else len(ax.get_legend_handles_labels()[0])
    kw: dict[str, Any] = {"loc": "lower center", "bbox_to_anchor": (0.5, 1.01),
                          "borderaxespad": 0.0, "fontsize": fontsize,
                          "ncol": ncol or max(1, min(n, 5)), "columnspacing": 1.2,
                          "handlelength": 1.8, **kwargs}
    return ax.legend(handles=handles, **kw) if handles is not None else ax.legend(**kw)


def legends(fig) -> list[Any]:
    """Every legend of ``fig``: the figure's own and each axes' (also legends added to the
    axes as artists, as a second legend of the same axes is)."""
    from matplotlib.legend import Legend

    found = list(fig.legends)
    for ax in fig.axes:
        found += [c for c in ax.get_children() if isinstance(c, Legend)]
    return found


def legend_overlaps(fig) -> list[tuple[Any, Any]]:
    """The data each legend of ``fig`` covers: pairs ``(legend, artist)``.

    Data are the lines, patches (bars, boxes), collections (error bars, scatter) and images
    of every axes, as drawn: a line is sampled along its segments, clipped to its axes. A
    legend covers an artist when a drawn point of the line, or a part of the patch's or
    image's extent of positive area, lies inside the legend's frame. Artists whose ``gid``
    is ``"background"`` (the field under a field plot) are not data.

    Returns:
        Every covering pair; empty when no legend covers data.
    """
    renderer = _renderer(fig)
    fig.canvas.draw()
    pairs = []
    for leg in legends(fig):
        box = leg.get_window_extent(renderer)
        for ax in fig.axes:
            clip = ax.bbox
            for artist in _data_artists(ax):
                if _covers(box, clip, artist, renderer):
                    pairs.append((leg, artist))
    return pairs


def _renderer(fig):
    """The Agg renderer of ``fig``, giving it an Agg canvas first where it has none that
    renders (a figure closed by pyplot, or made without it)."""
    if not hasattr(fig.canvas, "get_renderer"):
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    return fig.canvas.get_renderer()


def _data_artists(ax) -> Iterable[Any]:
    for artist in [*ax.lines, *ax.patches, *ax.collections, *ax.images]:
        if artist.get_visible() and artist.get_gid() != "background":
            yield artist


def _inside(points: np.ndarray, box, clip) -> bool:
    """Whether any display point lies inside ``box`` and inside the clipping box."""
    if points.size == 0:
        return False
    x, y = points[:, 0], points[:, 1]
    ok = np.isfinite(x) & np.isfinite(y)
    ok &= (x >= clip.x0) & (x <= clip.x1) & (y >= clip.y0) & (y <= clip.y1)
    return bool(np.any(ok & (x > box.x0) & (x < box.x1) & (y > box.y0) & (y < box.y1)))


def _densify(points: np.ndarray, per_segment: int = 24) -> np.ndarray:
    """Points along a polyline: ``per_segment`` between consecutive vertices."""
    if len(points) < 2:
        return points
    s = np.linspace(0.0, 1.0, per_segment, endpoint=False)[None, :, None]
    a, b = points[:-1, None, :], points[1:, None, :]
    return np.vstack([(a + s * (b - a)).reshape(-1, 2), points[-1:]])


def _covers(box, clip, artist, renderer) -> bool:
    from matplotlib.collections import LineCollection, PathCollection
    from matplotlib.lines import Line2D

    if isinstance(artist, Line2D):
        xy = artist.get_transform().transform(np.asarray(artist.get_xydata(), dtype=float))
        has_line = artist.get_linestyle() not in ("None", "none", " ", "")
        return _inside(_densify(xy) if has_line else xy, box, clip)
    if isinstance(artist, LineCollection):
        tr = artist.get_transform()
        return any(_inside(_densify(tr.transform(np.asarray(seg, dtype=float))), box, clip)
                   for seg in artist.get_segments() if len(seg))
    if isinstance(artist, PathCollection):
        offsets = artist.get_offset_transform().transform(artist.get_offsets())
        return _inside(np.asarray(offsets, dtype=float), box, clip)
    ext = artist.get_window_extent(renderer)
    x0, x1 = max(ext.x0, box.x0, clip.x0), min(ext.x1, box.x1, clip.x1)
    y0, y1 = max(ext.y0, box.y0, clip.y0), min(ext.y1, box.y1, clip.y1)
    return bool(np.isfinite([x0, x1, y0, y1]).all() and x1 - x0 > 0.5 and y1 - y0 > 0.5)


# ------------------------------------------------------------------------------------------
# Field plots
# ------------------------------------------------------------------------------------------

def field_window(xs: Iterable[float], ys: Iterable[float], field, *, margin: float = 0.3,
                 min_span: float = 1.0, aspect: tuple[float, float] = (0.45, 1.2)
                 ) -> tuple[float, float, float, float]:
    """The part of the field to show: the data's bounds plus ``margin``, clipped to the walled
    area.

    The window ``[x0, x1] x [y0, y1]`` is the bounding box of the finite points, widened by
    ``margin`` on every side and to at least ``min_span`` in each direction, then widened
    further about its centre until its height over its width ``(y1 - y0) / (x1 - x0)`` lies
    in ``aspect`` (so that an equal-aspect plot of it is neither a strip nor a tower), and
    clipped to the walls ``|x| <= L/2 + b``, ``|y| <= W/2 + b`` (shifted inwards first where
    it sticks out). With no finite point it is the whole walled area.

    Args:
        xs, ys: the plotted points' coordinates [m] (field frame).
        field: a :class:`~soccer_env.presets.FieldSpec`.
        margin: space around the data [m], >= 0.
        min_span: the least width and height [m], > 0.
        aspect: the least and most height over width, ``0 < low <= high``.

    Returns:
        ``(x0, x1, y0, y1)`` [m].

    Raises:
        ValueError: for a negative margin, a span <= 0 or a bad aspect range.
    """
    low, high = aspect
    if not (math.isfinite(margin) and margin >= 0.0):
        raise ValueError(f"margin must be a finite number of metres >= 0, got {margin!r}")
    if not (math.isfinite(min_span) and min_span > 0.0):
        raise ValueError(f"min_span must be a finite number of metres > 0, got {min_span!r}")
    if not (0.0 < low <= high < math.inf):
        raise ValueError(f"aspect must be (low, high) with 0 < low <= high, got {aspect!r}")
    xw, yw = field.half_length + field.boundary, field.half_width + field.boundary
    x = np.asarray(list(xs), dtype=float)
    y = np.asarray(list(ys), dtype=float)
    ok = np.isfinite(x) & np.isfinite(y)
    if not ok.any():
        return -xw, xw, -yw, yw
    x, y = np.clip(x[ok], -xw, xw), np.clip(y[ok], -yw, yw)
    cx, cy = 0.5 * (x.min() + x.max()), 0.5 * (y.min() + y.max())
    w = max(x.max() - x.min() + 2 * margin, min_span)
    h = max(y.max() - y.min() + 2 * margin, min_span)
    h = min(max(h, low * w), 2 * yw)
    w = min(max(w, h / high), 2 * xw)
    h = min(max(h, low * w), 2 * yw)

    def place(c: float, span: float, wall: float) -> tuple[float, float]:
        lo = min(max(c - span / 2, -wall), wall - span)
        return lo, lo + span

    return (*place(cx, w, xw), *place(cy, h, yw))


def draw_field(ax, field) -> None:
    """Draw ``field`` under the data of ``ax`` (equal aspect): grass, the run-off strip to the
    walls, the lines (touch and goal lines, halfway line, centre circle, defense areas), the
    goals and the walls. Every artist has ``gid="background"`` and a z-order below the data.

    Args:
        ax: the axes, in field coordinates [m].
        field: a :class:`~soccer_env.presets.FieldSpec`.
    """
    from matplotlib.patches import Circle, Rectangle

    hx, hy, b = field.half_length, field.half_width, field.boundary
    gw, gd = field.goal_width / 2, field.goal_depth
    dd, dw = field.defense_depth, field.defense_width / 2
    bg = {"gid": "background"}
    ax.add_patch(Rectangle((-hx - b, -hy - b), 2 * (hx + b), 2 * (hy + b), fc=_RUNOFF,
                           ec=_WALLS, lw=2.0, zorder=0, **bg))
    ax.add_patch(Rectangle((-hx, -hy), 2 * hx, 2 * hy, fc=_GRASS, ec=_LINES, lw=1.5, zorder=0.1,
                           **bg))
    line = {"color": _LINES, "lw": 1.2, "zorder": 0.2, **bg}
    ax.plot([0, 0], [-hy, hy], **line)
    if field.center_circle_radius > 0:
        ax.add_patch(Circle((0, 0), field.center_circle_radius, fill=False, ec=_LINES,
                            lw=1.2, zorder=0.2, **bg))
    for s in (-1, 1):
        if dd > 0 and dw > 0:
            ax.plot([s * hx, s * (hx - dd), s * (hx - dd), s * hx], [dw, dw, -dw, -dw], **line)
        ax.plot([s * hx, s * (hx + gd), s * (hx + gd), s * hx], [gw, gw, -gw, -gw],
                color=_GOALS, lw=2.0, zorder=0.3, solid_capstyle="butt", **bg)
    ax.set_aspect("equal")


def describe_world(robot: Any = "ssl", field: Any = None) -> str:
    """The robots and the field in words, for a title: ``"SSL robots on the ssl-div-b field
    (9 m x 6 m)"``, ``"humanoid-2012 humanoids on the humanoid-2012 field (6 m x 4 m)"``.

    Args:
        robot: a robot preset name or :class:`~soccer_env.presets.RobotSpec`, or the robot kind
            ``"humanoid"`` (the default humanoid preset).
        field: a field preset name or :class:`~soccer_env.presets.FieldSpec`; None: the
            robot's default field.
    """
    from soccer_env import presets

    spec = presets.robot(robot)
    fld = presets.field(field if field is not None else presets.default_field(spec))
    if spec.kind == "ssl":
        who = "SSL robots" if spec.name == "ssl" else f"SSL robots ({spec.name})"
    else:
        who = "humanoids" if spec.name == spec.kind else f"{spec.name} humanoids"
    return f"{who} on the {fld.name} field ({fld.length:g} m x {fld.width:g} m)"
