"""The benchmarks: step rates (``soccer-env bench``), the keepers' save rates and the rollout
collection rate of training.

**Step rates**: the environments against bare pymunk stepping the same bodies. Run
``soccer-env bench`` (or ``python benchmarks/bench_step.py``). Each figure is the median of
``repeats`` timed runs, each of ``steps`` steps with actions drawn beforehand from a seeded
generator (sampling is not timed); Goalkeeper-v0 runs through ``gymnasium.make`` with its
default wrappers and includes its resets, as a training loop would. The cost of perceived
observations is the median ratio of truth and perceived runs timed in alternation. With
``--batch N`` it also times the batched Goalkeeper-v0 and the batched 2 vs 2 match VecEnv
against single environments (:func:`bench_batched`).

Humanoids (Xu et al.'s 2012 ``humanoid-2012`` with its ``kidsize-2012`` head camera): the keeper
with its three watching team-mates (four robots, each with its camera, localization, radio,
fusion and tracker when perceived) and a 3 vs 3 match; their random actions neither kick nor
dive (a robot that dives at random lies blind most of the time, which would understate the
perception's cost).

**Save rates** (:func:`keeper_save_rates`, ``python benchmarks/keeper_save_rate.py``): the
scripted keeper and a keeper that stands still on Goalkeeper-v0's seeded shots
(:func:`agents.runs.evaluation.evaluate`).

**Rollout rates** (:func:`rollout_rate`, ``python benchmarks/rollout_rate.py``): environment
steps per second while stable-baselines3's PPO collects rollouts, in
:class:`~agents.vec.workers.WorkerVecEnv` against stable-baselines3's own vectorised environments.

**Code.** :mod:`.runners` (what is timed and how: the environments stepped with random actions,
bare pymunk, rates, memory), :mod:`.steps` (the step rates), :mod:`.profiling` (``--profile``),
:mod:`.compile_cost` (``--compile``: the kernels' compile and load times in fresh
interpreters), :mod:`.tables` (the plain-text tables), :mod:`.command` (the ``soccer-env
bench`` command), :mod:`.save_rates` and :mod:`.rollouts` (the scripts' benchmarks); this
package gathers their public names.
"""

from __future__ import annotations

from soccer_lab.bench.command import main, parser
from soccer_lab.bench.compile_cost import COMPILE_CASES, bench_compile, format_compile
from soccer_lab.bench.profiling import PROFILE_CASES, format_profile, profile_perceived
from soccer_lab.bench.rollouts import (
    ROLLOUT_CONFIGS,
    format_rollout_rates,
    rollout_main,
    rollout_rate,
    rollout_rates,
)
from soccer_lab.bench.runners import HUMANOID, HUMANOID_CAMERA, memory_per_item
from soccer_lab.bench.save_rates import format_save_rates, keeper_save_rates, save_rate_main
from soccer_lab.bench.steps import (
    PERCEIVED_PRESETS,
    PIXELS_CASES,
    REFERENCE,
    bench_batched,
    bench_frames,
    bench_goalkeeper,
    bench_match,
    bench_perceived_cost,
    bench_pixels,
    run_benchmarks,
)
from soccer_lab.bench.tables import format_table

__all__ = ["run_benchmarks", "bench_batched", "bench_frames", "format_table", "REFERENCE",
           "PERCEIVED_PRESETS", "parser", "main", "keeper_save_rates", "format_save_rates",
           "save_rate_main", "ROLLOUT_CONFIGS", "rollout_rate", "rollout_rates",
           "format_rollout_rates", "rollout_main", "memory_per_item", "bench_goalkeeper",
           "bench_match", "bench_perceived_cost", "PROFILE_CASES", "profile_perceived",
           "format_profile", "HUMANOID", "HUMANOID_CAMERA", "COMPILE_CASES", "bench_compile",
           "format_compile", "PIXELS_CASES", "bench_pixels"]
