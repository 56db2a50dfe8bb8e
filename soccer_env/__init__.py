"""soccer_env: Gymnasium and PettingZoo robot-soccer environments with honest perception.

Quick start::

    import gymnasium as gym
    import soccer_env  # registers the environments

    env = gym.make("soccer_env/Goalkeeper-v0")
    match = soccer_env.parallel_env(blue=3, yellow=3, field="ssl-div-b")

Layers, each importing only those below it (``tests/test_layers.py`` checks every import):
:mod:`~soccer_env.presets` and :mod:`~soccer_env.state` (every preset table, the snapshots
that flow between layers), :mod:`~soccer_env.sim` (the world, walk engine, commands, referee,
head control), :mod:`~soccer_env.sensors` (overhead cameras, head cameras, radio, rendered
images), :mod:`~soccer_env.perception` (what a team believes), :mod:`~soccer_env.observations`,
:mod:`~soccer_env.render` and :mod:`~soccer_env.envs` (a core with task hooks, the tasks, their
registration). Below all of them, :mod:`estimators` (numpy only); above, :mod:`agents` and the
application layer :mod:`soccer_lab`, which this package never imports.

"Xu et al. (2012)" to "Yu et al. (2010)" are the five source papers, cited in full in the README's
"Source
papers" section.
"""

from soccer_env import presets
from soccer_env.envs import (
    GoalkeeperEnv,
    ShootoutEnv,
    ShotDistribution,
    SoccerParallelEnv,
    env,
    parallel_env,
)
from soccer_env.envs.registration import GYMNASIUM, PETTINGZOO, register_all
from soccer_env.sim.commands import OUT_OF_RANGE_MODES, validate_actions
from soccer_env.sim.world import COMMAND_FIELDS, MAX_TEAM_SIZE, World
from soccer_env.state import WorldState

__version__ = "0.1.0"

__all__ = [
    "presets",
    "GoalkeeperEnv",
    "ShootoutEnv",
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

#: Gymnasium ids registered by this package, with their ``max_episode_steps``
#: (:data:`soccer_env.envs.registration.GYMNASIUM` has their entry points and descriptions).
ENV_IDS = {env_id: task.max_episode_steps for env_id, task in GYMNASIUM.items()}
#: PettingZoo ids registered by this package (``pettingzoo.make("parallel", id)`` or
#: ``pettingzoo.make("aec", id)``).
PETTINGZOO_IDS = tuple(PETTINGZOO)

register_all()
