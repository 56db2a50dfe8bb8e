"""Figure helpers shared by the demo and the paper benchmarks (matplotlib, no display)."""

from __future__ import annotations

from pathlib import Path
from types import ModuleType

__all__ = ["pyplot", "save_figure"]

DPI = 110


def pyplot() -> ModuleType:
    """``matplotlib.pyplot`` on the file-only Agg backend (imported on first use: matplotlib is
    an optional dependency and slow to import)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, path: str | Path) -> str:
    """Lay out ``fig``, write it to ``path`` as PNG, close it and return the path."""
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    pyplot().close(fig)
    return str(path)
