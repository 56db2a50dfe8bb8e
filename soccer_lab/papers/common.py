"""What the paper reproductions share: checking their settings (:func:`check_count`), running
their episodes over processes (:func:`map_jobs`), and writing their tables (:func:`write_csv`,
:func:`write_report`: Markdown, CSV and JSON files)."""

from __future__ import annotations

import csv
import json
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["check_count", "write_csv", "write_report", "map_jobs", "lock_on"]


def check_count(name: str, value: Any, lo: int, hi: int) -> int:
    """``value`` as an ``int`` if it is an integer (not a bool) in ``[lo, hi]``, else
    ``ValueError`` naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) \
            or not lo <= value <= hi:
        raise ValueError(f"{name} must be an integer in [{lo}, {hi}], got {value!r}")
    return int(value)


def lock_on(err: np.ndarray, start: int, stop: int, threshold: float, hold: int
            ) -> int | None:
    """Steps from ``start`` until the error ``err`` stays below ``threshold`` for ``hold``
    steps in a row, before ``stop``; None if it never does."""
    run = 0
    for k in range(start, stop):
        run = run + 1 if err[k] < threshold else 0
        if run >= hold:
            return k - hold + 1 - start
    return None


def map_jobs(fn: Callable[[Any], Any], jobs: Sequence[Any], workers: int | None) -> list[Any]:
    """``[fn(job) for job in jobs]``, in order, over ``workers`` processes (None: every core;
    one, or a single job: in this process). ``fn`` must be a module-level function."""
    from agents.common.processes import map_jobs as run

    return run(fn, jobs, workers or None)


def write_csv(path: Path, rows: list[dict[str, Any]]) -> None:
    """``rows`` (dicts) as a CSV file with a header: every key of any row, in order of first
    appearance (a row without a key leaves its cell empty)."""
    fields = list(dict.fromkeys(k for row in rows for k in row))
    with path.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)


def write_report(out: Path, stem: str, text: str, rows: list[dict[str, Any]],
                 data: dict[str, Any]) -> list[str]:
    """``out/stem.md`` (``text``), ``.csv`` (``rows``) and ``.json`` (``data``); returns
    their paths."""
    paths = [out / f"{stem}.md", out / f"{stem}.csv", out / f"{stem}.json"]
    paths[0].write_text(text + "\n")
    write_csv(paths[1], rows)
    paths[2].write_text(json.dumps(data, indent=1, default=str))
    return [str(p) for p in paths]
