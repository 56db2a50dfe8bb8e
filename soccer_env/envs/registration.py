"""The environments' registration: one table of everything ``gymnasium.make`` and
``pettingzoo.make`` can build from this package.

Adding a task is one line here (its id, entry point, episode limit and a one-line
description) plus its module. The ids are defined here once (:data:`GOALKEEPER_ID`,
:data:`SHOOTOUT_ID`, :data:`MATCH_ID`); code that names an environment imports them.
"""

from __future__ import annotations

from typing import NamedTuple

from estimators.registry import Registry

__all__ = ["GOALKEEPER_ID", "SHOOTOUT_ID", "MATCH_ID", "GymTask", "GYMNASIUM", "PETTINGZOO",
           "register_all"]

#: The keeper task's id (``gymnasium.make(GOALKEEPER_ID)``).
GOALKEEPER_ID = "soccer_env/Goalkeeper-v0"
#: The attacker task's id (``gymnasium.make(SHOOTOUT_ID)``).
SHOOTOUT_ID = "soccer_env/Shootout-v0"
#: The match's id (``pettingzoo.make("parallel", MATCH_ID)``; ``soccer_env.parallel_env`` builds
#: the same match directly).
MATCH_ID = "soccer_env/Match-v0"


class GymTask(NamedTuple):
    """A Gymnasium task: its ``entry_point`` (``module:Class``), ``max_episode_steps`` and,
    for tasks with a batched implementation, its ``vector_entry_point``
    (``gymnasium.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")``)."""

    entry_point: str
    max_episode_steps: int
    vector_entry_point: str | None = None


#: The Gymnasium tasks (``gymnasium.make(id)``).
GYMNASIUM: Registry[GymTask] = Registry("Gymnasium environment", [
    (GOALKEEPER_ID, GymTask("soccer_env.envs.goalkeeper:GoalkeeperEnv", 480,
                            "soccer_env.envs.batched:make_vector"),
     "a keeper robot (SSL or humanoid) defends its goal against one seeded shot"),
    (SHOOTOUT_ID, GymTask("soccer_env.envs.shootout:ShootoutEnv", 600,
                          "soccer_env.envs.batched:make_shootout_vector"),
     "an attacker (SSL or humanoid) must score past the scripted keeper from a seeded start"),
])

#: The PettingZoo environments (``pettingzoo.make("parallel" | "aec", id)``): their parallel
#: and AEC entry points.
PETTINGZOO: Registry[tuple[str, str]] = Registry("PettingZoo environment", [
    (MATCH_ID, ("soccer_env.envs.match:parallel_env", "soccer_env.envs.aec:env"),
     "a match between two teams of SSL robots, humanoids or one of each"),
])


def register_all() -> None:
    """Register every environment of the tables that is not registered yet."""
    from gymnasium.envs.registration import register, registry

    for env_id, task in GYMNASIUM.items():
        if env_id not in registry:
            register(id=env_id, entry_point=task.entry_point,
                     max_episode_steps=task.max_episode_steps,
                     vector_entry_point=task.vector_entry_point)
    try:  # PettingZoo >= 1.27 has a registry like Gymnasium's.
        import pettingzoo as pz
    except ImportError:  # pragma: no cover - PettingZoo is a dependency
        return
    if not hasattr(pz, "parallel_registry"):  # pragma: no cover - older PettingZoo
        return
    for env_id, (parallel, aec) in PETTINGZOO.items():
        if env_id not in pz.parallel_registry:
            pz.register("parallel", env_id, entry_point=parallel)
        if env_id not in pz.aec_registry:
            pz.register("aec", env_id, entry_point=aec)
