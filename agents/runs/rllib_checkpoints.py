"""RLlib checkpoints of the runs of :mod:`agents.runs.rllib_runs`: signing, checking and
loading them.

RLlib checkpoints are pickles (``class_and_ctor_args.pkl``, the state files; cloudpickle
underneath), and unpickling runs whatever code the file names. So every checkpoint a run
writes is signed: :func:`sign_checkpoint` writes the SHA-256 digest of each of its files with
an HMAC of them under a key kept in the user's configuration folder
(:func:`checkpoint_key_path`, created on first use, readable by the user only), and
:func:`check_checkpoint` loads (resumes from) only checkpoints signed with that key and not
changed since: the user's own runs. Any other checkpoint (someone else's, one from another
machine or account, or one edited since) raises :class:`~agents.policies.files.UnsafeFileError`
unless ``trust=True`` (``--trust``), as the stable-baselines3 files that need unpickling do.

Nothing here imports Ray but :func:`load_checkpoint`, when called.
"""

from __future__ import annotations

import hashlib
import hmac
import json
import os
import secrets
import shutil
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from agents.policies.files import TRUST_HELP, UnsafeFileError, read_json

__all__ = ["CHECKPOINT_INFO", "SIGNATURE_FILE", "FINAL_CHECKPOINT", "RLLIB_METADATA",
           "checkpoint_key_path", "sign_checkpoint", "is_rllib_checkpoint",
           "check_checkpoint", "checkpoint_steps", "save_checkpoint", "load_checkpoint"]

#: The JSON file in each checkpoint with its steps and iteration.
CHECKPOINT_INFO = "soccer_env_checkpoint.json"
#: The JSON file in each checkpoint with its files' digests and their HMAC.
SIGNATURE_FILE = "soccer_env_signature.json"
#: The last checkpoint of a run, in its folder.
FINAL_CHECKPOINT = "final_checkpoint"
#: RLlib's own file in every checkpoint folder.
RLLIB_METADATA = "rllib_checkpoint.json"


def checkpoint_key_path() -> Path:
    """The signing key's file: ``$XDG_CONFIG_HOME/soccer_env/checkpoint_key`` (by default
    ``~/.config/soccer_env/checkpoint_key``)."""
    base = os.environ.get("XDG_CONFIG_HOME") or Path.home() / ".config"
    return Path(base) / "soccer_env" / "checkpoint_key"


def _key(create: bool) -> bytes | None:
    path = checkpoint_key_path()
    if path.is_file():
        return path.read_bytes()
    if not create:
        return None
    path.parent.mkdir(parents=True, exist_ok=True)
    key = secrets.token_bytes(32)
    # Created readable and writable by the user only; never replaced once there.
    try:
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    except FileExistsError:  # another process made it meanwhile
        return path.read_bytes()
    with os.fdopen(fd, "wb") as fh:
        fh.write(key)
    return key


def _digests(folder: Path) -> dict[str, str]:
    """SHA-256 of every file under ``folder`` but the signature, by relative path (POSIX);
    a link is refused (``ValueError``): it could point anywhere."""
    out = {}
    for path in sorted(folder.rglob("*")):
        rel = path.relative_to(folder).as_posix()
        if path.is_symlink():
            raise ValueError(f"{folder} holds a link, {rel}: not a checkpoint this package "
                             "wrote")
        if path.is_file() and rel != SIGNATURE_FILE:
            h = hashlib.sha256()
            with open(path, "rb") as fh:
                for block in iter(lambda: fh.read(1 << 20), b""):
                    h.update(block)
            out[rel] = h.hexdigest()
    return out


def _mac(key: bytes, digests: Mapping[str, str]) -> str:
    message = json.dumps(digests, sort_keys=True).encode()
    return hmac.new(key, message, hashlib.sha256).hexdigest()


def sign_checkpoint(folder: str | os.PathLike) -> None:
    """Sign the checkpoint ``folder`` with this user's key (see the module docstring)."""
    folder = Path(folder)
    digests = _digests(folder)
    signature = {"scheme": "hmac-sha256 over the JSON of the files' sha256 digests",
                 "files": digests, "mac": _mac(_key(create=True), digests)}
    (folder / SIGNATURE_FILE).write_text(json.dumps(signature, indent=1))


def is_rllib_checkpoint(path: str | os.PathLike) -> bool:
    """Whether ``path`` is a folder holding an RLlib checkpoint."""
    return Path(path).is_dir() and (Path(path) / RLLIB_METADATA).is_file()


def check_checkpoint(folder: str | os.PathLike, trust: bool = False) -> dict[str, Any]:
    """The :data:`CHECKPOINT_INFO` of checkpoint ``folder`` (``{"steps", "agent_steps",
    "iteration", ...}``), after checking that loading it is safe: signed with this user's
    key and unchanged since. Raises :class:`~agents.policies.files.UnsafeFileError` for any
    other checkpoint unless ``trust``, and ``ValueError`` for a folder that is not an RLlib
    checkpoint of this package."""
    folder = Path(folder)
    if not is_rllib_checkpoint(folder):
        raise ValueError(f"{folder} is not an RLlib checkpoint (a folder with "
                         f"{RLLIB_METADATA})")
    if not trust:
        reason = None
        key = _key(create=False)
        try:
            signature = read_json(folder / SIGNATURE_FILE)
            digests = _digests(folder)
        except FileNotFoundError:
            reason = "it is not signed"
        except (ValueError, TypeError) as err:
            reason = f"its signature cannot be read ({err})"
        if reason is None and key is None:
            reason = f"this account has no signing key ({checkpoint_key_path()})"
        if reason is None and (not isinstance(signature, dict)
                               or signature.get("files") != digests
                               or not hmac.compare_digest(str(signature.get("mac")),
                                                          _mac(key, digests))):
            reason = ("its signature does not match: it was written under another key (by "
                      "someone else, or on another machine or account) or changed since")
        if reason is not None:
            raise UnsafeFileError(
                f"{folder} is not a checkpoint of your own runs: {reason}. RLlib checkpoints "
                f"are pickles (cloudpickle): {TRUST_HELP}")
    try:
        return read_json(folder / CHECKPOINT_INFO)
    except (OSError, ValueError) as err:
        raise ValueError(f"{folder} has no readable {CHECKPOINT_INFO} ({err}): not a "
                         "checkpoint of soccer-env train") from None


def checkpoint_steps(folder: str | os.PathLike, trust: bool = False) -> int:
    """The environment steps checkpoint ``folder`` has trained (:func:`check_checkpoint`)."""
    return int(check_checkpoint(folder, trust)["steps"])


def save_checkpoint(algo: Any, folder: str | os.PathLike, info: Mapping[str, Any]) -> Path:
    """Save ``algo`` (``Algorithm.save_to_path``) into ``folder`` (replacing one there) with
    ``info`` as :data:`CHECKPOINT_INFO`, and sign it."""
    folder = Path(folder)
    if folder.exists():
        shutil.rmtree(folder)
    algo.save_to_path(str(folder.resolve()))
    (folder / CHECKPOINT_INFO).write_text(json.dumps(dict(info), indent=1))
    sign_checkpoint(folder)
    return folder


def load_checkpoint(folder: str | os.PathLike, trust: bool = False) -> Any:
    """The RLlib algorithm of checkpoint ``folder`` (``Algorithm.from_checkpoint``), once
    :func:`check_checkpoint` finds it safe to load (Ray starts on this machine unless it
    runs). The environments' ids are registered first, which the checkpoints of version
    0.1.0 name (newer ones name the environments' classes)."""
    from ray.rllib.algorithms.algorithm import Algorithm

    from agents.runs.rllib_envs import register_envs

    check_checkpoint(folder, trust)
    register_envs()
    return Algorithm.from_checkpoint(str(Path(folder).resolve()))
