"""Batched environments as stable-baselines3 ``VecEnv``s: the Goalkeeper's
:class:`BatchedVecEnv` and the match's :class:`BatchedMatchVecEnv`.

:class:`~soccer_env.envs.batched.GoalkeeperVectorEnv` steps its episodes in one batch with
Gymnasium's vector API; stable-baselines3 expects its own ``VecEnv`` contract: automatic reset
within the step that ends an episode, the last observation in
``infos[i]["terminal_observation"]``, ``infos[i]["TimeLimit.truncated"]``, ``seed()`` before
``reset()``, one info dict per environment. This adapter runs the vector environment with
``SAME_STEP`` autoreset and translates, adding ``Monitor``'s episode statistics
(``infos[i]["episode"] = {"r", "l", "t"}``) and ``is_success`` / ``outcome`` at episode ends.
"""

from __future__ import annotations

import functools
import time
from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode
from stable_baselines3.common.vec_env.base_vec_env import (
    VecEnv,
    VecEnvIndices,
    VecEnvStepReturn,
)

from agents.scripted import TEAMS
from agents.vec.match import MatchVecEnv
from soccer_env.envs.batched import GoalkeeperVectorEnv, ShootoutVectorEnv
from soccer_env.envs.batched_match import MatchBatch
from soccer_env.envs.registration import GOALKEEPER_ID, GYMNASIUM, SHOOTOUT_ID

__all__ = ["BatchedVecEnv", "BatchedMatchVecEnv", "BATCHED_TASKS"]


#: The batched single-agent tasks by id.
BATCHED_TASKS = {GOALKEEPER_ID: GoalkeeperVectorEnv, SHOOTOUT_ID: ShootoutVectorEnv}


class BatchedVecEnv(VecEnv):
    """``num_envs`` batched Goalkeeper-v0 (or Shootout-v0) episodes as a stable-baselines3
    ``VecEnv``.

    Args:
        num_envs: environments.
        env_kwargs: the task's keyword arguments (what the batch supports: the geometric
            detector, no rendering).
        max_episode_steps: the time limit (None: the registration's, 480 steps for the
            Goalkeeper, 600 for the Shootout).
        env_id: ``"soccer_env/Goalkeeper-v0"`` or ``"soccer_env/Shootout-v0"``.
    """

    def __init__(self, num_envs: int = 16, env_kwargs: dict[str, Any] | None = None,
                 max_episode_steps: int | None = None,
                 env_id: str = GOALKEEPER_ID) -> None:
        if env_id not in BATCHED_TASKS:
            raise ValueError(f"env_id must be one of {list(BATCHED_TASKS)}, got {env_id!r}")
        cls = BATCHED_TASKS[env_id]
        if max_episode_steps is None:
            max_episode_steps = GYMNASIUM[env_id].max_episode_steps
        self.venv = cls(num_envs, max_episode_steps=max_episode_steps,
                        autoreset_mode=AutoresetMode.SAME_STEP, **(env_kwargs or {}))
        super().__init__(num_envs, self.venv.single_observation_space,
                         self.venv.single_action_space)
        self._seed: int | None = None
        self._actions: np.ndarray | None = None
        self._returns = np.zeros(num_envs)
        self._lengths = np.zeros(num_envs, dtype=np.int64)
        self._t0 = time.time()

    def seed(self, seed: int | None = None) -> Sequence[int | None]:
        """Seed the next :meth:`reset`: environment ``k`` gets ``seed + k``."""
        self._seed = seed
        return [None if seed is None else seed + k for k in range(self.num_envs)]

    def reset(self) -> np.ndarray:
        obs, _ = self.venv.reset(seed=self._seed)
        self._seed = None
        self._returns[:] = 0.0
        self._lengths[:] = 0
        self.reset_infos = [{} for _ in range(self.num_envs)]
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = np.asarray(actions)

    def step_wait(self) -> VecEnvStepReturn:
        if self._actions is None:
            raise RuntimeError("call step_async(actions) before step_wait()")
        actions, self._actions = self._actions, None
        obs, rewards, terminated, truncated, info = self.venv.step(actions)
        self._returns += rewards
        self._lengths += 1
        dones = terminated | truncated
        infos: list[dict[str, Any]] = [{"TimeLimit.truncated": bool(tr and not te)}
                                       for te, tr in zip(terminated.tolist(),
                                                         truncated.tolist())]
        if dones.any():
            final = info["final_info"]
            elapsed = round(time.time() - self._t0, 6)
            for k in np.nonzero(dones)[0].tolist():
                entry = infos[k]
                entry["terminal_observation"] = info["final_obs"][k]
                entry["outcome"] = final["outcome"][k]
                if terminated[k]:
                    entry["is_success"] = bool(final["is_success"][k])
                entry["episode"] = {"r": float(self._returns[k]), "l": int(self._lengths[k]),
                                    "t": elapsed}
            self._returns[dones] = 0.0
            self._lengths[dones] = 0
        return obs, rewards.astype(np.float32), dones, infos

    def close(self) -> None:
        self.venv.close()

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        return [getattr(self.venv, attr_name) for _ in self._get_indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        setattr(self.venv, attr_name, value)

    def env_method(self, method_name: str, *method_args: Any, indices: VecEnvIndices = None,
                   **method_kwargs: Any) -> list[Any]:
        """Call the batched environment's ``method_name`` once; its result for each index."""
        result = getattr(self.venv, method_name)(*method_args, **method_kwargs)
        return [result for _ in self._get_indices(indices)]

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper], indices: VecEnvIndices = None
                       ) -> list[bool]:
        return [False for _ in self._get_indices(indices)]


def _rows(agents: list[str], some: list[str]) -> slice | list[int]:
    """The rows of ``some`` of ``agents``: a slice if they are contiguous and in order."""
    rows = [agents.index(a) for a in some]
    if rows and rows == list(range(rows[0], rows[0] + len(rows))):
        return slice(rows[0], rows[0] + len(rows))
    return rows


class BatchedMatchVecEnv(MatchVecEnv):
    """:class:`~agents.vec.match.MatchVecEnv` with its matches stepped as one batch
    (:class:`~soccer_env.envs.batched_match.MatchBatch`): the same batch layout (entry
    ``k * L + j`` is learning agent ``j`` of match ``k``), opponents, self-play, seeds and
    info dicts, with the per-match Python work of a step reduced to what happens rarely.

    The arguments (``env_kwargs``, ``n_matches``, ``learner``, ``opponent``, ``first_match``)
    are :class:`MatchVecEnv`'s; the matches must be ones the batch runs (the geometric
    detector, no rendering; otherwise :class:`~soccer_env.envs.batched.NotBatchable` says what
    is refused). Raw and perceived observations and humanoids run each match's own
    perception, walk engines and heads (as a single match's), so they gain little from the
    batch.

    Opponents run over the whole batch at once: a network (a numpy copy of a model) on every
    opponent row in one call, the scripted team through
    :meth:`~agents.scripted.team.ScriptedTeam.act_batch`; any other
    callable is called once per match, as :class:`MatchVecEnv` calls it.

    The matches are those of :class:`MatchVecEnv` with the same seeds up to the rounding of
    the shared physics space and of the observations' arithmetic (float64 here, single
    precision in a match's own observation builder): tested to agree on every event, score
    and end, with observations within 1e-4, over a few hundred steps.

    ``get_attr`` reads each entry's match's ``score``, ``restart_team`` and ``cycles`` from
    the batch and any other attribute from a match of the same configuration (the matches
    share it); ``set_attr`` and ``env_method`` are refused (the batch has no match objects
    to change or call).
    """

    #: Attributes that differ between matches, read from the batch's arrays.
    PER_MATCH = ("score", "restart_team", "cycles")
    def _make_matches(self) -> Any:
        self.batch = MatchBatch(self.n_matches, **self.env_kwargs)
        self.matches = []
        return self.batch.probe

    def reset(self) -> np.ndarray:
        """Reset every match (seeded if :meth:`seed` was called since the last reset) and
        return the stacked observations ``(num_envs, obs_dim)`` float32."""
        L = self.agents_per_match
        self._seed_pools()
        seeds = [self._seeds[k * L] for k in range(self.n_matches)]
        obs = self.batch.reset(seeds)
        for k in range(self.n_matches):
            self._draw_opponent(k)
        self._split(obs)
        self._ep_lengths = [0] * self.n_matches
        self._ep_returns[:] = 0.0
        self.reset_infos = [{} for _ in range(self.num_envs)]
        self._reset_seeds()
        self._reset_options()
        self._started = True
        return self._learner_obs

    def _split(self, obs: np.ndarray) -> None:
        """Keep the learners' rows ``(num_envs, obs_dim)`` and the opponents' ``(M, n_opp,
        obs_dim)`` of the batch's observations ``(M, N, obs_dim)``."""
        self._learner_obs = obs[:, self._learner_rows].reshape(self.num_envs, self._obs_size)
        self._opp_obs = obs[:, self._opp_rows]

    @functools.cached_property
    def _learner_rows(self) -> slice | list[int]:
        """The learners' rows in a match's robot order (a slice when they are contiguous,
        which numpy indexes without copying the index)."""
        return _rows(self.batch.possible_agents, self.learner_agents)

    @functools.cached_property
    def _opp_rows(self) -> slice | list[int]:
        """The opponents' rows in a match's robot order."""
        return _rows(self.batch.possible_agents, self.opponent_agents)

    def _opponent_batch(self) -> np.ndarray:
        """Every match's opponent actions ``(M, n_opp, 6)`` from their last observations."""
        obs = self._opp_obs
        n, n_opp = self.n_matches, len(self.opponent_agents)
        out = np.empty((n, n_opp, 6), dtype=np.float32)
        groups: dict[int, list[int]] = {}
        for k, opp in enumerate(self._match_opponents):
            groups.setdefault(id(opp), []).append(k)
        for ks in groups.values():
            opp = self._match_opponents[ks[0]]
            sel: Any = slice(None) if len(ks) == n else ks
            part = obs[sel]
            if opp.per_agent:
                rows = part.reshape(-1, self._obs_size)
                out[sel] = self._checked(opp, rows).reshape(-1, n_opp, 6)
            elif opp.batch is not None:
                acts = np.asarray(opp.batch(part), dtype=np.float32)
                if acts.shape != part.shape[:2] + (6,):
                    raise ValueError(f"opponent {opp.label} returned actions of shape "
                                     f"{acts.shape} for observations of shape {part.shape}")
                out[sel] = acts
            else:
                out[sel] = np.stack([self._checked(opp, o) for o in part])
        return out

    def step_wait(self) -> VecEnvStepReturn:
        """Step every match once; finished matches are reset (see :class:`MatchVecEnv`)."""
        obs, rewards, dones, compact = self.step_arrays()
        return obs, rewards, dones, self.expand_infos(compact, self.agents_per_match)

    def step_arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple]:
        """:meth:`step_wait` with the infos in the compact form :meth:`expand_infos` reads
        (what a worker process sends: a few lists instead of a dict per entry)."""
        if not self._started:
            raise RuntimeError("call reset() before stepping a MatchVecEnv")
        if self._actions is None:
            raise RuntimeError("call step_async(actions) before step_wait()")
        actions, self._actions = self._actions, None
        n, L = self.n_matches, self.agents_per_match
        full = np.empty((n, self.batch.n_robots, 6), dtype=np.float32)
        full[:, self._learner_rows] = actions.reshape(n, L, 6)
        if self.opponent_agents:
            full[:, self._opp_rows] = self._opponent_batch()
        result = self.batch.step(full)
        rewards = result.rewards[:, self._learner_rows].reshape(-1).astype(np.float32)
        term, trunc = result.terminated, result.truncated
        ended = term | trunc
        dones = np.repeat(ended, L)
        self._split(result.obs)
        ep_returns = self._ep_returns
        ep_returns += rewards
        scores = result.scores.tolist()
        finished: dict[int, dict[str, Any]] = {}
        if ended.any():
            elapsed = round(time.time() - self._t_start, 6)
            own = [TEAMS.index(t) for t in self._teams_of_entries]
            for k in np.nonzero(ended)[0].tolist():
                base = k * L
                last = result.final_obs[k][self._learner_rows]
                score = scores[k]
                for j in range(L):
                    i = base + j
                    gf, ga = score[own[j]], score[1 - own[j]]
                    finished[i] = {
                        "terminal_observation": last[j].copy(),
                        "episode": {"r": float(ep_returns[i]), "l": int(result.lengths[k]),
                                    "t": elapsed},
                        "is_success": gf > ga, "goals_for": gf, "goals_against": ga}
                ep_returns[base:base + L] = 0.0
                self._draw_opponent(k)
        compact = (result.events.tolist(), scores, (trunc & ~term).tolist(), finished)
        return self._learner_obs.copy(), rewards, dones, compact

    @staticmethod
    def expand_infos(compact: tuple, agents_per_match: int) -> list[dict[str, Any]]:
        """One info dict per entry (:class:`MatchVecEnv`'s) from :meth:`step_arrays`'s
        compact infos: each match's event, score and truncation flag, and the finished
        entries' extras by entry index."""
        events, scores, truncs, finished = compact
        infos: list[dict[str, Any]] = []
        append = infos.append
        for event, (b, y), tl in zip(events, scores, truncs):
            score = {"blue": b, "yellow": y}
            for _ in range(agents_per_match):
                append({"score": score, "event": event, "TimeLimit.truncated": tl})
        for i, extra in finished.items():
            infos[i].update(extra)
        return infos

    def close(self) -> None:
        self.batch.close()

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        """``attr_name`` of the match of each entry: from the batch for
        :attr:`PER_MATCH`, else the configuration the matches share."""
        ks = self._matches_of(indices)
        if attr_name in self.PER_MATCH:
            values = getattr(self.batch, attr_name)
            return [values[k].tolist() for k in ks]
        value = getattr(self._probe, attr_name)
        return [value for _ in ks]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        raise ValueError("the batched matches share one configuration and keep their state in "
                         "arrays: set the match's arguments when making the VecEnv "
                         f"(set_attr({attr_name!r}) is not supported)")

    def env_method(self, method_name: str, *method_args: Any, indices: VecEnvIndices = None,
                   **method_kwargs: Any) -> list[Any]:
        raise ValueError(f"the batched matches are not match objects: env_method("
                         f"{method_name!r}) is not supported; use MatchVecEnv for per-match "
                         "calls")

    def get_images(self) -> Sequence[np.ndarray | None]:
        raise ValueError("the batched matches do not render; use MatchVecEnv for videos")
