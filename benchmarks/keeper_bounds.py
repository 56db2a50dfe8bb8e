"""How far perception can take a keeper: the scripted keeper under perceived ``ssl-2012``
observations, on true observations, and with an oracle that knows the shot perfectly from the
moment the vision could first have seen it.

Usage: ``python benchmarks/keeper_bounds.py [--episodes 1000] [--workers 2]``.

The oracle observation is the truth, except that from the kick until the vision's first view
of the moving ball (the kick time, half a frame period on average until the next capture,
plus the vision latency) the ball reads as lying still where it was kicked from: no estimator
fed by these cameras can know more, so the oracle's save rate bounds what better estimation
(or a learner on perceived observations) can reach with this keeper's way of playing. The
actuation latency and command loss of ``ssl-2012`` apply in every case. Seeds 0..N-1 of
Goalkeeper-v0's suite; Wilson 95 % intervals.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import gymnasium as gym
import numpy as np

import soccer_env  # noqa: F401
from agents.evaluation import evaluate
from soccer_env.presets import vision
from soccer_env.state import Belief

GK = "soccer_env/Goalkeeper-v0"


class FirstFrameOracle(gym.ObservationWrapper):
    """Truth-mode observations with the ball hidden in place until the vision's first view of
    the kick (see the module docstring)."""

    def __init__(self, env: gym.Env, preset: str = "ssl-2012") -> None:
        super().__init__(env)
        spec = vision(preset)
        period = 1.0 / spec.frame_rate if spec.frame_rate else 0.0
        self.blind = 0.5 * period + spec.latency + 0.5 * spec.latency_jitter

    def reset(self, **kwargs: Any):
        obs, info = self.env.reset(**kwargs)
        self._kick = info["shot"]["delay"]
        self._rest = np.array(info["truth"]["ball_position"])
        return self.observation(obs), info

    def observation(self, observation: np.ndarray) -> np.ndarray:
        base = self.env.unwrapped
        state = base.world.snapshot()
        if state.time < self._kick + self.blind:
            ball = np.zeros(6)
            ball[0:2] = self._rest
            return base.builder.build(Belief(state.time, ball, state.robots))[0]
        return observation


def oracle_env(**kwargs: Any) -> gym.Env:
    """Goalkeeper-v0 with :class:`FirstFrameOracle` observations."""
    return FirstFrameOracle(gym.make(GK, obs_mode="truth", **kwargs))


#: The oracle environment's id, registered here for :func:`agents.evaluation.evaluate` (which
#: runs it in this process with one worker).
ORACLE_ID = "soccer_env_bench/FirstFrameOracle-v0"
if ORACLE_ID not in gym.registry:
    gym.register(ORACLE_ID, entry_point=oracle_env)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--episodes", type=int, default=1000)
    p.add_argument("--workers", type=int, default=2)
    args = p.parse_args(argv)
    print(f"| scripted keeper, ssl-2012 | decisions | save rate ({args.episodes} shots, 95 % "
          "CI) |")
    print("|---|---|---|")
    for hz, dt in ((25, 0.04), (60, 1.0 / 60.0)):
        base = {"perception": "ssl-2012", "control_dt": dt}
        for label, kwargs in (("perceived (EKF)", {**base, "obs_mode": "perceived"}),
                              ("truth", {**base, "obs_mode": "truth"})):
            res = evaluate("scripted", kwargs, args.episodes, 0, args.workers)
            print(f"| {label} | {hz} Hz | {res.summary()} |")
        res = evaluate("scripted", base, args.episodes, 0, 1, env_id=ORACLE_ID)
        print(f"| oracle from the first frame | {hz} Hz | {res.summary()} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
