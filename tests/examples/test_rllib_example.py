"""The RLlib example runs as docs/tutorials/ray-cluster.md says, at its tiny size (seconds of
training)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("ray.rllib")

ROOT = Path(__file__).resolve().parents[2]


def test_rllib_match_example(tmp_path):
    env = {**os.environ, "SOCCER_ENV_EXAMPLE_TINY": "1"}
    proc = subprocess.run([sys.executable, str(ROOT / "examples" / "rllib_match.py"),
                           "--out", str(tmp_path / "checkpoint")], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    lines = proc.stdout.splitlines()
    assert [line.split(":")[0] for line in lines if line.startswith("iteration")] == [
        "iteration 1", "iteration 2"]
    assert any(line.startswith("evaluation match: blue (learner)") for line in lines)
    assert (tmp_path / "checkpoint" / "rllib_checkpoint.json").is_file()
