"""The rollout collection rate of training (``python benchmarks/rollout_rate.py``):
environment steps per second while stable-baselines3's PPO collects rollouts, in
:class:`~agents.vec.workers.WorkerVecEnv` against stable-baselines3's own vectorised
environments."""

from __future__ import annotations

import statistics
from typing import Any

__all__ = ["ROLLOUT_CONFIGS", "rollout_rate", "rollout_rates", "format_rollout_rates",
           "rollout_main"]

#: Vectorised environments compared by :func:`rollout_rates`: 16 environments in 2
#: :class:`~agents.vec.workers.WorkerVecEnv` processes (what ``soccer-env train`` uses), and
#: stable-baselines3's ``SubprocVecEnv`` and ``DummyVecEnv`` with 2 environments.
ROLLOUT_CONFIGS = ("worker-16x2", "subproc-2", "dummy-2")


def _rollout_venv(name: str, env_kwargs: dict[str, Any]) -> Any:
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    from agents.vec.factories import goalkeeper_env_fn
    from agents.vec.workers import WorkerVecEnv

    if name == "worker-16x2":
        return WorkerVecEnv([goalkeeper_env_fn(env_kwargs) for _ in range(16)], n_workers=2)
    if name == "subproc-2":
        return SubprocVecEnv([goalkeeper_env_fn(env_kwargs) for _ in range(2)])
    return DummyVecEnv([goalkeeper_env_fn(env_kwargs) for _ in range(2)])


def rollout_rate(name: str, env_kwargs: dict[str, Any], steps: int, seed: int = 0) -> float:
    """Steps per second spent collecting rollouts while PPO (default MLP policy, ``n_steps *
    n_envs`` about 4096 per rollout) trains ``steps`` steps on Goalkeeper-v0 in the
    vectorised environment ``name`` of :data:`ROLLOUT_CONFIGS`."""
    import torch
    from stable_baselines3 import PPO

    from agents.sb3.callbacks import rollout_timer

    torch.set_num_threads(1)
    venv = _rollout_venv(name, env_kwargs)
    venv.seed(seed)
    try:
        n_steps = max(64, 4096 // venv.num_envs)
        model = PPO("MlpPolicy", venv, n_steps=n_steps, batch_size=512, seed=seed,
                    device="cpu")
        timer = rollout_timer()
        model.learn(steps, callback=timer)
    finally:
        venv.close()
    return timer.rate


def rollout_rates(env_kwargs: dict[str, Any], steps: int, repeats: int
                  ) -> dict[str, list[float]]:
    """:func:`rollout_rate` of every configuration, ``repeats`` times in alternation (seed
    ``r`` in round ``r``), so that the machine's drift cancels in their ratios."""
    rates: dict[str, list[float]] = {c: [] for c in ROLLOUT_CONFIGS}
    for r in range(repeats):
        for name in ROLLOUT_CONFIGS:
            rates[name].append(rollout_rate(name, env_kwargs, steps, seed=r))
    return rates


def format_rollout_rates(rates: dict[str, list[float]], env_kwargs: dict[str, Any]) -> str:
    """The median rate of each configuration, its range and its ratio to ``dummy-2``."""
    base = statistics.median(rates["dummy-2"])
    lines = [f"Goalkeeper-v0 {env_kwargs}, PPO rollouts, median of "
             f"{len(rates['dummy-2'])}:"]
    for name in ROLLOUT_CONFIGS:
        med = statistics.median(rates[name])
        spread = f"{min(rates[name]):,.0f}-{max(rates[name]):,.0f}"
        lines.append(f"  {name:12s} {med:8,.0f} steps/s ({spread})  x{med / base:.2f} vs "
                     "dummy-2")
    return "\n".join(lines)


def rollout_main(argv: list[str] | None = None) -> int:
    """Entry point of ``benchmarks/rollout_rate.py``."""
    import argparse

    from soccer_env.presets import VISION
    from soccer_lab.cli_args import HelpFormatter

    p = argparse.ArgumentParser(description="PPO rollout collection rate on Goalkeeper-v0: "
                                            "environment steps per second while "
                                            "stable-baselines3 collects rollouts (policy "
                                            "forward passes included, gradient updates "
                                            "excluded).",
                                formatter_class=HelpFormatter)
    p.add_argument("--obs-mode", default="perceived", choices=("truth", "raw", "perceived"),
                   help="observation mode")
    p.add_argument("--perception", default="ssl-2012", choices=list(VISION),
                   help="SSL vision preset")
    p.add_argument("--steps", type=int, default=40_000,
                   help="environment steps per timed training run, >= 4096")
    p.add_argument("--repeats", type=int, default=3,
                   help="timed runs per configuration, in alternation")
    args = p.parse_args(argv)
    if args.steps < 4096 or args.repeats < 1:
        p.error("--steps must be >= 4096 and --repeats >= 1")
    env_kwargs = {"obs_mode": args.obs_mode, "perception": args.perception}
    rates = rollout_rates(env_kwargs, args.steps, args.repeats)
    print(format_rollout_rates(rates, env_kwargs))
    return 0
