"""The vectorised environments of stable-baselines3 (the ``train`` extra):

* :mod:`agents.vec.workers`: :class:`~agents.vec.workers.WorkerVecEnv`, blocks of
  environments in worker processes whose faults are reported, not waited on;
* :mod:`agents.vec.match`: :class:`~agents.vec.match.MatchVecEnv`, the PettingZoo match with
  parameter sharing against a scripted, idle, frozen or self-play opponent;
* :mod:`agents.vec.batched`: the batched keeper and shootout
  (:class:`~agents.vec.batched.BatchedVecEnv`) and batched matches
  (:class:`~agents.vec.batched.BatchedMatchVecEnv`);
* :mod:`agents.vec.match_workers`: the matches over worker processes
  (:class:`~agents.vec.match_workers.MatchWorkerVecEnv`);
* :mod:`agents.vec.factories`: :func:`~agents.vec.factories.make_match_vec_env` and the
  keeper learner's environment constructor;
* :mod:`agents.vec.self_play`: :class:`~agents.vec.self_play.SelfPlayCallback`;
* :mod:`agents.vec.team_residual`: the ``"team-residual"`` map in training
  (:class:`~agents.vec.team_residual.TeamResidualVecEnv`).

This front imports none of them (each imports stable-baselines3).
"""
