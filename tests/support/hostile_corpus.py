"""A corpus of hostile files, and the check that the package refuses each within its budgets.

``python tests/support/hostile_corpus.py write FOLDER`` writes the corpus (an honest model,
policy and statistics first, then each hostile file made from them, and ``cases.json``);
``python tests/support/hostile_corpus.py check FOLDER`` loads every case the way a user
would (``soccer-env eval``, ``soccer-env train --resume``) in this one process and prints a
JSON line per case: whether it was refused, the message, the process's peak resident memory
after it [MB] (counted from the end of the imports, whose own peak is reported apart), the
bytes the process wrote while loading it, and whether code from a file
ran. ``tests/agents/test_hostile_corpus.py`` runs the check in a subprocess under a
resource limit and asserts every line.

The files are those of the reliability reviews: small files that used to cost gigabytes
(members compressed with bzip2 that declare a small size, deflate bombs, a nested torch
record declaring 1 GiB, a sparse 1 GiB ``config.json``, networks of 8192 x 8192, a checkpoint
every step), files refused with a message that did not say why (a pickle in a ``.pth``
entry, JSON nested 200,000 deep, ``Infinity``, NaN statistics, a symlink to a device), and
files that would run code (a pickle of statistics, object arrays). RLlib checkpoints (forged
signatures, symlinked and traversal members) are tried by the RLlib tests, in their own
environment.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import pickle
import resource
import struct
import sys
import zipfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

GK = "soccer_env/Goalkeeper-v0"
#: The honest files every case is made from, in the corpus folder.
HONEST_MODEL, HONEST_POLICY, HONEST_STATS = "honest/model.zip", "honest/policy.npz", \
    "honest/stats.npz"
#: Where a payload would write if code from a file ran.
MARKER = "pwned"
#: The bytes of the bombs once unpacked.
BOMB_BYTES = 2**30


class Payload:
    """Unpickling this writes :data:`MARKER` into the corpus folder: proof that code ran."""

    def __init__(self, marker: Path) -> None:
        self.marker = marker

    def __reduce__(self) -> tuple:
        return (exec, (f"open({str(self.marker)!r}, 'w').write('code ran')",))


# -- writing ----------------------------------------------------------------------------------

def _honest(folder: Path) -> None:
    """A small PPO model of the keeper, a numpy policy of its shape and normalisation
    statistics, as training writes them."""
    import gymnasium as gym
    import numpy as np
    from stable_baselines3 import PPO
    from stable_baselines3.common.vec_env import DummyVecEnv, VecNormalize

    import soccer_env  # noqa: F401
    from agents.policies import NumpyPolicy
    from agents.sb3.normalization import save_vecnormalize

    (folder / "honest").mkdir(parents=True, exist_ok=True)
    env = gym.make(GK)
    PPO("MlpPolicy", env, n_steps=64, batch_size=64, device="cpu",
        policy_kwargs={"net_arch": [8]}).save(folder / HONEST_MODEL)
    n_obs, n_act = env.observation_space.shape[0], env.action_space.shape[0]
    NumpyPolicy([("linear", np.zeros((n_act, n_obs)), np.zeros(n_act))], "clip",
                -np.ones(n_act), np.ones(n_act)).save(folder / HONEST_POLICY)
    save_vecnormalize(VecNormalize(DummyVecEnv([lambda: gym.make(GK)])), folder / HONEST_STATS)


def _members(path: Path) -> dict[str, bytes]:
    with zipfile.ZipFile(path) as z:
        return {i.filename: z.read(i) for i in z.infolist()}


def _zip(path: Path, members: dict[str, bytes], methods: dict[str, int] | None = None) -> Path:
    """``members`` written to ``path``, stored unless ``methods`` names another method."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(path, "w") as z:
        for name, data in members.items():
            z.writestr(name, data, compress_type=(methods or {}).get(name, zipfile.ZIP_STORED))
    return path


def _declare(path: Path, member: str, size: int) -> None:
    """Patch the uncompressed size that ``path``'s local and central headers declare for
    ``member`` to ``size`` (a small lie about a large member)."""
    data = bytearray(path.read_bytes())
    name = member.encode()
    for signature, offset in ((b"PK\x03\x04", 22), (b"PK\x01\x02", 24)):
        name_at = 30 if signature == b"PK\x03\x04" else 46
        start = 0
        while (start := data.find(signature, start)) >= 0:
            if data[start + name_at:start + name_at + len(name)] == name:
                data[start + offset:start + offset + 4] = struct.pack("<I", size)
            start += 4
    path.write_bytes(bytes(data))


def _deflate_bomb(path: Path, members: dict[str, bytes], bomb: str, prefix: bytes,
                  fill: bytes) -> Path:
    """``members`` with ``bomb`` deflated: ``prefix`` then ``fill`` up to
    :data:`BOMB_BYTES` (about 1 MB on disk)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    chunk = fill * (2**20 // len(fill))
    with zipfile.ZipFile(path, "w") as z:
        for name, data in members.items():
            if name != bomb:
                z.writestr(name, data)
        info = zipfile.ZipInfo(bomb)
        info.compress_type = zipfile.ZIP_DEFLATED
        with z.open(info, "w") as f:
            f.write(prefix)
            for _ in range((BOMB_BYTES - len(prefix)) // len(chunk)):
                f.write(chunk)
    return path


def _run(folder: Path, name: str, model: dict[str, bytes] | None = None,
         config: dict[str, Any] | None = None) -> Path:
    """A run folder ``name`` holding ``model`` as its ``final_model.zip`` and a checkpoint,
    and ``config`` (default: a new run's) as its ``config.json``."""
    from agents.runs.training.config import TrainConfig

    run = folder / name
    (run / "checkpoints").mkdir(parents=True, exist_ok=True)
    members = model or _members(folder / HONEST_MODEL)
    _zip(run / "final_model.zip", members)
    _zip(run / "checkpoints" / "model_128_steps.zip", members)
    (run / "config.json").write_text(json.dumps(config or {**TrainConfig().to_dict(),
                                                           "out": "/somewhere/else"}))
    return run


def _model_with(folder: Path, **changes: Any) -> dict[str, bytes]:
    members = _members(folder / HONEST_MODEL)
    data = json.loads(members["data"])
    data.update(changes)
    members["data"] = json.dumps(data).encode()  # json.dumps writes Infinity as Python does
    return members


def _torch_record_declaring(size: int) -> bytes:
    """A torch weight record (a zip) whose one tensor member declares ``size`` bytes."""
    payload = b"\0" * 54_321  # a size whose four bytes occur nowhere else in the record
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as record:
        record.writestr("archive/data/0", payload)
    return buffer.getvalue().replace(struct.pack("<I", len(payload)), struct.pack("<I", size))


def _torch_pickle(marker: Path) -> bytes:
    """A ``.pth`` entry whose pickle runs code: what ``torch.save`` of such an object
    writes."""
    import torch

    buffer = io.BytesIO()
    torch.save({"policy": Payload(marker)}, buffer)
    return buffer.getvalue()


def _npz_rewrite(src: Path, dst: Path, **arrays: Any) -> Path:
    import numpy as np

    with np.load(src, allow_pickle=False) as data:
        content = {k: data[k] for k in data.files}
    content.update(arrays)
    np.savez(dst, **content)
    return dst


def write_corpus(folder: Path) -> list[dict[str, str]]:
    """Write the corpus into ``folder`` and return its cases (also in ``cases.json``): each
    ``{"name", "what", "load", "target", "expect"}`` with ``load`` ``"eval"`` (``soccer-env
    eval --policy TARGET``) or ``"resume"`` (``soccer-env train --resume TARGET``) and
    ``expect`` a regular expression the refusal's message must match."""
    folder = Path(folder)
    _honest(folder)
    marker = folder / MARKER
    honest = _members(folder / HONEST_MODEL)
    cases: list[dict[str, str]] = []

    def case(name: str, what: str, load: str, target: Path, expect: str) -> None:
        cases.append({"name": name, "what": what, "load": load,
                      "target": str(target.relative_to(folder)), "expect": expect})

    _costly_files(folder, honest, case)
    _unclear_and_unsafe_files(folder, honest, marker, case)
    (folder / "cases.json").write_text(json.dumps(cases, indent=1))
    return cases


def _costly_files(folder: Path, honest: dict[str, bytes], case: Callable[..., None]) -> None:
    """The small files that used to cost gigabytes (or a checkpoint every step)."""
    run = _run(folder, "bzip2_data")
    _zip(run / "final_model.zip", honest, {"data": zipfile.ZIP_BZIP2})
    _declare(run / "final_model.zip", "data", 1_000)
    case("bzip2_data", "SB3 zip whose data entry is bzip2 and declares 1,000 bytes", "eval",
         run / "final_model.zip", r"member 'data' is compressed with bzip2; only stored and "
                                  r"deflate")
    run = _run(folder, "deflate_data")
    data = honest["data"]
    _deflate_bomb(run / "final_model.zip", honest, "data", data, b" ")
    case("deflate_data", "SB3 zip whose data entry is JSON and 1 GiB of spaces, deflated",
         "eval", run / "final_model.zip", r"unpacks to 1,07[0-9,]+ bytes, more than the "
                                         r"67,108,864 that are read")
    run = _run(folder, "deflate_data_lying")
    _deflate_bomb(run / "final_model.zip", honest, "data", data, b" ")
    _declare(run / "final_model.zip", "data", len(data))
    case("deflate_data_lying", "the same, declaring the JSON's size alone", "eval",
         run / "final_model.zip", r"member 'data' is not what its header declares")
    policy = _members(folder / HONEST_POLICY)
    path = _zip(folder / "bzip2_header.npz", policy, {"header.npy": zipfile.ZIP_BZIP2})
    _declare(path, "header.npy", 100)
    case("bzip2_header", "policy .npz whose header.npy member is bzip2 and declares 100 "
                         "bytes", "eval", path, r"header.npy' is compressed with bzip2")
    run = _run(folder, "torch_record", {**honest, "policy.pth": _torch_record_declaring(2**30)})
    case("torch_record", "policy.pth whose nested tensor record declares 1 GiB", "eval",
         run / "final_model.zip", r"'archive/data/0' declares 1,073,741,824 bytes")
    run = _run(folder, "checkpoint_bomb")
    _deflate_bomb(run / "checkpoints" / "model_128_steps.zip", honest,
                  "policy.optimizer.pth", b"", b"\0")
    case("checkpoint_bomb", "checkpoint whose optimizer entry is a 1 GiB deflate bomb",
         "resume", run / "checkpoints" / "model_128_steps.zip",
         r"model_128_steps.zip unpacks to 1,07[0-9,]+ bytes, more than the 67,108,864")
    run = _run(folder, "sparse_config")
    with open(run / "config.json", "wb") as f:
        f.truncate(BOMB_BYTES)
    case("sparse_config", "a sparse 1 GiB config.json (0 bytes on disk)", "eval", run,
         r"config.json.* more than the 16,777,216 bytes")
    run = _run(folder, "huge_network", _model_with(folder, policy_kwargs={
        "net_arch": [8192, 8192]}))
    case("huge_network", "net_arch [8192, 8192] in a model's data", "eval",
         run / "final_model.zip", r"more than the 4,194,304 built from a file without --trust")
    run = _run(folder, "checkpoint_every", config={**json.loads(
        (folder / "huge_network" / "config.json").read_text()), "checkpoint_every": 1})
    case("checkpoint_every", "checkpoint_every: 1 in a run's config.json", "resume",
         run / "checkpoints" / "model_128_steps.zip",
         r"checkpoint_every 1 is below 10,000.*--checkpoint-every.*--trust")


def _unclear_and_unsafe_files(folder: Path, honest: dict[str, bytes], marker: Path,
                              case: Callable[..., None]) -> None:
    """The files refused with a message that did not say why, and those that run code."""
    run = _run(folder, "pth_pickle", {**honest, "policy.pth": _torch_pickle(marker)})
    case("pth_pickle", "a policy.pth entry whose pickle runs code", "eval",
         run / "final_model.zip", r"a weight entry \(.pth\) is a pickle that names the "
                                  r"global exec, not weights only; .*--trust")
    run = _run(folder, "deep_json")
    (run / "config.json").write_text("[" * 200_000 + "]" * 200_000)
    case("deep_json", "config.json nested 200,000 deep", "eval", run,
         r"config.json nests JSON 200,000 deep, more than the 64 levels")
    run = _run(folder, "infinite_steps", _model_with(folder, num_timesteps=float("inf")))
    case("infinite_steps", "num_timesteps: Infinity in a model's data", "eval",
         run / "final_model.zip", r"Infinity is not a JSON")
    run = _run(folder, "nan_statistics")
    _npz_rewrite(folder / HONEST_STATS, run / "final_vecnormalize.npz",
                 obs_mean=float("nan") * _stats_mean(folder))
    case("nan_statistics", "normalisation statistics holding NaN", "eval", run,
         r"final_vecnormalize.npz.*not finite \(NaN or infinite\)")
    run = _run(folder, "device_config")
    (run / "config.json").unlink()
    os.symlink("/dev/zero", run / "config.json")
    case("device_config", "config.json a symlink to /dev/zero", "eval", run,
         r"config.json.*not a regular file")
    run = _run(folder, "statistics_pickle")
    (run / "final_vecnormalize.pkl").write_bytes(pickle.dumps(Payload(marker)))
    case("statistics_pickle", "statistics as a pickle that runs code", "eval", run,
         r"final_vecnormalize.pkl.*--trust")
    path = folder / "object_array.npz"
    import numpy as np

    _npz_rewrite(folder / HONEST_POLICY, path, extra=np.array([Payload(marker)], dtype=object))
    case("object_array", "policy .npz with an object array (a pickle) member", "eval", path,
         r"object_array.npz")


def _stats_mean(folder: Path) -> Any:
    import numpy as np

    with np.load(folder / HONEST_STATS) as data:
        return np.ones_like(data["obs_mean"])


# -- checking ---------------------------------------------------------------------------------

def _written_bytes() -> int:
    """The bytes this process has written so far (``/proc/self/io``'s ``wchar``: every
    ``write`` to a file or pipe)."""
    for line in Path("/proc/self/io").read_text().splitlines():
        if line.startswith("wchar:"):
            return int(line.split()[1])
    raise RuntimeError("/proc/self/io has no wchar")


def _peak_mb() -> float:
    """This process's peak resident memory [MB] since :func:`_restart_peak` (``VmHWM``)."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024.0
    raise RuntimeError("/proc/self/status has no VmHWM")


def _restart_peak() -> None:
    """Start the peak of :func:`_peak_mb` afresh from what is resident now (Linux's
    ``clear_refs``): the imports' own peak (numba compiling the kernels on a fresh install)
    is not a file's cost."""
    Path("/proc/self/clear_refs").write_text("5")


def _argv(folder: Path, case: dict[str, str]) -> list[str]:
    target = str(folder / case["target"])
    if case["load"] == "resume":
        return ["train", "--resume", target, "--steps", "2176", "--no-progress"]
    return ["eval", "--policy", target, "--episodes", "1", "--video", "0", "--out",
            str(folder / "eval_out" / case["name"])]


def check_case(folder: Path, case: dict[str, str]) -> dict[str, Any]:
    """Load ``case`` as a user would, in this process; what happened (see the module
    docstring). ``refused``: the command stopped with a message (``obscure`` names an
    exception other than the command's own refusal)."""
    from soccer_lab.cli import main

    before = _written_bytes()
    err = io.StringIO()
    refused, obscure, message = False, None, ""
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            main(_argv(folder, case))
        except SystemExit as stop:
            refused = stop.code not in (0, None)
        except Exception as exc:  # noqa: BLE001 - reported, and the test fails on it
            refused, obscure, message = True, type(exc).__name__, str(exc)
    written = _written_bytes() - before
    return {"name": case["name"], "refused": refused, "obscure": obscure,
            "message": message or (err.getvalue().strip().splitlines() or [""])[-1],
            "peak_mb": round(_peak_mb(), 1), "written_bytes": written,
            "ran_code": (folder / MARKER).exists()}


def check_corpus(folder: Path) -> list[dict[str, Any]]:
    """Every case of ``folder``'s ``cases.json`` through :func:`check_case`, in order, after
    importing what a loader imports (so that the first case's peak is its own)."""
    import stable_baselines3  # noqa: F401
    import torch  # noqa: F401

    import soccer_env  # noqa: F401
    import soccer_lab.cli  # noqa: F401

    folder = Path(folder)
    cases = json.loads((folder / "cases.json").read_text())
    imports = round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, 1)
    _restart_peak()
    baseline = {"name": "(imports)", "imports_peak_mb": imports, "peak_mb": round(_peak_mb(), 1)}
    return [baseline] + [check_case(folder, case) for case in cases]


def main(argv: list[str]) -> int:
    if len(argv) != 2 or argv[0] not in ("write", "check"):
        print("usage: hostile_corpus.py write|check FOLDER", file=sys.stderr)
        return 2
    folder = Path(argv[1])
    if argv[0] == "write":
        for case in write_corpus(folder):
            print(f"{case['name']:18s} {case['what']}")
        return 0
    for result in check_corpus(folder):
        print(json.dumps(result), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
