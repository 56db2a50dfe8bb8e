"""Particle filters: the filter cores and the trackers built on them.

* :mod:`~estimators.particle.core`: the bootstrap, fission-bootstrap and modified fission-
  bootstrap particle filters of Xu, Xie, Wang and Ni (2012) on ``(N, d)`` particle
  arrays (building blocks: ``predict`` / ``correct`` / ``step``), their resampling and SFN
  steps, and Xu et al.'s (2012) UNGM benchmark;
* :mod:`~estimators.particle.ball`: a ball tracker on those filters for a team's fused ball
  positions (:class:`ParticleBallTracker`);
* :mod:`~estimators.particle.localization`: adaptive self-localization by KLD-sampling, Guo
  and Li (2013; :class:`KLDLocalizer`), with KLD-sampling's sample size
  (:mod:`~estimators.particle.kld`) and the landmark table of ambiguous sightings
  (:mod:`~estimators.particle.landmarks`).
"""

from .ball import CHI2_2DOF_9999, ParticleBallTracker
from .core import (
    FBPF,
    MFBPF,
    PARTICLE_FILTERS,
    BootstrapPF,
    sfn,
    systematic_resample,
    ungm_model,
    ungm_simulate,
)
from .kld import kld_sample_size, normal_quantile
from .landmarks import LandmarkTable
from .localization import RECOVERIES, KLDConfig, KLDLocalizer, seed_poses

__all__ = [
    "BootstrapPF",
    "FBPF",
    "MFBPF",
    "PARTICLE_FILTERS",
    "sfn",
    "systematic_resample",
    "ungm_model",
    "ungm_simulate",
    "ParticleBallTracker",
    "CHI2_2DOF_9999",
    "KLDConfig",
    "KLDLocalizer",
    "RECOVERIES",
    "LandmarkTable",
    "kld_sample_size",
    "normal_quantile",
    "seed_poses",
]
