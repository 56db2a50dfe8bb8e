"""Helpers of the fault tests: environments that fail inside a rollout worker."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


class FailingAfter:
    """An environment constructor (picklable, so that a worker process can call it) whose
    environments raise ``RuntimeError`` inside ``step`` after ``after`` steps."""

    MESSAGE = "the field's lights went out"

    def __init__(self, make: Callable[[], Any], after: int) -> None:
        self.make, self.after = make, after

    def __call__(self) -> Any:
        env = self.make()
        step, after, count = env.step, self.after, [0]

        def failing_step(action):
            count[0] += 1
            if count[0] > after:
                raise RuntimeError(FailingAfter.MESSAGE)
            return step(action)

        env.step = failing_step
        return env


class HangingAfter:
    """An environment constructor (picklable) whose environments stop answering inside
    ``step`` after ``after`` steps, alive: ``how="loop"`` spins in an endless loop,
    ``"deadlock"`` waits for a lock it holds, ``"stop"`` stops its own process (``SIGSTOP``,
    as ``kill -STOP`` would)."""

    HOWS = ("loop", "deadlock", "stop")

    def __init__(self, make: Callable[[], Any], after: int, how: str = "loop") -> None:
        if how not in self.HOWS:
            raise ValueError(f"how must be one of {self.HOWS}, got {how!r}")
        self.make, self.after, self.how = make, after, how

    def __call__(self) -> Any:
        import os
        import signal
        import threading

        env = self.make()
        step, after, how, count = env.step, self.after, self.how, [0]

        def hanging_step(action):
            count[0] += 1
            if count[0] > after:
                if how == "stop":
                    os.kill(os.getpid(), signal.SIGSTOP)
                elif how == "deadlock":
                    lock = threading.Lock()
                    lock.acquire()
                    lock.acquire()
                else:
                    while True:
                        pass
            return step(action)

        env.step = hanging_step
        return env


class SlowToBuild:
    """An environment constructor (picklable) that takes ``seconds`` longer to build its
    environment: a worker's start-up that outlasts a short reply timeout."""

    def __init__(self, make: Callable[[], Any], seconds: float) -> None:
        self.make, self.seconds = make, seconds

    def __call__(self) -> Any:
        import time

        time.sleep(self.seconds)
        return self.make()
