"""Command-line options shared by ``soccer-env train``, ``eval`` and ``ablation``."""

from __future__ import annotations

import argparse
import json
from collections.abc import Mapping
from typing import Any

__all__ = ["add_env_arguments", "env_kwargs_from_args", "key_values", "add_trust_argument"]


def add_trust_argument(p: argparse.ArgumentParser) -> None:
    """``--trust``: load the pickled parts of stable-baselines3 files (see
    :mod:`agents.model_files`)."""
    p.add_argument("--trust", action="store_true",
                   help="also load what only unpickling can read (a stable-baselines3 .zip's "
                        "serialized entries, *_vecnormalize.pkl statistics): unpickling runs "
                        "whatever code the file names, so only for files from a source you "
                        "trust (default: arrays and JSON only; .npz policies never need it)")


def key_values(items: list[str], what: str) -> dict[str, Any]:
    """``key=value`` pairs, values parsed as JSON where they parse (else kept as strings)."""
    out: dict[str, Any] = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise ValueError(f"{what} must be key=value, got {item!r}")
        try:
            out[key] = json.loads(value)
        except json.JSONDecodeError:
            out[key] = value
    return out


def add_env_arguments(p: argparse.ArgumentParser) -> None:
    """``--obs-mode``, ``--perception``, ``--ball-filter`` and ``--env-kwarg``."""
    p.add_argument("--obs-mode", choices=("truth", "raw", "perceived"), default=None,
                   help="observation mode (environment default: truth)")
    p.add_argument("--perception", default=None,
                   help="vision preset: ideal, ssl-2012, realistic, harsh")
    p.add_argument("--ball-filter", default=None,
                   help="ball filter of perceived observations (kf, kf-comp, ekf, ...)")
    p.add_argument("--env-kwarg", action="append", default=[], metavar="KEY=VALUE",
                   help="another environment keyword argument (value parsed as JSON), "
                        "repeatable, e.g. shaping='{\"intercept\": 1}'")


def env_kwargs_from_args(args: argparse.Namespace, base: Mapping[str, Any] | None = None
                         ) -> dict[str, Any]:
    """The environment keyword arguments given by :func:`add_env_arguments`'s options, over
    ``base``."""
    kwargs = dict(base or {})
    kwargs.update(key_values(args.env_kwarg, "--env-kwarg"))
    if args.obs_mode is not None:
        kwargs["obs_mode"] = args.obs_mode
    if args.perception is not None:
        kwargs["perception"] = args.perception
    if args.ball_filter is not None:
        perception = kwargs.get("perception")
        perception = (dict(perception) if isinstance(perception, Mapping)
                      else {} if perception is None else {"vision": perception})
        perception["ball_filter"] = args.ball_filter
        kwargs["perception"] = perception
    return kwargs
