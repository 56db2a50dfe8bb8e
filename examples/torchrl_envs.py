"""TorchRL: the keeper by its Gymnasium id and the match through ``PettingZooWrapper``.

    pip install torchrl==0.14.1        # beside torch==2.13.0 (see docs/guide/rl-libraries.md)
    python examples/torchrl_envs.py [--tiny]

TorchRL's ``PettingZooWrapper`` turns every entry of every agent's info into a tensor, so
the match is made with ``info_mode="flat"`` (numbers only, the same keys at every step; the
default infos hold nested dicts, which it cannot convert). ``GymEnv`` reads no info unless
told to: ``auto_register_info_dict()`` adds every flat entry (the outcome code,
``is_success``, the truth and the belief) to the tensordicts.
"""

from __future__ import annotations

import argparse
import os

import torch
from torchrl.envs import GymEnv, PettingZooWrapper
from torchrl.envs.utils import check_env_specs

import soccer_env
from soccer_env.envs.flat_info import OUTCOME_CODES
from soccer_env.envs.registration import GOALKEEPER_ID


def main(tiny: bool) -> None:
    torch.set_num_threads(1)
    # The keeper by id. GymEnv tries optional keywords (frameskip) that the environment
    # refuses with Python's standard TypeError, which TorchRL takes to mean "not supported".
    keeper = GymEnv(GOALKEEPER_ID, obs_mode="perceived", perception="ssl-2012",
                    info_mode="flat")
    keeper.auto_register_info_dict()
    check_env_specs(keeper)
    keeper.set_seed(0)
    names = {code: name for name, code in OUTCOME_CODES.items()}
    for episode in range(1 if tiny else 5):
        rollout = keeper.rollout(480)  # a random keeper, until the shot ends or 8 s pass
        last = rollout[-1]["next"]
        outcome = names[int(last["outcome"])]
        print(f"keeper episode {episode}: {rollout.shape[0]} steps, outcome {outcome}, "
              f"success {bool(last['is_success'])}, ball error "
              f"{float(rollout['next', 'ball_error'].mean()) * 1000:.1f} mm")

    # The match, parallel API: the agents are grouped by team ("blue", "yellow").
    match = PettingZooWrapper(
        soccer_env.parallel_env(blue=2, yellow=2, max_cycles=20 if tiny else 600,
                                obs_mode="perceived", perception="realistic",
                                info_mode="flat"),
        use_mask=False, categorical_actions=False, seed=0)
    check_env_specs(match)
    print("groups:", match.group_map)
    rollout = match.rollout(20 if tiny else 600, break_when_any_done=False)
    blue = rollout["next", "blue"]
    score = blue["info", "score_blue"][-1, 0], blue["info", "score_yellow"][-1, 0]
    print(f"match: {rollout.shape[0]} steps; blue's observations "
          f"{tuple(blue['observation'].shape)}; blue's reward sum "
          f"{float(blue['reward'].sum()):.2f}; score {int(score[0])}:{int(score[1])}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tiny", action="store_true",
                        default=bool(os.environ.get("SOCCER_EXAMPLES_TINY")),
                        help="a few steps only (CI; also SOCCER_EXAMPLES_TINY=1)")
    main(parser.parse_args().tiny)
