"""Hostile and corrupt files: loading a policy, statistics or checkpoint never runs code from
the file unless trusted, never allocates what a small file declares, and a damaged file gives
an error naming it (not a ``BadZipFile``, ``EOFError``, ``KeyError`` or ``UnpicklingError``
from deep inside a library)."""

from __future__ import annotations

import base64
import json
import pickle
import zipfile
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")
from stable_baselines3 import PPO  # noqa: E402

import soccer_env  # noqa: E402,F401
from agents.policies import NumpyPolicy  # noqa: E402
from agents.policies.files import UnsafeFileError, check_npz  # noqa: E402
from agents.runs.resolve import load_sb3, make_policy  # noqa: E402
from agents.sb3.normalization import read_vecnormalize  # noqa: E402
from soccer_lab.cli import main  # noqa: E402

GK = "soccer_env/Goalkeeper-v0"


class Payload:
    """Unpickling this writes a marker file: proof that code from the file ran."""

    def __init__(self, marker: Path) -> None:
        self.marker = marker

    def __reduce__(self):
        return (exec, (f"open({str(self.marker)!r}, 'w').write('code ran')",))


def _run_config() -> dict:
    return {"env_id": GK, "env_kwargs": {}, "algorithm": "PPO", "actions": "native",
            "frame_stack": 1, "critic": "shared", "hyperparams": {"n_steps": 64},
            "out": "/somewhere/else"}


@pytest.fixture(scope="module")
def honest_model(tmp_path_factory) -> Path:
    """A small PPO model file, as training writes it."""
    folder = tmp_path_factory.mktemp("honest")
    model = PPO("MlpPolicy", gym.make(GK), n_steps=64, batch_size=64, device="cpu",
                policy_kwargs={"net_arch": [8]})
    model.save(folder / "final_model.zip")
    return folder / "final_model.zip"


def _run_folder(tmp_path: Path, model_zip: Path) -> Path:
    run = tmp_path / "received_run"
    run.mkdir()
    (run / "final_model.zip").write_bytes(model_zip.read_bytes())
    (run / "config.json").write_text(json.dumps(_run_config()))
    return run


def _with_entry(model_zip: Path, out: Path, key: str, value) -> Path:
    """A copy of ``model_zip`` whose ``data`` has ``key`` set to ``value``."""
    with zipfile.ZipFile(model_zip) as src, zipfile.ZipFile(out, "w") as dst:
        for info in src.infolist():
            content = src.read(info)
            if info.filename == "data":
                data = json.loads(content)
                data[key] = value
                content = json.dumps(data).encode()
            dst.writestr(info.filename, content)
    return out


def _serialized(obj) -> dict:
    return {":type:": "<class 'object'>",
            ":serialized:": base64.b64encode(pickle.dumps(obj)).decode()}


# -- files that would run code ----------------------------------------------------------------

def test_a_crafted_statistics_pickle_is_not_loaded(tmp_path, honest_model, capsys):
    """A run folder whose statistics are a pickle that runs code: eval, ablation and resume
    refuse it, naming the file and --trust; nothing runs."""
    marker = tmp_path / "pwned"
    run = _run_folder(tmp_path, honest_model)
    (run / "final_vecnormalize.pkl").write_bytes(pickle.dumps(Payload(marker)))
    env = gym.make(GK)
    with pytest.raises(UnsafeFileError, match="final_vecnormalize.pkl.*pickle.*--trust"):
        make_policy(run, env)
    for argv in (["eval", "--policy", str(run), "--episodes", "1", "--video", "0",
                  "--out", str(tmp_path / "eval")],
                 ["ablation", "--policy", str(run), "--episodes", "1", "--configs", "ekf",
                  "--presets", "ssl-2012", "--out", str(tmp_path / "ablation"), "--quiet"],
                 ["train", "--resume", str(run / "final_model.zip"), "--steps", "100000",
                  "--no-progress"]):
        with pytest.raises(SystemExit):
            main(argv)
        assert "--trust" in capsys.readouterr().err, argv
    assert not marker.exists()
    # The resumed run wrote nothing, neither there nor where its config.json points.
    assert sorted(p.name for p in run.iterdir()) == ["config.json", "final_model.zip",
                                                     "final_vecnormalize.pkl"]
    # Trusted, the pickle is loaded (and here runs its code): the opt-in works.
    make_policy(run, env, trust=True)
    assert marker.exists()


@pytest.mark.parametrize("entry", ["observation_space", "policy_class", "lr_schedule",
                                   "_last_obs", "clip_range"])
def test_a_crafted_model_entry_is_replaced_not_unpickled(tmp_path, honest_model, entry):
    """A serialized entry that stable-baselines3 would unpickle, replaced by code: the
    model loads from its weights with the entry built here; nothing runs."""
    marker = tmp_path / "pwned"
    run = _run_folder(tmp_path, honest_model)
    _with_entry(honest_model, run / "final_model.zip", entry, _serialized(Payload(marker)))
    env = gym.make(GK)
    policy = make_policy(run, env)
    obs, _ = env.reset(seed=0)
    assert policy(obs).shape == (6,)
    assert not marker.exists()


def test_an_unknown_serialized_entry_is_refused(tmp_path, honest_model, capsys):
    marker = tmp_path / "pwned"
    run = _run_folder(tmp_path, honest_model)
    _with_entry(honest_model, run / "final_model.zip", "helper", _serialized(Payload(marker)))
    with pytest.raises(UnsafeFileError, match="'helper' can only be read by unpickling"):
        make_policy(run, gym.make(GK))
    with pytest.raises(SystemExit):
        main(["eval", "--policy", str(run), "--episodes", "1", "--video", "0", "--out",
              str(tmp_path / "eval")])
    assert "'helper' can only be read by unpickling" in capsys.readouterr().err
    assert not marker.exists()


def test_a_model_without_its_run_needs_the_spaces_or_trust(tmp_path, honest_model):
    with pytest.raises(UnsafeFileError, match="config.json.*trust"):
        load_sb3(honest_model)
    env = gym.make(GK)
    model = load_sb3(honest_model, env=env)
    assert isinstance(model, PPO)
    assert isinstance(make_policy(honest_model, env), NumpyPolicy)  # the env's spaces


# -- files that would exhaust memory ----------------------------------------------------------

def _npy_bytes(header: dict) -> bytes:
    """The bytes of a ``.npy`` header (format 1.0) describing ``header``."""
    import io

    buf = io.BytesIO()
    np.lib.format.write_array_header_1_0(buf, header)
    return buf.getvalue()


def _npz_with_header(path: Path, shape: tuple, payload: bytes = b"") -> Path:
    """An .npz whose one member declares ``shape`` (float64) but holds ``payload``."""
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("W0.npy", _npy_bytes({"descr": "<f8", "fortran_order": False,
                                               "shape": shape}) + payload)
    return path


def test_an_array_declaring_a_huge_shape_is_refused_from_its_header(tmp_path):
    """A 1 kB file declaring a 10^6 x 10^6 array: refused before anything is allocated."""
    path = _npz_with_header(tmp_path / "huge.npz", (1_000_000, 1_000_000), b"\0" * 1024)
    assert path.stat().st_size < 4096
    with pytest.raises(UnsafeFileError, match="declares shape"):
        check_npz(path)
    with pytest.raises(UnsafeFileError, match="declares shape"):
        NumpyPolicy.load(path)


def test_an_array_larger_than_its_bytes_is_refused(tmp_path):
    path = _npz_with_header(tmp_path / "short.npz", (64, 64), b"\0" * 100)
    with pytest.raises(ValueError, match="truncated or crafted"):
        NumpyPolicy.load(path)


def test_an_archive_that_unpacks_beyond_the_limit_is_refused(tmp_path, monkeypatch):
    """A zip bomb (small file, large unpacked members): refused from the archive's
    directory (the limit lowered here so that the test stays small)."""
    import agents.policies.files as files

    monkeypatch.setattr(files, "MAX_FILE_BYTES", 1_000_000)
    path = tmp_path / "bomb.npz"
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("W0.npy", _npy_bytes({"descr": "<f8", "fortran_order": False,
                                               "shape": (500_000,)}) + b"\0" * 4_000_000)
    assert path.stat().st_size < 100_000
    with pytest.raises(UnsafeFileError, match="unpacks to"):
        NumpyPolicy.load(path)


def test_object_arrays_are_refused(tmp_path):
    path = tmp_path / "objects.npz"
    np.savez(path, header=np.array([{"a": 1}], dtype=object))
    with pytest.raises(UnsafeFileError, match="Python objects"):
        NumpyPolicy.load(path)


# -- damaged files ------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def honest_policy(tmp_path_factory) -> Path:
    from agents.baselines import baseline_path

    return baseline_path("keeper-ppo-ssl2012")


@pytest.mark.parametrize("damage", ["empty", "truncated", "garbage", "missing key"])
def test_a_damaged_policy_file_names_itself(tmp_path, honest_policy, damage):
    path = tmp_path / "policy.npz"
    content = honest_policy.read_bytes()
    if damage == "empty":
        path.write_bytes(b"")
    elif damage == "truncated":
        path.write_bytes(content[: len(content) // 2])
    elif damage == "garbage":
        path.write_bytes(b"not a zip file at all" * 10)
    else:
        with np.load(honest_policy) as data:
            arrays = {k: data[k] for k in data.files if k != "W2"}
        np.savez(path, **arrays)
    with pytest.raises(ValueError, match="policy.npz"):
        NumpyPolicy.load(path)


def test_a_policy_with_non_finite_weights_is_refused(tmp_path, honest_policy):
    with np.load(honest_policy) as data:
        arrays = {k: data[k] for k in data.files}
    arrays["W0"] = arrays["W0"].copy()
    arrays["W0"][0, 0] = np.nan
    np.savez(tmp_path / "nan.npz", **arrays)
    with pytest.raises(ValueError, match="non-finite"):
        NumpyPolicy.load(tmp_path / "nan.npz")


@pytest.mark.parametrize("damage", ["truncated", "no data", "data not JSON"])
def test_a_damaged_model_file_names_itself(tmp_path, honest_model, damage):
    path = tmp_path / "model.zip"
    if damage == "truncated":
        content = honest_model.read_bytes()
        path.write_bytes(content[: len(content) // 2])
    else:
        with zipfile.ZipFile(honest_model) as src, zipfile.ZipFile(path, "w") as dst:
            for info in src.infolist():
                if info.filename == "data":
                    if damage == "no data":
                        continue
                    dst.writestr("data", b"{not json")
                else:
                    dst.writestr(info.filename, src.read(info))
    with pytest.raises(ValueError, match="model.zip"):
        load_sb3(path, env=gym.make(GK))


@pytest.mark.parametrize("damage", ["truncated", "foreign"])
def test_damaged_statistics_name_themselves(tmp_path, damage):
    path = tmp_path / "final_vecnormalize.npz"
    if damage == "truncated":
        np.savez(path, header=np.array("{}"), obs_mean=np.zeros(19))
        path.write_bytes(path.read_bytes()[:200])
    else:
        np.savez(path, header=np.array(json.dumps({"format": "something else"})))
    with pytest.raises(ValueError, match="final_vecnormalize.npz"):
        read_vecnormalize(path)


def test_a_damaged_trusted_pickle_names_itself(tmp_path, honest_model):
    """Even trusted, a truncated statistics pickle gives an error naming the file, not an
    UnpicklingError or EOFError from deep inside pickle."""
    from agents.sb3.normalization import load_vecnormalize

    run = _run_folder(tmp_path, honest_model)
    (run / "final_vecnormalize.pkl").write_bytes(pickle.dumps({"a": list(range(100))})[:40])
    with pytest.raises(ValueError, match="final_vecnormalize.pkl could not be read"):
        load_vecnormalize(run / "final_model.zip", trust=True)
