"""The environments: Gymnasium single-agent tasks and the PettingZoo match."""

from .goalkeeper import GoalkeeperEnv, ShotDistribution
from .match import SoccerParallelEnv, env, parallel_env

__all__ = ["GoalkeeperEnv", "ShotDistribution", "SoccerParallelEnv", "env", "parallel_env"]
