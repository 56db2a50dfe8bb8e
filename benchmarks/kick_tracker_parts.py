"""What each part of the humanoid kick tracker (``ball_tracker="kick"``,
:class:`estimators.LineBallTracker`) is worth to the scripted humanoid keeper: the tracker
whole, then with one part taken out at a time, on the same seeded shots.

Usage: ``python benchmarks/kick_tracker_parts.py [--episodes 1000] [--start-seed 0]
[--variants kick,one-phase,...]``.

The keeper is the humanoid ablation's (``humanoid-2012`` with three team-mates, perceived
``kidsize-2012``, KLD localization). The variants:

* ``kick``: the tracker as registered;
* ``no-kick-hypothesis``: no kick hypothesis is ever opened (the lines alone, each at its
  capture time, through the Kalman filter's acceleration noise);
* ``white-pose``: the observers' localization errors taken as white noise of each line (as
  the fusion does) instead of biases in the state;
* ``walking``: every line weighed with a walking robot's sway, even a standing robot's;
* ``floor-5``: the fusion's 5 % least relative range error instead of 2 %;
* ``one-phase``: the ball rolls after a kick (no sliding phase);
* ``fusion-mfbpf``: the default tracker before it (Hough fusion, MFBPF), for reference.

Each runs in this process (the variants are registered here); save rates with Wilson 95 %
intervals and ball RMSE, and how many shots each variant saves that the whole tracker does
not and the other way round (the same shots, paired).
"""

from __future__ import annotations

import argparse
import functools
import sys
from typing import Any

import soccer_env  # noqa: F401
from agents.runs.evaluation import evaluate
from estimators import LineBallTracker, SightingNoise
from soccer_env.perception import BALL_TRACKERS
from soccer_env.perception.options import line_tracker
from soccer_env.presets import BallSpec

#: Variants and the arguments of their trackers (see the module docstring).
VARIANTS = ("kick", "no-kick-hypothesis", "white-pose", "walking", "floor-5", "one-phase",
            "fusion-mfbpf")


class _Walking(LineBallTracker):
    """The tracker with every line weighed by the team's walking sigmas."""

    def line(self, t: float, ox: float, oy: float, angle: float, range_: float, own: bool,
             observer: int = 0, bearing_sigma: float | None = None,
             range_per_metre: float | None = None) -> None:
        super().line(t, ox, oy, angle, range_, own, observer)


def _variant(name: str, rng: Any, ball: BallSpec, max_speed: float, noise: SightingNoise,
             observers: tuple[int, ...]) -> LineBallTracker:
    """The kick tracker's factory with the part ``name`` taken out."""
    overrides: dict[str, Any] = {}
    if name == "no-kick-hypothesis":
        overrides = {"suspect": 1e12, "gate": 1e12}
    elif name == "white-pose":
        overrides = {"biases": False}
    elif name == "walking":
        overrides = {"cls": _Walking}
    elif name == "floor-5":
        noise = noise._replace(range_sigma_rel=0.05)
    elif name == "one-phase":
        overrides = {"sliding_deceleration": 0.0}
    return line_tracker(rng, ball, max_speed, noise, observers, **overrides)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--episodes", type=int, default=1000)
    p.add_argument("--start-seed", type=int, default=0)
    p.add_argument("--variants", default=",".join(VARIANTS))
    args = p.parse_args(argv)
    names = args.variants.split(",")
    unknown = sorted(set(names) - set(VARIANTS))
    if unknown:
        p.error(f"--variants: unknown {unknown}; allowed: {', '.join(VARIANTS)}")
    registered = []
    try:
        _table(names, args.episodes, args.start_seed, registered)
    finally:  # leave the registry as it was
        for tracker in registered:
            BALL_TRACKERS.unregister(tracker)
    return 0


def _table(names: list[str], episodes: int, start_seed: int, registered: list[str]) -> None:
    """Evaluate and print each variant (registering the trackers it needs in
    ``registered``)."""
    results: dict[str, Any] = {}
    print(f"| kick tracker, scripted humanoid keeper, kidsize-2012 | save rate ({episodes} "
          f"shots from seed {start_seed}, 95 % CI) | ball RMSE [mm] | saved by it alone "
          "/ by the whole tracker alone |")
    print("|---|---|---|---|")
    for name in names:
        tracker = name
        if name not in ("kick", "fusion-mfbpf"):
            tracker = f"kick-{name}"
            if tracker not in BALL_TRACKERS:
                BALL_TRACKERS.register(tracker, functools.partial(_variant, name),
                                       f"the kick tracker, {name}")
                registered.append(tracker)
        perception = {"camera": "kidsize-2012", "ball_tracker": tracker.replace(
            "fusion-mfbpf", "mfbpf")}
        res = evaluate("scripted", {"robot": "humanoid-2012", "obs_mode": "perceived",
                                    "perception": perception},
                       episodes, start_seed, 1)
        results[name] = res
        whole = results.get("kick")
        paired = "" if whole is None or name == "kick" else (
            f"{sum(a and not b for a, b in zip(res.saved, whole.saved))} / "
            f"{sum(b and not a for a, b in zip(res.saved, whole.saved))}")
        print(f"| {name} | {100 * res.save_rate:.1f} % ({100 * res.ci_low:.1f}-"
              f"{100 * res.ci_high:.1f}) | {1000 * res.ball_rmse_m:.0f} | {paired} |",
              flush=True)


if __name__ == "__main__":
    sys.exit(main())
