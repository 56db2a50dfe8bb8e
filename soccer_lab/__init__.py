"""The experiment layer of soccer_env: the ``soccer-env`` command, the demo, the step-rate
benchmarks and the reproductions of the source papers.

It sits above every other package (:mod:`estimators`, :mod:`soccer_env`, :mod:`agents`) and
nothing imports it.
"""
