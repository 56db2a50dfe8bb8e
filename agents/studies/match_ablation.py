"""The estimator ablation in matches: does a better estimator win games?
(``soccer-env ablation --env soccer_env/Match-v0``).

For each pair ``A:B`` of estimator configurations (names of
:data:`agents.studies.ablation_settings.ESTIMATOR_CONFIGS`, or for humanoids of
:data:`agents.studies.ablation_settings.HUMANOID_CONFIGS`) and each sensor preset, two teams
with the same policy (the scripted team unless told otherwise) play ``matches`` seeded
matches, one team perceiving through configuration ``A``, the other through ``B``, under the
same preset (for SSL teams the same camera frames, filtered each team its own way). Colours
swap every other match, so every seed is played from both sides
(:func:`agents.studies.matches.head_to_head`). The same seeds are used for every pair and
preset.

Each cell reports ``A``'s wins, draws and losses with Wilson 95 % intervals of their rates,
goals for and against, the goal difference per match with its paired 95 % interval, and each
team's ball-belief error (mean and RMS over the team's beliefs at every step).

Outputs (:func:`write_outputs`): ``match_ablation.md`` (the table and the command),
``match_ablation.csv`` (one row per cell), ``match_ablation.json`` (settings and every
match's score and errors) and ``match_ablation.png`` (goal difference with its interval and
W/D/L shares per cell).
"""

from __future__ import annotations

import json
import os
import shlex
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import soccer_env
from agents.common.processes import resolve_workers
from agents.policies.base import describe_policy
from agents.studies.ablation_report import write_files
from agents.studies.ablation_settings import (
    DEFAULT_HUMANOID,
    EstimatorConfig,
    parse_names,
    robot_kind,
)
from agents.studies.matches import (
    HeadToHead,
    Side,
    match_env_kwargs,
    match_jobs,
    run_match_jobs,
    team_policy,
)
from soccer_env.envs.registration import MATCH_ID

__all__ = ["DEFAULT_PAIRS", "DEFAULT_MATCH_PRESETS", "DEFAULT_TEAM_SIZE",
           "DEFAULT_DURATION", "DEFAULT_MATCHES", "MatchAblationResult", "run_match_ablation",
           "parse_pairs", "write_outputs", "plot", "figure"]

#: The pairs played unless told otherwise, per robot kind: the paper's EKF against raw
#: detections and against the KF without latency compensation; a humanoid team's Hough
#: fusion with MFBPF tracking against each robot's own sightings.
DEFAULT_PAIRS = {"ssl": (("ekf", "raw"), ("ekf", "kf")),
                 "humanoid": (("fusion-mfbpf", "own"),)}
#: The sensor presets played unless told otherwise, per robot kind.
DEFAULT_MATCH_PRESETS = {"ssl": ("ssl-2012", "realistic"), "humanoid": ("kidsize-2012",)}
#: Robots per team. With two scripted SSL teams of three (a keeper, an attacker, a defender)
#: a 300 s match has about five goals (seeds 0-7 with the truth: 0 to 11); teams of two
#: score about one goal in four matches and teams of six almost never, so most matches
#: would be draws and tell the estimators apart only through many more of them.
DEFAULT_TEAM_SIZE = 3
#: Match length [s].
DEFAULT_DURATION = 300.0
#: Matches per pair and preset.
DEFAULT_MATCHES = 100
#: Environment keyword arguments the ablation sets itself.
_OWN_KEYS = ("blue", "yellow", "match_duration", "obs_mode", "perception")


def parse_pairs(value: str | Iterable[str | Sequence[str]] | None, allowed: Iterable[str],
                robot: str = "ssl") -> list[tuple[str, str]]:
    """Pairs of configuration names from ``"a:b,c:d"`` or a sequence of ``"a:b"`` strings or
    ``(a, b)`` tuples (None: :data:`DEFAULT_PAIRS` of ``robot``). ``ValueError`` for an
    unknown name (listing the allowed ones), a malformed or repeated pair, or no pair."""
    allowed = list(allowed)
    if value is None:
        return list(DEFAULT_PAIRS[robot])
    items = ([v.strip() for v in value.split(",") if v.strip()] if isinstance(value, str)
             else list(value))
    if not items:
        raise ValueError("no configuration pair given; write pairs as A:B,C:D")
    pairs = []
    for item in items:
        parts = item.split(":") if isinstance(item, str) else list(item)
        parts = [str(p).strip() for p in parts]
        if len(parts) != 2 or not all(parts):
            raise ValueError(f"a configuration pair is written A:B, got {item!r}")
        for name in parts:
            if name not in allowed:
                raise ValueError(f"unknown estimator configuration {name!r} in pair {item!r}; "
                                 f"allowed: {','.join(allowed)}")
        pairs.append((parts[0], parts[1]))
    dupes = sorted({f"{a}:{b}" for a, b in pairs if pairs.count((a, b)) > 1})
    if dupes:
        raise ValueError(f"pair(s) given more than once: {', '.join(dupes)}")
    return pairs


def _side(config: EstimatorConfig, preset: str, policy: Any) -> Side:
    """A team playing ``policy`` and perceiving through ``config`` under ``preset``."""
    if config.env_kwargs:
        raise ValueError(f"configuration {config.name!r} sets environment keyword arguments "
                         f"{sorted(config.env_kwargs)}, which a match shares between both "
                         "teams; it cannot be one team's configuration")
    perception = config.make_env_kwargs(preset)["perception"]
    return Side(policy, config.obs_mode, perception, label=config.name)


@dataclass
class MatchAblationResult:
    """The outcome of :func:`run_match_ablation`.

    Attributes:
        robot: ``"ssl"`` or ``"humanoid"``.
        policy: the team policy both sides play.
        pairs: ``(A, B)`` configuration names, in table order.
        presets: sensor presets, in table order.
        matches, start_seed: matches per cell (seeds ``start_seed .. start_seed + (matches -
            1) // 2``, each from both sides).
        team_size, duration: robots per team and match length [s].
        cells: ``(preset, "A:B") -> HeadToHead``.
        config_specs: the configurations as they were run.
        env_kwargs: further keyword arguments shared by every match.
        workers: processes (the numbers do not depend on them).
        seconds: wall time [s].
    """

    robot: str
    policy: str
    pairs: list[tuple[str, str]]
    presets: list[str]
    matches: int
    start_seed: int
    team_size: int
    duration: float
    cells: dict[tuple[str, str], HeadToHead]
    config_specs: dict[str, EstimatorConfig]
    env_kwargs: dict[str, Any]
    workers: int
    seconds: float

    def cell(self, preset: str, a: str, b: str) -> HeadToHead:
        """The matches of ``a`` against ``b`` under ``preset``."""
        return self.cells[(preset, f"{a}:{b}")]

    def command(self) -> str:
        """A ``soccer-env ablation`` command line that reruns this ablation."""
        args = ["soccer-env", "ablation", "--env", MATCH_ID]
        if self.robot != "ssl":
            args += ["--robot", self.robot]
        args += ["--pairs", ",".join(f"{a}:{b}" for a, b in self.pairs), "--presets",
                 ",".join(self.presets), "--matches", str(self.matches), "--team-size",
                 str(self.team_size), "--duration", f"{self.duration:g}"]
        if self.start_seed:
            args += ["--start-seed", str(self.start_seed)]
        if self.policy != "scripted":
            args += ["--policy", self.policy]
        for key, value in self.env_kwargs.items():
            if not (self.robot == "humanoid" and key == "robot" and value == DEFAULT_HUMANOID):
                args += ["--env-kwarg", f"{key}={json.dumps(value)}"]
        args += ["--workers", str(self.workers)]
        return shlex.join(args)

    def rows(self) -> list[dict[str, Any]]:
        """One flat row per cell (preset-major), as in ``match_ablation.csv``."""
        out = []
        for preset in self.presets:
            for a, b in self.pairs:
                h = self.cell(preset, a, b)
                gd = h.goal_difference()
                row: dict[str, Any] = {"preset": preset, "a": a, "b": b,
                                       "matches": h.matches, "wins": h.wins,
                                       "draws": h.draws, "losses": h.losses}
                for o in ("wins", "draws", "losses"):
                    rate, lo, hi = h.rate(o)
                    row.update({f"{o}_rate": rate, f"{o}_ci_low": lo, f"{o}_ci_high": hi})
                row.update({"goals_for": h.goals_for, "goals_against": h.goals_against,
                            "goal_difference": gd[0], "gd_ci_low": gd[1], "gd_ci_high": gd[2]})
                for side, name in ((0, "a"), (1, "b")):
                    mean, rms = h.ball_error(side)
                    row.update({f"{name}_ball_error_mean_mm": 1000 * mean,
                                f"{name}_ball_error_rms_mm": 1000 * rms})
                row.update({"steps": h.steps, "seconds": h.seconds})
                out.append(row)
        return out

    def to_dict(self) -> dict[str, Any]:
        """Settings, configurations and every match (``match_ablation.json``)."""
        return {
            "settings": {
                "env_id": MATCH_ID, "robot": self.robot, "policy": self.policy,
                "pairs": [list(p) for p in self.pairs], "presets": self.presets,
                "matches": self.matches, "start_seed": self.start_seed,
                "team_size": self.team_size, "duration_s": self.duration,
                "env_kwargs": self.env_kwargs, "workers": self.workers,
                "command": self.command(),
                "sides": "match k: seed start_seed + k // 2, A plays blue when k is even",
                "intervals": "W/D/L: Wilson score, 95 %; goal difference: Student t over "
                             "seeds (each seed's two matches one paired unit), 95 %",
            },
            "configs": {n: c.to_dict() for n, c in self.config_specs.items()},
            "cells": [{"preset": p, "pair": key, **self.cells[(p, key)].to_dict()}
                      for p in self.presets for key in (f"{a}:{b}" for a, b in self.pairs)],
            "seconds": self.seconds,
        }

    def markdown(self) -> str:
        """The table of ``match_ablation.md``."""
        kind = "SSL" if self.robot == "ssl" else "humanoid"
        first, last = self.start_seed, self.start_seed + (self.matches - 1) // 2
        lines = [
            "# Estimator ablation in matches", "",
            f"Two {kind} teams of {self.team_size} playing `{self.policy}`, one perceiving "
            f"through configuration A, the other through B, under the same sensor preset; "
            f"{self.matches} matches of {self.duration:g} s per cell (seeds {first}-{last}, "
            "each played with A blue and with A yellow). W/D/L from A's side with Wilson 95 % "
            "intervals; goal difference A - B per match with a 95 % interval paired by seed; "
            "ball error: each team's belief against the true ball over every step, mean / "
            "RMS.", "",
            f"Command: `{self.command()}` ({self.seconds:.0f} s wall time).", "",
            "| preset | A | B | A wins [%] | draws [%] | B wins [%] | goals A : B | goal "
            "difference per match | A ball error [mm] | B ball error [mm] |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        for preset in self.presets:
            for a, b in self.pairs:
                h = self.cell(preset, a, b)
                gd, lo, hi = h.goal_difference()
                ea, eb = h.ball_error(0), h.ball_error(1)
                lines.append(
                    f"| {preset} | {a} | {b} | {_pct(h.rate('wins'))} | "
                    f"{_pct(h.rate('draws'))} | {_pct(h.rate('losses'))} | "
                    f"{h.goals_for} : {h.goals_against} | {gd:+.2f} ({lo:+.2f} to {hi:+.2f}) "
                    f"| {_mm(ea)} | {_mm(eb)} |")
        lines += ["", "Estimator configurations:", ""]
        for name, spec in self.config_specs.items():
            src = f" Source: {spec.source}." if spec.source else ""
            lines.append(f"- `{name}` ({spec.obs_mode}): {spec.description}.{src}")
        presets = robot_kind(self.robot).presets
        lines += ["", "Sensor presets:", ""]
        lines += [f"- `{p}`: {presets[p].source}." for p in self.presets]
        return "\n".join(lines)


def _pct(rate: tuple[float, float, float]) -> str:
    return f"{100 * rate[0]:.0f} ({100 * rate[1]:.0f}-{100 * rate[2]:.0f})"


def _mm(err: tuple[float, float]) -> str:
    return f"{1000 * err[0]:.0f} / {1000 * err[1]:.0f}"


def run_match_ablation(pairs: str | Iterable[Any] | None = None,
                       presets: str | Sequence[str] | None = None,
                       matches: int = DEFAULT_MATCHES,
                       robot: str = "ssl", team_size: int = DEFAULT_TEAM_SIZE,
                       duration: float = DEFAULT_DURATION, start_seed: int = 0,
                       workers: int | None = None, policy: Any = "scripted",
                       env_kwargs: Mapping[str, Any] | None = None,
                       progress: Callable[[int, int], None] | None = None
                       ) -> MatchAblationResult:
    """Play every pair of estimator configurations against each other under every preset.

    Args:
        pairs: ``"A:B,C:D"`` or a sequence of pairs (default: :data:`DEFAULT_PAIRS`).
        presets: sensor presets of the robot kind (default: :data:`DEFAULT_MATCH_PRESETS`;
            ``"all"``: every one).
        matches: matches per cell (>= 1; even plays every seed from both sides).
        robot: ``"ssl"`` or ``"humanoid"`` (robot ``humanoid-2012`` on its field unless
            ``env_kwargs`` names another humanoid).
        team_size: robots per team (1..11).
        duration: match length [s] (> 0).
        start_seed: the first seed.
        workers: processes (None: all cores); the numbers do not depend on it.
        policy: the team policy of both sides (a :class:`~agents.studies.matches.Side` policy).
        env_kwargs: further match keyword arguments shared by every match (e.g. ``field``,
            ``formation_jitter``); not the team sizes, ``match_duration``, ``obs_mode`` or
            ``perception``.
        progress: called as ``progress(done, total)`` after each match.

    Raises:
        ValueError: unknown names, a malformed pair, counts out of range or a refused
            keyword argument.
    """
    kind = robot_kind(robot)
    pair_list = parse_pairs(pairs, kind.configs, robot)
    preset_names = parse_names(DEFAULT_MATCH_PRESETS[robot] if presets is None else presets,
                               kind.presets, "sensor preset(s)")
    if isinstance(team_size, bool) or int(team_size) != team_size or not 1 <= team_size <= 11:
        raise ValueError(f"team_size must be an integer in 1..11, got {team_size!r}")
    if not (isinstance(duration, (int, float)) and 0 < duration < float("inf")):
        raise ValueError(f"duration must be a positive number of seconds, got {duration!r}")
    base = dict(env_kwargs or {})
    refused = sorted(set(_OWN_KEYS) & set(base))
    if refused:
        raise ValueError(f"env_kwargs must not set {refused}: the ablation sets the team "
                         "sizes (team_size), the match length (duration) and each team's "
                         "perception")
    if robot == "humanoid":
        base.setdefault("robot", DEFAULT_HUMANOID)
    shared = {**base, "blue": int(team_size), "yellow": int(team_size),
              "match_duration": float(duration)}
    specs = {n: kind.configs[n] for pair in pair_list for n in pair}
    keys, jobs = [], []
    for preset in preset_names:
        for a, b in pair_list:
            key = (preset, f"{a}:{b}")
            cell_jobs = match_jobs(_side(specs[a], preset, policy),
                                   _side(specs[b], preset, policy), matches, start_seed,
                                   shared)
            keys += [key] * len(cell_jobs)
            jobs += cell_jobs
    _probe(jobs[0])
    workers = resolve_workers(workers)
    t0 = time.perf_counter()
    records = run_match_jobs(jobs, workers, progress)
    cells: dict[tuple[str, str], HeadToHead] = {}
    for key, job, rec in zip(keys, jobs, records):
        if key not in cells:
            cells[key] = HeadToHead(job[1], job[2], [], shared)
        cells[key].records.append(rec)
    return MatchAblationResult(robot, describe_policy(policy), pair_list, preset_names,
                               int(matches), int(start_seed), int(team_size), float(duration),
                               cells, specs, base, workers, time.perf_counter() - t0)


def _probe(job: tuple) -> None:
    """Build the first match and its team policies here, so that bad input fails before any
    work starts, with the environment's own message."""
    env_kwargs, a, b, _, _ = job
    env = soccer_env.parallel_env(**match_env_kwargs(env_kwargs, a, b))
    try:
        team_policy(a.policy, env, "blue")
        team_policy(b.policy, env, "yellow")
    finally:
        env.close()


# ------------------------------------------------------------------------------------------
# Outputs
# ------------------------------------------------------------------------------------------

def plot(res: MatchAblationResult, path: Path) -> str:
    """Write :func:`figure` of ``res`` to ``path`` (PNG); return the path."""
    from soccer_env.render.plots import save_figure

    return save_figure(figure(res), path)


def figure(res: MatchAblationResult) -> Any:
    """Per cell (a row: pair and preset): A's goal difference per match with its interval,
    and the W/D/L shares; legends above the panels, the title naming the teams, the robots and
    the field.

    Returns:
        The :class:`matplotlib.figure.Figure` (constrained layout; :func:`plot` saves it).
    """
    import numpy as np

    from soccer_env.render.plots import (
        LABEL_SIZE,
        TICK_SIZE,
        TITLE_SIZE,
        describe_world,
        interval_key,
        legend_above,
        pyplot,
        style_key,
    )

    plt = pyplot()
    labels = [f"A {a} vs B {b}\npreset {p}" for p in res.presets for a, b in res.pairs]
    cells = [res.cell(p, a, b) for p in res.presets for a, b in res.pairs]
    y = np.arange(len(cells))[::-1]
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 2.2 + 0.7 * len(cells)), sharey=True,
                             layout="constrained")
    gd = np.array([c.goal_difference() for c in cells])
    bounded = np.isfinite(gd[:, 1]) & np.isfinite(gd[:, 2])
    err = np.abs(gd[:, 1:] - gd[:, :1]).T
    keys = []
    if bounded.any():
        axes[0].errorbar(gd[bounded, 0], y[bounded], xerr=err[:, bounded], fmt="o",
                         capsize=3, color="tab:blue")
        keys.append(interval_key("mean, 95 % interval", marker="o", horizontal=True,
                                 color="tab:blue"))
    if not bounded.all():  # one seed: no interval
        axes[0].plot(gd[~bounded, 0], y[~bounded], "o", mfc="none", color="tab:blue")
        keys.append(style_key("mean (one seed: no interval)", ls="None", marker="o",
                              color="tab:blue", mfc="none"))
    axes[0].axvline(0.0, color="grey", lw=1, ls="--")
    keys.append(style_key("no difference", ls="--", lw=1, color="grey"))
    axes[0].set_xlabel("goal difference A - B per match", fontsize=LABEL_SIZE)
    axes[0].set_yticks(y, labels)
    shares = np.array([[c.rate(o)[0] for o in ("wins", "draws", "losses")] for c in cells])
    left = np.zeros(len(cells))
    for j, (name, color) in enumerate((("A wins", "tab:green"), ("draws", "tab:grey"),
                                       ("B wins", "tab:red"))):
        axes[1].barh(y, 100 * shares[:, j], left=left, color=color, label=name)
        left += 100 * shares[:, j]
    axes[1].set_xlim(0, 100)
    axes[1].set_xlabel("share of matches [%]", fontsize=LABEL_SIZE)
    legend_above(axes[0], keys)
    legend_above(axes[1])
    kwargs = dict(res.env_kwargs)
    robot = kwargs.get("robot", DEFAULT_HUMANOID if res.robot == "humanoid" else "ssl")
    fig.suptitle(f"Estimators in matches on {MATCH_ID.split('/')[-1]}: two {res.policy} teams "
                 f"of {res.team_size}, {res.duration:g} s matches, {res.matches} per row\n"
                 f"{describe_world(robot, kwargs.get('field'))}", fontsize=TITLE_SIZE)
    for ax in axes:
        ax.grid(axis="x", alpha=0.3)
        ax.tick_params(labelsize=TICK_SIZE)
    return fig


def write_outputs(res: MatchAblationResult, out: str | os.PathLike) -> dict[str, Path]:
    """Write ``match_ablation.md``, ``.csv``, ``.json`` and ``.png`` to ``out``; return their
    paths by kind."""
    return write_files(out, "match_ablation", res.markdown(), res.rows(), res.to_dict(),
                       lambda path: plot(res, path))
