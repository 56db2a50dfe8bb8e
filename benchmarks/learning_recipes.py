"""The recipe study of learning under perception: one keeper per recipe, the same seeds and step
budget, each evaluated on the 1,000-shot suite.

Usage::

    python benchmarks/learning_recipes.py --preset ssl-2012 --steps 2000000 \
        [--recipes plain,belief,...] [--out runs/recipes] [--dry-run]

Every recipe is ``soccer-env train`` with the base recipe of the shipped keepers (PPO choosing
a point on the guard line 25 times a second, ``intercept`` shaping 2, ``log_std_init -0.5``,
``ent_coef 0.005``, perceived observations of ``--preset``, seed 0) plus its own options; the
model picked by the periodic evaluation on held-out shots (seeds 1,000,000 on) is then
evaluated with ``soccer-env eval`` on seeds 0-999 under the plain preset (with the recipe's
belief features where it has them). Each run's folder keeps its command, ``summary.json``
(training time) and ``suite.json``; the script prints a Markdown table of them all.
"""

from __future__ import annotations

import argparse
import json
import shlex
import subprocess
import sys
import time
from pathlib import Path

#: Sensor ranges of the randomised recipe: from ``ssl-2012``'s figures to ``realistic``'s.
RANDOMIZE = {"frame_rate": [25, 60], "latency": [0.045, 0.08], "ball_sigma": [0.0014, 0.025],
             "robot_sigma": [0.0013, 0.025], "ball_detection": [0.95, 1.0]}

#: Whole presets drawn per episode (cameras, noise, latency and command link together).
PRESETS = {"preset": ["ssl-2012", "realistic"]}


def _randomized(randomize: dict) -> list[str]:
    """The option that perceives through ``--preset``'s vision with ``randomize``."""
    return ["--env-kwarg", "perception=" + json.dumps({"vision": "{preset}",
                                                        "randomize": randomize})]


_RESIDUAL = ["--actions", "guard-residual"]
_BELIEF = ["--env-kwarg", "belief_features=true"]
_PRIVILEGED = ["--critic", "privileged"]

#: recipe -> (training options beyond the base, whether its observation has belief features,
#: description).
RECIPES: dict[str, tuple[list[str], bool, str]] = {
    "plain": ([], False, "PPO on the perceived observation"),
    "belief": (_BELIEF, True, "+ belief features"),
    "privileged": (_PRIVILEGED, False, "+ privileged critic"),
    "stack4": (["--frame-stack", "4"], False, "+ the last 4 observations"),
    "recurrent": (["--algo", "recurrent-ppo"], False, "RecurrentPPO (LSTM 64)"),
    "randomized": (_randomized(RANDOMIZE), False,
                   "+ sensor randomisation (ssl-2012 to realistic)"),
    "belief+privileged": (_BELIEF + _PRIVILEGED, True, "+ belief features + privileged critic"),
    "residual": (_RESIDUAL, False, "a correction to the scripted keeper's guard point"),
    "residual+belief+privileged": (_RESIDUAL + _BELIEF + _PRIVILEGED, True,
                                   "residual + belief features + privileged critic"),
    "residual+randomized": (_RESIDUAL + _randomized(RANDOMIZE), False,
                            "residual + sensor randomisation"),
    "residual+presets": (_RESIDUAL + _randomized(PRESETS), False,
                         "residual, each episode under ssl-2012 or realistic"),
    "residual+belief+presets": (_RESIDUAL + _BELIEF + _randomized(PRESETS), True,
                                "residual + belief features, each episode under ssl-2012 or "
                                "realistic"),
    "ball-residual+belief": (["--actions", "ball-residual", *_BELIEF], True,
                             "the scripted keeper acting on a learned correction of its "
                             "believed ball velocity, + belief features"),
    "belief+privileged+randomized": (_BELIEF + _PRIVILEGED + _randomized(RANDOMIZE), True,
                                     "+ belief features + privileged critic + randomisation"),
}

BASE = ["--obs-mode", "perceived", "--actions", "guard", "--env-kwarg", "control_dt=0.04",
        "--env-kwarg", 'shaping={"intercept": 2}', "--hp",
        'policy_kwargs={"log_std_init": -0.5}', "--hp", "ent_coef=0.005", "--seed", "0",
        "--no-progress"]


def commands(preset: str, recipe: str, steps: int, out: Path) -> tuple[list[str], list[str]]:
    """The training and the suite-evaluation command lines of ``recipe``."""
    extra, belief, _ = RECIPES[recipe]
    extra = [a.replace("{preset}", preset) for a in extra]
    run = out / preset / recipe
    randomized = any(a.startswith("perception=") for a in extra)
    # A randomised recipe's perception is its --env-kwarg (which --perception would replace);
    # it selects its model under the plain preset.
    train = ["soccer-env", "train", *([] if randomized else ["--perception", preset]), *BASE,
             *extra, "--steps", str(steps), "--out", str(run)]
    if randomized:
        train += ["--eval-perception", preset]
    evaluate = ["soccer-env", "eval", "--policy", str(run / "best_policy.npz"), "--obs-mode",
                "perceived", "--perception", preset, "--env-kwarg", "control_dt=0.04",
                "--episodes", "1000", "--video", "0", "--json", "--out", str(run / "suite")]
    if belief:
        evaluate += ["--env-kwarg", "belief_features=true"]
    return train, evaluate


def _runnable(command: list[str]) -> list[str]:
    """``command`` with ``soccer-env`` taken from this interpreter's environment when it has
    one (the script may run without the virtual environment activated)."""
    local = Path(sys.executable).parent / command[0]
    return [str(local), *command[1:]] if local.exists() else command


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--preset", default="ssl-2012")
    p.add_argument("--steps", type=int, default=2_000_000)
    p.add_argument("--recipes", default=",".join(RECIPES))
    p.add_argument("--out", default="runs/recipes")
    p.add_argument("--dry-run", action="store_true", help="print the commands only")
    p.add_argument("--table", action="store_true", help="only print the table of done runs")
    args = p.parse_args(argv)
    names = args.recipes.split(",")
    unknown = sorted(set(names) - set(RECIPES))
    if unknown:
        p.error(f"unknown recipe(s) {unknown}; known: {list(RECIPES)}")
    out = Path(args.out)
    for name in names if not args.table else []:
        train, evaluate = commands(args.preset, name, args.steps, out)
        run = out / args.preset / name
        if args.dry_run:
            print(shlex.join(train))
            print(shlex.join(evaluate))
            continue
        if not (run / "summary.json").exists():
            # A run that did not finish (no summary) is started again from scratch.
            again = ["--force"] if run.exists() else []
            subprocess.run(_runnable(train + again), check=True)
        if not (run / "suite.json").exists():
            t0 = time.perf_counter()
            res = subprocess.run(_runnable(evaluate), check=True, capture_output=True, text=True)
            record = json.loads(res.stdout)
            record["eval_seconds"] = time.perf_counter() - t0
            record["commands"] = [shlex.join(train), shlex.join(evaluate)]
            (run / "suite.json").write_text(json.dumps(record, indent=1))
    print(f"| recipe ({args.preset}, {args.steps:,} steps) | suite save rate (95 % CI) | "
          "training time | rollout steps/s |")
    print("|---|---|---|---|")
    for name in names:
        run = out / args.preset / name
        if not (run / "suite.json").exists():
            continue
        suite = json.loads((run / "suite.json").read_text())
        summary = json.loads((run / "summary.json").read_text())
        print(f"| {name}: {RECIPES[name][2]} | {100 * suite['save_rate']:.1f} % "
              f"({100 * suite['ci_low']:.1f}-{100 * suite['ci_high']:.1f}) | "
              f"{summary['seconds'] / 60:.1f} min | {summary['rollout_steps_per_s']:,.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
