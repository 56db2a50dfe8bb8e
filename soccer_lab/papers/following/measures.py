"""The measures of Yu, Wei and Zhang (2010)'s reproduction: which frames count, the
trackers' errors, losses and recoveries, pooled per variant (:func:`summarise`) and by turn
rate or image jump (:func:`binned`), and the aim's verdict (see
:mod:`soccer_lab.papers.following`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["TURN_BINS", "JUMP_BINS", "scored", "errors", "transitions", "was_on", "rate",
           "summarise", "binned", "verdict"]

#: Turn-rate bins as fractions of the robot's top turn rate.
TURN_BINS = (("slow", 0.0, 1.0 / 3.0), ("medium", 1.0 / 3.0, 2.0 / 3.0),
             ("fast", 2.0 / 3.0, math.inf))
#: Bins of the ball's image jump between frames, in its apparent radii (a window of scale x
#: has a half-width, the mean-shift bandwidth, of about x radii).
JUMP_BINS = (("< 1", 0.0, 1.0), ("1-2", 1.0, 2.0), ("2-4", 2.0, 4.0),
             (">= 4", 4.0, math.inf))


def scored(ep: dict[str, Any]) -> np.ndarray:
    """Frames that count: after the first, the ball's centre in the image."""
    m = ep["rec"]["in_view"].copy()
    m[0] = False
    return m


def errors(ep: dict[str, Any], lab: str) -> tuple[np.ndarray, np.ndarray]:
    """Pixel error per frame and whether it is off target (beyond the ball's radius)."""
    rec, o = ep["rec"], ep["out"][lab]
    err = np.hypot(o["x"] - rec["u"], o["y"] - rec["v"])
    return err, err > rec["radius"]


def transitions(off: np.ndarray, mask: np.ndarray) -> tuple[int, int]:
    """Losses (on -> off) and recoveries (off -> on) between consecutive scored frames; the
    first frame (the start) counts as on target."""
    state = np.where(mask, off.astype(float), np.nan)
    state[0] = 0.0
    d = np.diff(state[~np.isnan(state)])
    return int(np.sum(d > 0)), int(np.sum(d < 0))


def was_on(off: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Frames whose previous frame was scored and on target (the start counts as on)."""
    prev = np.zeros(len(off), bool)
    prev[1:] = mask[:-1] & ~off[:-1]
    prev[1] = True
    return prev & mask


def rate(x: np.ndarray) -> float:
    """The mean of boolean or numeric ``x``; NaN when empty."""
    return float(np.mean(x)) if len(x) else math.nan


def summarise(eps: list[dict[str, Any]]) -> dict[str, Any]:
    """Per tracker: rates, errors, transitions, timing and depth over ``eps`` pooled."""
    res: dict[str, Any] = {"trackers": {}}
    frames = sum(int(scored(e).sum()) for e in eps)
    total = sum(len(e["rec"]["t"]) - 1 for e in eps)
    for lab in eps[0]["labels"]:
        err, off, lost, ms, rel, signed, hazard = [], [], [], [], [], [], []
        losses = recoveries = 0
        for e in eps:
            m = scored(e)
            er, of = errors(e, lab)
            hazard.append(of[was_on(of, m)])
            err.append(er[m])
            off.append(of[m])
            lost.append(e["out"][lab]["lost"][m])
            ms.append(e["out"][lab]["ms"][1:])
            lo, rc = transitions(of, m)
            losses += lo
            recoveries += rc
            on = m & ~of & np.isfinite(e["out"][lab]["size_distance"])
            truth = e["rec"]["distance"][on]
            est = e["out"][lab]["size_distance"][on]
            rel.append(np.abs(est - truth) / truth)
            signed.append((est - truth) / truth)
        err_a, off_a = np.concatenate(err), np.concatenate(off)
        rel_a, signed_a = np.concatenate(rel), np.concatenate(signed)
        on_err = err_a[~off_a]
        res["trackers"][lab] = {
            "frames": int(len(err_a)),
            "lost_rate": rate(np.concatenate(lost)),
            "off_target_rate": rate(off_a),
            "loss_hazard": rate(np.concatenate(hazard)),
            "median_error_px": float(np.median(err_a)) if len(err_a) else math.nan,
            "rmse_on_target_px": (float(np.sqrt(np.mean(on_err ** 2))) if len(on_err)
                                  else math.nan),
            "losses": losses, "recoveries": recoveries,
            "ms_per_frame": float(np.nanmean(np.concatenate(ms))),
            "depth_frames": int(len(rel_a)),
            "depth_median_rel": float(np.median(rel_a)) if len(rel_a) else math.nan,
            "depth_median_signed": float(np.median(signed_a)) if len(signed_a) else math.nan,
        }
    res["frames"] = frames
    res["out_of_view_rate"] = 1.0 - frames / total if total else math.nan
    res["bp_ms_per_frame"] = float(np.nanmean(np.concatenate([e["bp_ms"] for e in eps])))
    return res


def binned(eps: list[dict[str, Any]], key: str) -> list[dict[str, Any]]:
    """Rates per bin of the turn rate (``key="turn"``, fractions of the top turn rate) or of
    the ball's image jump in its apparent radii (``"jump"``), pooled over ``eps``."""
    bins = TURN_BINS if key == "turn" else JUMP_BINS
    labels = eps[0]["labels"]
    rows = []
    for name, lo, hi in bins:
        parts: dict[str, list[np.ndarray]] = {"jump": [], "still": [], "rate": []}
        acc = {lab: {"off": [], "lost": [], "hazard": []} for lab in labels}
        for e in eps:
            rec = e["rec"]
            x = (rec["turn_rate"] / e["max_turn"] if key == "turn"
                 else rec["jump"] / rec["radius"])
            sel = scored(e) & (x >= lo) & (x < hi)
            parts["jump"].append(rec["jump"][sel] / rec["radius"][sel])
            parts["still"].append(rec["jump_still"][sel] / rec["radius"][sel])
            parts["rate"].append(rec["turn_rate"][sel])
            for lab in labels:
                of = errors(e, lab)[1]
                acc[lab]["off"].append(of[sel])
                acc[lab]["lost"].append(e["out"][lab]["lost"][sel])
                acc[lab]["hazard"].append(of[sel & was_on(of, scored(e))])
        jump, still, turn = (np.concatenate(parts[k]) for k in ("jump", "still", "rate"))
        row: dict[str, Any] = {"bin": name, "frames": int(len(jump)),
                               "mean_turn_rate": rate(turn),
                               "mean_jump_radii": rate(jump),
                               "mean_jump_radii_without_sway": rate(still)}
        for lab in labels:
            row[f"{lab} off_target_rate"] = rate(np.concatenate(acc[lab]["off"]))
            row[f"{lab} lost_rate"] = rate(np.concatenate(acc[lab]["lost"]))
            row[f"{lab} loss_hazard"] = rate(np.concatenate(acc[lab]["hazard"]))
        rows.append(row)
    return rows


def verdict(kalman: float, plain: float) -> str:
    """Met if the Kalman tracker's share is at most half the plain one's."""
    if not (math.isfinite(kalman) and math.isfinite(plain)):
        return "not testable (no frames)"
    if plain == 0.0 and kalman == 0.0:
        return "not testable (neither tracker lost the ball)"
    return "met" if kalman <= 0.5 * plain else "not met"
