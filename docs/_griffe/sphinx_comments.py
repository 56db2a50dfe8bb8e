"""A griffe extension for the API reference: docstrings written for Sphinx read well in
mkdocstrings.

* Sphinx roles (``:class:`~estimators.Tracker```, ``:func:`mean_shift```, ``:math:`x```)
  become code spans (```Tracker```), the ``~`` form keeping the last name only, and a
  paragraph that ends in ``::`` before a literal block ends in ``:`` (the indented block is a
  code block in Markdown too);
* an attribute without a docstring takes the ``#:`` comment lines just above its
  assignment, Sphinx's form of an attribute docstring (``BALL_FILTERS`` and the other
  registries are documented so).
"""

from __future__ import annotations

import ast
import re
from typing import Any

import griffe

_ROLE = re.compile(r":(?:py:)?(?:class|func|meth|mod|data|attr|exc|obj|const|math|ref|term)"
                   r":`(~?)([^`]+)`")


def _code(match: re.Match[str]) -> str:
    tilde, target = match.groups()
    if tilde:
        target = target.rsplit(".", 1)[-1]
    return f"`{target}`"


_LITERAL = re.compile(r"(?<=[^\s:]):: *$", re.M)


def plain(text: str) -> str:
    """``text`` with every Sphinx role replaced by a code span, and ``::`` before a literal
    block by ``:``."""
    return _LITERAL.sub(":", _ROLE.sub(_code, text))


class SphinxComments(griffe.Extension):
    """Rewrite Sphinx roles in every docstring; read ``#:`` comments of attributes."""

    def on_instance(self, *, node: Any, obj: griffe.Object, agent: Any, **kwargs: Any) -> None:
        if obj.docstring is not None:
            obj.docstring.value = plain(obj.docstring.value)

    def on_attribute_instance(self, *, node: Any, attr: griffe.Attribute, agent: Any,
                              **kwargs: Any) -> None:
        if attr.docstring is not None or not isinstance(node, ast.AST):
            return
        lines = getattr(agent, "code", "").splitlines()
        row = getattr(node, "lineno", 0) - 2  # the line above the assignment, 0-based
        comment: list[str] = []
        while 0 <= row < len(lines) and lines[row].lstrip().startswith("#:"):
            comment.insert(0, lines[row].lstrip()[2:].strip())
            row -= 1
        if comment:
            attr.docstring = griffe.Docstring(plain(" ".join(comment)), parent=attr,
                                              lineno=row + 2)
