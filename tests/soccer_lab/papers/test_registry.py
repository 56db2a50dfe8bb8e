"""The registry of paper reproductions and the citations: every reproduction registered with a
description naming its paper, and every paper module citing the papers it names."""

from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path

import pytest

from soccer_lab.papers import CITATIONS, PAPERS

#: The paper each reproduction is of, as the descriptions and CITATIONS name it.
PAPER_OF = {"ekf": "Zhao et al. (2012)", "ungm": "Xu et al. (2012)",
            "localization": "Guo and Li (2013)", "hough": "Xu et al. (2012)",
            "team": "Xu et al. (2012)", "meanshift": "Li et al. (2010)",
            "following": "Yu et al. (2010)"}
#: Each paper's first author and year.
FIRST = {"Xu et al. (2012)": ("Xu", "2012"), "Guo and Li (2013)": ("Guo", "2013"),
         "Zhao et al. (2012)": ("Zhao", "2012"), "Li et al. (2010)": ("Li", "2010"),
         "Yu et al. (2010)": ("Yu", "2010")}
PAPERS_DIR = Path(__file__).resolve().parents[3] / "soccer_lab" / "papers"


def test_every_reproduction_is_registered_with_its_paper():
    assert list(PAPERS) == list(PAPER_OF)
    for name, short in PAPER_OF.items():
        assert PAPERS.description(name).startswith(short + ": ")
        assert callable(PAPERS[name])
    assert sorted(CITATIONS) == sorted(FIRST)
    for short, (first, year) in FIRST.items():
        assert CITATIONS[short].startswith(first + " ") and year in CITATIONS[short]


def test_a_registered_run_is_its_module_run(tmp_path, monkeypatch):
    from soccer_lab.papers import hough

    monkeypatch.setattr(hough, "run", lambda out, **kw: {"out": out, **kw})
    assert PAPERS["hough"](tmp_path, trials=3) == {"out": tmp_path, "trials": 3}


def _paper_sources():
    return sorted(p for p in PAPERS_DIR.rglob("*.py") if p.name != "common.py")


@pytest.mark.parametrize("path", _paper_sources(), ids=lambda p: str(p.relative_to(PAPERS_DIR)))
def test_module_docstrings_cite_their_paper_by_author_and_year(path):
    doc = " ".join((ast.get_docstring(ast.parse(path.read_text())) or "").split())
    assert not re.search(r"[Pp]apers? 00\d", doc), "cite papers by author and year"
    name = path.stem if path.parent == PAPERS_DIR else path.parent.name
    if name in PAPER_OF and path.name in (f"{name}.py", "__init__.py"):
        first, year = FIRST[PAPER_OF[name]]
        assert re.search(rf"\b{first}\b[^.]{{0,40}}\.?[^.]{{0,40}}{year}", doc), (
            f"{path} does not cite {first} {year}")


def test_the_modules_import():
    for name in PAPERS:
        assert hasattr(importlib.import_module(f"soccer_lab.papers.{name}"), "run")
