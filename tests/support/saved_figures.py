"""The figures a module saves, kept for tests that read them."""

from __future__ import annotations

from types import ModuleType
from typing import Any


def saved_figures(monkeypatch: Any, module: ModuleType) -> list:
    """Every figure ``module`` saves through its ``save_figure`` from now on (the test's
    ``monkeypatch`` undoes it), laid out as written."""
    figures = []
    save = module.save_figure

    def keep(fig, path):
        out = save(fig, path)
        figures.append(fig)
        return out

    monkeypatch.setattr(module, "save_figure", keep)
    return figures
