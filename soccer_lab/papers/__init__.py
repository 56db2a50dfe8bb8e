"""Reproductions of the source papers' claims, run by ``soccer-env paper <name>``.

Each module simulates the paper's setting, prints the paper's figures beside ours and writes
tables (Markdown and CSV) and PNG plots to an output folder. Its ``run(out, ...)`` returns at
least ``{"text", "files", "seconds"}``: the printed report, the files written and the wall
time. Each is split the same way: the settings (validated), the loop (episodes or jobs,
spread over processes by :func:`soccer_lab.papers._io.map_jobs`) and the report (tables, plots
and the text).

:data:`PAPERS` registers the reproductions (name -> ``run``, with a one-line description);
:data:`CITATIONS` gives the source papers by number.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

from estimators.registry import Registry

__all__ = ["PAPERS", "CITATIONS"]

#: The source papers by number, as the reproductions and the README cite them.
CITATIONS = {
    "000": "Xu, Xie, Wang, Ni, \"Target localization algorithm for cooperative multi-soccer "
           "robots based on Hough space\", Journal of Image and Graphics 17(6), 2012",
    "001": "Guo, Li, \"A method of localization for mobile robot based on "
           "obstacle-ground-corner\", Acta Scientiarum Naturalium Universitatis Sunyatseni, "
           "2013",
    "002": "Zhao, Wang, Li, \"Application of extended Kalman filter algorithm in intelligent "
           "robot soccer competition\", 2012",
    "003": "Li, Wu, Kong, \"Mean shift-based and feature-restricted particle filter for "
           "maneuver targets tracking\", Control and Decision 25(1), 2010",
    "004": "Yu, Wei, Zhang, \"Person following of mobile robot using monocular camera\", "
           "Chinese Journal of Scientific Instrument 31(3), 2010",
}


def _run_of(name: str) -> Callable[..., dict[str, Any]]:
    """``run`` of the module ``soccer_lab.papers.<name>``, imported when called (so that one
    reproduction, or a process of its pool, imports only its own module) and looked up on
    every call."""

    def run(*args: Any, **kwargs: Any) -> dict[str, Any]:
        return importlib.import_module(f"{__name__}.{name}").run(*args, **kwargs)

    run.__name__ = run.__qualname__ = f"run_{name}"
    run.__doc__ = f"``soccer_lab.papers.{name}.run(*args, **kwargs)``."
    return run


#: The paper reproductions: name -> its module's ``run``, and what it reproduces.
PAPERS: Registry[Callable[..., dict[str, Any]]] = Registry("paper reproduction", [
    ("ekf", _run_of("ekf"), "paper 002: EKF ball prediction with latency compensation (open "
                            "and closed loop)"),
    ("ungm", _run_of("ungm"), "paper 000: bootstrap PF, FBPF and MFBPF on the UNGM benchmark"),
    ("localization", _run_of("localization"), "paper 001: KLD-sampling localization against "
                                              "fixed-size filters, walking"),
    ("hough", _run_of("hough"), "paper 000: Hough-space fusion of several robots' sightings "
                                "(Table 1 geometry)"),
    ("team", _run_of("team"), "paper 000 in the closed loop: humanoid matches and keeper, one "
                              "robot alone against team fusion and particle tracking"),
    ("meanshift", _run_of("meanshift"), "paper 003: the feature-restricted mean-shift PF "
                                        "against plain PFs on robots manoeuvring in rendered "
                                        "overhead images"),
    ("following", _run_of("following"), "paper 004: the Kalman-started mean shift against "
                                        "plain mean shift on a turning humanoid's head-camera "
                                        "images"),
])
