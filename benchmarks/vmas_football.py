"""VMAS football's env-steps/s on the CPU, for the comparisons of
``benchmarks/match_workers.py`` (run it with a Python that has ``vmas`` and torch installed,
e.g. a separate virtual environment: ``pip install torch==2.13.0 vmas``).

Usage: ``python benchmarks/vmas_football.py [--agents 2] [--envs 512 ...] [--steps 200]
[--target ENV_STEPS] [--threads 2]``; prints one JSON line ``{"env_steps_per_s": ..., ...}``
per ``--envs`` value, in the order given. With ``--target``, each size steps
``target / envs`` times (between 20 and ``--steps``) instead of ``--steps``.

The scenario is VMAS's ``football`` with ``--agents`` blue agents controlled by random
continuous actions against as many red agents played by VMAS's scripted AI, ``--envs``
environments stepped in one batched call (VMAS steps 0.1 s of simulated time per step, far
simpler physics than ours: point-mass agents, no kicker, dribbler or chip). An env-step is one
environment advancing by one step.
"""

from __future__ import annotations

import argparse
import json
import time


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--agents", type=int, default=2)
    p.add_argument("--envs", type=int, nargs="+", default=[512])
    p.add_argument("--steps", type=int, default=200)
    p.add_argument("--target", type=int, default=0)
    p.add_argument("--threads", type=int, default=2)
    args = p.parse_args()
    import torch
    import vmas

    torch.set_num_threads(args.threads)
    for n in args.envs:
        steps = (args.steps if not args.target else
                 max(20, min(args.steps, -(-args.target // n))))
        env = vmas.make_env("football", num_envs=n, device="cpu", continuous_actions=True,
                            seed=0, n_blue_agents=args.agents, n_red_agents=args.agents,
                            ai_red_agents=True, ai_blue_agents=False)
        env.reset()
        torch.manual_seed(0)
        actions = [[env.get_random_action(a) for a in env.agents] for _ in range(steps)]
        for a in actions[:5]:
            env.step(a)
        t0 = time.perf_counter()
        for a in actions:
            env.step(a)
        elapsed = time.perf_counter() - t0
        print(json.dumps({"env_steps_per_s": n * steps / elapsed,
                          "vmas": getattr(vmas, "__version__", "?"),
                          "torch": torch.__version__, "threads": args.threads, "envs": n,
                          "agents": args.agents, "steps": steps}), flush=True)


if __name__ == "__main__":
    main()
