"""Batched single-agent tasks: :class:`GoalkeeperVectorEnv` and :class:`ShootoutVectorEnv`,
``num_envs`` episodes stepped as one batch in one process (:class:`BatchedTask` holds what
they share).

``gymnasium.make_vec("soccer_env/Goalkeeper-v0", num_envs=N)`` and
``gymnasium.make_vec("soccer_env/Shootout-v0", num_envs=N)`` return them (the tasks'
``vector_entry_point``, :func:`make_vector` and :func:`make_shootout_vector`; for arguments the
batch does not run yet, a ``SyncVectorEnv`` of single environments, with a warning). The
physics is a :class:`~soccer_env.sim.batch.WorldBatch` (the worlds in a few shared pymunk
spaces, one Chipmunk step per space and substep), and everything else runs in numpy over the
batch: actions to commands, the Goalkeeper's invisible attacker and the Shootout's scripted
keeper, the outcome, rewards and shaping, observations
(:meth:`~soccer_env.observations.ObservationBuilder.build_batch`) and the time limit. What is
left per environment is what happens rarely: a shot fired, a ball leaving the field, an
episode starting.

Episodes are those of ``gymnasium.make(id, ...)``: environment ``k`` reset with seed ``s + k``
draws the same start, and steps through the same states up to the rounding of the shared space
(each world's coordinates are offset by its patch of the space: differences of about 1e-12 m,
which contacts can amplify; tested). Finished environments reset at the next step
(Gymnasium's ``NEXT_STEP`` autoreset: that step's action is ignored and it returns the new
episode's first observation with reward 0; see below for the other modes), drawing their next
episode from their own generator as a single environment's ``reset()`` does.

Perceived observations of SSL robots run as one batch
(:class:`~soccer_env.perception.batched.FilteredPerceptionBatch`): the overhead cameras of
every field capture in one array pass, and the robot and ball filters of every environment
update together, drawing from each environment's own sensor stream exactly as a single
environment's perception does, so that the beliefs are the single environment's bit for bit
(tested). The command channels (actuation latency, command loss) of every environment run as
one batch too. Configurations the batched perception does not take
(:func:`~soccer_env.perception.batched.batch_refusal`: raw observations, latency jitter,
randomised sensor figures, belief features, the least-squares ball predictor, humanoids) keep
each environment's own perception and channels, fed with its world's state after every
batched physics step: the same beliefs, at about the single environment's cost.

Humanoid keepers (with their team-mates) and attackers run in the batch too: their walk
engines, heads and perception world by world, so a humanoid batch saves only the physics.

Scope: the geometric detector (not ``pixels``), no rendering. Other arguments are the tasks'.

The batch answers as Gymnasium's ``SyncVectorEnv`` of the same single environments
(``vectorization_mode="sync"``) does, in every autoreset mode (``autoreset_mode``:
``NEXT_STEP``, the default; ``SAME_STEP``, which stable-baselines3 expects and
:class:`agents.vec.batched.BatchedVecEnv` adapts, the finished environments' last observations
in ``info["final_obs"]`` and their infos in ``info["final_info"]``; ``DISABLED``, where the
caller resets finished environments with ``reset(options={"reset_mask": mask})``), with the
same seeding (an int ``s`` seeds environment ``k`` with ``s + k``, a list each its own, None
keeps the generators going) and the same ``reset_mask`` (only those environments reset). The
time limit truncates as Gymnasium's ``TimeLimit`` does, terminated or not.

Infos: the single environments' keys, each an array over the batch with its ``_key`` mask, as
``SyncVectorEnv`` aggregates them (:mod:`soccer_env.envs.batched_infos`): ``truth``,
``estimate``, ``reward_terms``, ``outcome`` (``""`` while an episode goes on), the task's own
entries (the Goalkeeper's ``shot``, ``shot_fired``, ``keeper_touched``; the Shootout's
``start``, ``keeper_touched``), ``robot_state`` with humanoids and ``is_success`` where an
episode terminated; with ``info_mode="flat"`` the flat keys of
:mod:`soccer_env.envs.flat_info`. They are built in numpy over the batch from the batch's
state, the batched perception's present beliefs and the rule kernels' reward terms.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.utils import seeding
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from soccer_env.envs.batched_infos import BatchInfos, EpisodeTable, InfoParts
from soccer_env.envs.goalkeeper import GoalkeeperEnv, fire_shot, place_episode
from soccer_env.envs.registration import GOALKEEPER_ID, GYMNASIUM, SHOOTOUT_ID
from soccer_env.envs.senses import Senses
from soccer_env.envs.shootout import ShootoutEnv
from soccer_env.envs.task_rules import (
    EXIT_GOAL,
    EXIT_OUT,
    GOALKEEPER_OUTCOMES,
    SHOOTOUT_OUTCOMES,
    goal_distance,
    goalkeeper_rows,
    shootout_rows,
)
from soccer_env.envs.vector_args import (
    NotBatchable,
    check_autoreset_mode,
    reset_mask,
    vector_or_sync,
    vector_seeds,
)
from soccer_env.sim.batch import MAX_WORLDS, WorldBatch
from soccer_env.sim.commands import validate_actions
from soccer_env.sim.heads import aim_heads
from soccer_env.sim.referee import classify_exit
from soccer_env.validation import check_int

__all__ = ["BatchedTask", "GoalkeeperVectorEnv", "ShootoutVectorEnv", "NotBatchable",
           "make_vector", "make_shootout_vector"]

#: Goalkeeper-v0's and Shootout-v0's time limits (their registrations' ``max_episode_steps``).
DEFAULT_MAX_STEPS = GYMNASIUM[GOALKEEPER_ID].max_episode_steps
SHOOTOUT_MAX_STEPS = GYMNASIUM[SHOOTOUT_ID].max_episode_steps


def make_vector(num_envs: int = 16, max_episode_steps: int | None = DEFAULT_MAX_STEPS,
                **kwargs: Any) -> VectorEnv:
    """Goalkeeper-v0's ``vector_entry_point``: a :class:`GoalkeeperVectorEnv`, or, for
    arguments the batch does not run yet (the pixels detector, rendering), Gymnasium's
    ``SyncVectorEnv`` of single environments with a warning saying why, so that
    ``gymnasium.make_vec(id, num_envs=N)`` works for every configuration."""
    return vector_or_sync(GoalkeeperVectorEnv, GOALKEEPER_ID, num_envs, max_episode_steps,
                          kwargs)


class BatchedTask(VectorEnv):
    """``num_envs`` episodes of a single-agent task stepped as one batch: what the batched
    tasks share (checks, seeding, the step's skeleton, autoreset, infos). A task implements
    :meth:`_setup`, :meth:`_place`, :meth:`_begin`, :meth:`_commands`, :meth:`_judge`,
    :meth:`_success` and :meth:`_task_entries`.

    Args:
        num_envs: environments (1..65536).
        max_episode_steps: the time limit (truncation), as the registration's.
        autoreset_mode: Gymnasium's ``NEXT_STEP`` (the default: a finished environment
            resets at the next step, whose action it ignores), ``SAME_STEP`` (it resets in
            the step that ends its episode, which returns the new episode's first observation,
            the last one in ``info["final_obs"]`` and the episode's infos in
            ``info["final_info"]``; what stable-baselines3 expects) or ``DISABLED`` (finished
            environments wait for ``reset(options={"reset_mask": mask})``; stepping one before
            raises ``RuntimeError``).
        **kwargs: the task's arguments (the geometric detector, no ``render_mode``).
    """

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}
    #: The single environment the batch plays and its registered id.
    TASK: type = GoalkeeperEnv
    TASK_ID = GOALKEEPER_ID
    #: The task's outcome names by rule code (:mod:`~soccer_env.envs.task_rules`).
    OUTCOMES: tuple[str | None, ...] = GOALKEEPER_OUTCOMES

    def __init__(self, num_envs: int = 16, max_episode_steps: int | None = DEFAULT_MAX_STEPS,
                 autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP,
                 **kwargs: Any) -> None:
        self.num_envs = check_int("num_envs", num_envs, 1, MAX_WORLDS)
        self.autoreset_mode = check_autoreset_mode(autoreset_mode)
        self._same_step = self.autoreset_mode == AutoresetMode.SAME_STEP
        self.max_episode_steps = (None if max_episode_steps is None else
                                  check_int("max_episode_steps", max_episode_steps, 1, 10**9))
        # A single environment checks every argument with its own messages and gives the
        # task's pieces (shaping, spaces, observation layout).
        probe = self.TASK(**kwargs)
        _check_batchable(probe, self.TASK_ID)
        self.probe = probe
        self.field, self.ball_spec = probe.field, probe.ball_spec
        self._robot = probe.robot_spec
        self.shaping = probe.shaping
        self.builder = probe.builder
        self._model = probe.robot_model
        self._names = [f"{probe._learner[0]} of environment {k}" for k in range(self.num_envs)]
        self._out_of_range = probe.out_of_range_actions
        w0 = probe.world
        self.batch = WorldBatch(self.num_envs, self.field, self.ball_spec, w0.robot_specs,
                                w0.n_blue, w0.n_yellow, w0.control_dt,
                                w0.control_dt / w0.n_substeps)
        self.control_dt = w0.control_dt
        self.single_observation_space = probe.observation_space
        self.single_action_space = probe.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.metadata = {**self.TASK.metadata, **type(self).metadata,
                         "autoreset_mode": self.autoreset_mode}
        self.render_mode = None
        self.spec = None
        n = self.num_envs
        self._rngs: list[np.random.Generator] = [np.random.default_rng(k) for k in range(n)]
        self._steps = np.zeros(n, dtype=np.int64)
        self._needs_reset = np.zeros(n, dtype=bool)
        self._started = False
        self._world_rngs: list[np.random.Generator | None] = [None] * n
        # Perception, command channels (actuation latency and command loss, which apply in
        # truth mode too) and head control beside the physics.
        self._senses = Senses(probe, self.batch, n)
        self._flying = np.zeros(n, dtype=bool)  # the balls in the air (see _airborne)
        #: Flat infos (``info_mode="flat"``).
        self.flat = probe.info_mode == "flat"
        terms = tuple(probe._zero_terms())
        self._infos = BatchInfos(n, w0.names, terms, self.OUTCOMES, self.flat, self._add_info)
        self._no_terms = np.zeros((n, len(terms)))
        self._setup()

    def _streams(self, k: int, sensors_first: bool) -> None:
        """Draw environment ``k``'s two stream seeds (the world's and the sensors', in the
        task's order) from its generator, as the single environment's ``_streams`` does; keep
        the sensors' generator when the environment perceives."""
        rng = self._rngs[k]
        first, second = rng.integers(2**63), rng.integers(2**63)
        sensors, world = (first, second) if sensors_first else (second, first)
        if self.batch.humanoid_indices:  # their falls, kick directions and odometry
            self._world_rngs[k] = np.random.default_rng(world)
        if not self._senses.plain:
            self._senses.sensor_rngs[k] = np.random.default_rng(sensors)

    # ------------------------------------------------------------------------------------
    # The task's hooks
    # ------------------------------------------------------------------------------------

    def _setup(self) -> None:
        """The task's own arrays over the batch (after the common attributes)."""
        raise NotImplementedError

    def _place(self, k: int) -> tuple[np.ndarray, tuple[float, float], Any]:
        """Environment ``k``'s next episode from its generator: robot poses, ball position and
        the task's own draw, drawn as the single environment's ``_place`` and ``_streams``
        draw them, so that the generator moves on exactly as a single environment's does."""
        raise NotImplementedError

    def _begin(self, k: int, drawn: Any) -> None:
        """Environment ``k``'s task state at the start of an episode (its world placed)."""
        raise NotImplementedError

    def _commands(self, act: np.ndarray) -> np.ndarray:
        """Every robot's commands ``(n, N, 6)`` from the learners' validated actions
        ``(n, 6)`` (the task adds its other robots' actions)."""
        raise NotImplementedError

    def _judge(self, act: np.ndarray, live: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """After the physics: every environment's outcome code (0 while the episode goes on;
        :attr:`OUTCOMES` names them), reward and reward terms ``(n, T)`` (the single
        environment's, in its order); ``live`` marks the environments that played this step
        (the others restart: code, reward and terms 0)."""
        raise NotImplementedError

    def _success(self, codes: np.ndarray) -> np.ndarray:
        """Whether each (terminal) outcome code is a success."""
        raise NotImplementedError

    def _task_entries(self) -> dict[str, Any]:
        """The task's own info entries as columns over the batch (dicts of them for the
        single environment's dicts), in the single environment's order: its full entries, or
        its flat ones (float64) with :attr:`flat`."""
        raise NotImplementedError

    # ------------------------------------------------------------------------------------
    # Episodes
    # ------------------------------------------------------------------------------------

    def _restart(self, k: int) -> None:
        poses, ball_xy, drawn = self._place(k)
        self.batch.restart(k, poses, ball_xy, self._world_rngs[k])
        self._aim(k)
        self._steps[k] = 0
        self._begin(k, drawn)
        self._senses.start(k)

    def _aim(self, k: int) -> None:
        """Environment ``k``'s humanoids' heads at the start of an episode (as
        ``SoccerCore._start``: turned to the ball, no glance under way)."""
        if self.batch.humanoid_indices:
            aim_heads(self.batch.worlds[k])
            if self._senses.heads[k] is not None:
                self._senses.heads[k].reset()

    def reset(self, *, seed: int | list[int | None] | None = None,
              options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict[str, Any]]:
        """Reset every environment, or with ``options={"reset_mask": mask}`` (``(n,)`` bool)
        those of the mask only: with ``seed`` an int, environment ``k`` is seeded with
        ``seed + k`` (a list gives each its own; None keeps the generators going, or seeds
        them from the OS's entropy before the first reset). The first reset resets every
        environment. Returns the observations and the reset environments' infos."""
        n = self.num_envs
        seeds = vector_seeds(seed, n)
        rows = reset_mask(options, n, type(self).__name__)
        if rows is not None and not self._started:
            raise RuntimeError("the first reset() starts every environment: call it without "
                               "a reset_mask")
        chosen = range(n) if rows is None else np.nonzero(rows)[0].tolist()
        for k in chosen:
            if seeds[k] is not None or not self._started:
                self._rngs[k] = seeding.np_random(seeds[k])[0]
        if rows is None:
            placed = [self._place(k) for k in range(n)]
            self.batch.reset(np.stack([p for p, _, _ in placed]),
                             np.array([b for _, b, _ in placed], dtype=np.float64),
                             self._world_rngs if self.batch.humanoid_indices else None)
            self._steps[:] = 0
            for k, (_, _, drawn) in enumerate(placed):
                self._aim(k)
                self._begin(k, drawn)
                self._senses.start(k)
            self._needs_reset[:] = False
        else:
            for k in chosen:
                self._restart(k)
            self._needs_reset[rows] = False
        self._senses.flush()
        self._started = True
        self._airborne()
        codes = np.zeros(n, dtype=np.int64)
        infos = self._infos.build(self._parts(codes, self._no_terms, codes != 0), rows)
        return self._observe(), infos

    # ------------------------------------------------------------------------------------
    # Stepping
    # ------------------------------------------------------------------------------------

    def _actions(self, actions: Any) -> np.ndarray:
        """The learners' actions ``(n, 6)`` as float64, shape checked."""
        n = self.num_envs
        try:
            act = np.array(actions, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError(f"actions must be ({n}, 6) numbers, got {actions!r}") from None
        if act.shape != (n, 6):
            names = ", ".join(self._model.action_names)
            raise ValueError(f"actions must have shape ({n}, 6) ({names}), got {act.shape}")
        return act

    def step(self, actions: np.ndarray):
        if not self._started:
            raise RuntimeError("call reset() before step()")
        n = self.num_envs
        act = self._actions(actions)
        restarting = self._needs_reset.copy()
        if self.autoreset_mode == AutoresetMode.DISABLED and restarting.any():
            raise RuntimeError(f"environments {np.nonzero(restarting)[0].tolist()} have ended: "
                               "with autoreset_mode DISABLED, reset them with reset(options="
                               "{'reset_mask': mask}) before stepping")
        live = ~restarting
        act[restarting] = 0.0  # a finished environment's action is ignored
        act = validate_actions(act, self._names, self._out_of_range)
        commands = self._commands(act)
        commands = self._senses.send(commands)
        self.batch.step(commands)
        self._steps += 1
        codes, rewards, terms = self._judge(act, live)
        # (The batched perception advances with the episodes that start at the end of the step,
        # unless the final observations need it before.)
        self._senses.update(np.nonzero(live)[0], defer=not self._same_step)
        terminated = codes != 0
        truncated = np.zeros(n, dtype=bool)
        if self.max_episode_steps is not None:  # (Gymnasium's TimeLimit: terminated or not)
            truncated = live & (self._steps >= self.max_episode_steps)
        ended = terminated | truncated
        infos: dict[str, Any] = {}
        if self._same_step and ended.any():
            # The finished environments start their next episode in this very step.
            last = self._observe()
            final_obs = np.full(n, None, dtype=object)
            for k in np.nonzero(ended)[0].tolist():
                final_obs[k] = last[k]
            infos = {"final_obs": final_obs, "_final_obs": ended.copy(),
                     "final_info": self._infos.build(self._parts(codes, terms, terminated),
                                                     ended),
                     "_final_info": ended.copy()}
            restarting = ended
            codes = np.where(ended, 0, codes)
            terms[ended] = 0.0
            ended = np.zeros(n, dtype=bool)
        # The environments that finished at the previous step (at this one, with SAME_STEP)
        # start their next episode now.
        for k in np.nonzero(restarting)[0].tolist():
            self._restart(k)
        self._senses.flush()
        if restarting.any() and not self._same_step:
            rewards[restarting] = 0.0
        self._needs_reset = ended
        infos.update(self._infos.build(self._parts(codes, terms, terminated & ~restarting)))
        return (self._observe(), rewards.astype(np.float64), terminated, truncated, infos)

    def _parts(self, codes: np.ndarray, terms: np.ndarray, terminated: np.ndarray
               ) -> InfoParts:
        """What the infos are made of now (:class:`~soccer_env.envs.batched_infos.
        InfoParts`): the batch's state, robot 0's present beliefs, the task's entries, and
        the step's outcome ``codes``, reward ``terms`` and ``terminated`` episodes."""
        batch = self.batch
        state = batch.state
        worlds = batch.worlds
        ball = state[:, 0].copy()
        # The ball's height: 0 but in flight (where it was in the air after the physics; an
        # episode started since has its ball on the carpet).
        ball[:, 2] = 0.0
        if self._flying.any():
            flying = np.nonzero(self._flying)[0].tolist()
            ball[flying, 2] = [worlds[k].ball_height for k in flying]
        robot_state, fallen = None, np.zeros(self.num_envs, dtype=bool)
        if batch.humanoid_indices and not self.flat:
            robot_state = [w.humanoid_state() for w in worlds]
        elif 0 in batch.humanoid_indices:  # (robot 0 lies or gets up)
            fallen[:] = [w.walk.fallen[w.walk.indices.index(0)] for w in worlds]
        return InfoParts(batch.times, ball, state[:, 1:], self._senses.present(), terms, codes,
                         self._success(codes), terminated, self._task_entries(), robot_state,
                         fallen)

    def _exits(self, scored: int) -> np.ndarray:
        """``(n,)`` exit codes of the last step (:mod:`~soccer_env.envs.task_rules`):
        ``EXIT_GOAL`` where the ball went into the goal at the end ``scored`` (+1: ``x >
        0``), ``EXIT_OUT`` where it left the field otherwise, ``NO_EXIT`` elsewhere."""
        codes = np.zeros(self.num_envs, dtype=np.int64)
        for k, ex in self.batch.exits():
            kind = classify_exit(ex, self.field, self.ball_spec)
            codes[k] = EXIT_GOAL if kind.kind == "goal" and kind.end == scored else EXIT_OUT
        return codes

    def _airborne(self) -> np.ndarray:
        """``(n,)`` whether each world's ball is in the air (kept for :meth:`_parts`)."""
        self._flying = np.array([w.ball_airborne for w in self.batch.worlds])
        return self._flying

    def _observe(self) -> np.ndarray:
        arrays = self._senses.arrays()
        if arrays is not None:  # (the builder lays out the robots it was made for: the first)
            ball, robots = arrays
            return self.builder.build_batch(robots[:, :self.builder.n_robots], ball)[:, 0]
        build = self.builder.build
        return np.stack([build(seen)[0] for seen in self._senses.seen])

    def close(self, **kwargs: Any) -> None:
        self.batch.close()
        self.closed = True


def _check_batchable(probe: Any, task_id: str) -> None:
    """Raise :class:`NotBatchable` for what the batched tasks do not run yet."""
    name = task_id.split("/")[-1].rsplit("-", 1)[0]  # "Goalkeeper"
    if probe.perception.detector == "pixels":
        raise NotBatchable(f"the batched {name} does not run the pixels detector (it renders "
                           "every world's frames); use vectorization_mode='sync'")
    if probe.render_mode is not None:
        raise NotBatchable(f"the batched {name} does not render; use "
                           "vectorization_mode='sync' for videos")


class GoalkeeperVectorEnv(BatchedTask):
    """``num_envs`` Goalkeeper-v0 episodes stepped as one batch (see the module docstring and
    :class:`BatchedTask` for the arguments; ``**kwargs`` are
    :class:`~soccer_env.envs.goalkeeper.GoalkeeperEnv`'s)."""

    TASK = GoalkeeperEnv
    TASK_ID = GOALKEEPER_ID

    def _setup(self) -> None:
        probe = self.probe
        self.shots = probe.shots
        self._weights, self._geometry = probe._weights, probe._geometry
        n = self.num_envs
        self._shots: list[dict[str, Any]] = [{}] * n
        self._shot_table = EpisodeTable(n)  # (the infos' "shot")
        self._delay = np.zeros(n)
        self._fired = np.zeros(n, dtype=bool)
        self._touched = np.zeros(n, dtype=bool)

    def _place(self, k: int) -> tuple[np.ndarray, tuple[float, float], dict[str, Any]]:
        rng = self._rngs[k]
        placed = place_episode(rng, self.field, self._robot, self.ball_spec, self.shots,
                               self.probe.n_mates)
        self._streams(k, sensors_first=True)  # (GoalkeeperEnv._streams' order)
        return placed

    def _begin(self, k: int, shot: dict[str, Any]) -> None:
        self._shots[k] = shot
        self._shot_table.set(k, shot)
        self._delay[k] = shot["delay"]
        self._fired[k] = False
        self._touched[k] = False
        if shot["delay"] <= 0.0:
            self._fire(k)

    def _fire(self, k: int) -> None:
        """The invisible attacker's kick in environment ``k`` (as GoalkeeperEnv._fire)."""
        fire_shot(self.batch.worlds[k], self._shots[k], self._robot)
        self._fired[k] = True

    def _commands(self, act: np.ndarray) -> np.ndarray:
        n, N = self.num_envs, self.batch.n_robots
        if N == 1:
            return self._model.commands(act)[:, None, :]
        full = np.zeros((n, N, 6))  # the team-mates stand and watch (zero actions)
        full[:, 0] = act
        return self._model.commands(full.reshape(-1, 6)).reshape(n, N, 6)

    def _judge(self, act: np.ndarray, live: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        batch = self.batch
        # The attacker's shots due this step, and the keeper's touches.
        due = live & ~self._fired & (batch.times >= self._delay - 1e-9)
        for k in np.nonzero(due)[0].tolist():
            self._fire(k)
        self._touched |= batch.touched()[:, 0]
        return goalkeeper_rows(self._exits(-1), self._fired, self._airborne(), live,
                               batch.state, act, self._weights, self._geometry,
                               self.control_dt)

    def _success(self, codes: np.ndarray) -> np.ndarray:
        return codes != EXIT_GOAL  # a save: any outcome but the goal

    def _task_entries(self) -> dict[str, Any]:
        shot = self._shot_table.columns
        if self.flat:
            return {"shot_fired": self._fired.astype(np.float64),
                    "keeper_touched": self._touched.astype(np.float64),
                    "shot_speed": shot["speed"].astype(np.float64),
                    "shot_chip": shot["chip"].astype(np.float64)}
        return {"shot": shot, "shot_fired": self._fired, "keeper_touched": self._touched}


class ShootoutVectorEnv(BatchedTask):
    """``num_envs`` Shootout-v0 episodes stepped as one batch: the attacker's start
    (:class:`~soccer_env.envs.shootout.ShootoutStart`), the scripted keeper over the batch
    (:meth:`~soccer_env.envs.keeper.ScriptedGoalkeeper.act_batch`), the outcome (goal, saved,
    out), the reward terms and the time limit. Arguments as :class:`BatchedTask`'s;
    ``**kwargs`` are :class:`~soccer_env.envs.shootout.ShootoutEnv`'s.

    The keeper's batched actions equal its per-environment ones bit for bit (one compiled rule,
    :func:`~soccer_env.envs.keeper.ssl_keeper`, on each row); the episodes agree with single
    environments as the Goalkeeper's do.
    """

    TASK = ShootoutEnv
    TASK_ID = SHOOTOUT_ID
    OUTCOMES = SHOOTOUT_OUTCOMES

    def _setup(self) -> None:
        probe = self.probe
        self.start = probe.start
        self.keeper = probe.keeper
        self._keeper_view = probe._keeper_view
        self._goal = probe._goal
        n = self.num_envs
        self._keeper_touched = np.zeros(n, dtype=bool)
        self._ball_to_goal = np.zeros(n)
        self._start_table = EpisodeTable(n)  # (the infos' "start")

    def _place(self, k: int) -> tuple[np.ndarray, tuple[float, float], dict[str, Any]]:
        rng = self._rngs[k]
        drawn = self.start.sample(rng, self.field, self._robot.radius)
        self._streams(k, sensors_first=False)
        return np.array([drawn["attacker"], drawn["keeper"]]), drawn["ball"], drawn

    def _begin(self, k: int, drawn: dict[str, Any]) -> None:
        self._start_table.set(k, drawn)
        self._keeper_touched[k] = False
        bx, by = drawn["ball"]
        self._ball_to_goal[k] = goal_distance((float(bx), float(by)), self._goal)

    def _commands(self, act: np.ndarray) -> np.ndarray:
        build = self._keeper_view.build
        if self.keeper.humanoid:
            # A humanoid keeper decides in plain Python, one environment at a time, from the
            # view a single environment builds (its dives turn on thresholds).
            views = ([build(w.snapshot())[0] for w in self.batch.worlds] if self._senses.truth
                     else [build(p.belief(1))[0] for p in self._senses.perceptions])
            keeper = np.stack([self.keeper(view) for view in views])
        else:  # the keeper plays from its team's belief (the truth in truth mode)
            arrays = self._senses.arrays()
            if arrays is not None:
                view = self._keeper_view.build_batch(arrays[1], arrays[0])[:, 0]
            else:
                view = np.stack([build(p.belief(1))[0] for p in self._senses.perceptions])
            keeper = self.keeper.act_batch(view)
        both = np.stack([act, np.clip(keeper, -1.0, 1.0)], axis=1)
        return self._model.commands(both.reshape(-1, 6)).reshape(self.num_envs, 2, 6)

    def _judge(self, act: np.ndarray, live: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        batch = self.batch
        touched = batch.touched()
        self._keeper_touched = np.where(touched[:, 1], True,
                                        np.where(touched[:, 0], False, self._keeper_touched))
        sc = self.shaping
        return shootout_rows(
            self._exits(+1), self._keeper_touched, self._airborne(), live, batch.state,
            self._ball_to_goal, act, self._goal,
            (float(sc["ball_progress"]), float(sc["ball_distance"]), float(sc["action_cost"])),
            self.control_dt)

    def _success(self, codes: np.ndarray) -> np.ndarray:
        return codes == EXIT_GOAL

    def _task_entries(self) -> dict[str, Any]:
        if self.flat:
            return {"keeper_touched": self._keeper_touched.astype(np.float64)}
        return {"start": self._start_table.columns, "keeper_touched": self._keeper_touched}


def make_shootout_vector(num_envs: int = 16,
                         max_episode_steps: int | None = SHOOTOUT_MAX_STEPS,
                         **kwargs: Any) -> VectorEnv:
    """Shootout-v0's ``vector_entry_point``: a :class:`ShootoutVectorEnv`, or Gymnasium's
    ``SyncVectorEnv`` of single environments (with a warning saying why) for arguments the
    batch does not run yet."""
    return vector_or_sync(ShootoutVectorEnv, SHOOTOUT_ID, num_envs, max_episode_steps,
                          kwargs)
