"""The Python examples of the README and of the documentation pages run as written, and their
relative links lead to files (and headings) that exist.

The README's blocks run one by one, each in a namespace of its own; a documentation page's run
in order in one namespace, since a tutorial builds on its earlier blocks. Two kinds of block
are not run: training examples (a ``.learn(`` or ``.train(`` call; shortened versions are in
test_api and the RLlib tests) and blocks that import a library of an optional extra that is
not installed (the RL libraries of "clients", Ray of "rllib", BenchMARL of "benchmarl",
Tianshou of "tianshou", whose own environment runs its block: tests/examples).
"""

import os
import re
import sys
import unicodedata
from pathlib import Path

import gymnasium as gym
import pytest

from estimators.registry import Registry

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DOCS = ROOT / "docs"
PAGES = sorted(DOCS.rglob("*.md"))
#: The libraries of optional extras, by the extra that installs them: a block importing one
#: is skipped where it is missing.
OPTIONAL = {"torchrl": "clients", "tensordict": "clients", "supersuit": "clients",
            "rl_zoo3": "clients", "pufferlib": "clients", "ray": "rllib",
            "benchmarl": "benchmarl", "tianshou": "tianshou"}
#: What a training example calls.
TRAINING = (".learn(", ".train(")


def python_blocks(path: Path) -> list[str]:
    """The fenced ``python`` blocks of the Markdown file ``path``, in order."""
    return re.findall(r"```python\n(.*?)```", path.read_text(), flags=re.S)


def run_block(code: str, namespace: dict, label: str) -> str | None:
    """Run ``code`` in ``namespace``; the reason it was not run, or None."""
    if any(call in code for call in TRAINING):
        return "training example: shortened version in test_api"
    try:
        exec(compile(code, label, "exec"), namespace)
    except ModuleNotFoundError as err:
        if err.name not in OPTIONAL:
            raise
        return f"{err.name} is not installed (the {OPTIONAL[err.name]} extra)"
    return None


BLOCKS = python_blocks(README)


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_readme_example(index):
    why = run_block(BLOCKS[index], {}, f"README block {index}")
    if why:
        pytest.skip(why)


def _registries() -> list[Registry]:
    """Every option registry of the packages' loaded modules."""
    found = {}
    for name, module in list(sys.modules.items()):
        if name.split(".")[0] in ("estimators", "soccer_env", "agents"):
            for value in vars(module).values():
                if isinstance(value, Registry):
                    found[id(value)] = value
    return list(found.values())


@pytest.fixture
def restore_registries():
    """Remove what a page registers (a ball filter, an ablation configuration, a Gymnasium
    id) once it has run, so that no other test sees it."""
    import agents.studies.ablation  # noqa: F401  (the registries a page may add to, loaded first)
    import soccer_env  # noqa: F401

    before = {id(r): set(r) for r in _registries()}
    ids = set(gym.registry)
    yield
    for registry in _registries():
        for name in set(registry) - before.get(id(registry), set(registry)):
            registry.unregister(name)
    for env_id in set(gym.registry) - ids:
        del gym.registry[env_id]


@pytest.mark.parametrize("page", [p.relative_to(DOCS).as_posix() for p in PAGES
                                  if python_blocks(p)])
def test_docs_page_examples(page, restore_registries, monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    namespace: dict = {}
    skipped = [why for index, code in enumerate(python_blocks(DOCS / page))
               if (why := run_block(code, namespace, f"docs/{page} block {index}"))]
    optional = [why for why in skipped if not why.startswith("training")]
    if optional:
        pytest.skip("; ".join(optional))


def test_readme_has_the_two_commands_first():
    text = README.read_text()
    assert text.index("make demo") < text.index("## Installation")
    assert text.index("make test") < text.index("## Installation")


# Links ------------------------------------------------------------------------------------


def _slug(heading: str) -> str:
    """The anchor of a Markdown heading as MkDocs (Python-Markdown's ``toc``) makes it: the
    text without code marks, ASCII, without punctuation, lower case, dashes for spaces."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading).replace("`", "")
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode()
    text = re.sub(r"[^\w\s-]", "", text).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


def _anchors(path: Path) -> set[str]:
    text = re.sub(r"```.*?```", "", path.read_text(), flags=re.S)
    return {_slug(m) for m in re.findall(r"^#+ (.+)$", text, flags=re.M)}


def _links(path: Path) -> list[str]:
    """The targets of the inline links and images of ``path``, outside code."""
    text = re.sub(r"```.*?```", "", path.read_text(), flags=re.S)
    text = re.sub(r"`[^`\n]*`", "", text)
    return re.findall(r"\]\(([^)\s]+)\)", text)


@pytest.mark.parametrize("page", ["README.md"] + [p.relative_to(ROOT).as_posix()
                                                  for p in PAGES])
def test_relative_links_lead_to_files(page):
    path = ROOT / page
    broken = []
    for target in _links(path):
        if re.match(r"[a-z]+:", target):  # https:, mailto:
            continue
        file, _, anchor = target.partition("#")
        goal = (path.parent / file).resolve() if file else path
        if not goal.is_file():
            broken.append(f"{target} (no file {os.path.relpath(goal, ROOT)})")
        elif anchor and goal.suffix == ".md" and anchor not in _anchors(goal):
            broken.append(f"{target} (no heading #{anchor})")
    assert not broken, f"{page}: broken links: {broken}"


def test_link_check_reads_links_and_headings():
    assert _slug("The game flow (`game=...`)") == "the-game-flow-game"
    assert _slug("The shipped SSL team (2 vs 2)") == "the-shipped-ssl-team-2-vs-2"
    assert "docs/index.md" in _links(README)
    assert "installation" in _anchors(DOCS / "getting-started.md")
