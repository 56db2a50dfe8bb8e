"""RL Baselines3 Zoo: the shipped keeper's PPO recipe from ``hyperparams/ppo.yml``.

    pip install rl_zoo3==2.9.2
    python examples/rl_zoo3_keeper.py [--tiny] [--log-folder logs]

Two runs of ``python -m rl_zoo3.train``, as the shipped keeper ``keeper-ppo-ssl2012`` was
trained (``soccer-env train``; agents/baselines): 1 M steps on true observations with the
hyperparameters, action map (``agents.policies.wrappers.GuardActions``), observation
normalisation and environment arguments of ``hyperparams/ppo.yml``, then 5 M more on perceived
observations (``ssl-2012`` vision, the EKF) with an entropy bonus, continuing from the first
run's model and normalisation statistics (``-i``). ``--tiny`` runs one rollout of each (4,096
steps). The commands are printed; run them yourself to change anything (``-params
key:value``).
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

from soccer_env.envs.registration import GOALKEEPER_ID

ENV_ID = GOALKEEPER_ID
HYPERPARAMS = Path(__file__).resolve().parent.parent / "hyperparams" / "ppo.yml"
PERCEIVED = ["obs_mode:'perceived'", "perception:'ssl-2012'", "control_dt:0.04",
             "shaping:{'intercept':2.0}"]


def latest_run(folder: Path) -> Path:
    """The newest run folder the Zoo made for the keeper under ``folder``."""
    runs = list((folder / "ppo").glob("soccer_env-Goalkeeper-v0_*"))
    if not runs:
        raise FileNotFoundError(f"no rl_zoo3 run of {ENV_ID} under {folder}")
    return max(runs, key=lambda p: int(re.sub(r".*_", "", p.name)))


def zoo(args: list[str]) -> None:
    command = [sys.executable, "-m", "rl_zoo3.train", "--algo", "ppo", "--env", ENV_ID,
               "--gym-packages", "soccer_env", "--num-threads", "1", "--seed", "0", *args]
    print("$", shlex.join(command), flush=True)
    subprocess.run(command, check=True)


def main(tiny: bool, log_folder: Path) -> None:
    steps = ["-n", "64"] if tiny else []  # one rollout: 16 environments x 256 steps
    zoo(["-conf", str(HYPERPARAMS), "--log-folder", str(log_folder / "truth"), *steps])
    first = latest_run(log_folder / "truth")
    zoo(["-conf", str(HYPERPARAMS), "--log-folder", str(log_folder / "perceived"),
         "-i", str(first / f"{ENV_ID.replace('/', '-')}.zip"),
         "--env-kwargs", *PERCEIVED, "-params", "ent_coef:0.005",
         *(steps or ["-n", "5000000"])])
    print("models:", first, latest_run(log_folder / "perceived"))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tiny", action="store_true",
                        default=bool(os.environ.get("SOCCER_EXAMPLES_TINY")),
                        help="one rollout per run (CI; also SOCCER_EXAMPLES_TINY=1)")
    parser.add_argument("--log-folder", type=Path, default=Path("logs"),
                        help="where the Zoo writes its runs (default: logs)")
    args = parser.parse_args()
    main(args.tiny, args.log_folder)
