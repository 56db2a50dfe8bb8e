"""What needs stable-baselines3 (the ``train`` extra): the algorithms by name
(:mod:`agents.sb3.algorithms`), model files read without unpickling
(:mod:`agents.sb3.model_files`), normalisation statistics without pickle
(:mod:`agents.sb3.normalization`), numpy copies of trained actors and models as policies
(:mod:`agents.sb3.policies`), models started from numpy policies (:mod:`agents.sb3.warm_start`),
ignored actions kept out of PPO's update (:mod:`agents.sb3.masking`),
the privileged critic's policy (:mod:`agents.sb3.privileged`) and the callbacks every run uses
(:mod:`agents.sb3.callbacks`).

This front imports none of them: :mod:`~agents.sb3.algorithms`,
:mod:`~agents.sb3.model_files`, :mod:`~agents.sb3.normalization` and
:mod:`~agents.sb3.policies` import stable-baselines3 and torch only when a function needs
them, so the command line and the evaluation import them without the extra;
:mod:`~agents.sb3.warm_start`, :mod:`~agents.sb3.masking`, :mod:`~agents.sb3.privileged` and
:mod:`~agents.sb3.callbacks` import stable-baselines3 at once.
"""
