"""The environments: Gymnasium single-agent tasks and the PettingZoo match, on one core
(:mod:`soccer_env.envs.base`), registered from one table (:mod:`soccer_env.envs.registration`)."""

from soccer_env.envs.aec import env
from soccer_env.envs.goalkeeper import GoalkeeperEnv, ShotDistribution
from soccer_env.envs.match import SoccerParallelEnv, parallel_env
from soccer_env.envs.shootout import ShootoutEnv

__all__ = ["GoalkeeperEnv", "ShotDistribution", "ShootoutEnv", "SoccerParallelEnv", "env",
           "parallel_env"]
