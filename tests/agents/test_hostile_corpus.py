"""The hostile-file corpus (``tests/support/hostile_corpus.py``, which writes it and loads
it): every file is refused, with a message that says why; none runs code; and loading all
of them, one after the other in one process as ``soccer-env eval`` and ``soccer-env train
--resume`` do, adds less than 192 MB to what that process holds after its imports (512 MB
in all on the reference machine) and writes less than 10 MB.

The check runs in a subprocess with an address-space limit (a safety net: a regression
fails with a MemoryError instead of taking the machine's memory); the peak is its
``VmHWM`` counted from the end of its imports, the writes its ``/proc/self/io``
``wchar``."""

from __future__ import annotations

import json
import os
import re
import resource
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("stable_baselines3")
import hostile_corpus  # noqa: E402

#: The aims: a process that loads any of the files peaks below 512 MB and writes less than
#: 10 MB. What the imports hold resident (torch, stable-baselines3, the package) is not a
#: file's cost and varies between installations (320 MB on the reference machine, 440 MB
#: in a fresh virtual environment on /tmp), so the files' share is bounded: 512 MB less the
#: reference machine's imports [MB].
FILES_MB, WRITTEN_BYTES = 512 - 320, 10 * 2**20
#: The subprocess's address space (torch alone reserves about 1.2 GB of it).
ADDRESS_SPACE = 3 * 2**30


def _limit() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    folder = tmp_path_factory.mktemp("hostile")
    cases = hostile_corpus.write_corpus(folder)
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    done = subprocess.run([sys.executable, hostile_corpus.__file__, "check", str(folder)],
                          capture_output=True, text=True, timeout=600, preexec_fn=_limit,
                          env=env)
    assert done.returncode == 0, done.stderr[-3000:]
    lines = [json.loads(line) for line in done.stdout.splitlines()]
    assert [r["name"] for r in lines[1:]] == [c["name"] for c in cases]
    return folder, {c["name"]: c for c in cases}, lines


def test_every_hostile_file_is_refused_saying_why(results):
    folder, cases, lines = results
    for result in lines[1:]:
        case = cases[result["name"]]
        assert result["refused"] and result["obscure"] is None, result
        assert re.search(case["expect"], result["message"]), (case["what"], result["message"])
        assert case["target"].split("/")[0] in result["message"], result["message"]


def test_no_hostile_file_runs_code_or_costs_what_its_size_does_not_promise(results):
    folder, _, lines = results
    assert not (folder / hostile_corpus.MARKER).exists()
    assert not any(r.get("ran_code") for r in lines)
    resident = lines[0]["peak_mb"]  # after the imports, where the peak starts afresh
    for result in lines[1:]:
        assert result["peak_mb"] - resident < FILES_MB, (resident, result)
        assert result["written_bytes"] < WRITTEN_BYTES, result
    # Nothing was written into the received runs (a refused resume writes no checkpoint).
    for name in ("checkpoint_every", "checkpoint_bomb"):
        assert sorted(p.name for p in (folder / name / "checkpoints").iterdir()) == [
            "model_128_steps.zip"]
        assert not (folder / name / "summary.json").exists()


def test_the_corpus_is_small_on_disk(results):
    """The files are small: what they would cost comes from what they declare or unpack to."""
    folder, _, _ = results
    sizes = [p.stat().st_blocks * 512 for p in Path(folder).rglob("*") if p.is_file()]
    assert sum(sizes) < 8 * 2**20
