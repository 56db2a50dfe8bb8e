"""What every layer of :mod:`agents` shares, below all of them (the standard library and
numpy only): pools of worker processes (:mod:`agents.common.processes`), Wilson's score
interval (:mod:`agents.common.stats`) and the argument checks of runs and adapters
(:mod:`agents.common.checks`). The layers of ``agents`` are listed in :mod:`agents`."""

from __future__ import annotations

from agents.common.checks import check_counts, check_full_infos
from agents.common.processes import (
    ignore_interrupts,
    map_jobs,
    process_context,
    process_pool,
    resolve_workers,
)
from agents.common.stats import t975, wilson

__all__ = ["check_counts", "check_full_infos", "ignore_interrupts", "map_jobs",
           "process_context", "process_pool", "resolve_workers", "t975", "wilson"]
