"""Training under faults: a run folder is never overwritten without --force, a resumed run
writes where the user says, bad input is refused before anything is written, and Ctrl-C or
a failing rollout worker ends training with a checkpoint to resume from."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("stable_baselines3")

from soccer_lab.cli import main  # noqa: E402

pytestmark = pytest.mark.slow

#: A tiny in-process run: two rollouts of 128 steps.
TINY = ["--steps", "256", "--n-envs", "2", "--workers", "0", "--hp", "n_steps=64",
        "--eval-every", "0", "--checkpoint-every", "128", "--no-progress"]


def _mtimes(folder: Path) -> dict[str, int]:
    return {str(p.relative_to(folder)): p.stat().st_mtime_ns for p in folder.rglob("*")
            if p.is_file()}


def test_an_existing_run_is_kept_unless_forced(tmp_path, capsys):
    run = tmp_path / "run"
    assert main(["train", *TINY, "--out", str(run)]) == 0
    (run / "notes.txt").write_text("mine")
    (run / "checkpoints" / "model_999_steps.zip").write_bytes(b"stale")
    before = _mtimes(run)
    capsys.readouterr()
    with pytest.raises(SystemExit):
        main(["train", *TINY, "--seed", "1", "--out", str(run)])
    err = capsys.readouterr().err
    assert "already holds a training run" in err and "--force" in err, err
    assert _mtimes(run) == before  # nothing touched
    assert main(["train", *TINY, "--seed", "1", "--out", str(run), "--force"]) == 0
    assert json.loads((run / "config.json").read_text())["seed"] == 1
    assert not (run / "checkpoints" / "model_999_steps.zip").exists()  # stale ones gone
    assert (run / "notes.txt").read_text() == "mine"  # not a run file: kept


def test_a_resumed_run_writes_where_the_user_says_not_where_its_files_say(tmp_path):
    original = tmp_path / "original"
    assert main(["train", *TINY, "--out", str(original)]) == 0
    copy = tmp_path / "received"
    shutil.copytree(original, copy)
    config = json.loads((copy / "config.json").read_text())
    assert config["out"] == str(original)  # the copy's file points at the original
    before = _mtimes(original)
    checkpoint = copy / "checkpoints" / "model_128_steps.zip"
    # The run's checkpoint interval is below what a received config.json may set: given again.
    again = ["--steps", "384", "--checkpoint-every", "128", "--no-progress"]
    assert main(["train", "--resume", str(checkpoint), *again]) == 0
    assert _mtimes(original) == before  # the original run untouched
    assert json.loads((copy / "summary.json").read_text())["steps"] == 384
    assert json.loads((copy / "config.json").read_text())["out"] == str(copy)
    # --out elsewhere: a fresh folder is written; one holding a run needs --force.
    assert main(["train", "--resume", str(checkpoint), *again,
                 "--out", str(tmp_path / "branch")]) == 0
    with pytest.raises(SystemExit):
        main(["train", "--resume", str(checkpoint), *again, "--out", str(original)])
    assert _mtimes(original) == before


@pytest.mark.parametrize("args,message", [
    (["--hp", "n_steps=-3"], "could not be built with hyperparameters"),
    (["--hp", "learning_rate=\"fast\""], "could not be built with hyperparameters"),
    (["--env", "soccer_env/Match-v0", "--opponent", "nowhere.npz"], "no such file"),
    (["--env", "soccer_env/Match-v0", "--opponent", "champion"], "opponent must be one of"),
])
def test_bad_values_are_refused_before_anything_is_written(tmp_path, capsys, args, message):
    with pytest.raises(SystemExit):
        main(["train", *TINY, "--out", str(tmp_path / "x"), *args])
    assert message in capsys.readouterr().err
    assert not (tmp_path / "x").exists()


def test_a_numpy_policy_file_plays_the_match_opponent(tmp_path):
    """--opponent takes a numpy policy file (loaded without pickle): a match learner trains
    against a copy of an earlier learner."""
    first = tmp_path / "first"
    match = ["--env", "soccer_env/Match-v0", "--env-kwarg", "blue=1", "--env-kwarg",
             "yellow=1", "--n-envs", "1", "--workers", "0", "--hp", "n_steps=64",
             "--eval-every", "0", "--checkpoint-every", "0", "--no-progress"]
    assert main(["train", *match, "--steps", "64", "--out", str(first)]) == 0
    second = tmp_path / "second"
    assert main(["train", *match, "--steps", "64", "--out", str(second), "--opponent",
                 str(first / "final_policy.npz")]) == 0
    assert json.loads((second / "config.json").read_text())["opponent"].endswith(".npz")


def test_match_self_play_runs_its_matches_in_worker_processes(tmp_path):
    """--env soccer_env/Match-v0 --workers 2: the matches are stepped by two worker
    processes, the self-play opponent (a frozen copy of the learner) is sent to them."""
    run = tmp_path / "selfplay"
    assert main(["train", "--env", "soccer_env/Match-v0", "--env-kwarg", "blue=1",
                 "--env-kwarg", "yellow=1", "--n-envs", "2", "--workers", "2", "--opponent",
                 "self", "--hp", "n_steps=64", "--steps", "256", "--eval-every", "0",
                 "--checkpoint-every", "0", "--out", str(run), "--no-progress"]) == 0
    config = json.loads((run / "config.json").read_text())
    assert config["n_workers"] == 2 and config["opponent"] == "self"
    assert json.loads((run / "summary.json").read_text())["steps"] >= 256


def test_a_failing_worker_ends_training_with_a_checkpoint(tmp_path, monkeypatch, capsys,
                                                          no_hang):
    """An environment that raises in the second rollout worker: training ends within
    seconds, naming the worker and carrying the environment's traceback; the model of the
    last completed update is saved and the message says how to resume."""
    from faulty_envs import FailingAfter

    import agents.vec.factories as factories
    from agents.runs.folders import TrainingStopped
    from agents.runs.training import TrainConfig, train

    real = factories.goalkeeper_env_fn
    monkeypatch.setattr(factories, "goalkeeper_env_fn",
                        lambda *a, **k: FailingAfter(real(*a, **k), after=200))
    cfg = TrainConfig(total_steps=10_000, n_envs=2, n_workers=2, out=str(tmp_path / "run"),
                      hyperparams={"n_steps": 64}, eval_every=0, checkpoint_every=0,
                      progress_bar=False)
    with pytest.raises(TrainingStopped) as err:
        train(cfg)
    stopped = err.value
    assert stopped.reason == "worker failed"
    text = str(stopped)
    assert "rollout worker 0" in text and FailingAfter.MESSAGE in text, text
    # Rollouts of 2 environments x 64 steps: each environment's 201st step falls in the 4th
    # rollout, so the checkpoint is the model after the 3rd update, 384 steps.
    assert stopped.steps == 384
    assert stopped.checkpoint == tmp_path / "run" / "checkpoints" / \
        f"model_{stopped.steps}_steps.zip"
    assert stopped.checkpoint.is_file()
    assert (stopped.checkpoint.parent / f"model_vecnormalize_{stopped.steps}_steps.npz"
            ).is_file()
    assert f"--resume {stopped.checkpoint} --steps 10000" in text
    # The CLI says the same without a traceback, and exits with 1.
    capsys.readouterr()
    assert main(["train", "--steps", "10000", "--n-envs", "2", "--workers", "2", "--hp",
                 "n_steps=64", "--eval-every", "0", "--checkpoint-every", "0",
                 "--no-progress", "--out", str(tmp_path / "cli")]) == 1
    err_text = capsys.readouterr().err
    assert err_text.startswith("soccer-env train: training stopped: rollout worker")
    assert "continue with: soccer-env train --resume" in err_text


def test_ctrl_c_saves_a_checkpoint_and_prints_the_resume_command(tmp_path, no_hang):
    """Ctrl-C to the whole process group (as a terminal sends it) while training: one
    message, no traceback from any process, exit code 130, a checkpoint of the last
    completed update, and the printed command resumes from it."""
    run = tmp_path / "run"
    cmd = [sys.executable, "-m", "soccer_lab.cli", "train", "--steps", "1000000", "--n-envs",
           "4", "--workers", "2", "--hp", "n_steps=64", "--eval-every", "0",
           "--checkpoint-every", "0", "--no-progress", "--out", str(run)]
    # A suite started in the background of a non-interactive shell inherits SIGINT ignored
    # (POSIX), which the training would inherit too: give it the terminal's default.
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        # An update has completed once TensorBoard's log, created with a header, has grown
        # twice (the logs of each rollout are written before the update on it): wait for
        # that, however long the workers take to start, rather than a fixed time.
        sizes: set[int] = set()
        deadline = time.monotonic() + 300.0
        while len(sizes - {0}) < 3:
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() < deadline, "no update within 300 s"
            logs = list((run / "tb").rglob("events.out.tfevents.*")) if (run / "tb").is_dir() \
                else []
            if logs:
                sizes.add(sum(f.stat().st_size for f in logs))
            time.sleep(0.1)
        time.sleep(1.0)
        os.killpg(proc.pid, signal.SIGINT)
        try:
            out, err = proc.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            status = Path(f"/proc/{proc.pid}/status")
            masks = ([line for line in status.read_text().splitlines()
                      if line.startswith(("SigBlk", "SigIgn", "SigCgt", "State"))]
                     if status.exists() else [])
            os.killpg(proc.pid, signal.SIGKILL)
            out, err = proc.communicate()
            pytest.fail(f"training did not stop within 60 s of Ctrl-C ({masks}); stderr:\n{err}")
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
    assert "training interrupted" in err and "continue with: soccer-env train --resume" in err
    command = err.split("continue with: ")[1].split()
    checkpoint = Path(command[command.index("--resume") + 1])
    assert checkpoint.is_file() and checkpoint.parent == run / "checkpoints"
    steps = int(checkpoint.stem.split("_")[1])
    assert steps > 0 and steps % 256 == 0  # whole rollouts of 4 x 64 steps
    assert main(["train", "--resume", str(checkpoint), "--steps", str(steps + 256),
                 "--workers", "0", "--no-progress"]) == 0
    assert json.loads((run / "summary.json").read_text())["steps"] == steps + 256
