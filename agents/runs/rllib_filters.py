"""Observation statistics of the RLlib backend's match: RLlib's ``MeanStdFilter`` connector
with one set of statistics per module (:class:`MeanStdFilter`), and statistics of several
agents pooled into one (:func:`pooled_statistics`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ray.rllib.connectors.env_to_module.mean_std_filter import (
    MeanStdFilter as RLlibMeanStdFilter,
)

__all__ = ["MeanStdFilter", "pooled_statistics"]


def pooled_statistics(states: list[Mapping[str, Any]]) -> Any:
    """One ``RunningStat`` (``ray.rllib.utils.filter``) of the observations counted by the
    ``MeanStdFilter`` states ``states`` of several agents (each ``{"running_stats": [...],
    ...}`` of a flat ``Box`` observation): their counts, means and sums of squared deviations
    pooled, as if one filter had seen every observation. ``ValueError`` for a structured
    observation."""
    from ray.rllib.utils.filter import RunningStat

    stats = []
    for state in states:
        if len(state["running_stats"]) != 1:
            raise ValueError("observation statistics of a structured observation (not a flat "
                             "Box) cannot be pooled")
        stats.append(RunningStat.from_state(state["running_stats"][0]))
    if len(stats) == 1:
        return stats[0]
    counts = [float(s.num_pushes) for s in stats]
    total = sum(counts)
    mean = sum(c * s.mean_array for c, s in zip(counts, stats)) / max(total, 1.0)
    pooled = RunningStat(stats[0].shape)
    pooled.num_pushes = int(total)
    pooled.mean_array = mean
    pooled.sum_sq_diff_array = sum(s.sum_sq_diff_array + c * (s.mean_array - mean) ** 2
                                   for c, s in zip(counts, stats))
    return pooled


class MeanStdFilter(RLlibMeanStdFilter):
    """RLlib's ``MeanStdFilter`` connector for the match with one set of observation
    statistics per module (network) instead of one per agent (robot): the robots that a
    module plays are normalised alike, as one ``VecNormalize`` normalises a team in the
    stable-baselines3 backend, and a module's numpy copy
    (:func:`agents.runs.rllib_export.export_numpy`) normalises as RLlib does. Its state (in
    checkpoints, merged over the env runners) is keyed by module id; a state keyed by agent
    (the checkpoints of version 0.1.0) is pooled per module as it is set
    (:func:`pooled_statistics`). It keeps RLlib's class name, under which checkpoints hold
    the state.

    Args:
        agent_module: the module of each agent
            (:attr:`agents.runs.rllib.MatchPolicies.agent_module`).
        kwargs: those of RLlib's ``MeanStdFilter`` (``multi_agent`` is True).
    """

    def __init__(self, *, agent_module: Mapping[str, str], **kwargs: Any) -> None:
        super().__init__(**{**kwargs, "multi_agent": True})
        self.agent_module = dict(agent_module)
        #: Each module's first agent, whose filter its agents share.
        self.first_agent: dict[str, str] = {}
        for agent, module in self.agent_module.items():
            self.first_agent.setdefault(module, agent)

    def get_ctor_args_and_kwargs(self) -> tuple[tuple, dict[str, Any]]:
        """What rebuilds this connector from a checkpoint."""
        return (), {"agent_module": self.agent_module, "de_mean_to_zero": self.de_mean_to_zero,
                    "de_std_to_one": self.de_std_to_one, "clip_by_value": self.clip_by_value}

    def _init_new_filters(self) -> None:
        # RLlib's filters are one per agent (Ray 2.60): the agents of a module share one.
        super()._init_new_filters()
        filters = self._filters
        for agent in list(filters):
            first = self.first_agent.get(self.agent_module.get(agent, ""))
            if first in filters:
                filters[agent] = filters[first]

    def _by_agent(self, state: Mapping[str, Any]) -> dict[str, Any]:
        """A state by module as RLlib's filter takes it: under each module's first agent
        (a state by agent is pooled per module first)."""
        if not set(state) & set(self.first_agent) and set(state) & set(self.agent_module):
            by_module: dict[str, list[Any]] = {}
            for agent, value in state.items():
                if agent in self.agent_module:
                    by_module.setdefault(self.agent_module[agent], []).append(value)
            state = {m: {**values[0], "running_stats": [pooled_statistics(values).to_state()]}
                     for m, values in by_module.items()}
        return {self.first_agent[m]: v for m, v in state.items() if m in self.first_agent}

    def _by_module(self, state: Mapping[str, Any]) -> dict[str, Any]:
        return {m: state[a] for m, a in self.first_agent.items() if a in state}

    def get_state(self, components: Any = None, *, not_components: Any = None,
                  **kwargs: Any) -> dict[str, Any]:
        """The statistics by module id."""
        return self._by_module(super().get_state(components, not_components=not_components,
                                                 **kwargs))

    def set_state(self, state: Mapping[str, Any]) -> None:
        """Set the statistics by module id (or by agent id, pooled per module)."""
        super().set_state(self._by_agent(state))

    def merge_states(self, states: list[Mapping[str, Any]]) -> dict[str, Any]:
        """Merge the env runners' states (by module id) into this one's."""
        return self._by_module(super().merge_states([self._by_agent(s) for s in states]))
