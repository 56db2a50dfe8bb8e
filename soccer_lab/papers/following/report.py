"""The report of Yu, Wei and Zhang (2010)'s reproduction: the measures of every
episode pooled (:func:`analyse`), the printed text with the paper's claim and the aim
(:func:`text`), the CSV rows and JSON data, and the figure (:func:`plot`); see
:mod:`soccer_lab.papers.following`."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from soccer_env.render.plots import (
    LABEL_SIZE,
    TICK_SIZE,
    TITLE_SIZE,
    colour_key,
    legend_beside,
    pyplot,
    save_figure,
    style_key,
)
from soccer_lab.papers.following.episode import ROBOTS, VARIANTS
from soccer_lab.papers.following.measures import (
    TURN_BINS,
    binned,
    errors,
    summarise,
    verdict,
)

__all__ = ["PAPER", "AIM", "analyse", "text", "rows", "data", "plot"]

PAPER = {
    "claim": "mean shift assumes the target moves less than the kernel bandwidth between "
             "frames, which fails when the robot itself moves (the target jumps in the image "
             "plane); a Kalman filter on the image-plane state with the robot's rotation and "
             "advance as control input predicts where to start mean shift, and keeps the track",
    "results": "outdoor person following: robust, good tracking and real time (no figures "
               "in the part of the paper we have)",
}
AIM = ("the Kalman-started tracker losing the ball at most half as often as plain mean shift "
       "under fast turns")


def _pct(x: float) -> str:
    return "n/a" if not math.isfinite(x) else f"{100 * x:.1f} %"


def _num(x: float, fmt: str = ".2f") -> str:
    return "n/a" if not math.isfinite(x) else format(x, fmt)


def analyse(eps: list[dict[str, Any]], scales: tuple[float, ...]) -> dict[str, Any]:
    """The measures per variant and pooled (``summary``), by turn rate per variant and
    pooled (``turn_bins``) and by image jump (``jump_bins``); the aim's verdicts per window
    scale on the fast bin, both variants pooled (``verdicts``)."""
    by_variant = {v: [e for e in eps if e["variant"] == v] for v in VARIANTS}
    summary = {v: summarise(by_variant[v]) for v in VARIANTS}
    summary["all"] = summarise(eps)
    turn_bins = {v: binned(by_variant[v], "turn") for v in VARIANTS}
    turn_bins["all"] = binned(eps, "turn")
    jump_bins = binned(eps, "jump")
    fast = turn_bins["all"][-1]
    verdicts = {}
    for sc in scales:
        p_lab = f"plain x{sc:g}"
        for order, k_lab in (("ours", f"kalman x{sc:g}"), ("paper", f"kalman-paper x{sc:g}")):
            verdicts[f"x{sc:g} ({order})"] = _verdict(fast, k_lab, p_lab)
    return {"by_variant": by_variant, "summary": summary, "turn_bins": turn_bins,
            "jump_bins": jump_bins, "verdicts": verdicts}


def _verdict(fast: dict[str, Any], k_lab: str, p_lab: str) -> dict[str, Any]:
    """The aim judged on the fast bin for the Kalman tracker ``k_lab`` against ``p_lab``."""
    return {
        "kalman_off_target": fast[f"{k_lab} off_target_rate"],
        "plain_off_target": fast[f"{p_lab} off_target_rate"],
        "kalman_lost": fast[f"{k_lab} lost_rate"],
        "plain_lost": fast[f"{p_lab} lost_rate"],
        "off_target": verdict(fast[f"{k_lab} off_target_rate"],
                              fast[f"{p_lab} off_target_rate"]),
        "kalman_hazard": fast[f"{k_lab} loss_hazard"],
        "plain_hazard": fast[f"{p_lab} loss_hazard"],
        "lost": verdict(fast[f"{k_lab} lost_rate"], fast[f"{p_lab} lost_rate"]),
        "hazard": verdict(fast[f"{k_lab} loss_hazard"], fast[f"{p_lab} loss_hazard"])}


def text(s: Any, eps: list[dict[str, Any]], res: dict[str, Any]) -> str:
    """The printed report of the run of settings ``s``
    (:class:`~soccer_lab.papers.following.Settings`) and :func:`analyse`'s ``res``."""
    from soccer_env import presets

    labels = eps[0]["labels"]
    wmax = presets.robot(s.robot).max_turn_speed
    lines = [_intro(s, eps), "", *_summary_table(res["summary"], labels)]
    oov = res["summary"]["all"]["out_of_view_rate"]
    lines += ["", "Off target: farther from the ball's true pixel than its apparent radius. "
              "Loss hazard: the share of frames off target among those whose previous frame "
              "was on target (how often a held track is lost, whatever happens after). "
              f"Ball out of view (not scored): {_pct(oov)} of frames. Hue back-projection "
              f"(shared): {res['summary']['all']['bp_ms_per_frame']:.3f} ms per frame.", "",
              *_turn_table(res["turn_bins"], labels, wmax), "",
              *_jump_table(res["jump_bins"], labels), "",
              *_aim_lines(res["turn_bins"]["all"][-1], res["verdicts"], wmax)]
    return "\n".join(lines)


def _intro(s: Any, eps: list[dict[str, Any]]) -> str:
    """The setting: robot, field, camera, episodes, trackers."""
    from soccer_env import presets
    from soccer_env.presets.sensors import head_camera

    field_name, camera_name = ROBOTS[s.robot]
    spec = presets.robot(s.robot)
    cam = head_camera(camera_name)
    ball = presets.ball(presets.field(field_name).ball)
    windows = [e["window"][0] for e in eps]
    w, h = s.size
    return (
        f"Yu et al. (2010) on a turning humanoid: robot `{s.robot}` (top turn rate "
        f"{spec.max_turn_speed:g} rad/s, gait sway {math.degrees(spec.sway_pan):g} degrees yaw "
        f"/ {math.degrees(spec.sway_tilt):g} degrees pitch at {spec.step_frequency:g} "
        f"steps/s) on field `{field_name}` (ball radius {1000 * ball.radius:.0f} mm), head "
        f"camera `{camera_name}` ({cam.frame_rate:g} Hz, {math.degrees(cam.hfov):.0f} degrees) "
        f"rendered at {w} x {h} (`{s.appearance}`), head at pan 0 and tilt "
        f"{math.degrees(eps[0]['tilt']):.1f} degrees. {s.episodes} seeded episode(s) of "
        f"{s.duration:g} s per variant (seed {s.seed}; odd episodes roll the ball): `turn` "
        "sweeps the heading in place, `follow` also walks towards the ball. All trackers on "
        "the same hue back-projections, started at the ball's true pixel; window: the ball's "
        f"apparent diameter at the start ({min(windows)}-{max(windows)} px) times x "
        f"({', '.join(f'{sc:g}' for sc in s.window_scales)}). The Kalman tracker gets the walk "
        "engine's odometry (rotation, advance) between frames, not the truth.")


def _summary_table(summary: dict[str, Any], labels: list[str]) -> list[str]:
    lines = [
        "| variant | tracker | frames | reports lost | off target | loss hazard | median "
        "error [px] | RMSE on target [px] | losses | recoveries | ms per frame | size-based "
        "distance: median rel. error (signed) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for v in (*VARIANTS, "all"):
        for lab in labels:
            r = summary[v]["trackers"][lab]
            lines.append(
                f"| {v} | {lab} | {r['frames']} | {_pct(r['lost_rate'])} | "
                f"{_pct(r['off_target_rate'])} | {_pct(r['loss_hazard'])} | "
                f"{_num(r['median_error_px'], '.1f')} | "
                f"{_num(r['rmse_on_target_px'], '.1f')} | {r['losses']} | {r['recoveries']} | "
                f"{_num(r['ms_per_frame'], '.3f')} | {_pct(r['depth_median_rel'])} "
                f"({_pct(r['depth_median_signed'])}) |")
    return lines


def _turn_table(turn_bins: dict[str, list[dict[str, Any]]], labels: list[str],
                wmax: float) -> list[str]:
    lines = ["By turn rate (true body turn rate over the frame period; bins at 1/3 and 2/3 of "
             f"{wmax:g} rad/s): the ball's mean image jump between frames in its apparent "
             "radii (without the gait's sway), and per tracker the share of frames off "
             "target / the loss hazard:", "",
             "| variant | turn rate [rad/s] | frames | mean rate | jump [radii] | "
             + " | ".join(labels) + " |", "|---" * (5 + len(labels)) + "|"]
    for v in (*VARIANTS, "all"):
        for b, (name, lo, hi) in zip(turn_bins[v], TURN_BINS):
            span = (f"{name} {lo * wmax:.2f}-{hi * wmax:.2f}" if math.isfinite(hi)
                    else f"{name} >= {lo * wmax:.2f}")
            lines.append(
                f"| {v} | {span} | {b['frames']} | {_num(b['mean_turn_rate'])} | "
                f"{_num(b['mean_jump_radii'], '.1f')} "
                f"({_num(b['mean_jump_radii_without_sway'], '.1f')}) | "
                + " | ".join(f"{_pct(b[f'{lab} off_target_rate'])} / "
                             f"{_pct(b[f'{lab} loss_hazard'])}" for lab in labels) + " |")
    return lines


def _jump_table(jump_bins: list[dict[str, Any]], labels: list[str]) -> list[str]:
    lines = ["By the ball's true image jump between frames in its apparent radii (a "
             "window of scale x has a half-width of about x radii, the bandwidth), both "
             "variants, share of frames off target / loss hazard:", "",
             "| jump [radii] | frames | mean turn rate [rad/s] | " + " | ".join(labels) + " |",
             "|---" * (3 + len(labels)) + "|"]
    for b in jump_bins:
        lines.append(f"| {b['bin']} | {b['frames']} | {_num(b['mean_turn_rate'])} | "
                     + " | ".join(f"{_pct(b[f'{lab} off_target_rate'])} / "
                                  f"{_pct(b[f'{lab} loss_hazard'])}" for lab in labels)
                     + " |")
    return lines


def pipeline_label() -> str:
    """The tracker label of the humanoid pixel pipeline's ball tracker
    (:class:`soccer_env.perception.pixels.BallImageTracker`)."""
    from soccer_env.perception.pixels import BallImageTracker

    kind = "kalman" if BallImageTracker.ORDER == "ours" else "kalman-paper"
    return f"{kind} x{BallImageTracker.WINDOW_SCALE:g}"


def _aim_lines(fast: dict[str, Any], verdicts: dict[str, Any], wmax: float) -> list[str]:
    lines = [f"Yu et al.'s (2010) claim: {PAPER['claim']}. Its results: {PAPER['results']}.", "",
             f"Our criterion (not the paper's): {AIM}. Fast turns "
             f"(>= {TURN_BINS[-1][1] * wmax:.2f} rad/s, "
             f"{fast['frames']} frames, both variants), Kalman against plain, judged on the "
             "share of frames off target (the lost-track rate):"]
    for key, vd in verdicts.items():
        lines.append(f"- window {key}: {_pct(vd['kalman_off_target'])} against "
                     f"{_pct(vd['plain_off_target'])}: **{vd['off_target']}**; by the "
                     f"trackers' own lost reports {_pct(vd['kalman_lost'])} against "
                     f"{_pct(vd['plain_lost'])}: {vd['lost']}; by the loss hazard "
                     f"{_pct(vd['kalman_hazard'])} against {_pct(vd['plain_hazard'])}: "
                     f"{vd['hazard']}.")
    lines += ["", "Orders: `kalman` starts mean shift at the prediction and takes its result as "
              "the measurement and the posterior (ours); `kalman-paper` takes the centroid of "
              "the back-projection in the region R (twice the target) around the prediction "
              "as the measurement, updates the Kalman filter, then starts mean shift from the "
              f"posterior (Yu et al. 2010 as printed). The humanoid pixel pipeline's ball tracker "
              f"runs `{pipeline_label()}`."]
    return lines


def rows(res: dict[str, Any], labels: list[str]) -> list[dict[str, Any]]:
    """The CSV rows: the summary per variant and tracker, the turn-rate bins, the jump
    bins."""
    out: list[dict[str, Any]] = []
    for v in (*VARIANTS, "all"):
        for lab in labels:
            out.append({"table": "summary", "variant": v, "tracker": lab,
                        **res["summary"][v]["trackers"][lab]})
    for v in (*VARIANTS, "all"):
        for b in res["turn_bins"][v]:
            out.append({"table": "turn_rate", "variant": v, **b})
    for b in res["jump_bins"]:
        out.append({"table": "jump", "variant": "all", **b})
    return out


def _plotted(res: dict[str, Any]) -> dict[str, Any]:
    """The figure's episode: the first of Yu et al.'s (2010) setting (following)."""
    return res["by_variant"]["follow"][0]


def _series(ep: dict[str, Any]) -> dict[str, Any]:
    """The plotted episode's time, turn rate, ball radius and every tracker's error."""
    series: dict[str, Any] = {"t": ep["rec"]["t"].tolist(),
                              "turn_rate": (ep["rec"]["rotation_true"]
                                            / ep["frame_dt"]).tolist(),
                              "radius": ep["rec"]["radius"].tolist()}
    for lab in ep["labels"]:
        series[f"{lab} error_px"] = errors(ep, lab)[0].tolist()
    return series


def data(s: Any, eps: list[dict[str, Any]], res: dict[str, Any]) -> dict[str, Any]:
    """The JSON data: the settings, every measure, the aim's verdicts and the plotted
    episode's series."""
    field_name, camera_name = ROBOTS[s.robot]
    ep_plot = _plotted(res)
    return {"robot": s.robot, "field": field_name, "camera": camera_name,
            "size": list(s.size), "appearance": s.appearance, "episodes": s.episodes,
            "duration": s.duration, "seed": s.seed, "window_scales": list(s.window_scales),
            "summary": res["summary"], "turn_bins": res["turn_bins"],
            "jump_bins": res["jump_bins"], "aim": AIM, "verdicts": res["verdicts"],
            "paper": PAPER,
            "episode_list": [{"variant": e["variant"], "index": e["index"],
                              "rolling": e["rolling"], "window_px": e["window"][0]}
                             for e in eps],
            "plotted_episode": {"variant": ep_plot["variant"], "index": ep_plot["index"],
                                **_series(ep_plot)}}


def plot(eps: list[dict[str, Any]], res: dict[str, Any], wmax: float, path: Path, *,
         robot: str | None = None) -> str:
    """The plotted episode's pixel errors with the turn rate, the frames off target of every
    episode and tracker, and the off-target share by turn rate.

    Each tracker kind has a hue and each window scale a shade of it (the first scale the full
    colour; lines of the other scales dashed): ``wmax`` is the robot's top turn rate [rad/s]
    (the turn-rate bins are fractions of it) and ``robot`` the robot preset, named in the
    title."""
    labels = eps[0]["labels"]
    ep_plot = _plotted(res)
    colours, dashes = _tracker_styles(labels)
    plt = pyplot()
    fig, (ax, rx, bx) = plt.subplots(1, 3, figsize=(18, 5.2), layout="constrained",
                                     gridspec_kw={"width_ratios": [1.25, 1.0, 0.9]})
    ax2 = _error_panel(ax, ep_plot, labels, colours, dashes)
    _off_target_panel(rx, eps, labels, colours, ep_plot["frame_dt"])
    _turn_rate_panel(bx, res, labels, colours, wmax)
    for a in (ax, ax2, rx, bx):
        a.tick_params(labelsize=TICK_SIZE)
    ax.grid(alpha=0.3)
    bx.grid(axis="y", alpha=0.3)
    if robot is None:  # the preset with this top turn rate
        from soccer_env import presets

        robot = next((r for r in ROBOTS if presets.robot(r).max_turn_speed == wmax), "humanoid")
    field, camera = ROBOTS.get(robot, ("?", "?"))
    who = "humanoid" if robot == "humanoid" else f"{robot} humanoid"
    fig.suptitle(f"Yu et al. (2010) ball following: a turning {who} on the {field} field, "
                 f"head camera {camera}; {len(eps)} episodes", fontsize=TITLE_SIZE)
    first = legend_beside(bx, [style_key(lab, ls=dashes[lab], color=colours[lab], lw=1.6)
                               for lab in labels],
                          title="tracker, window scale", handlelength=2.6)
    legend_beside(bx, [style_key("ball radius\n(off target above)", ls=":", lw=1.2,
                                 color="k"),
                       style_key("turn rate (right axis)", color="0.55", lw=1.0),
                       colour_key("frame off target", "0.35")],
                  title="lines and fills", below=first, handlelength=2.6)
    return save_figure(fig, path)


def _tracker_styles(labels: list[str]) -> tuple[dict[str, Any], dict[str, str]]:
    """Each tracker label's colour (its kind's hue, lighter for each further window scale)
    and line style (one per window scale)."""
    from matplotlib.colors import to_rgb

    kinds = list(dict.fromkeys(lab.rsplit(" x", 1)[0] for lab in labels))
    scales = list(dict.fromkeys(lab.rsplit(" x", 1)[1] for lab in labels))
    styles = ("-", "--", "-.", ":")
    colours, dashes = {}, {}
    for lab in labels:
        kind, scale = lab.rsplit(" x", 1)
        light = 0.5 * scales.index(scale) / max(len(scales) - 1, 1)
        base = np.array(to_rgb(f"C{kinds.index(kind)}"))
        colours[lab] = tuple(base + light * (1.0 - base))
        dashes[lab] = styles[scales.index(scale) % len(styles)]
    return colours, dashes


def _error_panel(ax: Any, ep_plot: dict[str, Any], labels: list[str],
                 colours: dict[str, Any], dashes: dict[str, str]) -> Any:
    """The plotted episode's pixel errors of every tracker and the ball's radius on ``ax``
    (log scale), its turn rate on a twin axis, which is returned."""
    t = ep_plot["rec"]["t"]
    for lab in labels:
        ax.plot(t, np.maximum(errors(ep_plot, lab)[0], 0.05), ls=dashes[lab],
                color=colours[lab], lw=1.2)
    ax.plot(t, ep_plot["rec"]["radius"], ":", color="k", lw=1.2)
    ax.set_yscale("log")
    ax.set_xlabel("time since the first frame [s]", fontsize=LABEL_SIZE)
    ax.set_ylabel("pixel error of the tracked ball [px]", fontsize=LABEL_SIZE)
    ax.set_title(f"Episode `{ep_plot['variant']}` #{ep_plot['index']}: pixel error and turn "
                 "rate", fontsize=LABEL_SIZE)
    ax2 = ax.twinx()
    ax2.plot(t, ep_plot["rec"]["rotation_true"] / ep_plot["frame_dt"], color="0.55", lw=1.0)
    ax2.set_ylabel("turn rate [rad/s] (grey line)", fontsize=LABEL_SIZE)
    return ax2


def _off_target_panel(rx: Any, eps: list[dict[str, Any]], labels: list[str],
                      colours: dict[str, Any], frame_dt: float) -> None:
    """Every episode, every tracker: its frames off target (one raster row per tracker, in
    the tracker's colour) on ``rx``; ``frame_dt`` the frame period [s]."""
    from matplotlib.colors import ListedColormap

    n = min(len(e["rec"]["t"]) for e in eps)
    raster = np.zeros((len(eps) * len(labels), n))
    for i, e in enumerate(eps):
        for j, lab in enumerate(labels):
            raster[i * len(labels) + j] = np.where(errors(e, lab)[1][:n], j + 1, 0)
    rx.imshow(raster, aspect="auto", interpolation="nearest",
              cmap=ListedColormap(["white", *(colours[lab] for lab in labels)]), vmin=0,
              vmax=len(labels), extent=(0.0, n * frame_dt, len(raster), 0))
    for i in range(1, len(eps)):
        rx.axhline(i * len(labels), color="0.7", lw=0.6)
    rx.set_yticks([(i + 0.5) * len(labels) for i in range(len(eps))],
                  [f"{e['variant']} #{e['index']}" for e in eps],
                  fontsize=TICK_SIZE if len(eps) <= 24 else 7)
    rx.set_xlabel("time since the first frame [s]", fontsize=LABEL_SIZE)
    rx.set_ylabel("episode (one row per tracker, in legend order)", fontsize=LABEL_SIZE)
    rx.set_title("Frames off target (coloured), every episode", fontsize=LABEL_SIZE)


def _turn_rate_panel(bx: Any, res: dict[str, Any], labels: list[str],
                     colours: dict[str, Any], wmax: float) -> None:
    """Each tracker's share of frames off target per turn-rate bin, both variants, on ``bx``;
    ``wmax`` the robot's top turn rate [rad/s]."""
    xs = np.arange(len(TURN_BINS))
    width = 0.8 / len(labels)
    for j, lab in enumerate(labels):
        vals = [b[f"{lab} off_target_rate"] for b in res["turn_bins"]["all"]]
        bx.bar(xs + (j - 0.5 * (len(labels) - 1)) * width, np.nan_to_num(vals), width,
               color=colours[lab], edgecolor="0.3", lw=0.4)
    bx.set_xticks(xs, [f"{nm}\n{lo * wmax:.2f}-{hi * wmax:.2f} rad/s" if math.isfinite(hi)
                       else f"{nm}\n>= {lo * wmax:.2f} rad/s" for nm, lo, hi in TURN_BINS])
    bx.set_ylim(0, 1)
    bx.set_xlabel("turn rate", fontsize=LABEL_SIZE)
    bx.set_ylabel("share of frames off target", fontsize=LABEL_SIZE)
    bx.set_title("Lost-track rate by turn rate, both variants", fontsize=LABEL_SIZE)
