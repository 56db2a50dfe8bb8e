"""The report of Guo and Li's (2013) reproduction: the printed text (the setting, the
filters' table, KLD-sampling against our criteria, Fox's binning, the recovery seed,
triangulation alone and the paper), the CSV rows, the JSON data and the figure; see
:mod:`soccer_lab.papers.localization`."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from estimators import KLDConfig
from soccer_env import presets
from soccer_env.render.plots import pyplot, save_figure
from soccer_lab.papers.localization.episode import CAMERA, CRUISE, FIELD, ROBOT
from soccer_lab.papers.localization.filters import FOX, SEED_MEMORY, SEEDED
from soccer_lab.papers.localization.measures import (
    AIM_POS_M,
    RECOVERED_HOLD,
    RECOVERED_M,
    SETTLE,
    WRONG_M,
    Summaries,
)

__all__ = ["PAPER", "AIMS", "text", "rows", "data", "plot"]

#: The paper's claims, printed beside ours.
PAPER = ("Guo and Li (2013): KLD-sampling keeps many particles while uncertain and few once "
         "converged; errors are larger in turns (wheel slip); robot speed <= 0.5 m/s.")

#: Our criteria, printed beside the paper's claims.
AIMS = ("Our criteria (not the paper's): KLD-sampling using at least 3 times fewer particles "
        "while tracking than while globally localizing, with median position error under "
        "0.15 m while walking.")


def text(s: Any, eps: list[dict[str, Any]], summary: dict[str, Any],
         tri_summary: dict[str, Any]) -> str:
    """The printed report of the run's settings ``s``
    (:class:`~soccer_lab.papers.localization.Settings`), its episodes' results ``eps`` and
    their summaries: the setting, the filters' medians over the episodes, each episode's
    median position error, KLD-sampling against our criteria, the recovery seed's effect,
    triangulation alone, and the paper."""
    seeds, tk = s.seeds, eps[0]["kidnap_time"]
    spec = presets.robot(ROBOT)
    span = f"seed {seeds[0]}" if len(seeds) == 1 else f"seeds {seeds[0]}-{seeds[-1]}"
    frames = int(np.median([ep["frames"] for ep in eps]))
    seen = int(np.median([ep["frames_seen"] for ep in eps]))
    kid = ("no kidnapping" if tk is None else
           f"kidnapped at {tk:.1f} s (two thirds of each episode) to a pose drawn from the seed, "
           f"at least 2 m away and turned by 90 deg or more, unknown to the filters")
    lines = [
        f"Walking humanoid ({ROBOT}, {CRUISE * spec.max_forward_speed:.2f} m/s, turning now "
        f"and then and at the edges) in {s.episodes} episode(s) of {s.duration:g} s ({span}; "
        f"route, camera noise and kidnapping drawn from the seed) on the {FIELD} field "
        f"(6 m x 4 m), head scanning +-90 deg, {CAMERA} camera (51 deg, 25 Hz, landmarks by "
        f"kind within 4 m: median {frames} frames per episode, {seen} with landmarks); the walk "
        f"engine's odometry; global start; {kid}. Each episode is recorded once and replayed "
        f"into every filter. Errors and tracking particles after the first {SETTLE:g} s, "
        f"leaving out the {SETTLE:g} s after the kidnapping; localized / recovered: position "
        f"error below {RECOVERED_M:g} m for {RECOVERED_HOLD:g} s.", "",
        *_filter_table(s, summary)]
    if tk is not None:
        lines += ["", "Kidnapped to (x [m], y [m], heading [deg]): " + "; ".join(
            f"seed {ep['seed']} ({ep['kidnap_to'][0]:.2f}, {ep['kidnap_to'][1]:.2f}, "
            f"{math.degrees(ep['kidnap_to'][2]):.0f})" for ep in eps) + "."]
    lines += ["", *_kld_lines(s, eps, summary), "", *_fox_lines(s, eps, summary), "",
              *_seed_lines(s, eps, summary), "",
              *_triangulation_table(s, tri_summary), "",
              "Median position error while tracking, in turns / walking straight (medians "
              "over the episodes): "
              + "; ".join(f"{name} {_fmt2(r['median_pos_turning_m'])} / "
                          f"{_fmt2(r['median_pos_straight_m'])} m"
                          for name, r in summary.items()) + ".", "",
              "Landmarks are known by kind only (each particle takes the candidate of the kind "
              "that explains a sighting best); the field looks the same turned by 180 degrees "
              "except for the goal-post colours, so a filter can settle on the mirror pose "
              "until it sees a post (the last column).", "", AIMS, "", PAPER]
    fell = [(ep["seed"], ep["falls"]) for ep in eps if ep["falls"]]
    if fell:
        lines += ["", "The robot fell: " + "; ".join(f"seed {sd} {n} time(s)" for sd, n in fell)
                  + "."]
    return "\n".join(lines)


def rows(s: Any, res: Summaries) -> list[dict[str, Any]]:
    """The CSV rows: per filter its medians over the episodes, then its figures per episode
    (seed by seed), then the same for triangulation alone."""
    out = [{"filter": name, "episode": "median",
            **{k: v for k, v in r.items() if not isinstance(v, list)}}
           for name, r in res.summary.items()]
    out += [{"filter": name, "episode": sd, **pe[name]}
            for sd, pe in zip(s.seeds, res.per_episode) for name in res.summary]
    out += [{"filter": name, "episode": "median", **r} for name, r in res.tri_summary.items()]
    out += [{"filter": name, "episode": sd, **pe[name]}
            for sd, pe in zip(s.seeds, res.tri_per_episode) for name in res.tri_summary]
    return out


def data(s: Any, eps: list[dict[str, Any]], res: Summaries) -> dict[str, Any]:
    """The JSON data: the settings, the summaries and every episode's results (its series
    per frame included)."""
    return {"duration": s.duration, "seed": s.seed, "episodes": s.episodes,
            "seeds": s.seeds, "kidnap_time": eps[0]["kidnap_time"],
            "kld_config": eps[0]["kld_config"], "summary": res.summary,
            "triangulation": res.tri_summary,
            "per_episode": [{k: v for k, v in ep.items()
                             if k not in ("kld_name", "kld_config")}
                            for ep in eps]}


def _filter_table(s: Any, summary: dict[str, Any]) -> list[str]:
    """The filters' medians over the episodes, and each episode's median position error."""
    lines = [
        f"Per filter, the median over the {s.episodes} episode(s) of each episode's figure "
        "(the times: \"never\" counts as infinitely late, the episodes in which it never "
        "happened in brackets):", "",
        "| filter | median position error [m] | median heading error [deg] | particles at the "
        "start (global) | mean particles in the first second | mean particles while tracking "
        "| median particles while tracking | ms per update | localized after [s] | recovered "
        "after the kidnapping [s] | frames at the mirror pose [%] |",
        "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, r in summary.items():
        rec = "-" if not s.kidnap else _fmt_never(r["recovery_s"], r["recovery_never"])
        lines.append(f"| {name} | {r['median_pos_m']:.3f} | {r['median_head_deg']:.1f} | "
                     f"{r['initial_particles']:.0f} | {r['first_second_particles']:.0f} | "
                     f"{r['tracking_particles']:.0f} | {r['tracking_particles_median']:.0f} | "
                     f"{r['ms_per_update']:.2f} | "
                     f"{_fmt_never(r['localized_s'], r['localized_never'])} | {rec} | "
                     f"{r['mirror_pct']:.0f} |")
    lines += ["", "Median position error while tracking per episode [m]:", "",
              "| filter | " + " | ".join(f"seed {sd}" for sd in s.seeds) + " |",
              "|---|" + "---|" * len(s.seeds)]
    for name, r in summary.items():
        lines.append(f"| {name} | "
                     + " | ".join(f"{v:.3f}" for v in r["median_pos_m_per_episode"]) + " |")
    return lines


def _kld_lines(s: Any, eps: list[dict[str, Any]], summary: dict[str, Any]) -> list[str]:
    """KLD-sampling's particles and error against our criteria."""
    kld = summary[eps[0]["kld_name"]]
    kld_cfg = KLDConfig(**eps[0]["kld_config"])
    ratio = kld["initial_particles"] / max(kld["tracking_particles"], 1.0)
    met = ratio >= 3.0 and kld["median_pos_m"] < AIM_POS_M
    at_min = float(np.median([ep["kld_at_min_pct"] for ep in eps]))
    return [f"KLD-sampling, medians over the {s.episodes} episode(s): {ratio:.0f} times fewer "
            f"particles while tracking than while globally localizing (the start); median "
            f"position error {kld['median_pos_m']:.3f} m while walking, under "
            f"{AIM_POS_M:g} m in {kld['pos_aim_episodes']} of {s.episodes} episode(s): "
            f"{'criteria met' if met else 'criteria NOT met'}. It keeps its global set only "
            f"until the first frame with landmarks (mean "
            f"{kld['first_second_particles']:.0f} in the first second) and sits at its "
            f"minimum of {kld_cfg.min_particles} in "
            f"{at_min:.0f} % of the frames (median {kld['tracking_particles_median']:.0f} "
            f"while tracking)"
            + ("; the mean while tracking comes from the recovery's uniform draws, which "
               "grow it to thousands." if kld["tracking_particles"]
               > 1.5 * kld["tracking_particles_median"] else ".")]


def _fox_lines(s: Any, eps: list[dict[str, Any]], summary: dict[str, Any]
               ) -> list[str]:
    """KLD-sampling binning the predicted samples (Fox 2003) against binning the resampled
    ones (ours)."""
    name = eps[0]["kld_name"]
    a, b = summary[name], summary[name + FOX]
    return [f"Where the bins are counted: on the resampled particles before the motion (ours,"
            f" the default) median position error {a['median_pos_m']:.3f} m, "
            f"{a['tracking_particles']:.0f} particles while tracking (median "
            f"{a['tracking_particles_median']:.0f}), {a['ms_per_update']:.2f} ms per update; "
            f"on the predicted samples, as Fox's KLD-sampling does: {b['median_pos_m']:.3f} m, "
            f"{b['tracking_particles']:.0f} (median {b['tracking_particles_median']:.0f}), "
            f"{b['ms_per_update']:.2f} ms; under {AIM_POS_M:g} m in "
            f"{a['pos_aim_episodes']} and {b['pos_aim_episodes']} of {s.episodes} "
            "episode(s)."]


def _seed_lines(s: Any, eps: list[dict[str, Any]], summary: dict[str, Any]
                ) -> list[str]:
    """KLD-sampling with the triangulation recovery seed against its uniform recovery."""
    name = eps[0]["kld_name"]
    a, b = summary[name], summary[name + SEEDED]
    return [f"Recovery seed (Xu et al.'s 2012 triangulation from the sightings of the last "
            f"{SEED_MEMORY} frames with landmarks, half of the injected particles around the "
            f"poses that fit best): median position error {a['median_pos_m']:.3f} m with "
            f"uniform recovery, {b['median_pos_m']:.3f} m with the seed; under "
            f"{AIM_POS_M:g} m in {a['pos_aim_episodes']} and {b['pos_aim_episodes']} of "
            f"{s.episodes} episode(s); localized after "
            f"{_fmt_never(a['localized_s'], a['localized_never'])} and "
            f"{_fmt_never(b['localized_s'], b['localized_never'])} s"
            + ("" if not s.kidnap else
               f"; recovered after {_fmt_never(a['recovery_s'], a['recovery_never'])} and "
               f"{_fmt_never(b['recovery_s'], b['recovery_never'])} s")
            + f"; frames at the mirror pose {a['mirror_pct']:.0f} % and "
            f"{b['mirror_pct']:.0f} %."]


def _triangulation_table(s: Any, tri: dict[str, Any]) -> list[str]:
    """Triangulation alone per frame: how often it gives a pose, how good, and why not."""
    lines = [
        f"Triangulation alone (Xu et al. 2012, no filter) at every frame, medians over the "
        f"{s.episodes} episode(s) of each episode's figure: the best pose of the candidate "
        f"assignments, a wrong assignment when it is more than {WRONG_M:g} m from the truth "
        "(the shares add up to 100 % of the frames; errors over the frames with a pose, and "
        "over the correct ones):", "",
        "| sightings | correct pose [%] | wrong assignment (ambiguous landmarks) [%] (at the "
        "mirror pose) | fewer than three landmarks [%] | degenerate geometry [%] | no "
        "assignment fits [%] | median position error [m] (correct ones) | median heading "
        "error [deg] (correct ones) | ms per frame |",
        "|---|---|---|---|---|---|---|---|---|"]
    for name, r in tri.items():
        lines.append(
            f"| {name} | {r['correct_pct']:.0f} | {r['wrong_pct']:.0f} "
            f"({r['mirror_pct']:.0f}) | {r['too_few_pct']:.0f} | {r['degenerate_pct']:.1f} | "
            f"{r['no_fit_pct']:.1f} | {_fmt2(r['median_pos_m'])} "
            f"({_fmt2(r['median_pos_correct_m'])}) | {_fmt1(r['median_head_deg'])} "
            f"({_fmt1(r['median_head_correct_deg'])}) | {r['ms_per_frame']:.2f} |")
    return lines


def _fmt(v: float | None) -> str:
    return "never" if v is None else f"{v:.1f}"


def _fmt1(v: float | None) -> str:
    return "-" if v is None else f"{v:.1f}"


def _fmt2(v: float | None) -> str:
    return "-" if v is None else f"{v:.3f}"


def _fmt_never(v: float | None, never: int) -> str:
    """A median time over episodes and, beside it, the episodes in which it never happened."""
    return _fmt(v) + (f" ({never} never)" if never else "")


def plot(s: Any, eps: list[dict[str, Any]]) -> str:
    """The first episode's position errors of every filter; every episode's KLD error and
    particle count."""
    import textwrap

    from soccer_env.render.plots import (
        LABEL_SIZE,
        TITLE_SIZE,
        legend_beside,
        style_key,
    )

    first, kld_name, tk = eps[0], eps[0]["kld_name"], eps[0]["kidnap_time"]
    plt = pyplot()
    fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(11, 8.5), sharex=True)
    t = np.array(first["frame_t"])
    for name, r in first["results"].items():
        ax1.plot(t, np.maximum(r["pos_err"], 1e-3), lw=1,
                 label=textwrap.fill(name, 38, subsequent_indent="  "))
    ax1.set_ylabel("position error [m]", fontsize=LABEL_SIZE)
    ax1.set_yscale("log")
    ax1.set_title(f"Every filter, episode seed {s.seeds[0]}", fontsize=LABEL_SIZE, loc="left")
    for k, ep in enumerate(eps):
        r = ep["results"][kld_name]
        te = np.array(ep["frame_t"])
        ax2.plot(te, np.maximum(r["pos_err"], 1e-3), lw=0.9, color=f"C{k % 10}",
                 label=f"seed {ep['seed']}")
        ax3.plot(te, r["counts"], lw=0.9, color=f"C{k % 10}")
    ax2.set_ylabel("position error [m]", fontsize=LABEL_SIZE)
    ax2.set_yscale("log")
    ax2.set_title(f"{kld_name}, every episode", fontsize=LABEL_SIZE, loc="left")
    ax3.set(yscale="log")
    ax3.set_xlabel("time since the episode's start [s]", fontsize=LABEL_SIZE)
    ax3.set_ylabel("particles", fontsize=LABEL_SIZE)
    ax3.set_title(f"{kld_name}: particle count, every episode", fontsize=LABEL_SIZE,
                  loc="left")
    for ax in (ax1, ax2):
        ax.axhline(RECOVERED_M, color="0.4", ls=":", lw=1.2)
    for ax in (ax1, ax2, ax3):
        ax.grid(alpha=0.3)
        if tk is not None:
            ax.axvline(tk, color="r", ls="--", lw=1.2)
    field = presets.field(FIELD)
    kidnap = (f", picked up and put down elsewhere at {tk:.1f} s" if tk is not None
              else ", never kidnapped")
    fig.suptitle(f"Guo and Li (2013) localization: one walking {ROBOT} humanoid on the "
                 f"{FIELD} field ({field.length:g} m x {field.width:g} m)\nhead camera "
                 f"{CAMERA}, global start{kidnap}", fontsize=TITLE_SIZE)
    legend_beside(ax1, title="filter")
    keys = [style_key(f"{RECOVERED_M:g} m: localized below", ls=":", lw=1.2, color="0.4")]
    if tk is not None:
        keys.append(style_key("kidnapping", ls="--", lw=1.2, color="r"))
    seeds = legend_beside(ax2, title="colour: episode")
    legend_beside(ax2, keys, title="line style", below=seeds)
    return save_figure(fig, s.out / "paper_localization.png")
