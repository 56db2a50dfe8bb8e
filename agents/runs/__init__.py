"""Runs: resolving a policy reference or a run folder (:mod:`agents.runs.resolve`),
evaluation on the fixed shot suite (:mod:`agents.runs.evaluation`), run folders
(:mod:`agents.runs.folders`), training with stable-baselines3 (:mod:`agents.runs.training`),
with RLlib (:mod:`agents.runs.rllib`, :mod:`agents.runs.rllib_envs`,
:mod:`agents.runs.rllib_filters`, :mod:`agents.runs.rllib_runs`,
:mod:`agents.runs.rllib_checkpoints`, :mod:`agents.runs.rllib_export`) and by imitation of a
privileged teacher (:mod:`agents.runs.imitation`, DAgger; torch only to fit).

This front imports none of them. Resolution, evaluation and the training package import
without stable-baselines3 (it is imported to load a ``.zip`` or to train); the RLlib modules
need Ray.

:mod:`agents.runs.benchmarl` makes the match a BenchMARL task; it imports without BenchMARL,
which its task classes need.
"""
