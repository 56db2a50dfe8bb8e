"""PPO rollout collection rate on Goalkeeper-v0: environment steps per second while
stable-baselines3 collects rollouts (policy forward passes included, gradient updates excluded).

Usage: ``python benchmarks/rollout_rate.py [--obs-mode perceived] [--perception ssl-2012]
[--steps 40000] [--repeats 3]``.

Compares, in one run and in alternation (so that the machine's drift cancels in the ratios),
the configurations of :data:`soccer_lab.bench.ROLLOUT_CONFIGS`:

* :class:`agents.vec.workers.WorkerVecEnv`, 16 environments in 2 worker processes (what
  ``soccer-env train`` uses by default);
* stable-baselines3's ``SubprocVecEnv`` with 2 environments (one per process);
* stable-baselines3's ``DummyVecEnv`` with 2 environments (in the learner's process).

Each configuration trains a PPO (default MLP policy, ``n_steps * n_envs`` about 4096 per
rollout) for ``--steps`` steps; the rate is the steps collected divided by the time spent in
``collect_rollouts`` (:func:`soccer_lab.bench.rollout_rate`). Prints the median over
``--repeats`` and the ratio to ``DummyVecEnv``.
"""

import sys

from soccer_lab.bench import rollout_main

if __name__ == "__main__":
    sys.exit(rollout_main())
