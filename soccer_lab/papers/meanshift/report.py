"""The report of Li, Wu and Kong (2010)'s reproduction: the episodes' measures pooled
(:func:`summarise`, :func:`motion`, :func:`diagnostics`), the printed text with the paper's
claims and the aims (:func:`text`) and the figure (:func:`plot`); see
:mod:`soccer_lab.papers.meanshift`."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from soccer_env import presets
from soccer_env.render.plots import pyplot, save_figure
from soccer_lab.papers.meanshift.scene import FRAME, INTERVAL, KINDS, ROBOT, TURN

__all__ = ["PAPER", "AIMS", "CDF_EDGES_MM", "summarise", "prep_ms", "motion", "diagnostics",
           "verdicts", "text", "plot", "lost_runs"]

#: Li et al.'s (2010) figures (experiment 2: Pentium 4 2.6 GHz, 640 x 480 images).
PAPER = {"plain_pf_particles": 200, "ms_pf_particles": 20, "cycle_ms": 33.0,
         "text": "Li et al. (2010): a plain PF needs at least 200 particles to track the robots "
                 "reliably, the feature-restricted mean-shift PF about 20; the system's cycle "
                 "stays about 33 ms (Pentium 4 2.6 GHz, 640 x 480)."}
#: The aims of the reproduction.
AIMS = {"ms_per_robot": 5.0,
        "text": "Our criteria (not the paper's): the 20-particle mean-shift PF at least as "
                "accurate as the 200-particle plain PF (the paper's claim); under 5 ms per "
                "tracked robot per 640 x 480 frame."}
#: Error CDF bins [mm].
CDF_EDGES_MM = np.geomspace(0.05, 3000.0, 121)


def _measures(err_px: np.ndarray, mate: np.ndarray, lost: np.ndarray | None, mpp: float,
              radius_px: float, fast: np.ndarray) -> dict[str, Any]:
    """Errors (pixels and mm), shares lost, off target and on a team-mate, of one tracker
    kind over robot-frames (``fast``: those faster than 2 m/s)."""
    e = err_px.ravel()
    mm = 1e3 * mpp
    return {"median_px": float(np.median(e)), "p90_px": float(np.percentile(e, 90)),
            "rmse_px": float(np.sqrt(np.mean(e * e))),
            "median_mm": float(np.median(e) * mm), "p90_mm": float(np.percentile(e, 90) * mm),
            "rmse_mm": float(np.sqrt(np.mean(e * e)) * mm),
            "median_fast_mm": float(np.median(err_px[fast]) * mm) if fast.any()
            else float("nan"),
            "lost_share": None if lost is None else float(lost.mean()),
            "off_target_share": float(np.mean(e > radius_px)),
            "on_teammate_share": float(mate.mean())}


def _why(ms: dict[str, Any], pf: dict[str, Any], diag: dict[str, Any]) -> str:
    """Why the mean-shift PF is less accurate than the 200-particle plain PF (figures)."""
    parts = []
    if ms["median_mm"] <= pf["median_mm"]:
        parts.append("it is the more precise while it tracks (median), but")
    parts.append(f"it reports its robot lost in {100 * ms['lost_share']:.1f} % of the frames "
                 f"(the true robot's colour mass leaves the +-30 % band in "
                 f"{100 * diag['true_area_fail_share']:.1f} % of robot-frames, and in "
                 f"{100 * diag['lost_while_passable_share']:.0f} % of the lost frames the global "
                 "search misses a robot that would pass), and a lost track stands still while "
                 "the robot moves on")
    return "; " + " ".join(parts)


def lost_runs(lost: list[np.ndarray]) -> list[int]:
    """Lengths [frames] of the runs of consecutive lost frames, per robot and episode."""
    out = []
    for arr in lost:
        for col in arr.T:
            padded = np.concatenate([[False], col, [False]]).astype(np.int8)
            edges = np.flatnonzero(np.diff(padded))
            out += (edges[1::2] - edges[::2]).tolist()
    return out


def summarise(eps: list[dict[str, Any]]
              ) -> tuple[dict[str, dict[str, Any]], list[dict[str, Any]]]:
    """Per tracker kind, the measures pooled over every robot, frame and episode (with the
    error CDF); and the CSV rows: the pooled one and one per episode for every kind."""
    mpp, radius_px = eps[0]["mpp"], eps[0]["radius_px"]
    speed = np.concatenate([np.asarray(e["speed"]) for e in eps])
    fast = speed > 2.0
    summary: dict[str, dict[str, Any]] = {}
    rows: list[dict[str, Any]] = []
    for k in KINDS:
        err = np.concatenate([np.asarray(e["err_px"][k]) for e in eps])
        mate = np.concatenate([np.asarray(e["mate"][k]) for e in eps])
        lost = (np.concatenate([np.asarray(e["lost"][k]) for e in eps]) if k in eps[0]["lost"]
                else None)
        s = _measures(err, mate, lost, mpp, radius_px, fast)
        s["ms_per_update"] = float(np.mean([e["ms_per_update"][k] for e in eps]))
        s["error_cdf"] = (np.searchsorted(np.sort(err.ravel() * 1e3 * mpp), CDF_EDGES_MM,
                                          side="right") / err.size).tolist()
        summary[k] = s
        rows.append({"episode": "all", "tracker": k,
                     **{kk: v for kk, v in s.items() if not isinstance(v, list)}})
        for e in eps:
            ek = np.asarray(e["err_px"][k])
            el = np.asarray(e["lost"][k]) if k in e["lost"] else None
            es = _measures(ek, np.asarray(e["mate"][k]), el, mpp, radius_px,
                           np.asarray(e["speed"]) > 2.0)
            rows.append({"episode": e["seed"], "tracker": k, **es,
                         "ms_per_update": e["ms_per_update"][k]})
    return summary, rows


def prep_ms(eps: list[dict[str, Any]]) -> float:
    """The shared images' time per frame [ms], the mean over the episodes."""
    return float(np.mean([e["prep_ms_per_frame"] for e in eps]))


def motion(eps: list[dict[str, Any]]) -> dict[str, float]:
    """The robots' true motion: speeds, and the AR(2) model's one-frame prediction error of
    the true track."""
    mpp = eps[0]["mpp"]
    speed = np.concatenate([np.asarray(e["speed"]) for e in eps])
    fast = speed > 2.0
    resid = np.concatenate([np.asarray(e["residual_px"]).ravel() for e in eps])
    return {"speed_median_m_s": float(np.median(speed)),
            "speed_p90_m_s": float(np.percentile(speed, 90)),
            "speed_max_m_s": float(speed.max()), "fast_share": float(fast.mean()),
            "step_median_px": float(np.median(speed) / 30.0 / mpp),
            "ar_residual_median_px": float(np.median(resid)),
            "ar_residual_p99_px": float(np.percentile(resid, 99)),
            "ar_residual_max_px": float(resid.max())}


def diagnostics(eps: list[dict[str, Any]]) -> dict[str, Any]:
    """The mean-shift PF's diagnostics: how often the true robot's window would fail its
    restriction or identity check, its lost-track events, and the lost frames in which the
    true robot would have passed both."""
    lost_all = np.concatenate([np.asarray(e["lost"]["ms-pf-20"]) for e in eps])
    area_ok = np.concatenate([np.asarray(e["true_area_ok"]) for e in eps])
    id_ok = np.concatenate([np.asarray(e["true_id_ok"]) for e in eps])
    runs = lost_runs([np.asarray(e["lost"]["ms-pf-20"]) for e in eps])
    visible = area_ok & id_ok
    return {"true_area_fail_share": float(1.0 - area_ok.mean()),
            "true_id_fail_share": float(1.0 - id_ok.mean()),
            "lost_events": len(runs),
            "lost_run_median_frames": float(np.median(runs)) if runs else 0.0,
            "lost_run_max_frames": int(max(runs)) if runs else 0,
            "lost_while_passable_share": float(visible[lost_all].mean()) if lost_all.any()
            else 0.0}


def verdicts(summary: dict[str, dict[str, Any]]) -> dict[str, Any]:
    """The aims judged: the mean-shift PF at least as accurate as the 200-particle plain PF
    (median and RMSE), and fast enough."""
    ms, p200 = summary["ms-pf-20"], summary["pf-200"]
    accurate = ms["median_mm"] <= p200["median_mm"] and ms["rmse_mm"] <= p200["rmse_mm"]
    fast_ok = ms["ms_per_update"] < AIMS["ms_per_robot"]
    return {"accurate": accurate, "under_5_ms": fast_ok, "text": AIMS["text"]}


def text(eps: list[dict[str, Any]], summary: dict[str, dict[str, Any]], per_team: int,
         duration: float, n_workers: int) -> str:
    """The printed report (see :mod:`soccer_lab.papers.meanshift`)."""
    mpp, radius_px = eps[0]["mpp"], eps[0]["radius_px"]
    ms = summary["ms-pf-20"]
    prep = prep_ms(eps)
    n_rob = 2 * per_team
    frames = sum(e["frames"] for e in eps)
    w, h = eps[0]["image"]
    lines = [f"Li et al. (2010): {per_team} blue + {per_team} yellow `{ROBOT}` robots manoeuvring "
             f"sharply (a new body-frame velocity at 80-100 % of "
             f"{presets.robot(ROBOT).max_speed:g} m/s and a turn rate within +-"
             f"{TURN * presets.robot(ROBOT).max_angular_speed:g} rad/s every "
             f"{INTERVAL[0]:g}-{INTERVAL[1]:g} s) on a MiroSot-sized field (2.2 x 1.8 m), "
             f"filmed from above by the `{FRAME}` camera ({w} x {h} at 30 Hz, 1/60 s exposure: "
             f"motion blur, flicker, noise; {1e3 * mpp:.2f} mm/px, robot radius "
             f"{radius_px:.1f} px, search window {eps[0]['window_px']} px); {len(eps)} seeded "
             f"episode(s) of {duration:g} s, {frames} frames x {n_rob} robots per tracker. "
             "Colour image: the robot's team colour (team-mates look the same); motion "
             "image: the frame difference. The mean-shift PF confirms identity by the "
             "robot's player dots; the plain PFs have no identity or lost-track test.", "",
             "| tracker | median error [px / mm] | p90 [mm] | RMSE [px / mm] | median at "
             "> 2 m/s [mm] | reported lost | off target (> robot radius) | on a team-mate | "
             "ms per robot per frame |",
             "|---|---|---|---|---|---|---|---|---|"]
    for k, s in summary.items():
        lost = "-" if s["lost_share"] is None else f"{100 * s['lost_share']:.1f} %"
        lines.append(f"| {k} | {s['median_px']:.1f} / {s['median_mm']:.0f} | "
                     f"{s['p90_mm']:.0f} | {s['rmse_px']:.1f} / {s['rmse_mm']:.0f} | "
                     f"{s['median_fast_mm']:.0f} | {lost} | "
                     f"{100 * s['off_target_share']:.1f} % | "
                     f"{100 * s['on_teammate_share']:.1f} % | {s['ms_per_update']:.3f} |")
    cycle = prep + n_rob * ms["ms_per_update"]
    diag = diagnostics(eps)
    lines += ["", *_motion_lines(motion(eps)), "", *_diagnostic_lines(diag)]
    lines += ["", f"Shared images per frame (4 colour look-ups, 2 box filters, frame "
              f"difference): {prep:.2f} ms; tracking all {n_rob} robots with the mean-shift PF "
              f"then costs {cycle:.2f} ms per frame ({n_rob} x {ms['ms_per_update']:.3f} ms "
              f"+ {prep:.2f} ms). Timed in {n_workers} process(es) on {os.cpu_count()} "
              "core(s).", ""]
    lines += [PAPER["text"], AIMS["text"], "", *_aim_lines(summary, diag, prep, n_rob, w, h)]
    return "\n".join(lines)


def _motion_lines(m: dict[str, float]) -> list[str]:
    return [f"Robots' true motion: speed median {m['speed_median_m_s']:.2f} m/s "
            f"(about {m['step_median_px']:.0f} px per frame), 90th percentile "
            f"{m['speed_p90_m_s']:.2f} m/s, largest {m['speed_max_m_s']:.2f} m/s; "
            f"{100 * m['fast_share']:.1f} % of robot-frames faster than 2 m/s (the "
            f"robots accelerate at most {presets.robot(ROBOT).max_acceleration:g} m/s^2, so "
            "a manoeuvre of 0.2-0.5 s rarely reaches top speed). The AR(2) model's one-frame "
            f"prediction error of the true track: median {m['ar_residual_median_px']:.2f}"
            f" px, 99th percentile {m['ar_residual_p99_px']:.1f} px, largest "
            f"{m['ar_residual_max_px']:.1f} px (collisions)."]


def _diagnostic_lines(diag: dict[str, Any]) -> list[str]:
    return ["Mean-shift PF diagnostics: the window on the true robot fails the colour-mass "
            f"restriction (+-30 % of the first frame's mass) in "
            f"{100 * diag['true_area_fail_share']:.1f} % of robot-frames and the identity check"
            f" in {100 * diag['true_id_fail_share']:.1f} %; {diag['lost_events']} lost-track "
            f"events, median {diag['lost_run_median_frames']:.0f} frames, longest "
            f"{diag['lost_run_max_frames']}; in {100 * diag['lost_while_passable_share']:.0f} "
            "% of the lost frames the true robot's window would have passed both tests (the "
            "global search, which tries the 8 windows of largest colour mass a window "
            "apart, did not reach it)."]


def _aim_lines(summary: dict[str, dict[str, Any]], diag: dict[str, Any], prep: float,
               n_rob: int, w: int, h: int) -> list[str]:
    """The aims and the paper's claims, each with its verdict and figures."""
    ms, p200, p20 = summary["ms-pf-20"], summary["pf-200"], summary["pf-20"]
    cycle = prep + n_rob * ms["ms_per_update"]
    acc_med = ms["median_mm"] <= p200["median_mm"]
    acc_rmse = ms["rmse_mm"] <= p200["rmse_mm"]
    acc_off = ms["off_target_share"] <= p200["off_target_share"]
    accurate = acc_med and acc_rmse
    fast_ok = ms["ms_per_update"] < AIMS["ms_per_robot"]
    pf20_worse = p20["rmse_mm"] > p200["rmse_mm"] or p20["off_target_share"] > \
        p200["off_target_share"]
    return [f"- 20-particle mean-shift PF at least as accurate as the 200-particle plain PF: "
            f"{'met' if accurate else 'not met'} (median {ms['median_mm']:.0f} vs "
            f"{p200['median_mm']:.0f} mm: {'<=' if acc_med else '>'}; RMSE "
            f"{ms['rmse_mm']:.0f} vs {p200['rmse_mm']:.0f} mm: "
            f"{'<=' if acc_rmse else '>'}; off target {100 * ms['off_target_share']:.1f} vs "
            f"{100 * p200['off_target_share']:.1f} %: {'<=' if acc_off else '>'})"
            + ("" if accurate else _why(ms, p200, diag)) + ".",
            f"- Under {AIMS['ms_per_robot']:g} ms per tracked robot per {w} x {h} frame: "
            f"{'met' if fast_ok else 'not met'} ({ms['ms_per_update']:.3f} ms for the "
            f"mean-shift PF's update; {ms['ms_per_update'] + prep / n_rob:.3f} ms with its "
            f"share of the shared images).",
            f"- Paper: a plain PF needs >= 200 particles: with 20 it is "
            f"{'worse' if pf20_worse else 'not worse'} than with 200 here (RMSE "
            f"{p20['rmse_mm']:.0f} vs {p200['rmse_mm']:.0f} mm, off target "
            f"{100 * p20['off_target_share']:.1f} vs {100 * p200['off_target_share']:.1f} %).",
            _printed_line(summary),
            f"- Paper: cycle about {PAPER['cycle_ms']:g} ms on a Pentium 4: tracking "
            f"{n_rob} robots here takes {cycle:.2f} ms per frame on this machine (no "
            "capture, no decision making; a modern CPU)."]


def _printed_line(summary: dict[str, dict[str, Any]]) -> str:
    """Li et al.'s (2010) step 4 as printed (``ms-pf-20-paper``) beside ours (``ms-pf-20``)."""
    ours, printed = summary["ms-pf-20"], summary["ms-pf-20-paper"]

    def figures(s: dict[str, Any]) -> str:
        return (f"median {s['median_px']:.2f} px, RMSE {s['rmse_px']:.2f} px, off target "
                f"{100 * s['off_target_share']:.1f} %, on a team-mate "
                f"{100 * s['on_teammate_share']:.1f} %, lost {100 * s['lost_share']:.1f} %")

    return ("- Step 4 as printed (the unweighted mean of the restricted particles, no "
            f"resampling): {figures(printed)}; ours (weighted mean, systematic resampling): "
            f"{figures(ours)}.")


def plot(eps: list[dict[str, Any]], summary: dict[str, dict[str, Any]], path: Path) -> str:
    """The error CDF per tracker kind, one robot's errors over an episode, and the shares of
    robot-frames off target, on a team-mate and reported lost; one colour per tracker kind."""
    from soccer_env.render.plots import (
        LABEL_SIZE,
        TITLE_SIZE,
        colour_key,
        legend_beside,
        style_key,
    )
    from soccer_lab.papers.meanshift.scene import FIELD

    mpp, radius_px = eps[0]["mpp"], eps[0]["radius_px"]
    colour = {k: f"C{j}" for j, k in enumerate(KINDS)}
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.6),
                             gridspec_kw={"width_ratios": [1.0, 1.0, 0.8]})
    radius_mm = 1e3 * mpp * radius_px
    # The errors' range: from where the first CDF leaves 0 to where the last reaches 1 (and
    # the robot radius), a factor of 2 either side.
    lo, hi = CDF_EDGES_MM[-1], radius_mm
    for k, s in summary.items():
        cdf = np.asarray(s["error_cdf"], dtype=float)
        axes[0].plot(CDF_EDGES_MM, cdf, color=colour.get(k), lw=1.5)
        lo = min(lo, CDF_EDGES_MM[np.argmax(cdf > 0.001)])
        hi = max(hi, CDF_EDGES_MM[np.argmax(cdf >= 0.999)] if cdf[-1] >= 0.999
                 else CDF_EDGES_MM[-1])
    axes[0].axvline(radius_mm, color="0.3", ls=":", lw=1.2)
    axes[0].set(xscale="log", ylim=(0, 1.02), xlim=(max(CDF_EDGES_MM[0], lo / 2),
                                                    min(CDF_EDGES_MM[-1], hi * 2)))
    axes[0].set_xlabel("position error [mm]", fontsize=LABEL_SIZE)
    axes[0].set_ylabel("share of robot-frames\nwith a smaller error", fontsize=LABEL_SIZE)
    axes[0].set_title("Error distribution, every robot and episode", fontsize=LABEL_SIZE)
    ex = np.asarray(eps[0]["err_px"]["ms-pf-20"])
    t = np.arange(1, ex.shape[0] + 1) / 30.0
    top = 0.0
    for k in KINDS:
        err = np.asarray(eps[0]["err_px"][k])[:, 0] * 1e3 * mpp
        axes[1].plot(t, err, color=colour[k], lw=0.9)
        top = max(top, float(np.max(err, initial=0.0)))
    if top >= radius_mm / 2:  # the radius where the errors come near it, not squeezing them
        axes[1].axhline(radius_mm, color="0.3", ls=":", lw=1.2)
    axes[1].set_yscale("symlog", linthresh=1.0)
    axes[1].set_xlabel("time since the episode's start [s]", fontsize=LABEL_SIZE)
    axes[1].set_ylabel("position error [mm]\n(linear below 1 mm, log above)",
                       fontsize=LABEL_SIZE)
    axes[1].set_title(f"Robot blue_0, episode seed {eps[0]['seed']}", fontsize=LABEL_SIZE)
    shares = (("off target", "off_target_share"), ("on a team-mate", "on_teammate_share"),
              ("reported lost\n(mean-shift PFs)", "lost_share"))
    xs = np.arange(len(shares))
    width = 0.8 / len(KINDS)
    for j, k in enumerate(KINDS):
        vals = [summary[k][key] for _, key in shares]
        axes[2].bar(xs + (j - (len(KINDS) - 1) / 2) * width,
                    [np.nan if v is None else 100 * v for v in vals], width, color=colour[k])
    axes[2].set_xticks(xs, [name for name, _ in shares])
    axes[2].set_ylim(bottom=0)
    axes[2].set_ylabel("share of robot-frames [%]", fontsize=LABEL_SIZE)
    axes[2].set_title("Lost tracks, every robot and episode", fontsize=LABEL_SIZE)
    for ax in axes:
        ax.grid(alpha=0.3)
    n = ex.shape[1] if ex.ndim == 2 else 1
    fig.suptitle(f"Li et al. (2010) trackers on overhead images: {n} {ROBOT.upper()} robots on "
                 f"the {FIELD.name} field ({FIELD.length:g} m x {FIELD.width:g} m), camera "
                 f"{FRAME}, {len(eps)} episode(s)", fontsize=TITLE_SIZE)
    first = legend_beside(axes[2], [colour_key(k, colour[k]) for k in KINDS], title="tracker")
    legend_beside(axes[2], [style_key(f"robot radius ({radius_mm:.0f} mm):\noff target beyond",
                                      ls=":", lw=1.2, color="0.3")],
                  title="line style", below=first)
    return save_figure(fig, path)
