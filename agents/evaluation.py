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
from collections.abc import Callable, Iterator, Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import gymnasium as gym

import soccer_env  # noqa: F401  (registers the environments)
from agents.policies import make_policy, reset_policy
from soccer_env.envs.registration import GOALKEEPER_ID

__all__ = ["wilson", "EvalResult", "evaluate", "record_video", "process_context",
           "process_pool", "map_jobs", "resolve_workers", "describe_policy",
           "ignore_interrupts", "check_full_infos"]


def check_full_infos(env_kwargs: Mapping[str, Any] | None, where: str) -> None:
    """Raise ``ValueError`` if ``env_kwargs`` ask for flat infos: the package's evaluation,
    training and match adapter read the full infos (truth, estimate, outcome names)."""
    mode = (env_kwargs or {}).get("info_mode", "full")
    if mode != "full":
        raise ValueError(f"{where} reads the environments' full infos: info_mode must be "
                         f"'full' (the default) there, got {mode!r} (info_mode='flat' is for "
                         "other RL libraries)")


def wilson(successes: int, n: int, z: float = 1.96) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion ``successes / n`` (95 % for
    ``z = 1.96``)."""
    if n <= 0 or not 0 <= successes <= n:
        raise ValueError(f"need 0 <= successes <= n and n >= 1, got {successes} of {n}")
    p = successes / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


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
        policy: a policy reference for :func:`~agents.policies.make_policy` (``"scripted"``,
            ``"idle"``, ``"baseline:NAME"``, a ``.zip``/``.npz`` path) or a callable; a
            callable runs in this process only (``workers`` must be 1 unless it pickles).
            A policy with memory is reset (its ``reset()``, see
            :func:`~agents.policies.reset_policy`) at the start of every episode.
        env_kwargs: keyword arguments of ``gymnasium.make`` (``obs_mode``, ``perception``,
            ...).
        episodes: number of shots; seeds ``start_seed`` onwards.
        workers: processes to spread the episodes over (the result does not depend on it).
        measure_estimator: time the perception's filters (adds a little overhead).
        trust: load a stable-baselines3 file's pickled entries (see
            :mod:`agents.model_files`; only for files from a source you trust).
    """
    if int(episodes) < 1:
        raise ValueError(f"episodes must be >= 1, got {episodes!r}")
    if int(workers) < 1:
        raise ValueError(f"workers must be >= 1, got {workers!r}")
    env_kwargs = dict(env_kwargs or {})
    check_full_infos(env_kwargs, "evaluate")
    seeds = list(range(int(start_seed), int(start_seed) + int(episodes)))
    workers = min(int(workers), len(seeds))
    name = describe_policy(policy)
    if isinstance(policy, (str, os.PathLike)) and (
            os.fspath(policy).endswith(".zip") or Path(policy).is_dir()):
        # Load a saved model once here (its numpy copy pickles cheaply) rather than import
        # torch and load it again in every worker; the workers never open the file.
        probe = gym.make(env_id, **env_kwargs)
        try:
            policy = make_policy(policy, probe, trust=trust)
        finally:
            probe.close()
    chunks = [seeds[i::workers] for i in range(workers)]
    jobs = [(policy, env_id, env_kwargs, c, measure_estimator) for c in chunks]
    parts = map_jobs(_run_episodes, jobs, workers)
    saved_by_seed: dict[int, bool] = {}
    outcomes: Counter = Counter()
    for chunk, part in zip(chunks, parts):
        saved_by_seed.update(zip(chunk, part["saved"]))
        outcomes.update(part["outcomes"])
    saved = [saved_by_seed[s] for s in seeds]
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


def process_context() -> Any:
    """The :mod:`multiprocessing` context for process pools of evaluation work (give it to
    ``ProcessPoolExecutor(mp_context=...)``): ``"forkserver"`` where the platform has it, else
    ``"spawn"``; never ``"fork"``, since a parent that has used torch deadlocks forked
    children. Workers import what they need afresh, so jobs must carry everything they use
    (functions at module level, picklable arguments)."""
    import multiprocessing as mp

    return mp.get_context("forkserver" if "forkserver" in mp.get_all_start_methods()
                          else "spawn")


def ignore_interrupts() -> None:
    """Make this process ignore Ctrl-C (``SIGINT``): the initializer of worker processes,
    whose parent handles the interrupt (a terminal sends it to the whole process group, and
    every worker would otherwise print its own traceback)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


@contextmanager
def process_pool(workers: int) -> Iterator[ProcessPoolExecutor]:
    """A ``ProcessPoolExecutor`` of ``workers`` processes (:func:`process_context`) that
    leave Ctrl-C to this process. When the block raises (Ctrl-C included), queued jobs are
    cancelled and the workers terminated at once instead of running on to the end of every
    submitted job (what leaving an executor's ``with`` block does)."""
    pool = ProcessPoolExecutor(workers, mp_context=process_context(),
                               initializer=ignore_interrupts)
    try:
        yield pool
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        # No public way to stop running jobs before Python 3.14's terminate_workers().
        for proc in list((getattr(pool, "_processes", None) or {}).values()):
            proc.terminate()
        raise
    pool.shutdown(wait=True)


def resolve_workers(workers: Any) -> int:
    """``workers`` as a process count: None for every core, else an integer >= 1
    (``ValueError`` otherwise)."""
    workers = (os.cpu_count() or 1) if workers is None else int(workers)
    if workers < 1:
        raise ValueError(f"workers must be >= 1, got {workers!r}")
    return workers


def map_jobs(fn: Callable[[Any], Any], jobs: Sequence[Any], workers: int | None = None,
             progress: Callable[[int, int], None] | None = None) -> list[Any]:
    """``[fn(job) for job in jobs]``, in job order, over ``workers`` processes (None: every
    core; with one, or a single job, in this process). ``fn`` must be a module-level
    function and the jobs must pickle (they reach fresh processes, see
    :func:`process_context`). ``progress(done, total)`` is called after each job."""
    workers = min(resolve_workers(workers), len(jobs))
    if workers <= 1:
        outs = []
        for job in jobs:
            outs.append(fn(job))
            if progress:
                progress(len(outs), len(jobs))
        return outs
    results: list[Any] = [None] * len(jobs)
    with process_pool(workers) as pool:
        futures = {pool.submit(fn, job): i for i, job in enumerate(jobs)}
        for done, fut in enumerate(as_completed(futures), 1):
            results[futures[fut]] = fut.result()
            if progress:
                progress(done, len(jobs))
    return results


def describe_policy(policy: Any) -> str:
    """A policy reference as text for tables: the path or name given, else the callable's
    name."""
    if isinstance(policy, (str, os.PathLike)):
        return os.fspath(policy)
    return getattr(policy, "__name__", type(policy).__name__)


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
