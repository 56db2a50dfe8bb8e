"""The application layer of soccer_env: the ``soccer-env`` command (:mod:`soccer_lab.cli`, with
the front-ends of ``train``, ``eval``, ``ablation`` and ``play`` in
:mod:`soccer_lab.commands`), the demo (:mod:`soccer_lab.demo`), the benchmarks
(:mod:`soccer_lab.bench`, also run by ``benchmarks/*.py``) and the reproductions of the source
papers (:mod:`soccer_lab.papers`).

It sits above every other package (:mod:`estimators`, :mod:`soccer_env`, :mod:`agents`) and
nothing imports it.
"""
