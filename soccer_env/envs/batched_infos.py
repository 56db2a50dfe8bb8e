"""The infos of the batched single-agent tasks (:mod:`soccer_env.envs.batched`), laid out as
Gymnasium's ``SyncVectorEnv`` lays out the infos of the single environments it steps.

Every key of a single environment's info becomes an array over the batch beside a mask
``_key`` (True where that environment reported the key); a nested dict stays a dict of such
arrays with masks of its own. An array's dtype is what ``SyncVectorEnv`` makes of the
values (:func:`column`): float64 for floats, bool for flags, an object array for strings and
tuples, ``(n, ...)`` for arrays. Where an environment did not report a key its entry is zero,
False or None. The full infos (``info_mode="full"``) hold ``truth``, ``estimate``,
``reward_terms``, ``outcome``, the task's own entries, ``robot_state`` with humanoids and
``is_success`` where an episode terminated; the flat ones (``info_mode="flat"``) the keys of
:mod:`soccer_env.envs.flat_info`. :class:`BatchInfos` builds either from the batch's arrays
(:class:`InfoParts`), one numpy operation per key for the whole batch.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import numpy as np

from estimators.exact import hypots
from soccer_env.envs.flat_info import COMMON_KEYS, NO_OUTCOME, OUTCOME_CODES

__all__ = ["InfoParts", "BatchInfos", "column", "EpisodeTable", "outcome_names",
           "flat_outcome_codes"]


def column(value: Any, n: int) -> np.ndarray:
    """An empty column over ``n`` environments for values like ``value``, as
    ``SyncVectorEnv`` makes it from the first environment's value: ``np.zeros(n)`` of the
    value's type for Python's ``int``, ``float`` and ``bool`` and numpy's numbers, ``(n,
    *shape)`` zeros of an array's dtype, else an object array of None."""
    if type(value) in (int, float, bool) or isinstance(value, np.number):
        return np.zeros(n, dtype=type(value))
    if isinstance(value, np.ndarray):
        return np.zeros((n, *value.shape), dtype=value.dtype)
    return np.full(n, None, dtype=object)


def outcome_names(outcomes: Sequence[str | None]) -> np.ndarray:
    """A task's outcome names by rule code as an object array to index with codes:
    :data:`~soccer_env.envs.flat_info.NO_OUTCOME` for code 0 (the episode goes on, as the
    single environments report it)."""
    names = np.empty(len(outcomes), dtype=object)
    names[:] = [NO_OUTCOME if o is None else o for o in outcomes]
    return names


def flat_outcome_codes(outcomes: Sequence[str | None]) -> np.ndarray:
    """The flat info's outcome codes (:data:`~soccer_env.envs.flat_info.OUTCOME_CODES`) by
    rule code, as float64."""
    return np.array([OUTCOME_CODES[NO_OUTCOME if o is None else o] for o in outcomes],
                    dtype=np.float64)


class EpisodeTable:
    """What each environment drew for its episode (a dict such as the Goalkeeper's shot), as
    one column per key (:func:`column`), for the infos: :meth:`set` at an episode's start,
    :attr:`columns` read at every step."""

    def __init__(self, n: int) -> None:
        self.n = n
        #: The columns by key, in the order of the first episode's dict.
        self.columns: dict[str, np.ndarray] = {}

    def set(self, k: int, drawn: dict[str, Any]) -> None:
        """Environment ``k``'s episode draws ``drawn``."""
        columns = self.columns
        for key, value in drawn.items():
            if key not in columns:
                columns[key] = column(value, self.n)
            columns[key][k] = value


class InfoParts(NamedTuple):
    """What a step's infos are made of, arrays over the batch's ``n`` environments.

    Attributes:
        times: ``(n,)`` each episode's time [s].
        ball: ``(n, 6)`` the true ball ``x, y, z, vx, vy`` [m, m/s] (column 5 unread).
        robots: ``(n, N, 6)`` the true robots ``x, y, theta, vx, vy, omega``.
        estimate: robot 0's belief at the present time, ``(times, ball, robots)`` laid out
            as the truth, or None when it is the truth.
        terms: ``(n, T)`` the step's reward terms (zeros at an episode's start).
        codes: ``(n,)`` the outcome's rule code (0 while the episode goes on).
        success: ``(n,)`` whether the outcome is a success (where ``terminated``).
        terminated: ``(n,)`` the episodes that terminated at this step.
        task: the task's own entries (:meth:`BatchedTask._task_entries`), columns or dicts of
            columns over the batch.
        robot_state: each environment's ``robot_state`` (humanoids), or None.
        fallen: ``(n,)`` robot 0 lies or gets up (humanoids; False for SSL robots).
    """

    times: np.ndarray
    ball: np.ndarray
    robots: np.ndarray
    estimate: tuple[np.ndarray, np.ndarray, np.ndarray] | None
    terms: np.ndarray
    codes: np.ndarray
    success: np.ndarray
    terminated: np.ndarray
    task: dict[str, Any]
    robot_state: list[dict[str, Any]] | None
    fallen: np.ndarray


class _Writer:
    """Puts columns and their masks into the infos of one build: ``mask`` the environments
    that report, ``keep`` the rows kept (None: all; the others are blanked to zero, False or
    None). The masks are rows of blocks filled once, each row its own memory."""

    __slots__ = ("mask", "keep", "_masks")

    def __init__(self, mask: np.ndarray, keep: np.ndarray | None) -> None:
        self.mask, self.keep = mask, keep
        self._masks = iter(())

    def _mask(self) -> np.ndarray:
        """The next mask: a row of the latest block of 64 (a new block when it is used up)."""
        row = next(self._masks, None)
        if row is None:
            block = np.empty((64, len(self.mask)), dtype=bool)
            block[:] = self.mask
            self._masks = iter(block)
            row = next(self._masks)
        return row

    def put(self, info: dict[str, Any], columns: dict[str, Any], fresh: bool = False) -> None:
        """Put ``columns`` into ``info``: each column (a copy unless ``fresh``: made for this
        info alone) blanked outside :attr:`keep`, or a dict of them, recursively; each beside
        its mask ``info["_" + key]``."""
        keep = self.keep
        for key, value in columns.items():
            if type(value) is dict:
                inner: dict[str, Any] = {}
                self.put(inner, value, fresh)
                value = inner
            else:
                if not fresh:
                    value = value.copy()
                if keep is not None:
                    value[~keep] = None if value.dtype == object else 0
            info[key] = value
            info["_" + key] = self._mask()


class BatchInfos:
    """Builds a batched task's infos (see the module docstring).

    Args:
        n: environments.
        names: the robots' names, in world order.
        term_names: the reward terms' names, in the single environment's order.
        outcomes: the task's outcome names by rule code (code 0: None, the episode goes
            on).
        flat: flat infos (``info_mode="flat"``).
        add_info: the vector environment's ``_add_info`` (Gymnasium's aggregation of one
            environment's info), for what comes one environment at a time (``robot_state``).
    """

    def __init__(self, n: int, names: Sequence[str], term_names: Sequence[str],
                 outcomes: Sequence[str | None], flat: bool,
                 add_info: Callable[[dict, dict, int], dict]) -> None:
        self.n = n
        self.names = tuple(names)
        self.term_names = tuple(term_names)
        self.flat = flat
        self._names = outcome_names(outcomes)
        self._codes = flat_outcome_codes(outcomes)
        self._add_info = add_info
        self._all = np.ones(n, dtype=bool)

    def build(self, parts: InfoParts, rows: np.ndarray | None = None) -> dict[str, Any]:
        """The infos of the environments ``rows`` (``(n,)`` bool; None: all) from ``parts``."""
        mask = self._all if rows is None else rows
        keep = None if rows is None or rows.all() else rows
        if self.flat:
            return self._flat(parts, mask, keep)
        return self._full(parts, mask, keep)

    def _state(self, times: np.ndarray, ball: np.ndarray, robots: np.ndarray
               ) -> dict[str, Any]:
        """``info["truth"]`` / ``info["estimate"]``'s columns (as
        :func:`~soccer_env.state.state_dict` lays out one environment's)."""
        return {"time": times, "ball_position": ball[:, 0:2], "ball_velocity": ball[:, 3:5],
                "ball_height": ball[:, 2],
                "robot_pose": {name: robots[:, i, 0:3] for i, name in enumerate(self.names)},
                "robot_velocity": {name: robots[:, i, 3:6]
                                   for i, name in enumerate(self.names)}}

    def _full(self, parts: InfoParts, mask: np.ndarray, keep: np.ndarray | None
              ) -> dict[str, Any]:
        """The full infos (the single environments' nested dicts, aggregated)."""
        info: dict[str, Any] = {}
        put = _Writer(mask, keep).put
        # (Each block copied once, its columns views of the copy: fresh.)
        times, ball, robots = parts.estimate or (parts.times, parts.ball, parts.robots)
        terms = parts.terms.copy()
        put(info, {"truth": self._state(parts.times.copy(), parts.ball.copy(),
                                        parts.robots.copy()),
                   "estimate": self._state(times.copy(), ball.copy(), robots.copy()),
                   "reward_terms": {name: terms[:, j]
                                    for j, name in enumerate(self.term_names)},
                   "outcome": self._names[parts.codes]}, True)
        put(info, parts.task)
        if parts.robot_state is not None:
            for k in np.nonzero(mask)[0].tolist():
                info = self._add_info(info, {"robot_state": parts.robot_state[k]}, k)
        ended = mask & parts.terminated
        if ended.any():
            _Writer(ended, None).put(info, {"is_success": parts.success & ended}, True)
        return info

    def _flat(self, parts: InfoParts, mask: np.ndarray, keep: np.ndarray | None
              ) -> dict[str, Any]:
        """The flat infos (:mod:`~soccer_env.envs.flat_info`'s keys, aggregated)."""
        ball, own = parts.ball, parts.robots[:, 0]
        _, eball, erobots = (parts.times, ball, parts.robots) if parts.estimate is None \
            else parts.estimate
        epose = erobots[:, 0]
        dx, dy = eball[:, 0] - ball[:, 0], eball[:, 1] - ball[:, 1]
        values = [parts.times, ball[:, 0], ball[:, 1], ball[:, 2], ball[:, 3], ball[:, 4],
                  own[:, 0], own[:, 1], own[:, 2], eball[:, 0], eball[:, 1], eball[:, 3],
                  eball[:, 4], epose[:, 0], epose[:, 1], epose[:, 2],
                  hypots(dx, dy),  # (math.hypot's, bit for bit, as flat_common's)
                  parts.fallen.astype(np.float64)]
        info: dict[str, Any] = {}
        put = _Writer(mask, keep).put
        put(info, dict(zip(COMMON_KEYS, values)))
        put(info, {f"reward_{name}": parts.terms[:, j]
                   for j, name in enumerate(self.term_names)})
        put(info, {"outcome": self._codes[parts.codes],
                   "is_success": (parts.terminated & parts.success).astype(np.float64)}, True)
        put(info, parts.task)
        return info
