"""The match as a PettingZoo AEC environment: :func:`env`.

PettingZoo's conversion of the parallel match (:class:`~soccer_env.envs.match.
SoccerParallelEnv`) to agents acting in turn, with each action checked when its agent acts and
a step once the match is over refused.
"""

from __future__ import annotations

from typing import Any

from pettingzoo.utils.conversions import parallel_to_aec_wrapper
from pettingzoo.utils.wrappers import OrderEnforcingWrapper

from soccer_env.envs.match import SoccerParallelEnv

__all__ = ["env"]


class CheckedAEC(parallel_to_aec_wrapper):
    """PettingZoo's conversion of the parallel match to AEC, checking each agent's action when
    the agent acts: a bad action raises there, naming the agent, and leaves the cycle as it
    was (the conversion alone stores it and fails at the cycle's last agent, after which
    every step fails until a reset)."""

    def step(self, action: Any) -> None:
        agent = self.agent_selection
        if action is not None and not (self.terminations.get(agent)
                                       or self.truncations.get(agent)):
            action = self.env.check_action(agent, action)
        super().step(action)


class OrderedAEC(OrderEnforcingWrapper):
    """PettingZoo's order checks, and a step once every agent is done raises (PettingZoo only
    warns, and the step does nothing)."""

    _was_reset = False

    def reset(self, seed: int | None = None, options: dict | None = None) -> None:
        super().reset(seed=seed, options=options)
        self._was_reset = True

    def step(self, action: Any) -> None:
        if self._was_reset and not self.agents:
            raise RuntimeError("every agent is done: the match is over; call reset() before "
                               "stepping again")
        super().step(action)


def env(**kwargs: Any):
    """The match as a PettingZoo AEC environment (agents act in turn; the physics steps
    once every agent has acted; each action is checked when its agent acts; a step once the
    match is over raises ``RuntimeError``)."""
    return OrderedAEC(CheckedAEC(SoccerParallelEnv(**kwargs)))
