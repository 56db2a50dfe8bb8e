"""How far perception can take a keeper: the scripted keeper under perceived ``ssl-2012``
observations, on true observations, and with an oracle that knows the shot perfectly from the
moment the vision could first have seen it.

Usage: ``python benchmarks/keeper_bounds.py [--robot ssl|humanoid] [--preset ssl-2012]
[--ball-tracker mfbpf] [--episodes 1000] [--workers 2]``.

The oracle observation is the truth, except that from the kick until the vision's first view
of the moving ball (the kick time, half a frame period on average until the next capture,
plus the vision latency) the ball reads as lying still where it was kicked from: no estimator
fed by these cameras can know more, so the oracle's save rate bounds what better estimation
(or a learner on perceived observations) can reach with this keeper's way of playing. The
actuation latency and command loss of the preset (``--preset``, default ``ssl-2012``) apply in
every case. Seeds 0..N-1 of
Goalkeeper-v0's suite; Wilson 95 % intervals.

``--robot humanoid``: the scripted humanoid keeper (``humanoid-2012``, three team-mates,
``kidsize-2012`` head cameras, KLD localization, the team's sightings fused and tracked by
MFBPF, or tracked line by line by ``--ball-tracker kick``) perceived, perceived
but with the true ball velocity (:class:`TrueBallVelocity`: believed pose and ball position,
the velocity alone true), the same from the first step the believed ball moves
(:class:`TrueVelocityOnceMoving`: what the belief's lag costs apart from its velocity error),
the first-frame oracle (the head camera's 25 Hz and 40 ms), and truth; 60 Hz decisions.
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

import gymnasium as gym
import numpy as np

import soccer_env  # noqa: F401
from agents.runs.evaluation import evaluate
from soccer_env.envs.registration import GOALKEEPER_ID
from soccer_env.presets import HEAD_CAMERAS, head_camera, vision
from soccer_env.state import Belief

GK = GOALKEEPER_ID


class FirstFrameOracle(gym.ObservationWrapper):
    """Truth-mode observations with the ball hidden in place until the vision's first view of
    the kick (see the module docstring)."""

    def __init__(self, env: gym.Env, preset: str = "ssl-2012") -> None:
        super().__init__(env)
        spec = head_camera(preset) if preset in HEAD_CAMERAS else vision(preset)
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
    """Goalkeeper-v0 with :class:`FirstFrameOracle` observations (of the ``perception``
    preset's camera)."""
    preset = kwargs.get("perception", "ssl-2012")
    if isinstance(preset, dict):  # a humanoid's perception settings: its camera
        preset = preset["camera"]
    return FirstFrameOracle(gym.make(GK, obs_mode="truth", **kwargs), preset)


class TrueBallVelocity(gym.ObservationWrapper):
    """Perceived observations with the ball's velocity replaced by the true one (in the
    believed body frame): what a keeper would do if its estimator knew the ball's motion at
    once but nothing else better."""

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env)
        names = env.unwrapped.builder.names
        self._ax, self._ay, self._vx, self._vy = (
            names.index(n) for n in ("self.ax", "self.ay", "ball.vx", "ball.vy"))

    def observation(self, observation: np.ndarray) -> np.ndarray:
        vx, vy = self.env.unwrapped.world.snapshot().ball[3:5]
        obs = observation.copy()
        c, s = float(obs[self._ax]), -float(obs[self._ay])
        obs[self._vx] = c * vx + s * vy  # blue: the team frame is the field's
        obs[self._vy] = -s * vx + c * vy
        return obs


class TrueVelocityOnceMoving(TrueBallVelocity):
    """:class:`TrueBallVelocity` from the first step the believed ball moves faster than
    ``threshold`` [m/s] (the belief has seen the shot), the belief's velocity before: what
    the lag before the belief moves costs, apart from the belief's velocity error after."""

    def __init__(self, env: gym.Env, threshold: float = 0.3) -> None:
        super().__init__(env)
        self.threshold = threshold
        self._moving = False

    def reset(self, **kwargs: Any):
        self._moving = False
        return super().reset(**kwargs)

    def observation(self, observation: np.ndarray) -> np.ndarray:
        speed = math.hypot(float(observation[self._vx]), float(observation[self._vy]))
        self._moving = self._moving or speed > self.threshold
        return super().observation(observation) if self._moving else observation


def true_velocity_env(**kwargs: Any) -> gym.Env:
    """Goalkeeper-v0, perceived, with :class:`TrueBallVelocity` observations."""
    return TrueBallVelocity(gym.make(GK, obs_mode="perceived", **kwargs))


def once_moving_env(**kwargs: Any) -> gym.Env:
    """Goalkeeper-v0, perceived, with :class:`TrueVelocityOnceMoving` observations."""
    return TrueVelocityOnceMoving(gym.make(GK, obs_mode="perceived", **kwargs))


#: The oracle environment's id, registered here for :func:`agents.runs.evaluation.evaluate` (which
#: runs it in this process with one worker).
ORACLE_ID = "soccer_env_bench/FirstFrameOracle-v0"
if ORACLE_ID not in gym.registry:
    gym.register(ORACLE_ID, entry_point=oracle_env)
TRUE_VELOCITY_ID = "soccer_env_bench/TrueBallVelocity-v0"
if TRUE_VELOCITY_ID not in gym.registry:
    gym.register(TRUE_VELOCITY_ID, entry_point=true_velocity_env)
ONCE_MOVING_ID = "soccer_env_bench/TrueVelocityOnceMoving-v0"
if ONCE_MOVING_ID not in gym.registry:
    gym.register(ONCE_MOVING_ID, entry_point=once_moving_env)


def humanoid(episodes: int, workers: int, tracker: str = "mfbpf") -> None:
    """The humanoid keeper's rows (see the module docstring), the team's ball tracker
    ``tracker`` (one of :data:`soccer_env.perception.BALL_TRACKERS`)."""
    perception = {"camera": "kidsize-2012", "ball_tracker": tracker}
    base = {"robot": "humanoid-2012", "perception": perception}
    print(f"| scripted humanoid keeper, kidsize-2012, 60 Hz, ball tracker {tracker} | save rate "
          f"({episodes} shots, 95 % CI) |")
    print("|---|---|")
    rows = (("perceived (KLD localization, team sightings)", {**base, "obs_mode": "perceived"},
             None),
            ("perceived, true ball velocity", base, TRUE_VELOCITY_ID),
            ("perceived, true ball velocity once the belief moves (> 0.3 m/s)", base,
             ONCE_MOVING_ID),
            ("oracle from the first frame", base, ORACLE_ID),
            ("truth", {**base, "obs_mode": "truth"}, None))
    for label, kwargs, env_id in rows:
        res = (evaluate("scripted", kwargs, episodes, 0, workers) if env_id is None else
               evaluate("scripted", kwargs, episodes, 0, 1, env_id=env_id))
        print(f"| {label} | {res.summary()} |", flush=True)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--episodes", type=int, default=1000)
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--robot", choices=("ssl", "humanoid"), default="ssl")
    p.add_argument("--preset", choices=("ssl-2012", "realistic", "harsh"), default="ssl-2012",
                   help="the SSL keeper's vision preset (default: %(default)s)")
    p.add_argument("--ball-tracker", default="mfbpf",
                   help="the humanoid team's ball tracker (default: %(default)s)")
    args = p.parse_args(argv)
    if args.robot == "humanoid":
        humanoid(args.episodes, args.workers, args.ball_tracker)
        return 0
    print(f"| scripted keeper, {args.preset} | decisions | save rate ({args.episodes} shots, "
          "95 % CI) |")
    print("|---|---|---|")
    for hz, dt in ((25, 0.04), (60, 1.0 / 60.0)):
        base = {"perception": args.preset, "control_dt": dt}
        for label, kwargs in (("perceived (EKF)", {**base, "obs_mode": "perceived"}),
                              ("truth", {**base, "obs_mode": "truth"})):
            res = evaluate("scripted", kwargs, args.episodes, 0, args.workers)
            print(f"| {label} | {hz} Hz | {res.summary()} |")
        res = evaluate("scripted", base, args.episodes, 0, 1, env_id=ORACLE_ID)
        print(f"| oracle from the first frame | {hz} Hz | {res.summary()} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
