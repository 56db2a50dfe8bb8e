"""Trained policies shipped with the package.

Each baseline is a :class:`~agents.policies.NumpyPolicy` (``NAME.npz``: the actor's weights,
a few tens of kB, run with numpy alone) and the stable-baselines3 model it was copied from
(``NAME.zip``, for fine-tuning with ``soccer-env train --resume``-style loading). The
``.npz`` carries the training configuration and its evaluation in ``policy.meta``.

>>> from agents.baselines import load_baseline
>>> keeper = load_baseline("keeper-ppo-ssl2012")       # doctest: +SKIP
>>> action = keeper(obs)                               # doctest: +SKIP
"""

from __future__ import annotations

from pathlib import Path

from ..policies import NumpyPolicy

__all__ = ["BASELINES", "load_baseline", "baseline_path"]

_HERE = Path(__file__).parent

#: Shipped baselines: name -> (file stem, description).
BASELINES: dict[str, tuple[str, str]] = {}


def baseline_path(name: str, kind: str = "npz") -> Path:
    """The file of baseline ``name``: ``kind="npz"`` (numpy policy) or ``"zip"`` (the
    stable-baselines3 model)."""
    if name not in BASELINES:
        raise ValueError(f"unknown baseline {name!r}; shipped: {sorted(BASELINES)}")
    if kind not in ("npz", "zip"):
        raise ValueError(f"kind must be 'npz' or 'zip', got {kind!r}")
    return _HERE / f"{BASELINES[name][0]}.{kind}"


def load_baseline(name: str) -> NumpyPolicy:
    """The shipped policy ``name`` (see :data:`BASELINES`), ready to call on observations."""
    return NumpyPolicy.load(baseline_path(name))
