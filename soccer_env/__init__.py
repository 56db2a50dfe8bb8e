"""soccer_env: Gymnasium and PettingZoo robot-soccer environments with honest perception.

Quick start::

    import gymnasium as gym
    import soccer_env  # registers the environments

    env = gym.make("soccer_env/Goalkeeper-v0")
    match = soccer_env.parallel_env(blue=3, yellow=3, field="ssl-div-b")
"""

from gymnasium.envs.registration import register, registry

from soccer_env import presets
from soccer_env.envs import GoalkeeperEnv, ShotDistribution, SoccerParallelEnv, env, parallel_env
from soccer_env.sim.commands import OUT_OF_RANGE_MODES, validate_actions
from soccer_env.sim.world import COMMAND_FIELDS, MAX_TEAM_SIZE, World
from soccer_env.state import WorldState

__version__ = "0.1.0"

__all__ = [
    "presets",
    "GoalkeeperEnv",
    "ShotDistribution",
    "SoccerParallelEnv",
    "env",
    "parallel_env",
    "World",
    "COMMAND_FIELDS",
    "MAX_TEAM_SIZE",
    "validate_actions",
    "OUT_OF_RANGE_MODES",
    "WorldState",
    "__version__",
]

#: Gymnasium ids registered by this package, with their ``max_episode_steps``.
ENV_IDS = {"soccer_env/Goalkeeper-v0": 480}
#: PettingZoo ids registered by this package (``pettingzoo.make("parallel", id)`` or
#: ``pettingzoo.make("aec", id)``).
PETTINGZOO_IDS = ("soccer_env/Match-v0",)

for _id, _steps in ENV_IDS.items():
    if _id not in registry:
        register(id=_id, entry_point="soccer_env.envs.goalkeeper:GoalkeeperEnv",
                 max_episode_steps=_steps)

try:  # PettingZoo >= 1.27 has a registry like Gymnasium's.
    import pettingzoo as _pz

    if "soccer_env/Match-v0" not in _pz.parallel_registry:
        _pz.register("parallel", "soccer_env/Match-v0",
                     entry_point="soccer_env.envs.match:parallel_env")
    if "soccer_env/Match-v0" not in _pz.aec_registry:
        _pz.register("aec", "soccer_env/Match-v0", entry_point="soccer_env.envs.match:env")
except AttributeError:  # pragma: no cover - older PettingZoo
    pass
