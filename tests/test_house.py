"""The house rules that a diff can break without another test noticing: no import cycles, no
private name taken from another module, modules and functions of a readable size.

* **Cycles**: no two modules of the packages reach each other by imports, whether at the top
  of a module or inside a function (an import hidden in a function is still a dependency).
* **Private names**: ``from m import _name`` is refused outside ``m`` (tests, benchmarks and
  examples included): what another module needs is public, named and documented. A private
  module (``pkg/_m.py``) may be imported from within ``pkg`` only.
* **Sizes**: modules up to :data:`MAX_MODULE_LINES` lines and functions up to
  :data:`MAX_FUNCTION_LINES`. One that is longer on purpose (a hot path kept whole) says so in
  its docstring with the words ``Kept whole:`` and the reason.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from source_tree import (
    PACKAGES,
    ROOT,
    SCRIPTS,
    cycles,
    import_graph,
    imports_in,
    module_name,
    package_of,
    source_files,
)

MAX_MODULE_LINES = 600
MAX_FUNCTION_LINES = 80
#: The words with which a docstring explains a module or function over the limits.
KEPT_WHOLE = "Kept whole:"


def is_private(name: str) -> bool:
    """``_name`` but not ``__dunder__``."""
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def private_imports(source: str, me: str, package: str) -> list[str]:
    """The private names and modules that the module ``me`` (of ``package``) imports from
    other modules of the project."""
    wrong = []
    for imp in imports_in(source, package):
        parts = imp.module.split(".")
        if parts[0] not in PACKAGES:
            continue
        if imp.name is not None and is_private(imp.name) and imp.module != me:
            wrong.append(f"line {imp.line}: {imp.name} from {imp.module}")
        for i, part in enumerate(parts):
            owner = ".".join(parts[:i])
            if is_private(part) and not (me == owner or me.startswith(owner + ".")):
                wrong.append(f"line {imp.line}: the private module {imp.module}")
                break
    return wrong


def oversized(source: str) -> list[str]:
    """The module (if over :data:`MAX_MODULE_LINES`) and the functions (over
    :data:`MAX_FUNCTION_LINES`) of ``source`` whose docstring does not say why they are kept
    whole."""
    tree = ast.parse(source)
    out = []
    lines = source.count("\n")
    if lines > MAX_MODULE_LINES and KEPT_WHOLE not in (ast.get_docstring(tree) or ""):
        out.append(f"the module ({lines} lines)")
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            length = node.end_lineno - node.lineno + 1
            if length > MAX_FUNCTION_LINES and KEPT_WHOLE not in (ast.get_docstring(node) or ""):
                out.append(f"{node.name} (line {node.lineno}, {length} lines)")
    return out


def all_files() -> list[Path]:
    return source_files(PACKAGES + SCRIPTS)


def test_no_import_cycles():
    graph = import_graph(source_files(PACKAGES))
    found = cycles(graph)
    described = [[f"{m} -> {', '.join(t for t in sorted(graph[m]) if t in group)}"
                  for m in group] for group in found]
    assert not found, f"modules that import each other (imports inside functions count): " \
                      f"{described}"


def test_the_cycle_finder_finds_cycles():
    """Not vacuous: a cycle through three modules, one closed inside a function, is found; a
    chain and a package re-exporting its submodule are not cycles."""
    graph = {"a": {"b": 1}, "b": {"c": 2}, "c": {"a": 3}, "d": {"a": 1}, "p": {"p.m": 1},
             "p.m": {"d": 1}}
    assert cycles(graph) == [["a", "b", "c"]]
    source = "def f():\n    from soccer_env.envs import goalkeeper\n"
    assert [i.module for i in imports_in(source, "soccer_env.sim")] == [
        "soccer_env.envs.goalkeeper"]


@pytest.mark.parametrize("path", all_files(), ids=lambda p: module_name(p))
def test_no_private_names_from_other_modules(path):
    wrong = private_imports(path.read_text(), module_name(path), package_of(path))
    assert not wrong, f"{module_name(path)} imports private names of other modules: {wrong}"


def test_the_private_check_finds_private_names():
    source = ("from estimators.kalman.ball import _predict, predict\n"
              "def f():\n    from .meanshift import _Windows\n"
              "from soccer_env.sim._hidden import thing\n"
              "from estimators.kalman.ball import __all__\n")
    found = private_imports(source, "estimators.image.following", "estimators.image")
    assert [f.split(":")[1].strip() for f in found] == [
        "_predict from estimators.kalman.ball", "_Windows from estimators.image.meanshift",
        "the private module soccer_env.sim._hidden"]
    # Its own private names, and a private module of its own package, are the module's own.
    mine = "from soccer_env.sim.world import _x\nfrom soccer_env.sim._hidden import y\n"
    assert private_imports(mine, "soccer_env.sim.world", "soccer_env.sim") == []


@pytest.mark.parametrize("path", all_files(), ids=lambda p: module_name(p))
def test_sizes(path):
    too_long = oversized(path.read_text())
    assert not too_long, (
        f"{path.relative_to(ROOT)}: over {MAX_MODULE_LINES} lines a module, over "
        f"{MAX_FUNCTION_LINES} a function, without '{KEPT_WHOLE} <why>' in its docstring: "
        f"{too_long}; split it along its seams")


def test_the_size_check_finds_long_functions():
    body = "".join(f"    x{i} = {i}\n" for i in range(MAX_FUNCTION_LINES))
    long = f"def f():\n{body}"
    kept = f'def g():\n    """{KEPT_WHOLE} a hot path."""\n{body}'
    assert oversized(long) == [f"f (line 1, {MAX_FUNCTION_LINES + 1} lines)"]
    assert oversized(kept) == []
    assert oversized("x = 1\n" * (MAX_MODULE_LINES + 1)) == [
        f"the module ({MAX_MODULE_LINES + 1} lines)"]


def test_every_import_is_read():
    """The graph has a node for every module of the packages."""
    files = source_files(PACKAGES)
    assert set(import_graph(files)) == {module_name(p) for p in files}
