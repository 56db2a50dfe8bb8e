"""Evaluate a keeper policy on the fixed shot suite of Goalkeeper-v0.

The suite is the episodes reset with seeds ``start_seed .. start_seed + episodes - 1``: the
seed fixes the shot (start, target, speed, chip, delay), the keeper's start and the sensors'
noise, so every policy and every observation configuration meets the same shots. A save is an
episode that ends (terminates) without a goal; an episode cut by the time limit counts as not
saved. Save rates come with Wilson's 95 % score interval.

Besides the save rate, each evaluation measures the estimation error (root mean square distance
between ``info["estimate"]`` and ``info["truth"]`` ball positions over all steps) and, when asked,
the estimator's compute per step (time spent in the perception pipeline's filters, without the
sensor simulation).
"""

from __future__ import annotations

import math
import os
import time
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import gymnasium as gym

import soccer_env  # noqa: F401  (registers the environments)
from agents.common.checks import check_full_infos
from agents.common.processes import map_jobs, stripes, unstripe
from agents.common.stats import sign_test, wilson
from agents.policies.base import describe_policy, reset_policy
from agents.runs.resolve import make_policy, policy_for_jobs, saved_model
from soccer_env.envs.registration import GOALKEEPER_ID

__all__ = ["EvalResult", "evaluate", "paired", "record_video"]


@dataclass
class EvalResult:
    """The outcome of :func:`evaluate`.

    Attributes:
        policy: the policy reference evaluated.
        env_kwargs: the environment's keyword arguments.
        episodes, saves: counts; ``save_rate`` their ratio with ``ci_low``, ``ci_high`` its
            Wilson 95 % interval.
        outcomes: episodes per outcome (``goal``, ``stopped``, ``cleared``, ``out``,
            ``time limit``).
        steps: environment steps in all; ``mean_steps`` per episode.
        ball_rmse_m: RMS distance between the believed and the true ball position [m] over
            all steps (0 for truth observations).
        estimator_us_per_step: mean time of the perception's filters per step [us] (None if
            not measured).
        seconds: wall time of the evaluation [s] (summed over workers).
        saved: per episode, in seed order, whether it was saved.
    """

    policy: str
    env_kwargs: dict[str, Any]
    episodes: int
    saves: int
    save_rate: float
    ci_low: float
    ci_high: float
    outcomes: dict[str, int]
    steps: int
    mean_steps: float
    ball_rmse_m: float
    estimator_us_per_step: float | None
    seconds: float
    saved: list[bool] = field(repr=False)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    def summary(self) -> str:
        """One line: save rate with its interval, outcomes and estimation error."""
        text = (f"save rate {100 * self.save_rate:.1f} % (95 % CI {100 * self.ci_low:.1f}-"
                f"{100 * self.ci_high:.1f}) over {self.episodes} shots; "
                f"{dict(sorted(self.outcomes.items()))}; ball estimate RMSE "
                f"{1000 * self.ball_rmse_m:.1f} mm")
        if self.estimator_us_per_step is not None:
            text += f"; estimator {self.estimator_us_per_step:.0f} us/step"
        return text


def paired(a: EvalResult, b: EvalResult) -> dict[str, Any]:
    """Two evaluations on the same shots compared shot by shot: the shots only ``a`` saved
    (``a_only``), only ``b`` (``b_only``), the save-rate difference ``a - b`` and the exact
    two-sided sign test's p-value over the shots that only one saved
    (:func:`~agents.common.stats.sign_test`). Raises ``ValueError`` unless both played the
    same number of shots in the same environment."""
    if a.episodes != b.episodes or a.env_kwargs != b.env_kwargs:
        raise ValueError("paired compares evaluations of the same shots: got "
                         f"{a.episodes} and {b.episodes} shots, environments {a.env_kwargs} "
                         f"and {b.env_kwargs}")
    a_only = sum(x and not y for x, y in zip(a.saved, b.saved))
    b_only = sum(y and not x for x, y in zip(a.saved, b.saved))
    return {"a": a.policy, "b": b.policy, "episodes": a.episodes, "a_only": a_only,
            "b_only": b_only, "difference": a.save_rate - b.save_rate,
            "sign_test_p": sign_test(a_only, b_only)}


class _Timer:
    """Accumulates the time spent in the wrapped perception methods."""

    def __init__(self) -> None:
        self.seconds = 0.0

    def wrap(self, fn: Callable) -> Callable:
        def timed(*args: Any) -> Any:
            t0 = time.perf_counter()
            try:
                return fn(*args)
            finally:
                self.seconds += time.perf_counter() - t0

        return timed


def _time_estimator(env: gym.Env) -> _Timer:
    """Time the estimation part of the env's perception (filters and belief prediction, not
    the sensor simulation), by wrapping its methods on the instance."""
    timer = _Timer()
    # An SSL team's estimation is its pipeline's ``consume`` and ``beliefs``; a humanoid
    # team's, its ``consume`` and ``belief`` (the truth has neither).
    for target in env.unwrapped.pipelines:
        for name in ("consume", "beliefs", "belief"):
            if hasattr(target, name):
                setattr(target, name, timer.wrap(getattr(target, name)))
    return timer


def _run_episodes(args: tuple) -> dict[str, Any]:
    """Episodes ``seeds`` of one configuration, in this process."""
    policy_ref, env_id, env_kwargs, seeds, measure = args
    env = gym.make(env_id, **env_kwargs)
    policy = make_policy(policy_ref, env)
    timer = _time_estimator(env) if measure else None
    outcomes: Counter = Counter()
    saved, steps, sq_err, t0 = [], 0, 0.0, time.perf_counter()
    for seed in seeds:
        obs, info = env.reset(seed=int(seed))
        reset_policy(policy)  # a policy with memory starts the episode afresh
        while True:
            obs, _, term, trunc, info = env.step(policy(obs))
            steps += 1
            t, e = info["truth"]["ball_position"], info["estimate"]["ball_position"]
            sq_err += (t[0] - e[0]) ** 2 + (t[1] - e[1]) ** 2
            if term or trunc:
                break
        outcome = info["outcome"] if term else "time limit"
        outcomes[outcome] += 1
        saved.append(bool(term and outcome != "goal"))
    env.close()
    return {"saved": saved, "outcomes": outcomes, "steps": steps, "sq_err": sq_err,
            "estimator_s": timer.seconds if timer else None,
            "seconds": time.perf_counter() - t0}


def evaluate(policy: str | os.PathLike | Callable = "scripted",
             env_kwargs: Mapping[str, Any] | None = None, episodes: int = 1000,
             start_seed: int = 0, workers: int = 1, measure_estimator: bool = False,
             env_id: str = GOALKEEPER_ID, trust: bool = False) -> EvalResult:
    """Run ``policy`` on ``episodes`` seeded episodes of ``env_id`` (Goalkeeper-v0 by default).

    Args:
        policy: a policy reference for :func:`~agents.runs.resolve.make_policy` (``"scripted"``,
            ``"idle"``, ``"baseline:NAME"``, a ``.zip``/``.npz`` path) or a callable; a
            callable runs in this process only (``workers`` must be 1 unless it pickles).
            A policy with memory is reset (its ``reset()``, see
            :func:`~agents.policies.base.reset_policy`) at the start of every episode.
        env_kwargs: keyword arguments of ``gymnasium.make`` (``obs_mode``, ``perception``,
            ...).
        episodes: number of shots; seeds ``start_seed`` onwards.
        workers: processes to spread the episodes over (the result does not depend on it).
        measure_estimator: time the perception's filters (adds a little overhead).
        trust: load a stable-baselines3 file's pickled entries (see
            :mod:`agents.sb3.model_files`; only for files from a source you trust).
    """
    if int(episodes) < 1:
        raise ValueError(f"episodes must be >= 1, got {episodes!r}")
    if int(workers) < 1:
        raise ValueError(f"workers must be >= 1, got {workers!r}")
    env_kwargs = dict(env_kwargs or {})
    check_full_infos(env_kwargs, "evaluate")
    seeds = list(range(int(start_seed), int(start_seed) + int(episodes)))
    name = describe_policy(policy)
    if saved_model(policy):
        # Load a saved model once here (its numpy copy pickles cheaply) rather than import
        # torch and load it again in every worker; the workers never open the file.
        policy = policy_for_jobs(policy, env_id, env_kwargs, trust)
    chunks = stripes(seeds, workers)
    jobs = [(policy, env_id, env_kwargs, c, measure_estimator) for c in chunks]
    parts = map_jobs(_run_episodes, jobs, len(chunks))
    outcomes: Counter = Counter()
    for part in parts:
        outcomes.update(part["outcomes"])
    saved = unstripe([p["saved"] for p in parts])
    steps = sum(p["steps"] for p in parts)
    saves = sum(saved)
    lo, hi = wilson(saves, len(seeds))
    est = ([p["estimator_s"] for p in parts] if measure_estimator else None)
    return EvalResult(
        policy=name,
        env_kwargs=env_kwargs, episodes=len(seeds), saves=saves,
        save_rate=saves / len(seeds), ci_low=lo, ci_high=hi, outcomes=dict(outcomes),
        steps=steps, mean_steps=steps / len(seeds),
        ball_rmse_m=math.sqrt(sum(p["sq_err"] for p in parts) / max(steps, 1)),
        estimator_us_per_step=None if est is None else 1e6 * sum(est) / max(steps, 1),
        seconds=sum(p["seconds"] for p in parts), saved=saved)


def record_video(policy: str | os.PathLike | Callable, path: str | os.PathLike,
                 env_kwargs: Mapping[str, Any] | None = None, seeds: Sequence[int] = (0, 1, 2),
                 env_id: str = GOALKEEPER_ID, width: int = 640, trust: bool = False) -> Path:
    """Render the episodes ``seeds`` (rgb_array, the belief drawn over the truth) to ``path``
    (``.mp4``; a ``.gif`` beside it if no ffmpeg is available). Each episode opens with its
    title card and ends on its outcome banner, whose frame is held for
    :data:`~soccer_env.render.video.HOLD_SECONDS` before the next episode. Returns the file
    written. ``trust``: as for :func:`evaluate`."""
    from soccer_env.render.video import hold_last, write_video

    kwargs = {**dict(env_kwargs or {}), "render_mode": "rgb_array", "render_width": width}
    env = gym.make(env_id, **kwargs)
    pol = make_policy(policy, env, trust=trust)
    fps = env.unwrapped.metadata["render_fps"]
    frames = []
    for seed in seeds:
        obs, _ = env.reset(seed=int(seed))
        reset_policy(pol)
        frames.append(env.render())
        while True:
            obs, _, term, trunc, _ = env.step(pol(obs))
            frames.append(env.render())
            if term or trunc:
                break
        hold_last(frames, fps)
    env.close()
    return write_video(frames, Path(path), fps)
