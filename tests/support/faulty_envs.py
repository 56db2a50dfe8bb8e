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
