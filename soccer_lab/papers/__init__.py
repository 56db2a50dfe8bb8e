"""Reproductions of the source papers' claims, run by ``soccer-env paper <name>``.

Each reproduction (a module, or a package for the larger ones) simulates the paper's setting,
prints the paper's figures beside ours and writes tables (Markdown and CSV) and PNG plots to an
output folder. Its ``run(out, ...)`` returns at least ``{"text", "files", "seconds"}``: the
printed report, the files written and the wall time. Each is split the same way: the settings
(validated), the loop (episodes or jobs, spread over processes by
:func:`soccer_lab.papers.common.map_jobs`) and the report (tables, plots and the text); a
package has a module for each (``episode``, ``measures``, ``report``, ...) and its ``run`` in
its ``__init__``. :mod:`soccer_lab.papers.common` holds what they share.

:data:`PAPERS` registers the reproductions (name -> ``run``, with a one-line description);
:data:`CITATIONS` gives the source papers in full.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

from estimators.registry import Registry

__all__ = ["PAPERS", "CITATIONS"]

#: The source papers, by the short name the reproductions, the docstrings and the
#: documentation cite them with: the full citation of each.
CITATIONS = {
    "Xu et al. (2012)": "Xu Jiaming, Xie Lun, Wang Zhiliang, Ni Shanchao. Target localization "
                        "algorithm for cooperative multi-soccer robots based on Hough space. "
                        "Journal of Image and Graphics 17(6): 687-695, 2012",
    "Guo and Li (2013)": "Guo Binghua, Li Zhonghua. A method of localization for mobile robot "
                         "based on obstacle-ground-corner. Acta Scientiarum Naturalium "
                         "Universitatis Sunyatseni 52(5): 45-50, 2013",
    "Zhao et al. (2012)": "Zhao Xiao, Wang Ming, Li Xiaoming. Application of extended Kalman "
                          "filter algorithm in intelligent robot soccer competition. Journal "
                          "of Mechanical & Electrical Engineering 2012(3): 334-338",
    "Li et al. (2010)": "Li Haitao, Wu Peiliang, Kong Lingfu. Mean shift-based and "
                        "feature-restricted particle filter for maneuver targets tracking. "
                        "Control and Decision 25(1): 149-152, 2010",
    "Yu et al. (2010)": "Yu Dan, Wei Wei, Zhang Yuanhui. Person following of mobile robot "
                        "using monocular camera. Chinese Journal of Scientific Instrument "
                        "31(3), 2010",
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


#: The paper reproductions: name -> its module's ``run``, and what it reproduces in one short
#: line that names the paper by its authors and year (``soccer-env paper --help`` lists them).
PAPERS: Registry[Callable[..., dict[str, Any]]] = Registry("paper reproduction", [
    ("ekf", _run_of("ekf"), "Zhao et al. (2012): EKF ball prediction, latency compensation"),
    ("ungm", _run_of("ungm"), "Xu et al. (2012): bootstrap PF, FBPF and MFBPF on UNGM"),
    ("localization", _run_of("localization"),
     "Guo and Li (2013): KLD-sampling localization, walking"),
    ("hough", _run_of("hough"), "Xu et al. (2012): Hough-space fusion of robots' sightings"),
    ("team", _run_of("team"), "Xu et al. (2012): team fusion in humanoid matches and saves"),
    ("meanshift", _run_of("meanshift"),
     "Li et al. (2010): mean-shift particle filter, overhead images"),
    ("following", _run_of("following"),
     "Yu et al. (2010): Kalman-started mean shift, head camera"),
])
