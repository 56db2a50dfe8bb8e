"""Agents: scripted baselines (and, with the training extra, learning utilities).

The package is a stack of layers, lowest first, each importing only itself and those below
(``tests/test_layers.py`` checks it, imports inside functions included):

* :mod:`agents.common`: what every layer shares (process pools, intervals, checks);
* :mod:`agents.scripted`: the scripted teams and the team's residual map (numpy only);
* :mod:`agents.policies`: the policy protocol, numpy networks, the learners' action maps and
  wrappers, safe files (numpy and gymnasium only);
* :mod:`agents.baselines`: the shipped policies;
* :mod:`agents.sb3`: what needs stable-baselines3;
* :mod:`agents.vec`: the vectorised environments;
* :mod:`agents.runs`: resolving policies and run folders, evaluation, training;
* :mod:`agents.studies`: matches, ratings, the estimator ablations;
* :mod:`agents.live`: policies on live SSL protocols (the ``ssl`` extra).

Up to :mod:`agents.baselines` nothing imports stable-baselines3, torch or Ray. This front
imports none of the layers: it offers the scripted keeper, which the environments define.
"""

from soccer_env.envs.keeper import ScriptedGoalkeeper

__all__ = ["ScriptedGoalkeeper"]
