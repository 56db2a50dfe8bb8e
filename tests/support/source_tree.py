"""The project's source tree as the house tests read it: modules, the imports of each (every
import statement, those inside functions included, and ``importlib.import_module`` calls with a
literal name), the import graph and its cycles.

Shared by ``tests/test_layers.py`` (imports point down the layers) and ``tests/test_house.py``
(no cycles, no private names taken from another module, sizes).
"""

from __future__ import annotations

import ast
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import cache
from pathlib import Path

#: The repository root.
ROOT = Path(__file__).resolve().parents[2]
#: The packages the wheel installs, lowest layer first.
PACKAGES = ("estimators", "soccer_env", "agents", "soccer_lab")
#: Other folders of Python code the house rules cover.
SCRIPTS = ("tests", "benchmarks", "examples")


@dataclass(frozen=True)
class Import:
    """One imported name: ``module`` is the module it resolves to (``from p import m`` gives
    ``p.m`` when ``m`` is a module of the project, else ``p``), ``name`` the name taken from it
    (``None`` for ``import m``)."""

    line: int
    module: str
    name: str | None


def module_name(path: Path, root: Path = ROOT) -> str:
    """Dotted name of the module at ``path`` (a package's ``__init__.py`` names the package)."""
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


@cache
def is_module(name: str, root: Path = ROOT) -> bool:
    """Whether ``name`` is a module or package of the project's tree."""
    base = root.joinpath(*name.split("."))
    return base.with_suffix(".py").exists() or (base / "__init__.py").exists()


def package_of(path: Path, root: Path = ROOT) -> str:
    """The package that relative imports in ``path`` start from."""
    me = module_name(path, root)
    return me if path.name == "__init__.py" else me.rpartition(".")[0]


def imports_in(source: str, package: str, root: Path = ROOT) -> list[Import]:
    """Every import of ``source``, a module of ``package`` (relative imports resolved), in the
    order of their lines."""
    out: list[Import] = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            out += [Import(node.lineno, alias.name, None) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(parent + ([base] if base else []))
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                if is_module(sub, root):
                    out.append(Import(node.lineno, sub, None))
                else:
                    out.append(Import(node.lineno, base, alias.name))
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr == "import_module" and node.args
              and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)
              and not node.args[0].value.startswith(".")):
            out.append(Import(node.lineno, node.args[0].value, None))
    return sorted(out, key=lambda i: i.line)


def imports_of(path: Path, root: Path = ROOT) -> list[Import]:
    """:func:`imports_in` for the module at ``path``."""
    return imports_in(path.read_text(), package_of(path, root), root)


def source_files(folders: Iterable[str] = PACKAGES, root: Path = ROOT) -> list[Path]:
    """The ``.py`` files under ``folders`` of ``root``."""
    return sorted(p for folder in folders for p in (root / folder).rglob("*.py"))


def import_graph(files: Iterable[Path], root: Path = ROOT) -> dict[str, dict[str, int]]:
    """``{module: {imported module: first line}}`` between the modules of ``files``. An import
    of a name from a module counts as an import of that module, an import of a submodule as
    one of the submodule (not of its package: a package's ``__init__`` that re-exports its
    submodules is no cycle, but a submodule that takes a name from its package's ``__init__``
    that imports it is one)."""
    files = list(files)
    modules = {module_name(p, root) for p in files}
    graph: dict[str, dict[str, int]] = {}
    for path in files:
        me = module_name(path, root)
        edges = graph.setdefault(me, {})
        for imp in imports_of(path, root):
            target = imp.module
            while target and target not in modules:
                target = target.rpartition(".")[0]
            if target and target != me:
                edges.setdefault(target, imp.line)
    return graph


def cycles(graph: Mapping[str, Iterable[str]]) -> list[list[str]]:
    """The strongly connected groups of more than one module (Tarjan's algorithm, iterative),
    each sorted; a module in a group can reach every other one of it by imports."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    groups: list[list[str]] = []
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph.get(start, ()))))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                group = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    group.append(member)
                    if member == node:
                        break
                if len(group) > 1:
                    groups.append(sorted(group))
    return sorted(groups)
