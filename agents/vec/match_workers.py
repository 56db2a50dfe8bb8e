"""Match collection over several processes: :class:`MatchWorkerVecEnv`.

:class:`~agents.vec.match.MatchVecEnv` steps its matches one after the other in one process,
so match training uses one core. :class:`MatchWorkerVecEnv` is the same VecEnv (the same
batch layout, opponents, self-play and info dicts) with its matches split over worker
processes in contiguous blocks; each worker runs a :class:`MatchVecEnv` over its block,
opponents included (an opponent's policy runs where its matches are).

Each step moves only a few bytes through the pipes: the actions go to the workers and the
observations, rewards and dones come back through one block of shared memory, and a worker
sends its entries' info dicts (a few numbers each; arrays only at the end of a match). The
parent writes every worker's actions, wakes them all, then waits for all of them, so the
workers step their matches at the same time while the learner waits.

Results do not depend on the number of workers: match ``k`` is seeded with ``seed + k`` and
draws its opponents from its own stream, wherever it runs (tested), so a run with one worker
and a run with four give the same batches.

With ``batched=True`` the same holds up to rounding: a match's coordinates are offset by its
patch of its worker's shared space, which depends on the split, so runs with different
numbers of workers agree to about 1e-12 m, until a contact amplifies the difference (tested
to agree on every event and end over a few hundred steps); a run is reproducible bit for bit
with the same number of workers.

Failures are those of :class:`~agents.vec.workers.WorkerVecEnv` (whose process handling this
class shares): a worker whose match raises, that dies, or that gives no reply within
``reply_timeout`` seconds (stopped, deadlocked, in an endless loop) raises
:class:`~agents.vec.workers.WorkerError` naming it and its batch entries, after stopping every
worker; workers ignore Ctrl-C.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from stable_baselines3.common.vec_env.base_vec_env import (
    CloudpickleWrapper,
    VecEnvIndices,
    VecEnvStepReturn,
)

import soccer_env
from agents.common.checks import positive_seconds
from agents.common.processes import REPLY_TIMEOUT, process_context
from agents.sb3.algorithms import is_sb3_model
from agents.sb3.policies import SB3Policy, numpy_copy
from agents.vec.batched import BatchedMatchVecEnv
from agents.vec.match import MatchVecEnv, base_seed
from agents.vec.workers import REPLY_OK, WorkerVecEnv, start_worker, worker_frame

__all__ = ["MatchWorkerVecEnv"]

_LIVE_MODEL = ("an opponent that follows a live stable-baselines3 model cannot be shared with "
               "worker processes: pass a frozen copy (numpy_copy(model)) or use "
               "workers=0")


class _Layout:
    """Where each array of the shared block lies: actions ``(n, 6)`` float32, observations
    ``(n, obs_dim)`` float32, rewards ``(n,)`` float32, dones ``(n,)`` uint8."""

    def __init__(self, n: int, obs_dim: int) -> None:
        self.n, self.obs_dim = n, obs_dim
        self.shapes = {"actions": (n, 6), "obs": (n, obs_dim), "rewards": (n,),
                       "dones": (n,)}
        self.dtypes = {"actions": np.float32, "obs": np.float32, "rewards": np.float32,
                       "dones": np.uint8}
        self.offsets: dict[str, int] = {}
        offset = 0
        for name, shape in self.shapes.items():
            self.offsets[name] = offset
            size = int(np.prod(shape)) * np.dtype(self.dtypes[name]).itemsize
            offset += -(-size // 64) * 64  # each array on its own cache lines
        self.nbytes = offset

    def views(self, buffer: Any, rows: range | None = None) -> dict[str, np.ndarray]:
        """Arrays over ``buffer`` (all rows, or the rows of one block)."""
        out = {}
        for name, shape in self.shapes.items():
            arr = np.frombuffer(buffer, dtype=self.dtypes[name], count=int(np.prod(shape)),
                                offset=self.offsets[name]).reshape(shape)
            out[name] = arr if rows is None else arr[rows.start:rows.stop]
        return out


def _match_worker(remote: Any, parent: Any, spec: CloudpickleWrapper, buffer: Any,
                  layout: _Layout, rows: range, cpu: int | None) -> None:
    """Run a :class:`MatchVecEnv` (or, batched, a
    :class:`~agents.vec.batched.BatchedMatchVecEnv`) over one block of matches and serve the
    parent's commands (replies as :mod:`agents.vec.workers`'s workers give them) until told to
    close; with ``cpu``, on that CPU only."""
    def body(current: list[int | None]) -> None:
        if cpu is not None:
            os.sched_setaffinity(0, {cpu})
        kwargs = dict(spec.var)
        batched = kwargs.pop("batched")
        if batched:
            venv: Any = BatchedMatchVecEnv(**kwargs)
        else:
            venv = MatchVecEnv(**kwargs)
        views = layout.views(buffer, rows)
        actions, obs, rewards, dones = (views["actions"], views["obs"], views["rewards"],
                                        views["dones"])
        remote.send((REPLY_OK, None))
        while True:
            try:
                cmd, data = remote.recv()
            except EOFError:
                return
            if cmd == "step":
                venv.step_async(actions)
                # A batch sends its infos compactly; the parent expands them.
                o, r, d, infos = venv.step_arrays() if batched else venv.step_wait()
                obs[:] = o
                rewards[:] = r
                dones[:] = d
                result: Any = infos
            elif cmd == "reset":
                seed, options = data
                if seed is not None:
                    venv.seed(seed)
                venv.set_options(options)
                obs[:] = venv.reset()
                result = venv.reset_infos
            elif cmd == "call":  # a MatchVecEnv method: opponents, attributes, renders
                name, args, kwargs = data.var
                result = getattr(venv, name)(*args, **kwargs)
            elif cmd == "attribute":
                result = getattr(venv, data)
            elif cmd == "close":
                venv.close()
                return
            else:  # pragma: no cover - programming error
                raise ValueError(f"unknown command {cmd!r}")
            remote.send((REPLY_OK, result))

    worker_frame(remote, parent, body)


class MatchWorkerVecEnv(WorkerVecEnv):
    """:class:`~agents.vec.match.MatchVecEnv` with its matches run by ``workers`` processes.

    ``env_kwargs``, ``n_matches``, ``learner`` and ``opponent`` are :class:`MatchVecEnv`'s (an
    opponent is checked and, if it is a model, copied here, then sent to the workers: it must
    pickle; a live model that numpy cannot copy is refused).

    Args:
        workers: processes (at most one per match; ``n_matches`` is split in contiguous
            blocks as evenly as possible).
        pin: keep worker ``w`` on the ``w``-th CPU this process may use
            (``os.sched_setaffinity``). A worker sleeps between steps, and the scheduler
            often wakes it on another core, whose caches are cold: on a 2-core machine with 2
            workers of 64 matches each, pinning raised the rate from 1.57 to 1.79 times the
            in-process rate (2 vs 2) and from 1.68 to 1.90 times (6 vs 6)
            (``benchmarks/match_workers.py``). ``None`` (the default) pins when there are at
            least as many workers as usable CPUs (the run takes the whole machine anyway) and
            the platform supports it; two such runs side by side share the same CPUs, so pass
            False to let the scheduler place them.
        start_method: multiprocessing start method (default ``"forkserver"`` where available,
            else ``"spawn"``).
        batched: each worker steps its block of matches as one batch
            (:class:`~agents.vec.batched.BatchedMatchVecEnv`, for the matches it runs) instead of
            one after the other.
        reply_timeout: seconds a worker may take to answer a request (finite, > 0; default
            :data:`~agents.vec.workers.REPLY_TIMEOUT`, 60 s), as
            :class:`~agents.vec.workers.WorkerVecEnv` takes it: until its first step's reply
            (building its matches, the first reset and step) a worker gets
            :data:`~agents.vec.workers.START_TIMEOUT` if that is longer.

    The batch layout, spaces, infos and methods are :class:`MatchVecEnv`'s:
    ``set_opponent``, ``set_opponent_pool``, ``opponents``, ``opponent_pool`` act on every
    worker's matches; ``get_attr``, ``set_attr``, ``env_method`` reach the match of each
    entry; ``get_images`` returns one frame per match.
    """

    def __init__(self, env_kwargs: Mapping[str, Any] | None = None, n_matches: int = 2,
                 learner: str = "blue", opponent: Any = None, workers: int = 2,
                 start_method: str | None = None, pin: bool | None = None,
                 batched: bool = False, reply_timeout: float = REPLY_TIMEOUT) -> None:
        if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or (
                workers < 1):
            raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
        reply_timeout = positive_seconds(reply_timeout, "reply_timeout")
        # A probe in this process checks every argument (and gives the spaces) before any
        # worker starts, so that bad input fails here with the constructor's own message.
        if batched:
            probe: MatchVecEnv = BatchedMatchVecEnv(env_kwargs, n_matches=1, learner=learner,
                                                    opponent=opponent)
        else:
            probe = MatchVecEnv(env_kwargs, n_matches=1, learner=learner, opponent=opponent)
        #: Whether each worker steps its matches as one batch.
        self.batched = bool(batched)
        if isinstance(n_matches, bool) or not isinstance(n_matches, (int, np.integer)) or (
                n_matches < 1):
            raise ValueError(f"n_matches must be an integer >= 1, got {n_matches!r}")
        self.env_kwargs = dict(probe.env_kwargs)
        self.n_matches = int(n_matches)
        self.learner = learner
        for name in ("learning_teams", "opponent_team", "learner_agents", "opponent_agents",
                     "agents_per_match"):
            setattr(self, name, getattr(probe, name))
        L = self.agents_per_match
        self.entry_agents = [(k, a) for k in range(self.n_matches) for a in self.learner_agents]
        self._entry_names = [f"{a} of match {k} (batch entry {i})"
                             for i, (k, a) in enumerate(self.entry_agents)]
        self.out_of_range_actions = probe.out_of_range_actions
        obs_space, act_space = probe.observation_space, probe.action_space
        metadata, render_mode = probe.metadata, probe.render_mode
        probe.close()
        opponent = self._portable(opponent)

        workers = min(int(workers), self.n_matches)
        ctx = process_context(start_method)
        n = self.n_matches * L
        self._layout = _Layout(n, obs_space.shape[0])
        self._buffer = ctx.RawArray("b", self._layout.nbytes)
        self._shared = self._layout.views(self._buffer)
        match_bounds = [w * self.n_matches // workers for w in range(workers + 1)]
        self._match_blocks = [range(match_bounds[w], match_bounds[w + 1])
                              for w in range(workers)]
        self._blocks = [range(b.start * L, b.stop * L) for b in self._match_blocks]
        self._owner = [(w, i - blk.start) for w, blk in enumerate(self._blocks) for i in blk]
        self.remotes, self.processes = [], []
        self.waiting = False
        self.closed = False
        cpus = sorted(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else []
        if pin is None:
            pin = bool(cpus) and workers >= len(cpus)
        elif pin and not cpus:
            raise ValueError("pin=True needs os.sched_setaffinity, which this platform lacks")
        #: The CPU of each worker (None: not pinned).
        self.cpus = [cpus[w % len(cpus)] if pin else None for w in range(workers)]
        for mblk, rows, cpu in zip(self._match_blocks, self._blocks, self.cpus):
            spec = dict(env_kwargs=self.env_kwargs, n_matches=len(mblk), learner=learner,
                        opponent=opponent, first_match=mblk.start, batched=self.batched)
            remote, proc = start_worker(ctx, _match_worker, CloudpickleWrapper(spec),
                                        self._buffer, self._layout, rows, cpu)
            self.remotes.append(remote)
            self.processes.append(proc)
        self._watch(reply_timeout)
        for w in range(workers):
            self._recv(w)  # each worker has built its matches
        self.num_envs = n
        super(WorkerVecEnv, self).__init__(n, obs_space, act_space)
        self.metadata = {**metadata, **self.metadata}
        self.render_mode = render_mode
        self._started = False

    @staticmethod
    def _portable(opponent: Any) -> Any:
        """``opponent`` in a form that can be sent to the workers (a model becomes its frozen
        numpy copy, as :class:`MatchVecEnv` would make it)."""
        if is_sb3_model(opponent):
            try:
                return numpy_copy(opponent)
            except ValueError:
                raise ValueError(_LIVE_MODEL) from None
        if isinstance(opponent, SB3Policy):
            raise ValueError(_LIVE_MODEL)
        return opponent

    @property
    def workers(self) -> int:
        """The number of worker processes."""
        return len(self.processes)

    # -- the VecEnv API -----------------------------------------------------------------------

    def seed(self, seed: int | None = None) -> Sequence[int | None]:
        """Seed the next :meth:`reset` as :meth:`MatchVecEnv.seed` does (match ``k``:
        ``seed + k``)."""
        seed = self._seed = base_seed(seed)
        return [seed + k for k, _ in self.entry_agents]

    def reset(self) -> np.ndarray:
        seed, self._seed = getattr(self, "_seed", None), None
        for w, blk in enumerate(self._blocks):
            self._send(w, ("reset", (seed, self._options[blk.start:blk.stop])))
        self.reset_infos = [x for w in range(len(self.remotes)) for x in self._recv(w)]
        self._reset_seeds()
        self._reset_options()
        self._started = True
        return self._shared["obs"].copy()

    def step_async(self, actions: np.ndarray) -> None:
        """Check the actions ``(num_envs, 6)`` (all of them, before any match moves), write
        them to the shared block and start every worker."""
        if not self._started:
            raise RuntimeError("call reset() before stepping a MatchWorkerVecEnv")
        a = np.asarray(actions, dtype=np.float32)
        if a.shape != (self.num_envs, 6):
            raise ValueError(f"actions must have shape ({self.num_envs}, 6) (one row of vx, "
                             f"vy, omega, kick, chip, dribble per batch entry), got {a.shape}")
        self._shared["actions"][:] = soccer_env.validate_actions(a, self._entry_names,
                                                                 self.out_of_range_actions)
        for w in range(len(self.remotes)):
            self._send(w, ("step", None))
        self.waiting = True

    def step_wait(self) -> VecEnvStepReturn:
        if not self.waiting:
            raise RuntimeError("call step_async(actions) before step_wait()")
        if self.batched:
            infos = []
            for w in range(len(self.remotes)):  # finished entries by their worker's index
                infos += BatchedMatchVecEnv.expand_infos(self._recv(w), self.agents_per_match)
        else:
            infos = [x for w in range(len(self.remotes)) for x in self._recv(w)]
        self.waiting = False
        shared = self._shared
        return (shared["obs"].copy(), shared["rewards"].copy(),
                shared["dones"].astype(bool), infos)

    def _all(self, cmd: str, data: Any) -> list[Any]:
        if cmd == "call":  # with cloudpickle: opponents may be lambdas or local functions
            data = CloudpickleWrapper(data)
        for w in range(len(self.remotes)):
            self._send(w, (cmd, data))
        return [self._recv(w) for w in range(len(self.remotes))]

    def get_images(self) -> Sequence[np.ndarray | None]:
        """One RGB frame per match (not per entry), if ``render_mode="rgb_array"``."""
        return [img for part in self._all("call", ("get_images", (), {})) for img in part]

    def _ask(self, cmd: str, indices: VecEnvIndices, *payload: Any) -> list[Any]:
        """Call the block VecEnv's ``cmd`` method with the local entry indices of each
        worker; answers in the order of ``indices``."""
        for i in self._get_indices(indices):
            if not 0 <= int(i) < self.num_envs:
                raise IndexError(f"batch entry {i} out of range 0..{self.num_envs - 1}")
        where, parts = self._by_worker(indices)
        for w, local in parts.items():
            name, args, kwargs = payload
            self._send(w, ("call", CloudpickleWrapper((cmd, args,
                                                       {**kwargs, "indices": local}))))
        answers = {}
        for w, local in parts.items():
            reply = self._recv(w)
            answers[w] = dict(zip(local, [None] * len(local) if reply is None else reply))
        return [answers[w][local] for w, local in where]

    def has_attr(self, attr_name: str) -> bool:
        return all(self._all("call", ("has_attr", (attr_name,), {})))

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        """Attribute ``attr_name`` of the match of each entry."""
        return self._ask("get_attr", indices, "get_attr", (attr_name,), {})

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        """Set attribute ``attr_name`` of the matches of the entries."""
        self._ask("set_attr", indices, "set_attr", (attr_name, value), {})

    def env_method(self, method_name: str, *method_args: Any, indices: VecEnvIndices = None,
                   **method_kwargs: Any) -> list[Any]:
        """Call ``method_name`` once on the match of each entry; one result per entry."""
        return self._ask("env_method", indices, "env_method", (method_name, *method_args),
                         method_kwargs)

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper], indices: VecEnvIndices = None
                       ) -> list[bool]:
        """Always False: the matches are bare PettingZoo environments."""
        return [False for _ in self._get_indices(indices)]

    # -- opponents ----------------------------------------------------------------------------

    def set_opponent(self, opponent: Any) -> None:
        """As :meth:`MatchVecEnv.set_opponent`, in every worker (a model is copied now)."""
        self._all("call", ("set_opponent", (self._portable(opponent),), {}))

    def set_opponent_pool(self, opponents: Sequence[Any], redraw_now: bool = False) -> None:
        """As :meth:`MatchVecEnv.set_opponent_pool`, in every worker; match ``k`` draws from
        its own seeded stream wherever it runs."""
        pool = [self._portable(o) for o in opponents]
        self._all("call", ("set_opponent_pool", (pool,), {"redraw_now": redraw_now}))

    @property
    def opponents(self) -> list[Any]:
        """The policy playing the opponent team in each match (copies from the workers)."""
        return [o for part in self._all("attribute", "opponents") for o in part]

    @property
    def opponent_pool(self) -> list[Any]:
        """The pool set by :meth:`set_opponent_pool` (copies from the first worker)."""
        return self._all("attribute", "opponent_pool")[0]

