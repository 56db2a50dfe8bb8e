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
from abc import ABC, abstractmethod
from collections.abc import Sequence
from typing import Any

__all__ = ["ReplayBuffer"]


class ReplayBuffer(ABC):
    """A ball tracker's frames of the last ``history`` seconds and the track state after each
    (see the module docstring): the tracker's :meth:`update_frame`.

    A base class of the tracker rather than a member, so that a frame in capture order costs
    no call beyond the tracker's own step (this runs for every camera frame). The tracker

    * keeps its current state in ``_track``: immutable (a ``NamedTuple``, so that the log
      needs no copies), with ``t``, the capture time of the latest frame in it (``-inf`` for
      the empty track);
    * sets ``history``, the seconds of frames kept for replay [s];
    * implements :meth:`process`, its step;
    * calls :meth:`reset_replay` when it resets, after setting ``_track`` to the empty state.

    Attributes:
        late: frames dropped as older than the window.
    """

    __slots__ = ()
    _track: Any
    history: float
    late: int

    @abstractmethod
    def process(self, state: Any, t: float, detections: Sequence[Sequence[float]],
                obstacles: Sequence[Sequence[float]]) -> Any:
        """The state after one frame captured at ``t`` [s], no earlier than ``state.t``, with
        ball ``detections`` and the robots seen (``obstacles``); ``state`` is not changed."""

    def reset_replay(self) -> None:
        """Forget every frame; the current ``_track`` is the state before the next."""
        self._base = self._track  # the state before the oldest frame still in the log
        self._log: list[tuple[float, Any, Any, Any]] = []
        self.late = 0

    def update_frame(self, t: float, detections: Sequence[Sequence[float]],
                     obstacles: Sequence[Sequence[float]] = ()) -> None:
        """The tracker's ``update`` without its checks, for a pipeline whose frames are checked
        already (a sensor's own: ``t`` a finite float, ``detections`` a sequence of finite
        ``(x, y)`` and ``obstacles`` of finite rows whose first two entries are a position,
        ``t`` no older than the latest frame by more than
        :data:`~estimators.protocol.MAX_REWIND`): processed at once when ``t`` is no earlier
        than the track's time, replayed in capture-time order when it is within the window,
        dropped (``late``) when it is older."""
        state = self._track
        log = self._log
        if t >= state.t:
            self._track = state = self.process(state, t, detections, obstacles)
            log.append((t, detections, obstacles, state))
        elif t < self._base.t:
            self.late += 1
            return
        else:  # out of order: rewind to the state before t and replay
            i = bisect.bisect_right([entry[0] for entry in log], t)
            state = log[i - 1][3] if i > 0 else self._base
            log.insert(i, (t, detections, obstacles, state))
            process = self.process
            for j in range(i, len(log)):
                tj, dj, oj, _ = log[j]
                state = process(state, tj, dj, oj)
                log[j] = (tj, dj, oj, state)
            self._track = state
        # Drop what is older than the replay window.
        horizon = log[-1][0] - self.history
        while len(log) > 1 and log[0][0] < horizon:
            self._base = log.pop(0)[3]
