"""The README's Python examples run as written (training excepted: see test_api)."""

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"
BLOCKS = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)
#: The RL libraries of the "clients" extra: a block using one is skipped where it is missing.
CLIENTS = ("torchrl", "tensordict", "supersuit", "rl_zoo3")


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_readme_example(index):
    code = BLOCKS[index]
    if ".learn(" in code:
        pytest.skip("training example: shortened version in test_api")
    namespace = {}
    if "policy = ScriptedGoalkeeper.for_env(env)" in code:
        exec(BLOCKS[index - 1], namespace)  # continues the previous example
    try:
        exec(compile(code, f"README block {index}", "exec"), namespace)
    except ModuleNotFoundError as err:
        if err.name not in CLIENTS:
            raise
        pytest.skip(f"{err.name} is not installed (the clients extra)")


def test_readme_has_the_two_commands_first():
    text = README.read_text()
    assert text.index("make demo") < text.index("## Installation")
    assert text.index("make test") < text.index("## Installation")
