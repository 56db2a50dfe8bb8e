"""The callbacks of a stable-baselines3 training run: the periodic save-rate evaluation that
keeps the best model (:class:`SaveRateEval`), the checkpoints (:class:`Checkpoints`), and
:func:`training_callbacks`, which puts them together with the rollout timer and self-play as
the configuration asks.

The periodic evaluation runs the current actor deterministically on ``eval_episodes`` shots
drawn from seeds :data:`~agents.runs.training.config.EVAL_SEED_START` onwards, apart from the
fixed test suite (seeds 0 onwards) that ``soccer-env eval`` and the ablation use, so that
picking the best model does not bias the reported save rate.

Imports stable-baselines3 (the training loop imports this module when a run starts).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from stable_baselines3.common.callbacks import BaseCallback

from agents.runs.evaluation import evaluate
from agents.runs.training.config import EVAL_SEED_START, TrainConfig
from agents.sb3.callbacks import RolloutTimer, rollout_timer
from agents.sb3.normalization import save_vecnormalize, vecnormalize_path
from agents.sb3.policies import numpy_copy
from agents.vec.self_play import SelfPlayCallback
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID

__all__ = ["SaveRateEval", "Checkpoints", "training_callbacks"]


class SaveRateEval(BaseCallback):
    """Every ``eval_every`` steps: the actor's save rate on ``eval_episodes`` shots, logged as
    ``eval/save_rate``; the best model is kept (``best_model.zip``, its statistics and
    ``best_policy.npz``) and every evaluation written to ``evaluations.json`` in ``out``.

    Attributes:
        history: the evaluations so far (steps, save rate and its interval, outcomes, ball
            RMSE).
    """

    def __init__(self, cfg: TrainConfig, out: Path, action_map: dict[str, Any] | None
                 ) -> None:
        super().__init__()
        self.cfg, self.out, self.action_map = cfg, out, action_map
        self.history: list[dict[str, Any]] = []
        self.best = -1.0
        self._next = cfg.eval_every

    def _on_training_start(self) -> None:
        # A resumed run starts at the checkpoint's step count: the next evaluation is the
        # next multiple of eval_every after it.
        every = self.cfg.eval_every
        self._next = (self.num_timesteps // every + 1) * every

    def _on_step(self) -> bool:
        if self.num_timesteps >= self._next:
            self._next += self.cfg.eval_every
            self.run()
        return True

    def run(self) -> dict[str, Any]:
        """Evaluate the current actor now; returns the entry added to :attr:`history`."""
        cfg, out = self.cfg, self.out
        norm = self.model.get_vec_normalize_env()
        policy = numpy_copy(self.model, vec_normalize=norm, action_map=self.action_map,
                            frame_stack=cfg.frame_stack)
        kwargs = cfg.env_kwargs if cfg.eval_env_kwargs is None else cfg.eval_env_kwargs
        res = evaluate(policy, kwargs, episodes=cfg.eval_episodes,
                       start_seed=EVAL_SEED_START, workers=max(1, cfg.n_workers))
        entry = {"steps": int(self.num_timesteps), "save_rate": res.save_rate,
                 "ci_low": res.ci_low, "ci_high": res.ci_high,
                 "outcomes": res.outcomes, "ball_rmse_m": res.ball_rmse_m}
        self.history.append(entry)
        self.logger.record("eval/save_rate", res.save_rate)
        self.logger.record("eval/mean_steps", res.mean_steps)
        (out / "evaluations.json").write_text(json.dumps(self.history, indent=1))
        if res.save_rate > self.best:
            self.best = res.save_rate
            self.model.save(out / "best_model.zip")
            if norm is not None:
                save_vecnormalize(norm, out / "best_vecnormalize.npz")
            policy.meta.update(cfg.policy_meta(entry))
            policy.save(out / "best_policy.npz")
        return entry


class Checkpoints(BaseCallback):
    """Every ``checkpoint_every`` steps: the model as ``checkpoints/model_<N>_steps.zip``
    (stable-baselines3's ``CheckpointCallback`` names) and its normalisation statistics
    beside it as ``.npz`` (no pickle)."""

    def __init__(self, cfg: TrainConfig, out: Path) -> None:
        super().__init__()
        self.out = out
        self.every = max(1, cfg.checkpoint_every // cfg.n_envs)

    def _on_step(self) -> bool:
        if self.n_calls % self.every == 0:
            folder = self.out / "checkpoints"
            folder.mkdir(parents=True, exist_ok=True)
            path = folder / f"model_{self.num_timesteps}_steps.zip"
            self.model.save(path)
            norm = self.model.get_vec_normalize_env()
            if norm is not None:
                save_vecnormalize(norm, vecnormalize_path(path))
        return True


def training_callbacks(cfg: TrainConfig, out: Path, action_map: dict[str, Any] | None
                       ) -> tuple[list[Any], RolloutTimer, SaveRateEval | None]:
    """The callbacks of a run of ``cfg`` writing into ``out``: the rollout timer, the
    checkpoints (``checkpoint_every``), the save-rate evaluation (``eval_every``,
    Goalkeeper-v0) and self-play (the match with ``opponent="self"``); also the timer and
    the evaluation (None without one), whose results the summary reports."""
    timer = rollout_timer()
    callbacks: list[Any] = [timer]
    if cfg.checkpoint_every:
        callbacks.append(Checkpoints(cfg, out))
    evaluator = None
    if cfg.eval_every and cfg.env_id == GOALKEEPER_ID:
        evaluator = SaveRateEval(cfg, out, action_map)
        callbacks.append(evaluator)
    if cfg.env_id == MATCH_ID and cfg.opponent == "self":
        callbacks.append(SelfPlayCallback(update_every=cfg.self_play_every))
    return callbacks, timer, evaluator
