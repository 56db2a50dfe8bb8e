"""The particle-filter benchmark of Xu, Xie, Wang and Ni (2012): the univariate
nonstationary growth model (UNGM).

``soccer-env paper ungm``: bootstrap PF, FBPF (as printed, resampling every step, and ours,
resampling below the threshold) and MFBPF (as printed, and with FBPF's test)
(:mod:`estimators.particle`) with 100 particles on ``runs`` simulated 50-step UNGM trajectories
(``x_0 ~ N(0, 10)``, process noise variance 10, measurement noise variance 1, ``N_th = 50``,
fission variance 1, as in the paper). Every filter sees the same trajectories and starts from
the same initial particles and generator state (one per run, seeded from ``seed``). Reports
the RMSE over each run's 50 steps (mean, standard deviation and median over runs), the share of
steps with ``N_eff < N_th`` (which decides each filter's SFN and resampling branch) and the
time per filter step, then paired differences of the RMSE, run by run, with their standard
errors: the runs are shared, so the paired difference removes the run-to-run spread of the
trajectories themselves, which is much larger than the filters' differences. The paper's
claim: MFBPF slightly better than FBPF (it gives a figure, not numbers).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from estimators import FBPF, MFBPF, BootstrapPF, ungm_model, ungm_simulate
from soccer_env.render.plots import pyplot, save_figure
from soccer_lab.papers.common import write_report

__all__ = ["run", "Settings", "FILTERS", "PAIRS", "PAPER_CLAIM", "paired_difference"]

PAPER_CLAIM = ("Xu et al. (2012), Fig. 12: with 100 particles, N_th = 50 and fission variance 1 "
               "on 50 UNGM steps, MFBPF's RMSE is slightly lower than FBPF's (no numbers given).")

#: Filters compared: name -> (description, constructor(particles, transition, likelihood, rng)).
FILTERS = {
    "bootstrap": ("bootstrap PF, resampling every step",
                  lambda p, t, lk, g: BootstrapPF(p, t, lk, g)),
    "fbpf": ("FBPF as printed (the default): SFN when N_eff < N_th, resampling every step",
             lambda p, t, lk, g: FBPF(p, t, lk, g, threshold=0.5, fission_variance=1.0,
                                      resample="always")),
    "fbpf-threshold": ("FBPF, SFN and resampling only when N_eff < N_th",
                       lambda p, t, lk, g: FBPF(p, t, lk, g, threshold=0.5,
                                                fission_variance=1.0, resample="threshold")),
    "mfbpf": ("MFBPF as printed: SFN when N_eff >= N_th, else copy-over resampling",
              lambda p, t, lk, g: MFBPF(p, t, lk, g, threshold=0.5, fission_variance=1.0)),
    "mfbpf-below": ("MFBPF with FBPF's test (N_eff < N_th)",
                    lambda p, t, lk, g: MFBPF(p, t, lk, g, threshold=0.5, fission_variance=1.0,
                                              sfn_when="below")),
}


#: Paired differences reported, ``(a, b, what the difference asks)``: RMSE of ``a`` minus ``b``.
PAIRS = (
    ("mfbpf", "fbpf", "the paper's claim, both as printed"),
    ("mfbpf", "fbpf-threshold", "MFBPF against FBPF resampling below the threshold"),
    ("fbpf-threshold", "fbpf", "resampling below the threshold against every step"),
    ("fbpf", "bootstrap", "does SFN help the printed FBPF?"),
)


def paired_difference(a: np.ndarray, b: np.ndarray) -> dict[str, float]:
    """Run-by-run difference ``d = a - b`` of two filters' RMSE on the same runs: its mean,
    standard error ``std(d, ddof=1) / sqrt(n)``, the normal 95 % interval
    ``mean +- 1.96 SE``, and the share of runs where ``a`` is lower."""
    d = np.asarray(a, dtype=np.float64) - np.asarray(b, dtype=np.float64)
    se = float(d.std(ddof=1) / math.sqrt(len(d))) if len(d) > 1 else math.nan
    mean = float(d.mean())
    return {"mean": mean, "se": se, "low": mean - 1.96 * se, "high": mean + 1.96 * se,
            "a_lower": float(np.mean(d < 0.0)), "equal": float(np.mean(d == 0.0))}


def _rmse_runs(runs: int, particles: int, steps: int, seed: int
               ) -> tuple[dict[str, np.ndarray], dict[str, Any], dict[str, float]]:
    """RMSE per run and filter, run 0's estimates, and each filter's share of steps with
    ``N_eff < N_th``."""
    transition, likelihood = ungm_model()
    rmse = {name: np.empty(runs) for name in FILTERS}
    below = dict.fromkeys(FILTERS, 0)
    example: dict[str, Any] = {}
    seeds = np.random.SeedSequence(seed).spawn(runs)
    for r in range(runs):
        sim_seed, filter_seed = seeds[r].spawn(2)
        _, xs, ys = ungm_simulate(steps, np.random.default_rng(sim_seed))
        init = np.random.default_rng(filter_seed)
        p0 = init.normal(0.0, math.sqrt(10.0), (particles, 1))
        state = init.bit_generator.state
        for name, (_, make) in FILTERS.items():
            rng = np.random.default_rng()
            rng.bit_generator.state = state  # the same draws for every filter
            f = make(p0, transition, likelihood, rng)
            est = np.empty(len(ys))
            for k, y in enumerate(ys):
                est[k] = f.step(y)[0]
                below[name] += f.n_eff < f.threshold * f.n
            rmse[name][r] = math.sqrt(float(np.mean((est - xs) ** 2)))
            if r == 0:
                example[name] = est
        if r == 0:
            example["truth"] = xs
    return rmse, example, {name: n / (runs * steps) for name, n in below.items()}


def _time_per_step(particles: int, repeats: int = 5, steps: int = 400) -> dict[str, float]:
    """Median over ``repeats`` of the mean time of one filter step [us] on UNGM."""
    transition, likelihood = ungm_model()
    out = {}
    for name, (_, make) in FILTERS.items():
        times = []
        for r in range(repeats):
            rng = np.random.default_rng(r)
            _, _, ys = ungm_simulate(steps, np.random.default_rng(100 + r))
            f = make(rng.normal(0.0, math.sqrt(10.0), (particles, 1)), transition, likelihood,
                     rng)
            t0 = time.perf_counter()
            for y in ys:
                f.step(y)
            times.append((time.perf_counter() - t0) / steps * 1e6)
        out[name] = float(np.median(times))
    return out


@dataclass(frozen=True)
class Settings:
    """What one run simulates (validated on construction).

    Attributes:
        out: the output folder.
        runs: simulated trajectories (>= 1).
        particles: particles per filter (>= 2).
        steps: steps per trajectory (>= 1).
        seed: seeds the trajectories and the filters' initial particles.
    """

    out: Path
    runs: int = 1000
    particles: int = 100
    steps: int = 50
    seed: int = 0

    def __post_init__(self) -> None:
        for name, lo in (("runs", 1), ("particles", 2), ("steps", 1)):
            value = getattr(self, name)
            if isinstance(value, bool) or int(value) != value or value < lo:
                raise ValueError(f"{name} must be an integer >= {lo}, got {value!r}")


def run(out: str | Path = "paper_output", runs: int = 1000, particles: int = 100,
        steps: int = 50, seed: int = 0) -> dict[str, Any]:
    """Run the benchmark, write ``paper_ungm.md``, ``.csv``, ``.json`` and ``.png`` into
    ``out`` and return ``{"text", "files", "seconds", "rmse", "us_per_step", "paired"}``
    (``paired``: :func:`paired_difference` for each of :data:`PAIRS`, keyed ``"a - b"``)."""
    settings = Settings(Path(out), runs, particles, steps, seed)
    t0 = time.perf_counter()
    settings.out.mkdir(parents=True, exist_ok=True)
    rmse, example, below = _rmse_runs(int(settings.runs), int(settings.particles),
                                      int(settings.steps), settings.seed)
    timing = _time_per_step(int(settings.particles))
    paired = {f"{a} - {b}": paired_difference(rmse[a], rmse[b]) for a, b, _ in PAIRS}
    text, rows = _tables(settings, rmse, timing, below, paired)
    files = write_report(settings.out, "paper_ungm", text, rows, {
        "runs": settings.runs, "particles": settings.particles, "steps": settings.steps,
        "seed": settings.seed, "rows": rows, "paired": paired, "share_below_n_th": below,
        "rmse_per_run": {k: v.tolist() for k, v in rmse.items()}})
    files.append(_plot(settings, rmse, example))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "rmse": {k: float(v.mean()) for k, v in rmse.items()}, "us_per_step": timing,
            "paired": paired}


# ------------------------------------------------------------------------------------------
# Report
# ------------------------------------------------------------------------------------------

def _tables(s: Settings, rmse: dict[str, np.ndarray], timing: dict[str, float],
            below: dict[str, float], paired: dict[str, dict[str, float]]
            ) -> tuple[str, list[dict[str, Any]]]:
    """The printed report and the CSV rows."""
    lines = [f"UNGM, Xu et al.'s (2012) benchmark: {s.runs} runs of {s.steps} steps, {s.particles} "
             "particles, N_th = N/2, fission variance 1; RMSE over each run (mean, standard "
             "deviation, median over runs), share of steps with N_eff < N_th, and time per "
             "filter step (median of 5 timings of 400 steps).",
             "",
             "| filter | RMSE mean | RMSE std | RMSE median | steps N_eff < N_th | us per step |",
             "|---|---|---|---|---|---|"]
    rows = []
    for name, (desc, _) in FILTERS.items():
        v = rmse[name]
        lines.append(f"| {name}: {desc} | {v.mean():.3f} | {v.std():.3f} | "
                     f"{np.median(v):.3f} | {below[name]:.0%} | {timing[name]:.1f} |")
        rows.append({"filter": name, "description": desc, "rmse_mean": float(v.mean()),
                     "rmse_std": float(v.std()), "rmse_median": float(np.median(v)),
                     "share_below_n_th": below[name], "us_per_step": timing[name]})
    lines += ["", f"Paired differences of the RMSE, run by run over the same {s.runs} runs "
              "(a minus b; negative: a lower). Standard error std(d)/sqrt(runs), 95 % "
              "interval mean +- 1.96 SE; 'differ' when the interval excludes 0.", "",
              "| a - b | question | mean | SE | 95 % interval | a lower in | differ |",
              "|---|---|---|---|---|---|---|"]
    for a, b, question in PAIRS:
        d = paired[f"{a} - {b}"]
        differ = "yes" if d["low"] > 0.0 or d["high"] < 0.0 else "no"
        lines.append(f"| {a} - {b} | {question} | {d['mean']:+.3f} | {d['se']:.3f} | "
                     f"{d['low']:+.3f} to {d['high']:+.3f} | {d['a_lower']:.0%} of runs | "
                     f"{differ} |")
    lines += ["", PAPER_CLAIM]
    return "\n".join(lines), rows


def _plot(s: Settings, rmse: dict[str, np.ndarray], example: dict[str, Any]) -> str:
    """Run 0's trajectory with the filters' estimates, and the RMSE per filter over runs."""
    from soccer_env.render.plots import (
        LABEL_SIZE,
        TICK_SIZE,
        TITLE_SIZE,
        colour_key,
        legend_beside,
        style_key,
    )

    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12.5, 4.6),
                                   gridspec_kw={"width_ratios": [1.4, 1.0]})
    names = list(FILTERS)
    colour = {n: f"C{k}" for k, n in enumerate(names)}
    ax1.plot(example["truth"], "k-", lw=2.2, label="true state")
    for name in names:
        if name in example:
            ax1.plot(example[name], lw=1.1, color=colour[name], label=name)
    ax1.set_xlabel("step k", fontsize=LABEL_SIZE)
    ax1.set_ylabel("state x_k (dimensionless)", fontsize=LABEL_SIZE)
    ax1.set_title("Run 0: the true state and each filter's estimate", fontsize=TITLE_SIZE)
    ax1.grid(alpha=0.3)
    box = ax2.boxplot([rmse[n] for n in names], patch_artist=True,
                      medianprops={"color": "k", "lw": 1.5},
                      flierprops={"marker": "o", "mfc": "none", "mec": "0.2", "ms": 5})
    for patch, name in zip(box["boxes"], names):
        patch.set(facecolor=colour[name], alpha=0.55, edgecolor="0.2")
    ax2.set_xticks(range(1, len(names) + 1), names, rotation=20, ha="right")
    ax2.set_ylabel(f"RMSE of x_k over {s.steps} steps", fontsize=LABEL_SIZE)
    ax2.set_title(f"RMSE per run: {s.runs} runs, {s.particles} particles",
                  fontsize=TITLE_SIZE)
    ax2.grid(axis="y", alpha=0.3)
    for ax in (ax1, ax2):
        ax.tick_params(labelsize=TICK_SIZE)
    fig.suptitle("Xu et al. (2012) particle-filter benchmark: the univariate nonstationary "
                 "growth model (UNGM)", fontsize=TITLE_SIZE)
    first = legend_beside(ax2, [style_key("true state", lw=2.2, color="k")]
                          + [colour_key(n, colour[n]) for n in names], title="filter")
    legend_beside(ax2, [style_key("median", color="k"),
                        colour_key("box: middle half of the runs", "0.75"),
                        style_key("run beyond the whiskers\n(1.5 box heights)", ls="None",
                                  marker="o", color="0.2", ms=5, mfc="none")],
                  title="box plot", below=first)
    return save_figure(fig, s.out / "paper_ungm.png")
