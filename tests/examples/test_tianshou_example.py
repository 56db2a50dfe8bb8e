"""The Tianshou example runs as docs/guide/rl-libraries.md says, at its tiny size: PPO trains on
the keeper's default infos in both of Tianshou's vector environments, on true and on perceived
observations; and the page's Tianshou block runs as written. Tianshou is not in the main
environment (tests/test_readme.py skips the block there): ``make test-tianshou`` runs this
file."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("tianshou")

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "guide" / "rl-libraries.md"


def _run(*args: str) -> str:
    env = {**os.environ, "SOCCER_EXAMPLES_TINY": "1", "OMP_NUM_THREADS": "1"}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
    proc = subprocess.run([sys.executable, str(ROOT / "examples" / "tianshou_keeper.py"),
                           "--tiny", *args], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-5000:]
    return proc.stdout


@pytest.mark.parametrize("args, label", [
    ((), "truth, 4 DummyVectorEnvs"),
    (("--vector", "subproc", "--obs-mode", "perceived"), "perceived, 4 SubprocVectorEnvs"),
])
def test_tianshou_keeper_example(args, label):
    out = _run(*args)
    assert f"PPO keeper ({label}): trained" in out
    steps = int(re.search(r", (\d+) steps, best test return", out).group(1))
    assert steps >= 2048
    saves = re.search(r"evaluation: (\d+)/4 saves, (\d+) steps per shot", out)
    assert saves and 0 <= int(saves.group(1)) <= 4 and int(saves.group(2)) > 0


def test_the_guides_tianshou_block_runs():
    blocks = [code for code in re.findall(r"```python\n(.*?)```", PAGE.read_text(), flags=re.S)
              if "from tianshou" in code]
    assert len(blocks) == 1
    namespace: dict = {}
    exec(compile(blocks[0], f"{PAGE.name} Tianshou block", "exec"), namespace)
    assert namespace["collector"].collect_step >= 2048
    assert -1.0 <= float(namespace["action"]) <= 1.0
