"""PPO rollout collection rate on Goalkeeper-v0: environment steps per second while
stable-baselines3 collects rollouts (policy forward passes included, gradient updates excluded).

Usage: ``python benchmarks/rollout_rate.py [--obs-mode perceived] [--perception ssl-2012]
[--steps 40000] [--repeats 3]``.

Compares, in one run and in alternation (so that the machine's drift cancels in the ratios):

* :class:`agents.vec_env.WorkerVecEnv`, 16 environments in 2 worker processes (what
  ``soccer-env train`` uses by default);
* stable-baselines3's ``SubprocVecEnv`` with 2 environments (one per process);
* stable-baselines3's ``DummyVecEnv`` with 2 environments (in the learner's process).

Each configuration trains a PPO (default MLP policy, ``n_steps * n_envs`` about 4096 per
rollout) for ``--steps`` steps; the rate is the steps collected divided by the time spent in
``collect_rollouts``. Prints the median over ``--repeats`` and the ratio to ``DummyVecEnv``.
"""

from __future__ import annotations

import argparse
import statistics

import soccer_env  # noqa: F401

CONFIGS = ("worker-16x2", "subproc-2", "dummy-2")


def _venv(name: str, env_kwargs: dict):
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    from agents.training import goalkeeper_env_fn as _make_fn
    from agents.vec_env import WorkerVecEnv

    if name == "worker-16x2":
        return WorkerVecEnv([_make_fn(env_kwargs) for _ in range(16)], n_workers=2)
    if name == "subproc-2":
        return SubprocVecEnv([_make_fn(env_kwargs) for _ in range(2)])
    return DummyVecEnv([_make_fn(env_kwargs) for _ in range(2)])


def rollout_rate(name: str, env_kwargs: dict, steps: int, seed: int = 0) -> float:
    """Steps per second spent collecting rollouts while PPO trains ``steps`` steps."""
    import torch
    from stable_baselines3 import PPO

    from agents.training import rollout_timer

    torch.set_num_threads(1)
    venv = _venv(name, env_kwargs)
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


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--obs-mode", default="perceived", choices=("truth", "raw", "perceived"))
    p.add_argument("--perception", default="ssl-2012")
    p.add_argument("--steps", type=int, default=40_000)
    p.add_argument("--repeats", type=int, default=3)
    args = p.parse_args()
    if args.steps < 4096 or args.repeats < 1:
        p.error("--steps must be >= 4096 and --repeats >= 1")
    env_kwargs = {"obs_mode": args.obs_mode, "perception": args.perception}
    rates: dict[str, list[float]] = {c: [] for c in CONFIGS}
    for r in range(args.repeats):
        for name in CONFIGS:
            rates[name].append(rollout_rate(name, env_kwargs, args.steps, seed=r))
    base = statistics.median(rates["dummy-2"])
    print(f"Goalkeeper-v0 {env_kwargs}, PPO rollouts, median of {args.repeats}:")
    for name in CONFIGS:
        med = statistics.median(rates[name])
        spread = f"{min(rates[name]):,.0f}-{max(rates[name]):,.0f}"
        print(f"  {name:12s} {med:8,.0f} steps/s ({spread})  x{med / base:.2f} vs dummy-2")


if __name__ == "__main__":
    main()
