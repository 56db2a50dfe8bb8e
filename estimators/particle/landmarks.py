"""Landmark positions by kind for localization from ambiguous sightings
(:class:`LandmarkTable`)."""

from __future__ import annotations

from collections.abc import Iterator, Mapping

import numpy as np

__all__ = ["LandmarkTable"]


class LandmarkTable(Mapping[str, np.ndarray]):
    """Landmark positions by kind [m] (a read-only mapping), validated once, with the layout
    of the candidates of a sequence of observed kinds cached (a robot sees the same few
    combinations of kinds again and again), for :meth:`~estimators.KLDLocalizer.update_kinds`.

    Args:
        table: kind -> ``(M_k, 2)`` positions of the landmarks of that kind [m] (one or more
            finite positions each).
    """

    def __init__(self, table: Mapping[str, np.ndarray]) -> None:
        positions: dict[str, np.ndarray] = {}
        for kind, value in table.items():
            pos = np.array(value, dtype=np.float64).reshape(-1, 2)
            if len(pos) == 0 or not np.isfinite(pos).all():
                raise ValueError(f"table[{kind!r}] must hold one or more finite (x, y) "
                                 f"positions")
            pos.flags.writeable = False
            positions[kind] = pos
        self.positions = positions
        self._layouts: dict[tuple[str, ...], tuple] = {}

    def __getitem__(self, kind: str) -> np.ndarray:
        return self.positions[kind]

    def __iter__(self) -> Iterator[str]:
        return iter(self.positions)

    def __len__(self) -> int:
        return len(self.positions)

    def layout(self, kinds: tuple[str, ...]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """For observations of ``kinds``: the candidates' ``x`` and ``y`` ((C,), every
        observation's candidates in turn) and how many each observation has ((m,), int64)."""
        lay = self._layouts.get(kinds)
        if lay is None:
            for kind in kinds:
                if kind not in self.positions:
                    raise ValueError(f"unknown landmark kind {kind!r}; the table has "
                                     f"{sorted(self.positions)}")
            cands = [self.positions[k] for k in kinds]
            counts = np.array([len(c) for c in cands], dtype=np.int64)
            L = np.concatenate(cands)
            lay = (np.ascontiguousarray(L[:, 0]), np.ascontiguousarray(L[:, 1]), counts)
            if len(self._layouts) < 4096:
                self._layouts[kinds] = lay
        return lay
