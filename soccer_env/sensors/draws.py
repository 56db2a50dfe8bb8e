"""Random numbers drawn from generators in blocks: what the overhead vision's frames use
(:class:`~soccer_env.sensors.overhead.OverheadVision` and
:class:`~soccer_env.sensors.overhead_batch.OverheadVisionBatch`).

A frame needs a few dozen numbers, and one numpy call per frame would cost more than using
them: :class:`BlockDraws` draws :data:`DRAW_BLOCK` at a time from one generator and hands them
out as slices of its block; :class:`BatchDraws` does the same for many generators at once, in one
array, drawing each generator's numbers in the same blocks and handing them out in the same
order as a :class:`BlockDraws` of that generator would, so that a batched sensor gives each
field's single sensor's numbers bit for bit. The sequence is a function of the generator's
state and the requests alone, so runs stay reproducible.
"""

from __future__ import annotations

import numpy as np

__all__ = ["BlockDraws", "BatchDraws", "DRAW_BLOCK"]

#: Numbers drawn from a generator at a time (or more, for a larger request).
DRAW_BLOCK = 4096


class BlockDraws:
    """Standard normal and uniform ``[0, 1)`` numbers of one generator, drawn in blocks of
    :data:`DRAW_BLOCK` (see the module docstring).

    Args:
        rng: the generator.
    """

    BLOCK = DRAW_BLOCK

    def __init__(self, rng: np.random.Generator) -> None:
        self._rng = rng
        self._normal = np.zeros(0)
        self._n = 0
        self._uniform = np.zeros(0)
        self._u = 0

    def normals(self, k: int) -> np.ndarray:
        """The next ``k`` standard normal numbers ``(k,)`` (a read-only view of the block)."""
        if self._n + k > len(self._normal):
            self._normal = np.concatenate((self._normal[self._n:],
                                           self._rng.standard_normal(max(k, self.BLOCK))))
            self._normal.setflags(write=False)
            self._n = 0
        self._n += k
        return self._normal[self._n - k:self._n]

    def uniforms(self, k: int) -> np.ndarray:
        """The next ``k`` uniform numbers in ``[0, 1)`` ``(k,)`` (a read-only view of the
        block)."""
        if self._u + k > len(self._uniform):
            self._uniform = np.concatenate((self._uniform[self._u:],
                                            self._rng.random(max(k, self.BLOCK))))
            self._uniform.setflags(write=False)
            self._u = 0
        self._u += k
        return self._uniform[self._u - k:self._u]


class BatchDraws:
    """:class:`BlockDraws` of ``m`` generators, of one kind (``"normal"`` or ``"uniform"``):
    each field's numbers drawn in the same blocks as a single :class:`BlockDraws` and handed
    out in the same order, kept in one array.

    Args:
        m: the number of fields (generators).
        kind: ``"normal"`` (standard normal) or ``"uniform"`` (``[0, 1)``).
    """

    def __init__(self, m: int, kind: str) -> None:
        self._kind = kind
        self._buf = np.zeros((m, DRAW_BLOCK))
        self._len = np.zeros(m, dtype=np.int64)
        self._pos = np.zeros(m, dtype=np.int64)

    def clear(self, k: int) -> None:
        """Field ``k`` starts afresh (a new :class:`BlockDraws`): nothing drawn yet."""
        self._len[k] = self._pos[k] = 0

    def take(self, fields: np.ndarray, need: np.ndarray, rngs: list, local: np.ndarray,
             width: int, env: np.ndarray) -> np.ndarray:
        """Hand each of ``fields`` its ``need`` numbers; returns ``(F, width)``: frame ``f``
        (of field ``env[f]``, its ``local[f]``-th frame) gets its field's numbers
        ``local * width .. + width`` of this request."""
        short = self._pos[fields] + need > self._len[fields]
        for k, n in zip(fields[short].tolist(), need[short].tolist()):
            rng, pos, length = rngs[k], int(self._pos[k]), int(self._len[k])
            fresh = (rng.standard_normal(max(n, DRAW_BLOCK)) if self._kind == "normal"
                     else rng.random(max(n, DRAW_BLOCK)))
            kept = length - pos
            size = kept + len(fresh)
            if size > self._buf.shape[1]:
                self._buf = np.pad(self._buf, ((0, 0), (0, size - self._buf.shape[1])))
            self._buf[k, :kept] = self._buf[k, pos:length]
            self._buf[k, kept:size] = fresh
            self._pos[k], self._len[k] = 0, size
        base = self._pos[env] + local * width
        out = self._buf[env[:, None], base[:, None] + np.arange(width)]
        self._pos[fields] += need
        return out
