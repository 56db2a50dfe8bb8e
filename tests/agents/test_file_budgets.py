"""Budgets on what is read from a file: archive members only stored or deflate-compressed (a
bzip2 member unpacks whole blocks whatever its header says), JSON bounded in size and depth
and without ``NaN`` or ``Infinity``, and only from regular files. Each refusal names the file
and the limit."""

from __future__ import annotations

import json
import os
import zipfile
from pathlib import Path

import numpy as np
import pytest

from agents.policies import NumpyPolicy
from agents.policies.files import (
    MAX_JSON_BYTES,
    MAX_JSON_DEPTH,
    UnsafeFileError,
    check_npz,
    parse_json,
    read_json,
)
from agents.runs.folders import run_config


def test_json_within_the_budgets_parses_as_json():
    text = '{"a": [1, 2.5, {"b": "]]]{{"}], "c": null}'  # brackets in strings open nothing
    assert parse_json(text, "x") == json.loads(text)
    assert parse_json(json.dumps({"deep": [[[[[1]]]]]}).encode(), "x") == {"deep": [[[[[1]]]]]}


@pytest.mark.parametrize("data, message", [
    ("[" * (MAX_JSON_DEPTH + 1) + "]" * (MAX_JSON_DEPTH + 1), "nests JSON 65 deep, more than"),
    ("[" * 200_000 + "]" * 200_000, "nests JSON 200,000 deep"),
    ('{"num_timesteps": Infinity}', "Infinity is not a JSON number"),
    ('{"mean": NaN}', "NaN is not a JSON number"),
    ('{"a": ', "is not valid JSON"),
    (" " * (MAX_JSON_BYTES + 1), f"more than the {MAX_JSON_BYTES:,} that are read"),
])
def test_json_beyond_the_budgets_is_refused_naming_the_file(data, message):
    with pytest.raises(ValueError, match=message) as err:
        parse_json(data, "run/config.json")
    assert str(err.value).startswith("run/config.json ")


def test_a_config_that_is_no_regular_file_is_refused(tmp_path):
    run = tmp_path / "run"
    run.mkdir()
    os.symlink("/dev/zero", run / "config.json")
    with pytest.raises(ValueError, match="is not a regular file"):
        run_config(run / "final_model.zip")
    (run / "config.json").unlink()
    (run / "config.json").write_text('{"a": ' + "[" * 1000 + "]" * 1000 + "}")
    with pytest.raises(UnsafeFileError, match="nests JSON 1,001 deep"):
        run_config(run / "final_model.zip")
    with pytest.raises(FileNotFoundError):
        read_json(tmp_path / "missing.json")


def _policy() -> NumpyPolicy:
    return NumpyPolicy([("linear", np.ones((2, 3)), np.zeros(2))], "clip", -np.ones(2),
                       np.ones(2))


def _npz(path: Path, method: int) -> Path:
    _policy().save(path)
    with zipfile.ZipFile(path) as src:
        members = [(i.filename, src.read(i)) for i in src.infolist()]
    with zipfile.ZipFile(path, "w", compression=method) as dst:
        for name, data in members:
            dst.writestr(name, data)
    return path


def test_an_archive_member_compressed_with_bzip2_or_lzma_is_refused(tmp_path):
    NumpyPolicy.load(_npz(tmp_path / "deflate.npz", zipfile.ZIP_DEFLATED))  # read as ever
    for method, name in ((zipfile.ZIP_BZIP2, "bzip2"), (zipfile.ZIP_LZMA, "LZMA")):
        path = _npz(tmp_path / f"{name}.npz", method)
        with pytest.raises(UnsafeFileError, match=f"compressed with {name}; only stored and "
                                                  "deflate members are read"):
            check_npz(path)
        with pytest.raises(UnsafeFileError, match=str(path)):
            NumpyPolicy.load(path)


def test_a_policy_header_with_infinity_is_refused(tmp_path):
    path = tmp_path / "policy.npz"
    _policy().save(path)
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files}
    header = json.loads(str(arrays["header"]))
    header["meta"] = {"steps": float("inf")}
    arrays["header"] = np.array(json.dumps(header))
    np.savez(path, **arrays)
    with pytest.raises(ValueError, match="header is not valid JSON .Infinity is not a JSON"):
        NumpyPolicy.load(path)


def test_a_model_data_entry_compressed_with_bzip2_is_refused(tmp_path):
    pytest.importorskip("stable_baselines3")
    from agents.sb3.model_files import model_data

    path = tmp_path / "model.zip"
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_BZIP2) as z:
        z.writestr("data", json.dumps({"n_envs": 1}) + " " * 5_000_000)
    with pytest.raises(UnsafeFileError, match="member 'data' is compressed with bzip2"):
        model_data(path)
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as z:
        z.writestr("data", "[" + "0," * (MAX_JSON_BYTES // 2) + "0]")  # an honest bomb
    with pytest.raises(UnsafeFileError, match=f"member 'data' is more than the "
                                              f"{MAX_JSON_BYTES:,} bytes"):
        model_data(path)


@pytest.fixture(scope="module")
def small_model(tmp_path_factory):
    """A small PPO model file of the keeper, as training writes it, and its spaces."""
    pytest.importorskip("stable_baselines3")
    import gymnasium as gym
    from stable_baselines3 import PPO

    import soccer_env  # noqa: F401

    env = gym.make("soccer_env/Goalkeeper-v0")
    path = tmp_path_factory.mktemp("model") / "model.zip"
    PPO("MlpPolicy", env, n_steps=64, batch_size=64, device="cpu",
        policy_kwargs={"net_arch": [8]}).save(path)
    return path, env.observation_space, env.action_space


def _rewrite(src: Path, dst: Path, **members: bytes) -> Path:
    """``src`` with ``members`` replaced, every member stored."""
    with zipfile.ZipFile(src) as z:
        entries = {i.filename: z.read(i) for i in z.infolist()}
    entries.update(members)
    with zipfile.ZipFile(dst, "w") as z:
        for name, data in entries.items():
            z.writestr(name, data)
    return dst


def test_a_model_whose_networks_would_be_huge_is_refused_before_they_are_built(
        tmp_path, small_model):
    from agents.sb3.model_files import MAX_NETWORK_PARAMETERS, load_model

    path, obs_space, act_space = small_model
    load_model(path, "PPO", observation_space=obs_space, action_space=act_space)  # honest
    with zipfile.ZipFile(path) as z:
        data = json.loads(z.read("data"))
    data["policy_kwargs"] = {"net_arch": [8192, 8192]}
    huge = _rewrite(path, tmp_path / "huge.zip", data=json.dumps(data).encode())
    with pytest.raises(UnsafeFileError, match=f"about [0-9,]+ parameters, more than the "
                                              f"{MAX_NETWORK_PARAMETERS:,} built from a file "
                                              "without --trust"):
        load_model(huge, "PPO", observation_space=obs_space, action_space=act_space)
    data["policy_kwargs"] = {"net_arch": ["wide"]}
    odd = _rewrite(path, tmp_path / "odd.zip", data=json.dumps(data).encode())
    with pytest.raises(ValueError, match="net_arch must be lists of layer sizes"):
        load_model(odd, "PPO", observation_space=obs_space, action_space=act_space)


def test_a_weight_record_declaring_more_than_it_holds_is_refused(tmp_path, small_model):
    import io
    import struct

    from agents.sb3.model_files import load_model

    path, obs_space, act_space = small_model
    payload = b"\0" * 54_321  # a size whose four bytes occur nowhere else in the record
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as record:
        record.writestr("archive/data/0", payload)
    crafted = buffer.getvalue().replace(struct.pack("<I", len(payload)),
                                        struct.pack("<I", 2**30))
    bad = _rewrite(path, tmp_path / "declares.zip", **{"policy.pth": crafted})
    with pytest.raises(UnsafeFileError, match="entry 'policy.pth': its member "
                                              "'archive/data/0' declares 1,073,741,824 bytes"):
        load_model(bad, "PPO", observation_space=obs_space, action_space=act_space)
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_BZIP2) as record:
        record.writestr("archive/data/0", payload)
    bz = _rewrite(path, tmp_path / "bzip.zip", **{"policy.pth": buffer.getvalue()})
    with pytest.raises(UnsafeFileError, match="'archive/data/0' is not stored or deflate"):
        load_model(bz, "PPO", observation_space=obs_space, action_space=act_space)
