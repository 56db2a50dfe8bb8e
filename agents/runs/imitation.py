"""A keeper that learns what its perception misses from a privileged teacher (DAgger).

The learner is the scripted keeper behind the ``"ball-residual"`` map
(:mod:`agents.policies.action_maps`): it acts on its perceived observation, its belief's
ball velocity corrected by ``a r`` (team frame, ``r`` = the map's largest correction,
3 m/s). The teacher is the same keeper told the true ball velocity, which the bounds show
is worth most of what perception costs (``benchmarks/keeper_bounds.py``). In the learner's
action space the teacher's action is

    a* = clip((v_true - v_belief) / r, -1, 1),

with ``v_belief`` the observation's ball velocity rotated into the team frame by the
believed heading, so that the keeper reading ``v_belief + a* r`` acts on the true velocity
(see :func:`teacher_action`).

DAgger (Ross, Gordon and Bagnell, "A reduction of imitation learning and structured
prediction to no-regret online learning", AISTATS 2011): round 0 plays the scripted keeper
(the zero correction), round ``k`` plays the network fitted after round ``k - 1``; every
step's input (the last ``frame_stack`` observations, oldest first, the first repeated) goes
with the teacher's label into one growing data set, on all of which the network is fitted
again (mean squared error, Adam). The network learns ``E[a* | the last frames]``: the part
of the velocity error that the belief's history predicts, such as how far a track that has
just committed to a kick still lags the ball.

Why not reinforcement learning: PPO with the same actions and belief learned from the
shots' outcomes alone, a signal too noisy over ten thousand shots for corrections worth a
few points, and its exploration noise on the velocity made the keeper dive at random; it
ended below the scripted keeper (``docs/results/learning.md``). The labels here are exact at
every step.

The fitting uses torch (the ``train`` extra); the result is a
:class:`~agents.policies.numpy_policy.NumpyPolicy` that needs numpy alone. A run folder
holds ``config.json``, ``round_<k>_policy.npz``, ``final_policy.npz``,
``evaluations.json`` and ``summary.json``.
"""

from __future__ import annotations

import json
import math
import os
import shlex
import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

import soccer_env  # noqa: F401  (registers the environments)
from agents.common.checks import check_counts, check_full_infos
from agents.common.processes import map_jobs, stripes, unstripe
from agents.policies.action_maps import (
    BALL_RESIDUAL,
    ball_residual_params,
    team_frame_ball_velocity,
)
from agents.policies.numpy_policy import NumpyPolicy
from agents.runs.evaluation import evaluate
from soccer_env.envs.keeper import ScriptedGoalkeeper
from soccer_env.envs.registration import GOALKEEPER_ID

__all__ = ["ImitationConfig", "teacher_action", "stack_history", "imitate"]

#: The first seed of the training shots: clear of the evaluation suites (``soccer-env eval``
#: from 0, the training runs' evaluations from 1,000,000).
TRAIN_SEED = 10_000_000


@dataclass
class ImitationConfig:
    """What :func:`imitate` trains.

    Args:
        env_kwargs: Goalkeeper-v0 keyword arguments (a perceived observation mode; full
            infos, which carry the true ball velocity the teacher reads).
        rounds: DAgger rounds (round 0 plays the scripted keeper).
        episodes: shots played per round.
        frame_stack: observations the network reads at once.
        hidden: sizes of the network's hidden layers (tanh).
        epochs: passes over the data set after each round.
        batch_size: samples per gradient step.
        learning_rate: Adam's step size.
        seed: seeds the network's initialisation and batches, and offsets the shots
            (``TRAIN_SEED + seed * 10_000_000`` onwards).
        eval_episodes: held-out shots (seeds ``eval_seed`` onwards) played after each round
            beside the scripted keeper (0: none).
        eval_seed: seed of the first held-out shot.
        workers: processes that play the shots (the result does not depend on it).
        torch_threads: threads of the fitting.
    """

    env_kwargs: dict[str, Any] = field(default_factory=dict)
    rounds: int = 3
    episodes: int = 3000
    frame_stack: int = 8
    hidden: tuple[int, ...] = (128, 128)
    epochs: int = 30
    batch_size: int = 512
    learning_rate: float = 1e-3
    seed: int = 0
    eval_episodes: int = 200
    eval_seed: int = 1_000_000
    workers: int = 1
    torch_threads: int = 1

    def __post_init__(self) -> None:
        self.env_kwargs = dict(self.env_kwargs)
        self.hidden = tuple(self.hidden)
        check_counts(self, (("rounds", 1), ("episodes", 1), ("frame_stack", 1), ("epochs", 1),
                            ("batch_size", 1), ("seed", 0), ("eval_episodes", 0),
                            ("eval_seed", 0), ("workers", 1), ("torch_threads", 1)))
        if not self.hidden or any(isinstance(h, bool) or not isinstance(h, (int, np.integer))
                                  or h < 1 for h in self.hidden):
            raise ValueError(f"hidden must be one or more integers >= 1, got {self.hidden!r}")
        rate = self.learning_rate
        if isinstance(rate, bool) or not isinstance(rate, (int, float)) \
                or not math.isfinite(rate) or rate <= 0:
            raise ValueError(f"learning_rate must be a finite number > 0, got {rate!r}")
        check_full_infos(self.env_kwargs, "imitation")
        if self.env_kwargs.get("obs_mode", "truth") == "truth":
            raise ValueError("env_kwargs must ask for perceived (or raw) observations: with "
                             "obs_mode='truth' the belief is the truth and the teacher has "
                             "nothing to teach")


def teacher_action(obs: np.ndarray, true_velocity: Sequence[float],
                   residual: float = BALL_RESIDUAL) -> np.ndarray:
    """The teacher's ``"ball-residual"`` action for observation ``obs`` of a blue keeper
    (whose team frame is the field frame): ``clip((v_true - v_belief) / residual, -1, 1)``
    with ``v_belief`` the observation's ball velocity in the team frame [m/s]
    (:func:`~agents.policies.action_maps.team_frame_ball_velocity`) and ``true_velocity``
    the ball's [m/s]; float32 ``(2,)``."""
    belief = team_frame_ball_velocity(obs)
    diff = np.asarray(true_velocity, dtype=np.float64) - belief
    return np.clip(diff / float(residual), -1.0, 1.0).astype(np.float32)


def stack_history(obs: np.ndarray, frame_stack: int) -> np.ndarray:
    """The network inputs of one episode's observations ``(T, n)``: row ``t`` is
    observations ``t - frame_stack + 1 .. t`` concatenated, oldest first, the first
    observation standing in for those before it, as
    :class:`~agents.policies.numpy_policy.NumpyPolicy` stacks them; ``(T, frame_stack n)``."""
    obs = np.asarray(obs)
    idx = np.arange(len(obs))[:, None] + np.arange(1 - frame_stack, 1)[None, :]
    return obs[np.maximum(idx, 0)].reshape(len(obs), -1)


def _play(job: tuple) -> list[tuple[np.ndarray, np.ndarray]]:
    """Shots ``seeds`` with ``policy`` (None: the scripted keeper) in this process: per shot,
    its observations ``(T, n)`` and the teacher's actions ``(T, 2)``."""
    env_kwargs, policy, seeds, residual = job
    env = gym.make(GOALKEEPER_ID, **env_kwargs)
    keeper = ScriptedGoalkeeper.for_env(env) if policy is None else policy
    shots = []
    for seed in seeds:
        obs, info = env.reset(seed=int(seed))
        if policy is not None:
            policy.reset()
        seen, labels = [], []
        while True:
            seen.append(obs)
            labels.append(teacher_action(obs, info["truth"]["ball_velocity"], residual))
            obs, _, term, trunc, info = env.step(keeper(obs))
            if term or trunc:
                break
        shots.append((np.array(seen, np.float32), np.array(labels, np.float32)))
    env.close()
    return shots


def _fit(x: np.ndarray, y: np.ndarray, cfg: ImitationConfig, round_: int
         ) -> tuple[list[tuple], tuple[np.ndarray, np.ndarray, float, float], float]:
    """The network fitted to inputs ``x`` and labels ``y`` from a fresh initialisation
    (seeded by the configuration's seed and the round): its layers, the input
    normalisation ``(mean, var, clip, epsilon)`` and the final epoch's mean squared error."""
    import torch

    threads = torch.get_num_threads()
    torch.set_num_threads(cfg.torch_threads)
    try:
        return _fit_network(torch, x, y, cfg, round_)
    finally:
        torch.set_num_threads(threads)


def _fit_network(torch: Any, x: np.ndarray, y: np.ndarray, cfg: ImitationConfig, round_: int
                 ) -> tuple[list[tuple], tuple[np.ndarray, np.ndarray, float, float], float]:
    """:func:`_fit`'s work, with ``torch`` imported and its threads set."""
    gen = torch.Generator().manual_seed(cfg.seed * 1000 + round_)
    mean, var = x.mean(0, dtype=np.float64), x.var(0, dtype=np.float64)
    norm = (mean, var, 10.0, 1e-8)
    xn = np.clip((x - mean) / np.sqrt(var + norm[3]), -norm[2], norm[2]).astype(np.float32)
    sizes = (x.shape[1], *cfg.hidden)
    mods: list[Any] = []
    # torch initialises layers from its global generator: seeded inside fork_rng, which
    # restores the caller's state afterwards.
    with torch.random.fork_rng(devices=[]):
        torch.manual_seed(cfg.seed * 1000 + round_)
        for a, b in zip(sizes[:-1], sizes[1:]):
            mods += [torch.nn.Linear(a, b), torch.nn.Tanh()]
        net = torch.nn.Sequential(*mods, torch.nn.Linear(sizes[-1], y.shape[1]))
    opt = torch.optim.Adam(net.parameters(), lr=cfg.learning_rate)
    xt, yt = torch.from_numpy(xn), torch.from_numpy(np.ascontiguousarray(y))
    loss_sum = 0.0
    for _ in range(cfg.epochs):
        order, loss_sum = torch.randperm(len(xt), generator=gen), 0.0
        for i in range(0, len(xt), cfg.batch_size):
            idx = order[i:i + cfg.batch_size]
            loss = torch.nn.functional.mse_loss(net(xt[idx]), yt[idx])
            opt.zero_grad()
            loss.backward()
            opt.step()
            loss_sum += loss.item() * len(idx)
    layers: list[tuple] = [("linear", m.weight.detach().numpy(), m.bias.detach().numpy())
                           if isinstance(m, torch.nn.Linear) else ("tanh",) for m in net]
    return layers, norm, loss_sum / len(xt)


def _policy(cfg: ImitationConfig, layers: list[tuple], norm: tuple, params: dict[str, float],
            meta: dict[str, Any]) -> NumpyPolicy:
    """The numpy keeper of fitted ``layers``: its output clipped into ``[-1, 1]``, read
    through the ``"ball-residual"`` map with ``params``."""
    ones = np.ones(2, np.float32)
    return NumpyPolicy(layers, "clip", -ones, ones, meta=meta, normalize=norm,
                       action_map={"kind": "ball-residual", "params": params},
                       frame_stack=cfg.frame_stack)


def _round_data(cfg: ImitationConfig, policy: NumpyPolicy | None, round_: int,
                residual: float) -> tuple[np.ndarray, np.ndarray, int]:
    """Round ``round_``'s shots played by ``policy``: network inputs, teacher's labels, the
    steps played. The shots are spread over the workers and put back in seed order."""
    first = TRAIN_SEED + cfg.seed * 10_000_000 + round_ * cfg.episodes
    chunks = stripes(range(first, first + cfg.episodes), cfg.workers)
    parts = map_jobs(_play, [(cfg.env_kwargs, policy, c, residual) for c in chunks],
                     len(chunks))
    shots = unstripe(parts)
    x = np.concatenate([stack_history(o, cfg.frame_stack) for o, _ in shots])
    y = np.concatenate([a for _, a in shots])
    return x, y, len(y)


def imitate(cfg: ImitationConfig, out: str | os.PathLike,
            command: Sequence[str] | None = None) -> dict[str, Any]:
    """Train a keeper by DAgger with the privileged teacher (see the module docstring) into
    the run folder ``out`` (created; refused if it holds a ``config.json``). Returns the
    summary (also ``summary.json``): steps played, seconds, steps per second, each round's
    loss and held-out save rate beside the scripted keeper's."""
    out = Path(out)
    if (out / "config.json").exists():
        raise FileExistsError(f"{out} already holds a run (config.json): choose another folder")
    out.mkdir(parents=True, exist_ok=True)
    env = gym.make(GOALKEEPER_ID, **cfg.env_kwargs)
    params = ball_residual_params(env)
    env.close()
    config = {**asdict(cfg), "algorithm": "DAgger", "teacher": "true ball velocity",
              "actions": "ball-residual", "command": list(command or [])}
    (out / "config.json").write_text(json.dumps(config, indent=2))
    t0, steps, policy, rounds, eval_s = time.perf_counter(), 0, None, [], 0.0
    x_all, y_all = [], []
    scripted = None
    for r in range(cfg.rounds):
        x, y, n = _round_data(cfg, policy, r, params["residual"])
        x_all.append(x)
        y_all.append(y)
        steps += n
        labels = np.concatenate(y_all)
        layers, norm, loss = _fit(np.concatenate(x_all), labels, cfg, r)
        meta = {"algorithm": "DAgger", "env_id": GOALKEEPER_ID,
                "env_kwargs": cfg.env_kwargs, "round": r, "steps": steps,
                "command": shlex.join(config["command"]), "config": config}
        policy = _policy(cfg, layers, norm, params, meta)
        path = policy.save(out / f"round_{r}_policy.npz")
        row = {"round": r, "steps": steps, "samples": len(labels),
               "loss": loss, "zero_loss": float(np.mean(labels ** 2)),
               "seconds": time.perf_counter() - t0}
        if cfg.eval_episodes:
            t_eval = time.perf_counter()
            if scripted is None:
                scripted = evaluate("scripted", cfg.env_kwargs, cfg.eval_episodes,
                                    cfg.eval_seed, cfg.workers).save_rate
            res = evaluate(path, cfg.env_kwargs, cfg.eval_episodes, cfg.eval_seed, cfg.workers)
            eval_s += time.perf_counter() - t_eval
            row.update(save_rate=res.save_rate, ci_low=res.ci_low, ci_high=res.ci_high,
                       scripted_save_rate=scripted)
        rounds.append(row)
        (out / "evaluations.json").write_text(json.dumps(rounds, indent=2))
    policy.save(out / "final_policy.npz")
    seconds = time.perf_counter() - t0
    # Training time: playing the shots and fitting, without the held-out evaluations.
    train_s = seconds - eval_s
    summary = {"rounds": rounds, "steps": steps, "seconds": seconds, "train_seconds": train_s,
               "steps_per_s": steps / train_s, "final_policy": str(out / "final_policy.npz")}
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary
