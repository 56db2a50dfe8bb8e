"""The BenchMARL example at its tiny size (seconds of training), MAPPO and IPPO, each reloaded
from its checkpoint in the same process and in a new one. Skipped without BenchMARL (the main
suite); ``make test-benchmarl`` runs it in the environment of the benchmarl extra."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("benchmarl", reason="the benchmarl extra (make test-benchmarl)")

ROOT = Path(__file__).resolve().parents[2]


def _run(*args: str) -> str:
    env = {**os.environ, "SOCCER_EXAMPLES_TINY": "1", "OMP_NUM_THREADS": "1"}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
    proc = subprocess.run([sys.executable, str(ROOT / "examples" / "benchmarl_match.py"),
                           *args], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-5000:]
    return proc.stdout


@pytest.mark.parametrize("algorithm", ["mappo", "ippo"])
def test_benchmarl_example_trains_evaluates_and_reloads(algorithm, tmp_path):
    out = _run("--algorithm", algorithm, "--tiny", "--out", str(tmp_path))
    lines = out.splitlines()
    assert any(line.startswith(f"{algorithm}: 2 iterations, 320 steps in ") for line in lines)
    assert any(line.startswith("evaluation match: blue ") and line.endswith(" steps")
               for line in lines)
    assert "reloaded checkpoint_320.pt (2 iterations, weights identical): blue " in out
    (folder,) = tmp_path.glob(f"{algorithm}_match_mlp_*")
    assert (folder / f"{folder.name}.json").is_file()  # BenchMARL's evaluation
    checkpoint = folder / "checkpoints" / "checkpoint_320.pt"
    assert checkpoint.is_file() and (folder / "config.pkl").is_file()
    again = _run("--restore", str(checkpoint))
    assert "reloaded checkpoint_320.pt (2 iterations): blue " in again
