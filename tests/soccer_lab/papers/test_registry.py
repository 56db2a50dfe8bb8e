"""The registry of paper reproductions and the citations: every reproduction registered with a
description naming its paper, and every paper module citing the papers it names."""

from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path

import pytest

from soccer_lab.papers import CITATIONS, PAPERS

#: The paper each reproduction is of.
PAPER_OF = {"ekf": "002", "ungm": "000", "localization": "001", "hough": "000", "team": "000",
            "meanshift": "003", "following": "004"}
SHORT = {"000": "Xu, Xie, Wang, Ni 2012", "001": "Guo, Li 2013", "002": "Zhao, Wang, Li 2012",
         "003": "Li, Wu, Kong 2010", "004": "Yu, Wei, Zhang 2010"}
PAPERS_DIR = Path(__file__).resolve().parents[3] / "soccer_lab" / "papers"


def test_every_reproduction_is_registered_with_its_paper():
    assert list(PAPERS) == list(PAPER_OF)
    for name, number in PAPER_OF.items():
        assert PAPERS.description(name).startswith(f"paper {number}")
        assert callable(PAPERS[name])
    assert sorted(CITATIONS) == sorted(SHORT)
    for number, short in SHORT.items():
        authors, year = short.rsplit(" ", 1)
        assert CITATIONS[number].startswith(authors + ', "') and year in CITATIONS[number]


def test_a_registered_run_is_its_module_run(tmp_path, monkeypatch):
    from soccer_lab.papers import hough

    monkeypatch.setattr(hough, "run", lambda out, **kw: {"out": out, **kw})
    assert PAPERS["hough"](tmp_path, trials=3) == {"out": tmp_path, "trials": 3}


def _paper_sources():
    return sorted(p for p in PAPERS_DIR.rglob("*.py") if p.name != "_io.py")


@pytest.mark.parametrize("path", _paper_sources(), ids=lambda p: str(p.relative_to(PAPERS_DIR)))
def test_module_docstrings_cite_each_paper_at_first_mention(path):
    doc = " ".join((ast.get_docstring(ast.parse(path.read_text())) or "").split())
    seen = set()
    for m in re.finditer(r"[Pp]apers? (00\d)", doc):
        number = m.group(1)
        if number in seen:
            continue
        seen.add(number)
        assert doc[m.end():].startswith(f" ({SHORT[number]})"), (number, doc[m.start():][:60])
    name = path.stem if path.parent == PAPERS_DIR else path.parent.name
    if name in PAPER_OF and path.name in (f"{name}.py", "__init__.py"):
        assert PAPER_OF[name] in seen, f"{path} does not cite paper {PAPER_OF[name]}"


def test_the_modules_import():
    for name in PAPERS:
        assert hasattr(importlib.import_module(f"soccer_lab.papers.{name}"), "run")
