"""The replay buffer: latency compensation for frames that arrive out of capture order.

A measurement corrects the state *at its capture time* (Zhao, Wang and Li 2012), so frames
must be processed in capture-time order; with several cameras, or a latency that jitters, a
frame may arrive after a later one. :class:`ReplayBuffer` keeps the frames of the last
``history`` seconds with the track state after each; a late frame rewinds to the state before
it, and it and every later frame are processed again in capture-time order. A frame older
than the window is dropped and counted (``late``).
"""

from __future__ import annotations

import bisect
from collections.abc import Callable
from typing import Any

__all__ = ["ReplayBuffer"]


class ReplayBuffer:
    """Frames of the last ``history`` seconds and the track state after each (see the module
    docstring).

    The tracker's step ``process(state, t, *frame) -> state`` must leave ``state`` unchanged
    and return a new one (an immutable state, such as a ``NamedTuple``, needs no copies), and
    every state has ``t``, the capture time of the latest frame in it (``-inf`` for the empty
    track).

    Args:
        history: seconds of frames kept for replay [s], >= 0.
        process: the tracker's step.

    Attributes:
        late: frames dropped as older than the window.
    """

    __slots__ = ("history", "late", "_process", "_log", "_base")

    def __init__(self, history: float, process: Callable[..., Any]) -> None:
        self.history = history
        self._process = process
        self.late = 0
        self._log: list[tuple[float, tuple, Any]] = []
        self._base: Any = None

    def reset(self, empty: Any) -> None:
        """Forget every frame; ``empty`` is the state before the first."""
        self._base = empty  # the state before the oldest frame still in the log
        self._log = []
        self.late = 0

    def push(self, state: Any, t: float, *frame: Any) -> Any:
        """The track state after the frame ``frame`` captured at ``t`` [s], given the current
        ``state`` (after every frame pushed so far): processed at once when ``t`` is no
        earlier than ``state.t``, replayed in capture-time order when it is within the window,
        dropped (``late``; ``state`` is returned) when it is older."""
        log = self._log
        if t >= state.t:
            state = self._process(state, t, *frame)
            log.append((t, frame, state))
        elif t < self._base.t:
            self.late += 1
            return state
        else:  # out of order: rewind to the state before t and replay
            i = bisect.bisect_right([entry[0] for entry in log], t)
            state = log[i - 1][2] if i > 0 else self._base
            log.insert(i, (t, frame, state))
            process = self._process
            for j in range(i, len(log)):
                tj, fj, _ = log[j]
                state = process(state, tj, *fj)
                log[j] = (tj, fj, state)
        # Drop what is older than the replay window.
        horizon = log[-1][0] - self.history
        while len(log) > 1 and log[0][0] < horizon:
            self._base = log.pop(0)[2]
        return state
