"""A subprocess VecEnv that steps several environments per worker process.

stable-baselines3's ``SubprocVecEnv`` runs one environment per process and sends every
environment's full ``info`` dict through a pipe each step. For environments as cheap as ours
(about 0.1 ms a step) that is the bottleneck: on a 2-core machine PPO collects about 1,200
Goalkeeper steps/s with two ``SubprocVecEnv`` processes, fewer than with ``DummyVecEnv``
(about 2,000), because the policy's forward pass (about 0.3 ms in torch) and the pickling of
large infos dominate. :class:`WorkerVecEnv` instead

* gives each of ``n_workers`` processes a block of environments, stepped in a loop, so that one
  policy forward pass serves many environment steps;
* forwards only the info keys a learner needs (:data:`DEFAULT_INFO_KEYS`: the episode
  statistics, the terminal observation, the truncation flag, the outcome) rather than every
  step's truth and estimate dicts;
* follows stable-baselines3's VecEnv contract otherwise: automatic reset with
  ``infos[i]["terminal_observation"]`` and ``infos[i]["TimeLimit.truncated"]``, ``seed()``
  before ``reset()``, ``get_attr``, ``set_attr``, ``env_method``, ``env_is_wrapped``,
  ``get_images``;
* fails fast: a worker whose environment raises sends the traceback and stops, a worker that
  dies (killed, out of memory) is noticed within :data:`POLL_SECONDS`, a worker that lives on
  but gives no reply within ``reply_timeout`` seconds (stopped by ``SIGSTOP``, deadlocked, in
  an endless loop) is ended, and either way the call raises :class:`WorkerError` naming the
  worker, its environments and the traceback, the signal or the silence, after stopping every
  worker (stable-baselines3's ``SubprocVecEnv`` waits forever on a dead worker's pipe).
  Workers ignore Ctrl-C (``SIGINT``): the parent handles the interrupt and closes them, so that
  an interrupt to the process group prints one traceback, not one per process.

The reply timeout (default :data:`REPLY_TIMEOUT`, 60 s) counts from the moment the parent
starts waiting for that worker, in polls of :data:`POLL_SECONDS`: a poll that returns late
(the parent itself was stopped, Ctrl-Z, or waited for a core) counts as one poll. Until a
worker has answered its first step, its replies (building the environments, the first reset,
the first step: imports and numba's compilation fall there) get :data:`START_TIMEOUT`
(300 s) instead, or the reply timeout if that is longer. A worker that stops answering is
ended with ``SIGTERM`` and ``SIGCONT`` (a stopped process that handles ``SIGTERM`` acts on it
only once continued), then ``SIGKILL`` after :data:`KILL_SECONDS`.
"""

from __future__ import annotations

import os
import signal
import time
import traceback
from collections.abc import Callable, Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from stable_baselines3.common.vec_env.base_vec_env import (
    CloudpickleWrapper,
    VecEnv,
    VecEnvIndices,
    VecEnvObs,
    VecEnvStepReturn,
)

from agents.common.checks import positive_seconds
from agents.common.processes import (
    REPLY_TIMEOUT,
    START_TIMEOUT,
    ignore_interrupts,
    process_context,
)

__all__ = ["WorkerVecEnv", "WorkerError", "DEFAULT_INFO_KEYS", "POLL_SECONDS",
           "CLOSE_SECONDS", "KILL_SECONDS", "REPLY_TIMEOUT", "START_TIMEOUT", "REPLY_OK",
           "REPLY_ERROR", "worker_frame", "start_worker"]

#: How often a waiting parent checks that the worker it waits on is still alive (seconds).
POLL_SECONDS = 0.5
#: How long ``close()`` waits for the workers to finish before terminating them (seconds,
#: all of them together).
CLOSE_SECONDS = 5.0
#: How long the workers get to end after ``SIGTERM`` before they are killed (seconds, all of
#: them together).
KILL_SECONDS = 1.0

#: The tags of a worker's replies: ``(REPLY_OK, result)`` or ``(REPLY_ERROR, (local
#: environment index or None, traceback))`` (:func:`worker_frame`).
REPLY_OK, REPLY_ERROR = "ok", "error"


class WorkerError(RuntimeError):
    """A rollout worker of :class:`WorkerVecEnv` died, stopped answering (no reply within
    the reply timeout) or its environment raised.

    Attributes:
        worker: the worker's index.
        environments: the global indices of the environments it stepped.
        exitcode: the process's exit code (negative: the signal that killed it), None while
            it ran on (as a worker that stopped answering did until it was ended).
        remote_traceback: the environment's traceback, when one raised.
        timeout: the seconds it was given to reply, when it stopped answering (else None).
    """

    def __init__(self, message: str, worker: int, environments: range,
                 exitcode: int | None = None, remote_traceback: str | None = None,
                 timeout: float | None = None) -> None:
        super().__init__(message)
        self.worker = worker
        self.environments = environments
        self.exitcode = exitcode
        self.remote_traceback = remote_traceback
        self.timeout = timeout

#: Info keys passed from the workers: Monitor's episode statistics, SB3's reset bookkeeping,
#: and the Goalkeeper's episode result (``is_success`` feeds SB3's success-rate log).
DEFAULT_INFO_KEYS = ("episode", "terminal_observation", "TimeLimit.truncated", "is_success",
                     "outcome")


def _continue(proc: Any) -> None:
    """Send ``SIGCONT`` to ``proc`` where the platform has it (a stopped process that handles
    ``SIGTERM`` acts on it only once continued); a process that has gone is ignored."""
    if hasattr(signal, "SIGCONT") and proc.pid is not None:
        try:
            os.kill(proc.pid, signal.SIGCONT)
        except ProcessLookupError:
            pass


def _stack(observations: list) -> Any:
    """One block's observations as a batch: an array, or for ``Dict`` observations a dict of
    arrays (stable-baselines3's layout)."""
    if observations and isinstance(observations[0], dict):
        return {k: np.stack([o[k] for o in observations]) for k in observations[0]}
    return np.stack(observations)


def _concatenate(blocks: list) -> Any:
    """The blocks' batches (see :func:`_stack`) as one."""
    if blocks and isinstance(blocks[0], dict):
        return {k: np.concatenate([b[k] for b in blocks]) for k in blocks[0]}
    return np.concatenate(blocks)


def worker_frame(remote: Any, parent: Any, body: Callable[[list[int | None]], None]) -> None:
    """The frame of every rollout worker process: ignore Ctrl-C (the parent handles it and
    closes the workers), run ``body(current)``, and if it raises, reply ``(REPLY_ERROR, (local
    environment index or None, traceback))`` (``current[0]``: the environment being built or
    stepped, set by ``body``) and stop; a parent that has gone gets no reply."""
    # Ctrl-C reaches the whole process group: the parent handles it and closes the workers.
    ignore_interrupts()
    parent.close()
    current: list[int | None] = [None]
    try:
        body(current)
    except (EOFError, BrokenPipeError, ConnectionResetError):
        pass  # the parent has gone: nothing to report to
    except BaseException:
        try:
            remote.send((REPLY_ERROR, (current[0], traceback.format_exc())))
        except (BrokenPipeError, ConnectionResetError, OSError):
            pass
    finally:
        remote.close()


def start_worker(ctx: Any, target: Callable[..., None], *args: Any) -> tuple[Any, Any]:
    """Start a daemon process running ``target(work_remote, remote, *args)``; returns this
    end of the pipe and the process."""
    remote, work_remote = ctx.Pipe()
    proc = ctx.Process(target=target, args=(work_remote, remote, *args), daemon=True)
    proc.start()
    work_remote.close()
    return remote, proc


def _worker(remote: Any, parent: Any, fns: CloudpickleWrapper, info_keys: tuple | None
            ) -> None:
    """Serve commands for a block of environments until told to close. Every reply is
    ``(REPLY_OK, result)``, or ``(REPLY_ERROR, (local environment index or None,
    traceback))`` after which the worker stops (its environments may be left in any
    state)."""
    def body(current: list[int | None]) -> None:
        envs = []
        for i, fn in enumerate(fns.var):
            current[0] = i
            envs.append(fn())
        current[0] = None
        _serve(remote, envs, info_keys, current)

    worker_frame(remote, parent, body)


def _serve(remote: Any, envs: list[gym.Env], info_keys: tuple | None,
           current: list[int | None]) -> None:
    """The command loop of :func:`_worker`; returns on ``close`` or when the parent's end of
    the pipe closes, raises what an environment raises (with ``current[0]`` the index of the
    environment it came from, None when not from one)."""
    from stable_baselines3.common.env_util import is_wrapped

    keep = None if info_keys is None else frozenset(info_keys)

    def trim(info: dict) -> dict:
        return info if keep is None else {k: v for k, v in info.items() if k in keep}

    while True:
        try:
            cmd, data = remote.recv()
        except EOFError:
            return
        if cmd == "step":
            obs_out, rewards, dones, infos, reset_infos = [], [], [], [], []
            for i, (env, action) in enumerate(zip(envs, data)):
                current[0] = i
                obs, reward, term, trunc, info = env.step(action)
                done = term or trunc
                info = trim(info)
                info["TimeLimit.truncated"] = trunc and not term
                reset_info = {}
                if done:
                    info["terminal_observation"] = obs
                    obs, reset_info = env.reset()
                    reset_info = trim(reset_info)
                obs_out.append(obs)
                rewards.append(reward)
                dones.append(done)
                infos.append(info)
                reset_infos.append(reset_info)
            current[0] = None
            result: Any = (_stack(obs_out), rewards, dones, infos, reset_infos)
        elif cmd == "reset":
            obs_out, reset_infos = [], []
            for i, (env, (seed, options)) in enumerate(zip(envs, data)):
                current[0] = i
                obs, info = env.reset(seed=seed, **({"options": options} if options else {}))
                obs_out.append(obs)
                reset_infos.append(trim(info))
            current[0] = None
            result = (_stack(obs_out), reset_infos)
        elif cmd == "render":
            result = [env.render() for env in envs]
        elif cmd == "get_spaces":
            result = (envs[0].observation_space, envs[0].action_space,
                      envs[0].get_wrapper_attr("render_mode"))
        elif cmd == "env_method":
            idx, name, args, kwargs = data
            result = [envs[i].get_wrapper_attr(name)(*args, **kwargs) for i in idx]
        elif cmd == "get_attr":
            idx, name = data
            result = [envs[i].get_wrapper_attr(name) for i in idx]
        elif cmd == "has_attr":
            try:
                for env in envs:
                    env.get_wrapper_attr(data)
                result = True
            except AttributeError:
                result = False
        elif cmd == "set_attr":
            idx, name, value = data
            for i in idx:
                setattr(envs[i], name, value)
            result = None
        elif cmd == "is_wrapped":
            idx, cls = data
            result = [is_wrapped(envs[i], cls) for i in idx]
        elif cmd == "close":
            for env in envs:
                env.close()
            return
        else:  # pragma: no cover - programming error
            raise ValueError(f"unknown command {cmd!r}")
        remote.send((REPLY_OK, result))


class WorkerVecEnv(VecEnv):
    """``len(env_fns)`` environments spread over ``n_workers`` processes in contiguous blocks
    (environment ``i`` lives in worker ``i * n_workers // n``).

    Args:
        env_fns: environment constructors (pickled with cloudpickle).
        n_workers: processes (at most one per environment).
        info_keys: info keys to forward (None: all of them, as ``SubprocVecEnv`` does).
        start_method: multiprocessing start method (default ``"forkserver"`` where available,
            as stable-baselines3 does, else ``"spawn"``).
        reply_timeout: seconds a worker may take to answer a request (finite, > 0; default
            :data:`REPLY_TIMEOUT`); one that lives on without answering is ended and the call
            raises :class:`WorkerError`. Until its first step's reply a worker gets
            :data:`START_TIMEOUT` if that is longer.
    """

    def __init__(self, env_fns: Sequence[Callable[[], gym.Env]], n_workers: int = 2,
                 info_keys: Sequence[str] | None = DEFAULT_INFO_KEYS,
                 start_method: str | None = None,
                 reply_timeout: float = REPLY_TIMEOUT) -> None:
        n = len(env_fns)
        if n < 1:
            raise ValueError("env_fns must hold at least one environment constructor")
        if not isinstance(n_workers, int) or n_workers < 1:
            raise ValueError(f"n_workers must be an integer >= 1, got {n_workers!r}")
        reply_timeout = positive_seconds(reply_timeout, "reply_timeout")
        n_workers = min(n_workers, n)
        ctx = process_context(start_method)
        bounds = [w * n // n_workers for w in range(n_workers + 1)]
        self._blocks = [range(bounds[w], bounds[w + 1]) for w in range(n_workers)]
        self._owner = [(w, i - blk.start) for w, blk in enumerate(self._blocks) for i in blk]
        self.remotes, self.processes = [], []
        keys = None if info_keys is None else tuple(info_keys)
        for blk in self._blocks:
            fns = CloudpickleWrapper([env_fns[i] for i in blk])
            remote, proc = start_worker(ctx, _worker, fns, keys)
            self.remotes.append(remote)
            self.processes.append(proc)
        self.waiting = False
        self.closed = False
        self._watch(reply_timeout)
        self._send(0, ("get_spaces", None))
        obs_space, act_space, render_mode = self._recv(0)
        super().__init__(n, obs_space, act_space)
        self.render_mode = render_mode

    # -- talking to the workers ---------------------------------------------------------------

    def _watch(self, reply_timeout: float) -> None:
        """Start watching the workers' replies: each gets ``reply_timeout`` seconds (checked
        finite and > 0), or :data:`START_TIMEOUT` if longer until it has answered a step."""
        #: Seconds a worker may take to answer a request.
        self.reply_timeout = reply_timeout
        self._asked: list[str | None] = [None] * len(self.processes)
        self._stepped = [False] * len(self.processes)

    def _send(self, w: int, message: tuple) -> None:
        """Send ``message`` to worker ``w``; a worker that has gone raises
        :class:`WorkerError`."""
        if self.closed:
            raise RuntimeError("this WorkerVecEnv is closed")
        self._asked[w] = message[0]
        try:
            self.remotes[w].send(message)
        except (BrokenPipeError, ConnectionResetError, OSError):
            self._fail(w, None)

    def _recv(self, w: int) -> Any:
        """Worker ``w``'s reply, checking every :data:`POLL_SECONDS` that it is alive; a
        worker that died, whose environment raised, or that gave no reply within its
        allowance (:attr:`reply_timeout`, or :data:`START_TIMEOUT` before its first step)
        raises :class:`WorkerError`."""
        remote, proc = self.remotes[w], self.processes[w]
        allowance = self.reply_timeout if self._stepped[w] else max(self.reply_timeout,
                                                                    START_TIMEOUT)
        waited = 0.0
        while True:
            wait = min(POLL_SECONDS, allowance - waited)
            if remote.poll(wait):
                break
            # Polls are counted, not the clock: a poll that returns late (this process was
            # stopped, Ctrl-Z, or waited for a core) counts as on time.
            waited += wait
            if not proc.is_alive() and not remote.poll(0):
                self._fail(w, None)
            if waited >= allowance:
                self._fail(w, None, allowance)
        try:
            tag, payload = remote.recv()
        except (EOFError, ConnectionResetError, OSError):
            self._fail(w, None)
        if tag == REPLY_ERROR:
            self._fail(w, payload)
        if self._asked[w] == "step":
            self._stepped[w] = True
        return payload

    def _fail(self, w: int, error: tuple[int | None, str] | None,
              silent: float | None = None) -> None:
        """Stop every worker and raise :class:`WorkerError` for worker ``w`` (``error``: the
        local index of the environment that raised, or None, and the traceback; None when
        the worker died or, with ``silent`` seconds, gave no reply within them)."""
        proc = self.processes[w]
        if silent is None:
            proc.join(timeout=1.0)
        code = proc.exitcode
        self._terminate()
        blk = self._blocks[w]
        where = (f"rollout worker {w} (pid {proc.pid}, environments {blk.start}-"
                 f"{blk.stop - 1})")
        remote_traceback = None
        if error is not None:
            local, remote_traceback = error
            env = "an environment" if local is None else f"environment {blk.start + local}"
            message = f"{where}: {env} raised\n{remote_traceback.rstrip()}"
        elif silent is not None:
            message = (f"{where} stopped answering: no reply within {silent:g} s (it may be "
                       "stopped (SIGSTOP), deadlocked or in an endless loop); it was ended")
        elif code is not None and code < 0:
            try:
                name = signal.Signals(-code).name
            except ValueError:
                name = f"signal {-code}"
            message = f"{where} died: killed by {name}"
        else:
            message = f"{where} died (exit code {code})"
        raise WorkerError(message, w, blk, code, remote_traceback, silent)

    def _terminate(self) -> None:
        """End every worker now (after a failure): no replies are awaited. ``SIGTERM`` and
        ``SIGCONT`` (for a stopped worker), then ``SIGKILL`` for any left after
        :data:`KILL_SECONDS`."""
        for proc in self.processes:
            if proc.is_alive():
                proc.terminate()
                _continue(proc)
        deadline = time.monotonic() + KILL_SECONDS
        for proc in self.processes:
            proc.join(timeout=max(0.0, deadline - time.monotonic()))
        for proc in self.processes:
            if proc.is_alive():
                proc.kill()
                proc.join()
        for remote in self.remotes:
            remote.close()
        self.waiting = False
        self.closed = True

    # -- stepping ---------------------------------------------------------------------------

    def step_async(self, actions: np.ndarray) -> None:
        for w, blk in enumerate(self._blocks):
            self._send(w, ("step", actions[blk.start:blk.stop]))
        self.waiting = True

    def step_wait(self) -> VecEnvStepReturn:
        results = [self._recv(w) for w in range(len(self.remotes))]
        self.waiting = False
        obs = _concatenate([r[0] for r in results])
        rewards = np.array([x for r in results for x in r[1]], dtype=np.float32)
        dones = np.array([x for r in results for x in r[2]], dtype=bool)
        infos = [x for r in results for x in r[3]]
        self.reset_infos = [x for r in results for x in r[4]]
        return obs, rewards, dones, infos

    def reset(self) -> VecEnvObs:
        for w, blk in enumerate(self._blocks):
            self._send(w, ("reset", [(self._seeds[i], self._options[i]) for i in blk]))
        results = [self._recv(w) for w in range(len(self.remotes))]
        self.reset_infos = [x for r in results for x in r[1]]
        self._reset_seeds()
        self._reset_options()
        return _concatenate([r[0] for r in results])

    def close(self) -> None:
        """Close the environments and end the workers: together they get
        :data:`CLOSE_SECONDS` to finish a pending step and close, then any left is ended (a
        stopped or stuck one too). Never raises for a worker that has died (the failure was
        raised where it was noticed)."""
        if self.closed:
            return
        deadline = time.monotonic() + CLOSE_SECONDS
        for remote, proc in zip(self.remotes, self.processes):
            try:
                if self.waiting and proc.is_alive() and \
                        remote.poll(max(0.0, deadline - time.monotonic())):
                    remote.recv()
                remote.send(("close", None))
            except (EOFError, BrokenPipeError, ConnectionResetError, OSError):
                pass
        for proc in self.processes:
            proc.join(timeout=max(0.0, deadline - time.monotonic()))
        self._terminate()

    def get_images(self) -> Sequence[np.ndarray | None]:
        for w in range(len(self.remotes)):
            self._send(w, ("render", None))
        return [img for w in range(len(self.remotes)) for img in self._recv(w)]

    # -- attributes and methods -------------------------------------------------------------

    def _by_worker(self, indices: VecEnvIndices) -> tuple[list[tuple[int, int]],
                                                          dict[int, list[int]]]:
        """The (worker, local index) of every global index, and the local indices per
        worker."""
        where = [self._owner[i] for i in self._get_indices(indices)]
        parts: dict[int, list[int]] = {}
        for w, local in where:
            parts.setdefault(w, []).append(local)
        return where, parts

    def _ask(self, cmd: str, indices: VecEnvIndices, *payload: Any) -> list[Any]:
        """Send ``cmd`` to the workers holding ``indices``; answers in the order of
        ``indices``."""
        where, parts = self._by_worker(indices)
        for w, local in parts.items():
            self._send(w, (cmd, (local, *payload)))
        answers = {w: dict(zip(local, self._recv(w))) for w, local in parts.items()}
        return [answers[w][local] for w, local in where]

    def has_attr(self, attr_name: str) -> bool:
        for w in range(len(self.remotes)):
            self._send(w, ("has_attr", attr_name))
        return all([self._recv(w) for w in range(len(self.remotes))])

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        return self._ask("get_attr", indices, attr_name)

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        _, parts = self._by_worker(indices)
        for w, local in parts.items():
            self._send(w, ("set_attr", (local, attr_name, value)))
        for w in parts:
            self._recv(w)

    def env_method(self, method_name: str, *method_args: Any, indices: VecEnvIndices = None,
                   **method_kwargs: Any) -> list[Any]:
        return self._ask("env_method", indices, method_name, method_args, method_kwargs)

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper],
                       indices: VecEnvIndices = None) -> list[bool]:
        return self._ask("is_wrapped", indices, wrapper_class)
