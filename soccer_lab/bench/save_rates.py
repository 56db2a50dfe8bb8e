"""The keepers' save rates (``python benchmarks/keeper_save_rate.py``): the scripted keeper
and a keeper that stands still on Goalkeeper-v0's seeded shots
(:func:`agents.runs.evaluation.evaluate`)."""

from __future__ import annotations

from typing import Any

__all__ = ["keeper_save_rates", "format_save_rates", "save_rate_main"]


def keeper_save_rates(episodes: int = 300, field: str = "ssl-div-b", workers: int | None = None,
                      policies: tuple[str, ...] = ("scripted", "idle")) -> dict[str, Any]:
    """The evaluation (:class:`~agents.runs.evaluation.EvalResult`) of each of ``policies`` on
    Goalkeeper-v0's shots of seeds ``0 .. episodes - 1`` on ``field``, truth observations, in
    ``workers`` processes (default: all cores; the result does not depend on it)."""
    import os

    from agents.runs.evaluation import evaluate

    workers = workers or os.cpu_count() or 1
    return {name: evaluate(name, {"field": field}, episodes, workers=workers)
            for name in policies}


def format_save_rates(results: dict[str, Any]) -> str:
    """One line per policy: save rate, Wilson 95 % interval and outcomes (commonest first)."""
    lines = []
    for name, res in results.items():
        outcomes = dict(sorted(res.outcomes.items(), key=lambda kv: (-kv[1], kv[0])))
        lines.append(f"{name:9s} save rate {res.save_rate:6.1%} (95 % CI {res.ci_low:.1%}-"
                     f"{res.ci_high:.1%}) over {res.episodes} shots: {outcomes}")
    return "\n".join(lines)


def save_rate_main(argv: list[str] | None = None) -> int:
    """Entry point of ``benchmarks/keeper_save_rate.py``."""
    import argparse
    import os

    from soccer_env.presets import FIELDS
    from soccer_lab.cli_args import HelpFormatter

    p = argparse.ArgumentParser(description="Save rate of the scripted keeper and of a keeper "
                                            "that stands still on Goalkeeper-v0.",
                                formatter_class=HelpFormatter)
    p.add_argument("--episodes", type=int, default=300, help="shots, seeds 0 onwards")
    p.add_argument("--field", default="ssl-div-b", choices=list(FIELDS), help="field preset")
    p.add_argument("--workers", type=int, default=None,
                   help="processes; the result does not depend on it (default: all cores)")
    args = p.parse_args(argv)
    workers = (os.cpu_count() or 1) if args.workers is None else args.workers
    if args.episodes < 1 or workers < 1:
        p.error("--episodes and --workers must be >= 1")
    print(format_save_rates(keeper_save_rates(args.episodes, args.field, workers)))
    return 0
