"""The environments: Gymnasium single-agent tasks and the PettingZoo match."""

from soccer_env.envs.goalkeeper import GoalkeeperEnv, ShotDistribution
from soccer_env.envs.match import SoccerParallelEnv, env, parallel_env

__all__ = ["GoalkeeperEnv", "ShotDistribution", "SoccerParallelEnv", "env", "parallel_env"]
