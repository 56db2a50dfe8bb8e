"""The PettingZoo match as a stable-baselines3 ``VecEnv`` with parameter sharing.

:class:`MatchVecEnv` steps ``n_matches`` matches
(:class:`~soccer_env.envs.match.SoccerParallelEnv`) in one process
(:class:`~agents.vec.match_workers.MatchWorkerVecEnv` splits them over worker processes, with
the same batches: :func:`~agents.vec.factories.make_match_vec_env` with ``workers=N``) and
exposes every learning agent of every match as one entry of the batch, so that one policy
controls them all (parameter sharing). The other team is played by a frozen
``opponent``, or, with ``learner="both"``, by the same policy: observations are in each team's
own frame, so a policy that learned to play blue can play yellow.

Batch layout: entry ``k * L + j`` is learning agent ``j`` of match ``k`` (``L`` learners per
match, in the match's agent order: blue robots, then yellow robots); see
:attr:`MatchVecEnv.entry_agents`.

SuperSuit's ``pettingzoo_env_to_vec_env_v1`` would do the same, but breaks between releases;
this adapter implements stable-baselines3's ``VecEnv`` contract directly (the semantics of its
``DummyVecEnv``): matches reset themselves when they end, the finished match's last
observation goes into ``infos[i]["terminal_observation"]``, ``infos[i]["TimeLimit.truncated"]``
flags a truncation (``max_cycles``), and ``seed(s)`` makes the next ``reset()`` reproducible.

Each step's info holds only what stable-baselines3 reads and the match's ``score`` and
``event`` (the match's own info dicts, with ``truth`` and ``estimate``, are large and not
copied). At the end of a match it also holds ``"episode": {"r", "l", "t"}`` (the agent's
return, the match's length in steps and the wall-clock seconds since the VecEnv was made,
as SB3's ``Monitor`` writes them, so ``VecMonitor`` is optional), ``"is_success"`` (the
agent's team won), ``"goals_for"`` and ``"goals_against"``.

Training against a fixed opponent and self-play::

    from stable_baselines3 import PPO
    from agents.vec.factories import make_match_vec_env
    from agents.vec.self_play import SelfPlayCallback

    venv = make_match_vec_env({"blue": 2, "yellow": 2, "match_duration": 60.0}, n_matches=4,
                              learner="blue", opponent="scripted", seed=0)
    model = PPO("MlpPolicy", venv).learn(100_000)
    venv.set_opponent(model)  # a frozen numpy copy of the current policy
    model.learn(100_000, callback=SelfPlayCallback(update_every=20_000, pool_size=4))
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from stable_baselines3.common.vec_env import VecEnv
from stable_baselines3.common.vec_env.base_vec_env import VecEnvIndices, VecEnvStepReturn

import soccer_env
from agents.common.checks import check_full_infos
from agents.policies.base import IdlePolicy
from agents.policies.numpy_policy import NumpyPolicy
from agents.sb3.algorithms import is_recurrent, is_sb3_model
from agents.sb3.policies import SB3Policy, numpy_copy
from agents.scripted import TEAMS, ScriptedTeam, scripted_team

__all__ = ["MatchVecEnv", "LEARNERS", "OPPONENT_NAMES", "base_seed"]

#: Allowed values of ``learner``.
LEARNERS = ("blue", "yellow", "both")
#: Opponents given by name.
OPPONENT_NAMES = ("scripted", "idle")

_NO_MEMORY = ("opponent policies with memory (a recurrent model, a frame-stacked numpy policy) "
              "are not supported: the match does not reset an opponent's memory when a match "
              "ends")
_OPPONENT_HELP = ("'scripted', 'idle', a numpy policy file (.npz), a callable batch policy "
                  "obs (k, obs_dim) -> actions (k, 6), or a stable-baselines3 model")


def base_seed(seed: int | None) -> int:
    """The seed a match VecEnv's ``seed(seed)`` counts its matches from: ``seed`` (an
    integer >= 0), or one drawn from the OS's entropy for None."""
    if seed is None:
        return int(np.random.default_rng().integers(np.iinfo(np.uint32).max))
    seed = int(seed)
    if seed < 0:
        raise ValueError(f"seed must be an integer >= 0 or None, got {seed}")
    return seed


class _Opponent:
    """A frozen policy for the non-learning team.

    ``per_agent`` policies map each row independently (a network), so the rows of all
    matches go through one call; the others (a scripted team, any user callable) see one
    match's team at a time.
    """

    __slots__ = ("fn", "per_agent", "label", "batch")

    def __init__(self, fn: Callable[[np.ndarray], np.ndarray], per_agent: bool, label: str,
                 batch: Callable[[np.ndarray], np.ndarray] | None = None) -> None:
        self.fn, self.per_agent, self.label = fn, per_agent, label
        #: The policy over many matches at once, ``(M, n, obs_dim) -> (M, n, 6)``, for
        #: those that are not ``per_agent`` but have such a path (the scripted team).
        self.batch = batch

    def __repr__(self) -> str:
        return f"<opponent {self.label}>"


class MatchVecEnv(VecEnv):
    """``n_matches`` soccer matches as one stable-baselines3 ``VecEnv``, one batch entry per
    learning agent (parameter sharing).

    Args:
        env_kwargs: keyword arguments of :func:`soccer_env.parallel_env` (team sizes, field,
            ``obs_mode``, ``match_duration`` [s], ``max_cycles``, ``shaping``, ...).
        n_matches: matches stepped in this process (>= 1).
        learner: ``"blue"``, ``"yellow"`` or ``"both"`` (both teams are batch entries; needs
            teams of equal size, so that an observation entry means the same for both).
        opponent: the other team's policy when ``learner`` is one team: ``"scripted"``
            (:class:`~agents.scripted.team.ScriptedTeam`, the default), ``"idle"`` (all-zero
            actions), the path of a numpy policy file (``.npz``, :meth:`NumpyPolicy.save`;
            loaded without pickle), a stable-baselines3 model (copied into a frozen
            :class:`NumpyPolicy` when possible), a :class:`NumpyPolicy`, or any callable
            ``obs (k, obs_dim) -> actions (k, 6)``, called with one match's team at a time
            (rows in robot order). Must be None with ``learner="both"``. Policies with memory
            (recurrent models, frame-stacked numpy policies) are refused.
        first_match: the global index of this VecEnv's first match, when the matches of one
            batch are split over processes
            (:class:`~agents.vec.match_workers.MatchWorkerVecEnv`):
            match ``k`` here is seeded as match ``first_match + k`` would be, so results do
            not depend on how the matches are split.

    Spaces: the match's per-agent ``Box`` observation (float32) and ``Box(-1, 1, (6,))``
    action. ``num_envs = n_matches * L`` with ``L`` the learning robots per match.

    Rewards are the match's per-agent rewards: the zero-sum goal reward (+1 / -1 per goal)
    plus the optional ``shaping`` terms. Matches end when their clock reaches
    ``match_duration`` (a termination) or after ``max_cycles`` steps (a truncation); then
    they reset at once, drawing the next formation from their own seeded stream.

    ``get_attr``, ``set_attr`` and ``env_method`` reach the match of each entry
    (``env_method`` calls each match once, whatever the number of its entries);
    ``get_images`` returns one frame per match (``render_mode="rgb_array"``).
    """

    def __init__(self, env_kwargs: Mapping[str, Any] | None = None, n_matches: int = 1,
                 learner: str = "blue", opponent: Any = None, *, first_match: int = 0
                 ) -> None:
        if learner not in LEARNERS:
            raise ValueError(f"learner must be one of {list(LEARNERS)}, got {learner!r}")
        if isinstance(n_matches, bool) or not isinstance(n_matches, (int, np.integer)) or (
                n_matches < 1):
            raise ValueError(f"n_matches must be an integer >= 1, got {n_matches!r}")
        if env_kwargs is not None and not isinstance(env_kwargs, Mapping):
            raise TypeError(f"env_kwargs must be a mapping of match keyword arguments, got "
                            f"{type(env_kwargs).__name__}")
        if isinstance(first_match, bool) or not isinstance(first_match, (int, np.integer)) or (
                first_match < 0):
            raise ValueError(f"first_match must be an integer >= 0, got {first_match!r}")
        self.first_match = int(first_match)
        self.env_kwargs = dict(env_kwargs or {})
        check_full_infos(self.env_kwargs, "MatchVecEnv")
        self.n_matches = int(n_matches)
        m0 = self._probe = self._make_matches()
        self.learner = learner
        sizes = {"blue": m0.world.n_blue, "yellow": m0.world.n_yellow}
        if learner == "both":
            if sizes["blue"] != sizes["yellow"]:
                raise ValueError(f"learner='both' needs teams of equal size (one policy reads "
                                 f"both teams' observations), got blue={sizes['blue']}, "
                                 f"yellow={sizes['yellow']}")
            if opponent is not None:
                raise ValueError("opponent must be None with learner='both' (both teams are "
                                 f"played by the learning policy), got {opponent!r}")
            learning = TEAMS
        else:
            if sizes[learner] < 1:
                raise ValueError(f"learner={learner!r} but the {learner} team has no robots "
                                 f"(blue={sizes['blue']}, yellow={sizes['yellow']})")
            learning = (learner,)
        self.learning_teams = learning
        self.opponent_team = None if learner == "both" else TEAMS[1 - TEAMS.index(learner)]
        agents = m0.possible_agents
        #: Learning agents of each match, in batch order.
        self.learner_agents = [a for a in agents if a.split("_")[0] in learning]
        #: Agents of each match played by the opponent.
        self.opponent_agents = [a for a in agents if a.split("_")[0] not in learning]
        self.agents_per_match = len(self.learner_agents)
        #: ``(match index, agent name)`` of every batch entry.
        self.entry_agents = [(k, a) for k in range(self.n_matches) for a in self.learner_agents]
        self._teams_of_entries = [a.split("_")[0] for a in self.learner_agents]
        self._entry_names = [f"{a} of match {k} (batch entry {i})"
                             for i, (k, a) in enumerate(self.entry_agents)]
        self.out_of_range_actions = m0.out_of_range_actions  # "clip" or "raise" outside [-1, 1]
        self._obs_size = m0.observation_space(agents[0]).shape[0]

        self.num_envs = self.n_matches * self.agents_per_match  # before VecEnv.__init__
        super().__init__(self.num_envs, m0.observation_space(self.learner_agents[0]),
                         m0.action_space(self.learner_agents[0]))
        self.metadata = {**m0.metadata, **self.metadata}

        self._pool: list[_Opponent] = []
        # One stream of opponent draws per match (seeded by ``seed`` and the match's global
        # index), so that the draws do not depend on how matches are split over processes.
        self._pool_rngs = [np.random.default_rng() for _ in range(self.n_matches)]
        self._pool_seed: int | None = None
        self._match_opponents: list[_Opponent | None] = [None] * self.n_matches
        if self.opponent_agents:
            self.set_opponent("scripted" if opponent is None else opponent)
        self._actions: np.ndarray | None = None
        self._opp_obs: np.ndarray | None = None
        self._ep_returns = np.zeros(self.num_envs, dtype=np.float64)
        self._ep_lengths = [0] * self.n_matches
        self._t_start = time.time()
        self._started = False

    def _make_matches(self) -> Any:
        """Build the matches (:attr:`matches`); return one of them, whose spaces, specs and
        observation layout every match shares."""
        self.matches = [soccer_env.parallel_env(**self.env_kwargs)
                        for _ in range(self.n_matches)]
        return self.matches[0]

    # ------------------------------------------------------------------------------------
    # Opponents
    # ------------------------------------------------------------------------------------

    def _resolve_opponent(self, opponent: Any) -> _Opponent:
        """Turn an ``opponent`` argument into a frozen :class:`_Opponent`."""
        if isinstance(opponent, _Opponent):
            return opponent
        if isinstance(opponent, str):
            if opponent == "scripted":  # the scripted team of the opponents' robots
                team = scripted_team(self._probe, self.opponent_team)
                return _Opponent(team.act, False, "scripted", team.act_batch)
            if opponent == "idle":
                return _Opponent(IdlePolicy(6), True, "idle")
            if opponent.endswith(".npz"):  # a numpy policy file: arrays only, no pickle
                opponent = NumpyPolicy.load(opponent)
            else:
                raise ValueError(f"opponent must be {_OPPONENT_HELP}; got the string "
                                 f"{opponent!r} (names: {list(OPPONENT_NAMES)})")
        if is_sb3_model(opponent):
            if is_recurrent(opponent):
                raise ValueError(_NO_MEMORY)
            try:
                policy: Any = numpy_copy(opponent)
            except ValueError:  # a network numpy cannot copy: it follows the live model
                return _Opponent(SB3Policy(opponent), True, type(opponent).__name__)
            self._check_policy_size(policy)
            return _Opponent(policy, True, f"{type(opponent).__name__} copy")
        if isinstance(opponent, ScriptedTeam):
            return _Opponent(opponent.act, False, "ScriptedTeam", opponent.act_batch)
        if isinstance(opponent, NumpyPolicy):
            if opponent.stateful:
                raise ValueError(_NO_MEMORY)
            self._check_policy_size(opponent)
            return _Opponent(opponent, True, type(opponent).__name__)
        if callable(opponent):
            return _Opponent(opponent, False, getattr(opponent, "__name__",
                                                      type(opponent).__name__))
        raise ValueError(f"opponent must be {_OPPONENT_HELP}, got {type(opponent).__name__}")

    def _check_policy_size(self, policy: Any) -> None:
        size = getattr(policy, "obs_size", None)
        if size is not None and size != self._obs_size:
            raise ValueError(f"opponent policy takes observations of size {size}, the match "
                             f"gives {self._obs_size}")

    def _require_opponent_team(self) -> None:
        if self.learner == "both":
            raise ValueError("learner='both' has no opponent: both teams are played by the "
                             "learning policy")

    def set_opponent(self, opponent: Any) -> None:
        """Play the non-learning team with ``opponent`` (any value the constructor takes)
        in every match from the next step on, and forget the opponent pool. A model is
        copied now: later training does not change the copy."""
        self._require_opponent_team()
        resolved = self._resolve_opponent(opponent)
        self._pool = []
        self._match_opponents = [resolved] * self.n_matches

    def set_opponent_pool(self, opponents: Sequence[Any], redraw_now: bool = False) -> None:
        """Draw each match's opponent uniformly from ``opponents`` (values the constructor
        takes) whenever the match resets; matches keep their present opponent until then,
        unless ``redraw_now``. The draws come from a stream seeded by :meth:`seed`."""
        self._require_opponent_team()
        if len(opponents) == 0:
            raise ValueError("opponents must hold at least one opponent")
        self._pool = [self._resolve_opponent(o) for o in opponents]
        if redraw_now:
            for k in range(self.n_matches):
                self._draw_opponent(k)

    @property
    def opponents(self) -> list[Any]:
        """The policy playing the opponent team in each match (None with ``"both"``)."""
        return [None if o is None else o.fn for o in self._match_opponents]

    @property
    def opponent_pool(self) -> list[Any]:
        """The pool set by :meth:`set_opponent_pool` (empty if none)."""
        return [o.fn for o in self._pool]

    def _draw_opponent(self, k: int) -> None:
        if self._pool:
            draw = self._pool_rngs[k].integers(len(self._pool))
            self._match_opponents[k] = self._pool[int(draw)]

    def _opponent_actions(self) -> list[np.ndarray] | None:
        """Actions ``(K, 6)`` of every match's opponent team from its last observations."""
        if not self.opponent_agents:
            return None
        obs = self._opp_obs
        n_opp = len(self.opponent_agents)
        out: list[np.ndarray] = [None] * self.n_matches  # type: ignore[list-item]
        groups: dict[int, list[int]] = {}
        for k, opp in enumerate(self._match_opponents):
            groups.setdefault(id(opp), []).append(k)
        for ks in groups.values():
            opp = self._match_opponents[ks[0]]
            if opp.per_agent and len(ks) > 1:
                rows = obs.reshape(-1, self._obs_size) if len(ks) == self.n_matches else (
                    obs[ks].reshape(-1, self._obs_size))
                acts = self._checked(opp, rows)
                for i, k in enumerate(ks):
                    out[k] = acts[i * n_opp:(i + 1) * n_opp]
            elif opp.batch is not None and len(ks) > 1:  # the scripted team, all at once
                acts = np.asarray(opp.batch(obs if len(ks) == self.n_matches else obs[ks]),
                                  dtype=np.float32)
                for i, k in enumerate(ks):
                    out[k] = acts[i]
            else:
                for k in ks:
                    out[k] = self._checked(opp, obs[k])
        return out

    @staticmethod
    def _checked(opp: _Opponent, rows: np.ndarray) -> np.ndarray:
        acts = np.asarray(opp.fn(rows), dtype=np.float32)
        if acts.shape != (len(rows), 6):
            raise ValueError(f"opponent {opp.label} returned actions of shape {acts.shape} for "
                             f"observations of shape {rows.shape}; expected ({len(rows)}, 6)")
        return acts

    # ------------------------------------------------------------------------------------
    # VecEnv API
    # ------------------------------------------------------------------------------------

    def seed(self, seed: int | None = None) -> Sequence[int | None]:
        """Seed the next :meth:`reset`: match ``k`` is reset with ``seed + first_match + k``
        and its opponent-pool draws with ``(seed, first_match + k)``. Returns each entry's
        match seed."""
        seed = base_seed(seed)
        self._seeds = [seed + self.first_match + k for k, _ in self.entry_agents]
        self._pool_seed = seed
        return list(self._seeds)

    def reset(self) -> np.ndarray:
        """Reset every match (seeded if :meth:`seed` was called since the last reset) and
        return the stacked observations ``(num_envs, obs_dim)`` float32."""
        L = self.agents_per_match
        self._seed_pools()
        out = np.empty((self.num_envs, self._obs_size), dtype=np.float32)
        opp = np.empty((self.n_matches, len(self.opponent_agents), self._obs_size),
                       dtype=np.float32)
        for k, m in enumerate(self.matches):
            options = self._options[k * L] or None
            obs, _ = m.reset(seed=self._seeds[k * L], options=options)
            self._draw_opponent(k)
            for j, a in enumerate(self.learner_agents):
                out[k * L + j] = obs[a]
            for j, a in enumerate(self.opponent_agents):
                opp[k, j] = obs[a]
            self._ep_lengths[k] = 0
        self._opp_obs = opp
        self._ep_returns[:] = 0.0
        self.reset_infos = [{} for _ in range(self.num_envs)]
        self._reset_seeds()
        self._reset_options()
        self._started = True
        return out

    def _seed_pools(self) -> None:
        """Seed every match's stream of opponent draws, if :meth:`seed` asked for it."""
        if self._pool_seed is not None:
            self._pool_rngs = [np.random.default_rng([self._pool_seed, self.first_match + k])
                               for k in range(self.n_matches)]
            self._pool_seed = None

    def step_async(self, actions: np.ndarray) -> None:
        """Store the actions ``(num_envs, 6)`` (one row per batch entry, in ``[-1, 1]``;
        values outside are clipped or rejected as the match's ``out_of_range_actions``
        says)."""
        a = np.asarray(actions, dtype=np.float32)
        if a.shape != (self.num_envs, 6):
            raise ValueError(f"actions must have shape ({self.num_envs}, 6) (one row of vx, "
                             f"vy, omega, kick, chip, dribble per batch entry), got {a.shape}")
        # Check every row before any match moves, so that a bad row leaves all matches as
        # they were (the matches check again, at no cost for valid actions).
        self._actions = soccer_env.validate_actions(a, self._entry_names, self.out_of_range_actions)

    def step_wait(self) -> VecEnvStepReturn:
        """Step every match once; finished matches are reset (see the module docstring)."""
        if not self._started:
            raise RuntimeError("call reset() before stepping a MatchVecEnv")
        if self._actions is None:
            raise RuntimeError("call step_async(actions) before step_wait()")
        actions, self._actions = self._actions, None
        L = self.agents_per_match
        learners, opponents = self.learner_agents, self.opponent_agents
        teams = self._teams_of_entries
        opp_actions = self._opponent_actions()
        obs_out = np.empty((self.num_envs, self._obs_size), dtype=np.float32)
        rewards = np.empty(self.num_envs, dtype=np.float32)
        dones = np.zeros(self.num_envs, dtype=bool)
        infos: list[dict[str, Any]] = [{} for _ in range(self.num_envs)]
        opp_obs = self._opp_obs
        ep_returns = self._ep_returns
        for k, m in enumerate(self.matches):
            base = k * L
            act = dict(zip(learners, actions[base:base + L]))
            if opp_actions is not None:
                act.update(zip(opponents, opp_actions[k]))
            obs, rew, term, trunc, minfo = m.step(act)
            self._ep_lengths[k] += 1
            a0 = learners[0]
            done_term, done_trunc = term[a0], trunc[a0]
            for j, a in enumerate(learners):
                i = base + j
                obs_out[i] = obs[a]
                rewards[i] = rew[a]
                info = minfo[a]
                infos[i] = {"score": info["score"], "event": info["event"],
                            "TimeLimit.truncated": done_trunc and not done_term}
            ep_returns[base:base + L] += rewards[base:base + L]
            if done_term or done_trunc:
                dones[base:base + L] = True
                score = m.score
                elapsed = round(time.time() - self._t_start, 6)
                length = self._ep_lengths[k]
                for j in range(L):
                    i = base + j
                    own = TEAMS.index(teams[j])
                    gf, ga = score[own], score[1 - own]
                    infos[i].update({
                        "terminal_observation": obs_out[i].copy(),
                        "episode": {"r": float(ep_returns[i]), "l": length, "t": elapsed},
                        "is_success": gf > ga, "goals_for": gf, "goals_against": ga})
                ep_returns[base:base + L] = 0.0
                self._ep_lengths[k] = 0
                obs, _ = m.reset()
                self._draw_opponent(k)
                for j, a in enumerate(learners):
                    obs_out[base + j] = obs[a]
            for j, a in enumerate(opponents):
                opp_obs[k, j] = obs[a]
        return obs_out, rewards, dones, infos

    def close(self) -> None:
        for m in self.matches:
            m.close()

    def _matches_of(self, indices: VecEnvIndices) -> list[int]:
        """Match index of each entry in ``indices``."""
        L = self.agents_per_match
        out = []
        for i in self._get_indices(indices):
            if not 0 <= int(i) < self.num_envs:
                raise IndexError(f"batch entry {i} out of range 0..{self.num_envs - 1}")
            out.append(int(i) // L)
        return out

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        """Attribute ``attr_name`` of the match of each entry."""
        return [getattr(self.matches[k], attr_name) for k in self._matches_of(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        """Set attribute ``attr_name`` of the matches of the entries."""
        for k in dict.fromkeys(self._matches_of(indices)):
            setattr(self.matches[k], attr_name, value)

    def env_method(self, method_name: str, *method_args: Any, indices: VecEnvIndices = None,
                   **method_kwargs: Any) -> list[Any]:
        """Call ``method_name`` once on the match of each entry; one result per entry."""
        ks = self._matches_of(indices)
        results = {k: getattr(self.matches[k], method_name)(*method_args, **method_kwargs)
                   for k in dict.fromkeys(ks)}
        return [results[k] for k in ks]

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper], indices: VecEnvIndices = None
                       ) -> list[bool]:
        """Always False: the matches are bare PettingZoo environments."""
        return [False for _ in self._matches_of(indices)]

    def get_images(self) -> Sequence[np.ndarray | None]:
        """One RGB frame per match (not per entry), if ``render_mode="rgb_array"``."""
        if self.render_mode != "rgb_array":
            warnings.warn(f"The render mode is {self.render_mode}, but this method assumes it "
                          "is `rgb_array` to obtain images.", stacklevel=2)
            return [None for _ in self.matches]
        return [m.render() for m in self.matches]
