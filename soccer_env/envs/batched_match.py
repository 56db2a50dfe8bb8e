"""Batched matches: :class:`MatchBatch`, ``n_matches`` SSL matches stepped as one batch in one
process.

The matches are those of :class:`~soccer_env.envs.match.SoccerParallelEnv` with the same
arguments: match ``k`` reset with seed ``s`` draws the kick-off and the formation a single
match reset with ``s`` draws, and steps through the same states up to the rounding of the
shared space (:mod:`soccer_env.sim.batch`; contacts amplify differences of 1e-12 m, so long
matches drift apart: tested over a few hundred steps). The physics is a
:class:`~soccer_env.sim.batch.WorldBatch`; actions to commands, rewards and shaping, the game
state, observations (:meth:`~soccer_env.observations.ObservationBuilder.build_batch`) and the
clocks run in numpy over the batch. What is left per match is what happens rarely: the ball
leaving the field (the referee's goal, free kick or kick-off, :mod:`soccer_env.sim.referee`)
and a match starting.

A finished match (its clock at ``match_duration``, or ``max_cycles`` steps) starts its next
match within the step that ends it, from its own generator as a single match's ``reset()``
does: :meth:`MatchBatch.step` returns the new match's first observation and the finished
match's last one in ``final_obs`` (stable-baselines3's convention; Gymnasium's
``SAME_STEP`` autoreset).

Perceived observations of SSL matches run as one batch
(:class:`~soccer_env.perception.batched.FilteredPerceptionBatch`: every field's cameras in one
array pass, every match's filters updated together, each match drawing from its own sensor
stream), with the same beliefs as a single match's, bit for bit (tested); so do the command
channels. Other configurations (raw observations, the two teams perceiving differently, latency
jitter, randomised sensor figures, belief features) keep each match's own perception and
channels, fed with its world's state after every batched physics step: the same beliefs, at
a single match's cost.

Humanoid and mixed matches run too: the humanoids' walk engines, heads and perception match by
match, so the batch saves their physics only.

Infos: :meth:`MatchBatch.infos` gives every match's per-agent infos as a single match's
``reset()`` and ``step()`` give them (``truth``, ``estimate``, ``reward_terms``, ``score``,
``event``, ``robot_state`` with humanoids; or its flat infos), and ``step(actions,
infos=True)`` the step's, those of a finished match taken before it starts over. They are built
match by match, on request only.

Scope: the geometric detector (not ``pixels``), no rendering.
:class:`NotBatchable` names what is refused.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from soccer_env.envs.batched import NotBatchable
from soccer_env.envs.flat_info import NO_EVENT, as_float64, flat_common, flat_match
from soccer_env.envs.match import MATCH_SHAPING, SoccerParallelEnv
from soccer_env.envs.senses import Senses
from soccer_env.envs.task_rules import match_rows, match_terms
from soccer_env.envs.vector_args import vector_seeds
from soccer_env.sim.batch import MAX_WORLDS, WorldBatch
from soccer_env.sim.commands import validate_actions
from soccer_env.sim.heads import aim_heads
from soccer_env.sim.referee import classify_exit, place_free_kick, place_kickoff
from soccer_env.state import Belief, WorldState, state_dict
from soccer_env.validation import check_int

__all__ = ["MatchBatch", "MatchStep"]


class MatchStep:
    """What :meth:`MatchBatch.step` returns (arrays over the batch, robots in the match's
    agent order: blue, then yellow).

    Attributes:
        obs: ``(M, N, obs_dim)`` float32 observations (of the new match, where one ended).
        rewards: ``(M, N)`` float64 rewards (the goal reward plus the shaping terms).
        terminated: ``(M,)`` bool: the match clock reached ``match_duration``.
        truncated: ``(M,)`` bool: ``max_cycles`` reached (and not terminated).
        events: ``(M,)`` object: the step's event of each match (``""`` for none,
            ``"goal"``, ``"touch"``, ``"goal_line"``, ``"over_bar"``).
        scores: ``(M, 2)`` int goals of blue and yellow (of the finished match where one
            ended).
        lengths: ``(M,)`` int steps of each match so far (of the finished match where one
            ended).
        final_obs: ``{k: (N, obs_dim)}`` the last observation of each match that ended.
        infos: with ``step(..., infos=True)``, each match's per-agent infos of the step, as
            its single match's ``step()`` returns them (of the finished match where one
            ended); else None.
    """

    __slots__ = ("obs", "rewards", "terminated", "truncated", "events", "scores", "lengths",
                 "final_obs", "infos")

    def __init__(self, obs: np.ndarray, rewards: np.ndarray, terminated: np.ndarray,
                 truncated: np.ndarray, events: np.ndarray, scores: np.ndarray,
                 lengths: np.ndarray, final_obs: dict[int, np.ndarray],
                 infos: list[dict[str, dict[str, Any]]] | None = None) -> None:
        self.obs, self.rewards = obs, rewards
        self.terminated, self.truncated = terminated, truncated
        self.events, self.scores, self.lengths = events, scores, lengths
        self.final_obs = final_obs
        self.infos = infos


class MatchBatch:
    """``n_matches`` matches of one configuration stepped as one batch (see the module
    docstring).

    Args:
        n_matches: matches (1..65536).
        **kwargs: :class:`~soccer_env.envs.match.SoccerParallelEnv`'s arguments (the
            geometric detector, no ``render_mode``).

    Attributes:
        probe: a single match of the same configuration, for its spaces, specs and
            observation layout (it is never stepped).
        batch: the :class:`~soccer_env.sim.batch.WorldBatch`.
        score: ``(M, 2)`` goals of blue and yellow in each running match.
        restart_team: ``(M,)`` the team whose restart waits for its first touch (-1: none).
        cycles: ``(M,)`` steps of each running match.
    """

    def __init__(self, n_matches: int = 16, **kwargs: Any) -> None:
        self.n_matches = check_int("n_matches", n_matches, 1, MAX_WORLDS)
        # A single match checks every argument with its own messages and gives the task's
        # pieces (spaces, observation layout, shaping).
        probe = SoccerParallelEnv(**kwargs)
        w0 = probe.world
        if any(c.detector == "pixels" for c in probe.perceptions):
            raise NotBatchable("the batched match does not run the pixels detector (it renders "
                               "every world's frames)")
        if probe.render_mode is not None:
            raise NotBatchable("the batched match does not render")
        if probe.game_rules is not None:
            raise NotBatchable("the batched match plays the simple referee only; the game flow "
                               "(game=...) runs in SoccerParallelEnv")
        self.probe = probe
        self.field, self.ball_spec = probe.field, probe.ball_spec
        self.match_duration, self.max_cycles = probe.match_duration, probe.max_cycles
        self.formation_jitter = probe.formation_jitter
        self.shaping = probe.shaping
        self.possible_agents = list(probe.possible_agents)
        self.n_robots = w0.n_robots
        self._teams = probe.world.teams  # (read-only int64, as the single match passes it)
        self._out_of_range = probe.out_of_range_actions
        self._slices = [(model, sl) for model, sl, _ in probe._teams_in_play]
        self.builder = probe.builder
        self.control_dt = w0.control_dt
        self.batch = WorldBatch(self.n_matches, self.field, self.ball_spec, w0.robot_specs,
                                w0.n_blue, w0.n_yellow, w0.control_dt,
                                w0.control_dt / w0.n_substeps)
        n = self.n_matches
        self._names = [f"{a} of match {k}" for k in range(n) for a in self.possible_agents]
        self._rngs: list[np.random.Generator] = [np.random.default_rng(k) for k in range(n)]
        self.score = np.zeros((n, 2), dtype=np.int64)
        self.restart_team = np.full(n, -1, dtype=np.int64)
        self.cycles = np.zeros(n, dtype=np.int64)
        self._started = False
        self._world_rngs: list[np.random.Generator | None] = [None] * n
        # Perception, command channels (actuation latency and command loss, which apply in
        # truth mode too) and head control beside the physics.
        self._senses = Senses(probe, self.batch, n)
        self._builders = probe._builders
        # What the infos of the latest step are made of: each match's event, scoring team
        # (-1: none) and ball displacement along x [m]; ``_fresh``: no step since the match
        # started (its reward terms are zero).
        self._flat = probe.info_mode == "flat"
        self._events = np.full(n, NO_EVENT, dtype=object)
        self._scorers = np.full(n, -1, dtype=np.int64)
        self._dx = np.zeros(n)
        self._fresh = np.ones(n, dtype=bool)

    # ------------------------------------------------------------------------------------
    # Matches
    # ------------------------------------------------------------------------------------

    def _place(self, k: int) -> tuple[np.ndarray, int]:
        """Match ``k``'s kick-off formation and kick-off team, drawn from its generator as
        :meth:`SoccerParallelEnv._place` and ``_streams`` draw them, so that the generator
        moves on exactly as a single match's does."""
        rng = self._rngs[k]
        kickoff = int(rng.integers(2))
        poses = place_kickoff(self.batch.worlds[k], kickoff, rng, self.formation_jitter)
        world = rng.integers(2**63)  # the world's stream (the humanoids' random events)
        sensors = rng.integers(2**63)  # the sensors' stream
        if self.batch.humanoid_indices:
            self._world_rngs[k] = np.random.default_rng(world)
        if not self._senses.plain:
            self._senses.sensor_rngs[k] = np.random.default_rng(sensors)
        return poses, kickoff

    def _begin(self, k: int, kickoff: int) -> None:
        """Match ``k``'s start after its world is placed: the game state, then (as
        ``SoccerCore._start``) its perception and command channels."""
        world = self.batch.worlds[k]
        if self.batch.humanoid_indices:  # heads turned to the ball, no glance under way
            aim_heads(world)
            if self._senses.heads[k] is not None:
                self._senses.heads[k].reset()
        self.score[k] = 0
        self.restart_team[k] = kickoff
        self.cycles[k] = 0
        self._fresh[k] = True
        self._senses.start(k)

    def reset(self, seed: int | Sequence[int | None] | None = None) -> np.ndarray:
        """Start every match; returns the observations ``(M, N, obs_dim)``.

        ``seed``: an int seeds match ``k`` with ``seed + k``; a sequence gives each match its
        own (None keeps that match's generator going); None keeps every generator going (or
        seeds them from the OS's entropy before the first reset).
        """
        n = self.n_matches
        seeds = vector_seeds(seed, n)
        for k, s in enumerate(seeds):
            if s is not None or not self._started:
                self._rngs[k] = np.random.default_rng(s)
        placed = [self._place(k) for k in range(n)]
        self.batch.reset(np.stack([p for p, _ in placed]), np.zeros((n, 2)),
                         self._world_rngs if self.batch.humanoid_indices else None)
        for k, (_, kickoff) in enumerate(placed):
            self._begin(k, kickoff)
        self._senses.flush()
        self._started = True
        return self._observe()

    # ------------------------------------------------------------------------------------
    # Stepping
    # ------------------------------------------------------------------------------------

    def step(self, actions: np.ndarray, infos: bool = False) -> MatchStep:
        """Step every match with ``actions`` ``(M, N, 6)`` (every robot's action in
        ``[-1, 1]``; outside values clipped or refused as ``out_of_range_actions`` says,
        non-finite ones refused, naming the robot and the match, before any match moves).
        Matches that end start their next match in this step (see the module docstring).
        ``infos``: add the step's per-agent infos (:attr:`MatchStep.infos`)."""
        if not self._started:
            raise RuntimeError("call MatchBatch.reset() before step()")
        n, N = self.n_matches, self.n_robots
        try:
            act = np.asarray(actions, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError(f"actions must be ({n}, {N}, 6) numbers, got {actions!r}") from None
        if act.shape != (n, N, 6):
            raise ValueError(f"actions must have shape ({n}, {N}, 6) (every robot of every "
                             f"match: vx, vy, omega, kick, chip, dribble), got {act.shape}")
        act = validate_actions(act.reshape(n * N, 6), self._names,
                               self._out_of_range).reshape(n, N, 6)
        batch = self.batch
        state = batch.state
        progress_on = bool(self.shaping["ball_progress"])
        ball_x_before = state[:, 0, 0].copy() if progress_on else None
        if len(self._slices) == 1:
            commands = self._slices[0][0].commands(act.reshape(n * N, 6)).reshape(n, N, 6)
        else:
            commands = np.concatenate(
                [m.commands(act[:, sl].reshape(-1, 6)).reshape(n, -1, 6)
                 for m, sl in self._slices], axis=1)
        commands = self._senses.send(commands)
        batch.step(commands)

        # The referee.
        self.cycles += 1
        self.restart_team[batch.touched().any(axis=1)] = -1
        events = np.full(n, NO_EVENT, dtype=object)
        scorer = np.full(n, -1, dtype=np.int64)
        for k, exit_ in batch.exits():
            world = batch.worlds[k]
            kind = classify_exit(exit_, self.field, self.ball_spec)
            events[k] = kind.kind
            if kind.kind == "goal":
                scorer[k] = kind.scorer
                self.score[k, kind.scorer] += 1
                self.restart_team[k] = 1 - kind.scorer
                world.place_all(place_kickoff(world, 1 - kind.scorer, self._rngs[k],
                                              self.formation_jitter))
            else:
                self.restart_team[k] = place_free_kick(world, exit_, kind)
            world.clear_exit()

        self._senses.update(np.arange(n))
        rewards = self._rewards(scorer, events, ball_x_before)
        self._events, self._scorers = events, scorer
        self._fresh[:] = False
        obs = self._observe()
        terminated = batch.times >= self.match_duration - 1e-9
        truncated = np.zeros(n, dtype=bool)
        if self.max_cycles is not None:
            truncated = ~terminated & (self.cycles >= self.max_cycles)
        scores, lengths = self.score.copy(), self.cycles.copy()
        final_obs: dict[int, np.ndarray] = {}
        ended = np.nonzero(terminated | truncated)[0].tolist()
        step_infos = [self._match_infos(k) if k in ended else {} for k in range(n)] \
            if infos else None
        if ended:
            for k in ended:
                final_obs[k] = obs[k].copy()
                poses, kickoff = self._place(k)
                batch.restart(k, poses, (0.0, 0.0), self._world_rngs[k])
                self._begin(k, kickoff)
            self._senses.flush()
            obs = self._observe()
        if step_infos is not None:
            for k in range(n):
                if k not in ended:
                    step_infos[k] = self._match_infos(k)
        return MatchStep(obs, rewards, terminated, truncated, events, scores, lengths, final_obs,
                         step_infos)

    def _rewards(self, scorer: np.ndarray, events: np.ndarray,
                 ball_x_before: np.ndarray | None) -> np.ndarray:
        """``(M, N)`` rewards: the single match's rule over the batch
        (:func:`~soccer_env.envs.task_rules.match_rows`)."""
        sc = self.shaping
        state = self.batch.state
        dx = state[:, 0, 0] - ball_x_before if ball_x_before is not None else np.zeros(len(state))
        self._dx = dx
        return match_rows(state, self._teams, scorer, dx, events == NO_EVENT,
                          (float(sc["ball_progress"]), float(sc["ball_distance"])),
                          self.control_dt)

    # ------------------------------------------------------------------------------------
    # Infos
    # ------------------------------------------------------------------------------------

    def infos(self) -> list[dict[str, dict[str, Any]]]:
        """Every match's per-agent infos now, as its single match gives them: after
        :meth:`reset` (or a match's restart) its ``reset()`` infos, after a step its
        ``step()`` infos (full or flat, as ``info_mode`` says)."""
        return [self._match_infos(k) for k in range(self.n_matches)]

    def _match_infos(self, k: int) -> dict[str, dict[str, Any]]:
        """Match ``k``'s per-agent infos (``SoccerParallelEnv._infos``' for its state, the
        latest step's reward terms and event, its score and beliefs)."""
        world = self.batch.worlds[k]
        state = world.snapshot()
        agents = self.possible_agents
        event = NO_EVENT if self._fresh[k] else self._events[k]
        terms = self._terms(k, state)
        beliefs = self._beliefs(k, state)
        score = [int(v) for v in self.score[k].tolist()]
        if self._flat:
            game = flat_match(event, score, None)
            walk = world.walk
            out = {}
            for i, a in enumerate(agents):
                fallen = walk is not None and i in walk.indices and bool(
                    walk.fallen[walk.indices.index(i)])
                info = flat_common(state, beliefs[i], i, fallen, terms[i])
                info.update(game)
                out[a] = as_float64(info)
            return out
        truth = state.truth_dict()
        estimates: dict[int, dict[str, Any]] = {}
        robot_state = world.humanoid_state() if world.walk is not None else None
        out = {}
        for i, a in enumerate(agents):
            b = beliefs[i]
            if id(b) not in estimates:
                estimates[id(b)] = truth if b is state else state_dict(b.time, b.ball,
                                                                       b.robots, state.names)
            out[a] = {"truth": truth, "estimate": estimates[id(b)], "reward_terms": terms[i],
                      "score": {"blue": score[0], "yellow": score[1]}, "event": event}
            if robot_state is not None:
                out[a]["robot_state"] = robot_state
        return out

    def _terms(self, k: int, state: WorldState) -> list[dict[str, float]]:
        """Match ``k``'s reward terms of every robot at its latest step (zeros before its
        first), as the single match names them."""
        if self._fresh[k]:
            zero = dict.fromkeys(("goal", *MATCH_SHAPING), 0.0)
            return [zero] * self.n_robots
        sc = self.shaping
        goal, progress, distance = match_terms(
            (float(state.ball[0]), float(state.ball[1])), state.robots, state.teams,
            int(self._scorers[k]), float(self._dx[k]), self._events[k] == NO_EVENT,
            (float(sc["ball_progress"]), float(sc["ball_distance"])),
            self.control_dt).T.tolist()
        return [{"goal": g, "ball_progress": p, "ball_distance": d}
                for g, p, d in zip(goal, progress, distance)]

    def _beliefs(self, k: int, state: WorldState) -> list[Any]:
        """Every robot's present belief in match ``k`` (``state`` itself in truth mode)."""
        senses = self._senses
        if senses.truth:
            return [state] * self.n_robots
        if senses.vision is not None:  # one belief for every robot of the match
            times, ball, robots = senses.vision.present()
            return [Belief(float(times[k]), ball[k], robots[k])] * self.n_robots
        perception = senses.perceptions[k]
        return [perception.current(i) for i in range(self.n_robots)]

    def _observe(self) -> np.ndarray:
        """``(M, N, obs_dim)`` observations with each team's game block
        (:data:`~soccer_env.envs.match.GAME_NAMES`)."""
        n = self.n_matches
        time_left = np.maximum(0.0, 1.0 - self.batch.times / self.match_duration)
        restart = self.restart_team
        flag = np.where(restart < 0, 0.0, np.where(restart == 0, 1.0, -1.0))
        blue, yellow = self.score[:, 0].astype(np.float64), self.score[:, 1].astype(np.float64)
        per_team = np.empty((n, 2, 4))
        per_team[:, 0] = np.stack([time_left, blue, yellow, flag], axis=1)
        per_team[:, 1] = np.stack([time_left, yellow, blue, -flag], axis=1)
        game = per_team[:, self._teams]
        arrays = self._senses.arrays()  # the truth, or one belief per match for its robots
        if arrays is not None:
            return self.builder.build_batch(arrays[1], arrays[0], game)
        # Each match's beliefs, through the builders a single match uses.
        out = np.empty((n, self.n_robots, self.builder.space().shape[0]), dtype=np.float32)
        for k, perception in enumerate(self._senses.perceptions):
            for group, builder in self._builders:
                out[k, group] = builder.build(perception.belief(group[0]), game[k, group])
        return out

    @property
    def times(self) -> np.ndarray:
        """``(M,)`` every running match's clock [s]."""
        return self.batch.times

    def close(self) -> None:
        self.batch.close()

