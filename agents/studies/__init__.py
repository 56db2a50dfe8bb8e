"""Studies built on the runs: seeded matches between two sides (:mod:`agents.studies.matches`),
Elo ratings fitted to them (:mod:`agents.studies.rating`), the estimator ablation of the
keeper (:mod:`agents.studies.ablation`, its settings in :mod:`agents.studies.ablation_settings`
and its report in :mod:`agents.studies.ablation_report`) and in matches
(:mod:`agents.studies.match_ablation`).

This front imports none of them.
"""
