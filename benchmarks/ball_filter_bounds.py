"""How far a better ball filter can take the scripted keeper: its save rate with each SSL ball
filter, with the kick-aware filter told the true kick time, and with the sensor's errors
removed one at a time.

Usage: ``python benchmarks/ball_filter_bounds.py [--preset ssl-2012] [--episodes 1000]
[--workers 2] [--filters ekf kick imm]``.

Rows (seeds 0..N-1 of Goalkeeper-v0's suite, Wilson 95 % intervals; the preset's latencies,
frame rate, detection rates and command loss apply in every row):

* each ``--filters`` ball filter, perceived: the closed-loop figure of the estimator ablation;
* ``kick, kick time known``: :class:`~estimators.KickAwareBall` told the shot's true kick time
  at the start of every episode (:meth:`~estimators.KickAwareBall.kick`):
  what any filter of this family could gain from detecting the kick perfectly, the bound of
  that line of work;
* ``ball noise off``: every filter again with the vision's ball noise zero (``ball_sigma =
  0``): the ceiling of any ball filter for this keeper, since a filter can at best remove the
  noise (the latency and the missed frames stay);
* ``robot pose noise off``: the robots' position and heading noise zero (``robot_sigma =
  robot_sigma_theta = 0``): what the keeper's error about its own pose costs, which no ball
  filter can win back;
* ``cameras at 50 m``: the cameras 50 m high instead of the preset's (4 m), so that a chipped
  ball's projection onto the ground moves by 1 % of its distance from the camera's axis
  instead of 14 % at 0.5 m height: an upper bound of what a chip-aware 3-D model could win
  (it also shrinks the shadows robots cast, so it bounds from above);
* ``truth``: the true state (the actuation latency and command loss still apply).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import gymnasium as gym

import soccer_env  # noqa: F401
from agents.runs.evaluation import evaluate
from soccer_env.envs.registration import GOALKEEPER_ID
from soccer_env.presets import vision

GK = GOALKEEPER_ID


class KnownKick(gym.Wrapper):
    """Goalkeeper-v0 whose kick-aware ball filter is told the shot's kick time at reset."""

    def reset(self, **kwargs: Any):
        obs, info = self.env.reset(**kwargs)
        tracker = self.env.unwrapped.pipelines[0].ball_tracker
        if not hasattr(tracker, "kick"):
            raise ValueError(f"the kick time can only be told to a ball filter with kick(), "
                             f"not {type(tracker).__name__}")
        tracker.kick(float(info["shot"]["delay"]))
        return obs, info


def known_kick_env(**kwargs: Any) -> gym.Env:
    """Goalkeeper-v0, perceived with the ``"kick"`` filter, told the kick time
    (:class:`KnownKick`)."""
    return KnownKick(gym.make(GK, **kwargs))


#: The known-kick environment's id, registered here for :func:`agents.runs.evaluation.evaluate`
#: (which runs it in this process with one worker).
KNOWN_KICK_ID = "soccer_env_bench/KnownKick-v0"
if KNOWN_KICK_ID not in gym.registry:
    gym.register(KNOWN_KICK_ID, entry_point=known_kick_env)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--preset", choices=("ideal", "ssl-2012", "realistic", "harsh"),
                   default="ssl-2012", help="the vision preset (default: %(default)s)")
    p.add_argument("--episodes", type=int, default=1000)
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--filters", nargs="+", default=["ekf", "kick", "imm"],
                   help="ball filters (names of soccer_env.perception.options.BALL_FILTERS)")
    args = p.parse_args(argv)
    preset, n = args.preset, args.episodes

    def run(label: str, spec: Any, ball_filter: str | None, env_id: str = GK) -> None:
        kwargs = ({"obs_mode": "truth", "perception": spec} if ball_filter is None else
                  {"obs_mode": "perceived",
                   "perception": {"vision": spec, "ball_filter": ball_filter}})
        res = evaluate("scripted", kwargs, n, 0, 1 if env_id != GK else args.workers,
                       env_id=env_id, measure_estimator=ball_filter is not None)
        us = res.estimator_us_per_step
        cost = "" if us is None else f"{us:.0f}"
        print(f"| {label} | {ball_filter or 'truth'} | {100 * res.save_rate:.1f} % "
              f"({100 * res.ci_low:.1f}-{100 * res.ci_high:.1f}) | {cost} |", flush=True)

    print(f"| scripted keeper, {preset} | ball filter | save rate ({n} shots, 95 % CI) "
          "| estimator [us/step] |")
    print("|---|---|---|---|")
    for f in args.filters:
        run("perceived", preset, f)
    if "kick" in args.filters:
        run("kick time known", preset, "kick", KNOWN_KICK_ID)
    for label, over in (("ball noise off", {"ball_sigma": 0.0}),
                        ("robot pose noise off", {"robot_sigma": 0.0,
                                                  "robot_sigma_theta": 0.0}),
                        ("cameras at 50 m", {"camera_height": 50.0})):
        spec = vision(preset, **over)
        for f in args.filters:
            run(label, spec, f)
    run("truth", preset, None)
    return 0


if __name__ == "__main__":
    sys.exit(main())
