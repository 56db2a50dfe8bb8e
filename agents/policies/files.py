"""Reading files from strangers without running code from them, and without letting a small
crafted file allocate gigabytes.

Policies, checkpoints and run folders may come from strangers. The numpy policies
(:class:`~agents.policies.numpy_policy.NumpyPolicy`) and the normalisation statistics are
written as ``.npz`` files, arrays and a JSON header, nothing pickled; :func:`check_npz` checks
one before ``np.load`` reads it. Every file is size-checked before it is read
(:data:`MAX_FILE_BYTES`, and each array of an ``.npz`` by its header,
:data:`MAX_ARRAY_ELEMENTS`; :func:`check_file_size`, :func:`open_archive`). An archive's members
are read only if stored or deflate-compressed (:data:`READ_METHODS`: their output is bounded as
it is read; bzip2 and LZMA decompress whole blocks at once, whatever the header declares). JSON
(a run's ``config.json``, a model's ``data``, a policy's header) is read with a measured size
and a bounded depth, and without the non-standard constants ``NaN`` and ``Infinity``
(:func:`read_json`, :func:`parse_json`; :data:`MAX_JSON_BYTES`, :data:`MAX_JSON_DEPTH`).

What cannot be read without unpickling (a stable-baselines3 ``.pkl``, the serialized
entries of a model ``.zip``, :mod:`agents.sb3.model_files`) is refused with
:class:`UnsafeFileError` unless trusted (``trust=True``, ``--trust`` on the command line): only
for files from a source you trust, since unpickling runs whatever code the file names.
"""

from __future__ import annotations

import json
import os
import re
import zipfile
from pathlib import Path
from typing import IO, Any

import numpy as np

__all__ = ["UnsafeFileError", "MAX_FILE_BYTES", "MAX_ARRAY_ELEMENTS", "MAX_JSON_BYTES",
           "MAX_JSON_DEPTH", "READ_METHODS", "TRUST_HELP", "check_file_size", "open_archive",
           "read_member", "read_bounded", "parse_json", "read_json", "check_npz"]

#: The largest file (and the largest total unpacked size of an archive) that is read, bytes.
#: Policies of this package are tens of kB; a large stable-baselines3 model a few MB (its
#: networks at :data:`~agents.sb3.model_files.MAX_NETWORK_PARAMETERS` and their optimizer
#: state fit in it).
MAX_FILE_BYTES = 64 * 2**20
#: The most elements one array of an ``.npz`` may hold (a 4,096 x 4,096 weight matrix).
MAX_ARRAY_ELEMENTS = 4096 * 4096

#: The largest JSON document read, bytes: a run's ``config.json`` or a model's ``data`` entry
#: is a few kB; no option lifts this.
MAX_JSON_BYTES = 16 * 2**20
#: The deepest nesting of arrays and objects in a JSON document read (the package's own go
#: 4 deep); no option lifts this.
MAX_JSON_DEPTH = 64
#: The compression methods of archive members that are read, by their number in the zip
#: format: those whose output Python's ``zipfile`` bounds as it reads.
READ_METHODS = {zipfile.ZIP_STORED: "stored", zipfile.ZIP_DEFLATED: "deflate"}
_METHOD_NAMES = {zipfile.ZIP_BZIP2: "bzip2", zipfile.ZIP_LZMA: "LZMA"}
#: JSON strings, which may hold brackets that open nothing.
_JSON_STRING = re.compile(rb'"(?:[^"\\]|\\.)*"')

#: What to tell a user whose file needs unpickling.
TRUST_HELP = ("unpickling runs whatever code the file names; pass --trust (trust=True) only "
              "for files from a source you trust")


class UnsafeFileError(ValueError):
    """A file that cannot be read without running code from it (or is too large to read
    safely), refused because loading it was not trusted."""


def check_file_size(path: Path) -> None:
    """Raise ``FileNotFoundError`` if ``path`` is not a file, :class:`UnsafeFileError` if it
    is larger than :data:`MAX_FILE_BYTES`: the first check of every file read."""
    if not path.is_file():
        raise FileNotFoundError(f"no file at {path}")
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise UnsafeFileError(f"{path} is {size:,} bytes, more than the {MAX_FILE_BYTES:,} "
                              "that are read")


def open_archive(path: Path) -> zipfile.ZipFile:
    """``path`` as a zip archive whose members unpack to at most :data:`MAX_FILE_BYTES` in
    all; ``ValueError`` naming the file for anything that is not such an archive."""
    check_file_size(path)
    try:
        archive = zipfile.ZipFile(path)
    except (zipfile.BadZipFile, OSError) as err:
        raise ValueError(f"{path} is not a valid archive ({err}); the file is damaged or not "
                         "of this kind") from None
    unpacked = sum(info.file_size for info in archive.infolist())
    if unpacked > MAX_FILE_BYTES:
        archive.close()
        raise UnsafeFileError(f"{path} unpacks to {unpacked:,} bytes, more than the "
                              f"{MAX_FILE_BYTES:,} that are read")
    for info in archive.infolist():
        if info.compress_type not in READ_METHODS:
            archive.close()
            method = _METHOD_NAMES.get(info.compress_type, f"method {info.compress_type}")
            raise UnsafeFileError(f"{path}: member {info.filename!r} is compressed with "
                                  f"{method}; only stored and deflate members are read (their "
                                  "size is bounded as they unpack)")
    return archive


def read_bounded(fh: IO[bytes], limit: int, name: str) -> bytes:
    """All of ``fh``, counted as it is read: :class:`UnsafeFileError` naming ``name`` as soon
    as it passes ``limit`` bytes (never trusting a size the file declares)."""
    chunks, total = [], 0
    while True:
        chunk = fh.read(min(1 << 20, limit + 1 - total))
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)
        total += len(chunk)
        if total > limit:
            raise UnsafeFileError(f"{name} is more than the {limit:,} bytes that are read")


def read_member(archive: zipfile.ZipFile, member: str, limit: int, path: Path) -> bytes:
    """Member ``member`` of ``archive`` (opened by :func:`open_archive` from ``path``), read
    by :func:`read_bounded` up to ``limit`` bytes; ``KeyError`` if there is none, and
    :class:`UnsafeFileError` for one whose content is not what its header declares (its
    size or checksum: a crafted or damaged archive)."""
    try:
        with archive.open(member) as fh:
            return read_bounded(fh, limit, f"{path}: member {member!r}")
    except zipfile.BadZipFile as err:
        raise UnsafeFileError(f"{path}: member {member!r} is not what its header declares "
                              f"({err}): a crafted or damaged archive") from None


def _refuse_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a JSON number")


def parse_json(data: bytes | str, name: str) -> Any:
    """``data`` parsed as JSON, refused with ``ValueError`` naming ``name``
    (:class:`UnsafeFileError` for limits): more than :data:`MAX_JSON_BYTES`, nested deeper
    than :data:`MAX_JSON_DEPTH`, ``NaN`` or ``Infinity``, or not JSON at all."""
    raw = data.encode("utf-8", "surrogatepass") if isinstance(data, str) else bytes(data)
    if len(raw) > MAX_JSON_BYTES:
        raise UnsafeFileError(f"{name} is {len(raw):,} bytes of JSON, more than the "
                              f"{MAX_JSON_BYTES:,} that are read")
    # The nesting, counted on the brackets outside strings before the parser recurses.
    bare = np.frombuffer(_JSON_STRING.sub(b"", raw), dtype=np.uint8)
    steps = (np.isin(bare, (ord("["), ord("{"))).astype(np.int64)
             - np.isin(bare, (ord("]"), ord("}"))))
    depth = int(np.cumsum(steps).max()) if steps.size else 0
    if depth > MAX_JSON_DEPTH:
        raise UnsafeFileError(f"{name} nests JSON {depth:,} deep, more than the "
                              f"{MAX_JSON_DEPTH} levels that are read")
    try:
        return json.loads(raw, parse_constant=_refuse_constant)
    except (ValueError, RecursionError) as err:
        raise ValueError(f"{name} is not valid JSON ({err})") from None


def read_json(path: str | os.PathLike) -> Any:
    """The JSON document in the file ``path`` (a regular file: not a device, pipe or
    directory), read by :func:`read_bounded` up to :data:`MAX_JSON_BYTES` and parsed by
    :func:`parse_json`. ``FileNotFoundError`` if there is none."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"no file at {path}")
    if not path.is_file():
        raise ValueError(f"{path} is not a regular file (a device, a pipe or a folder is not "
                         "read)")
    with open(path, "rb") as fh:
        data = read_bounded(fh, MAX_JSON_BYTES, str(path))
    return parse_json(data, str(path))


def check_npz(path: str | os.PathLike) -> None:
    """Check an ``.npz`` before ``np.load`` reads it: a valid archive of at most
    :data:`MAX_FILE_BYTES` unpacked, whose every member is a ``.npy`` array of at most
    :data:`MAX_ARRAY_ELEMENTS` elements of a plain (not object) dtype, read from its header
    only. Raises ``ValueError`` (:class:`UnsafeFileError` for a too-large one) naming the
    file and the member."""
    path = Path(path)
    with open_archive(path) as archive:
        for info in archive.infolist():
            try:
                with archive.open(info) as fh:
                    version = np.lib.format.read_magic(fh)
                    if version == (1, 0):
                        shape, _, dtype = np.lib.format.read_array_header_1_0(fh)
                    else:
                        shape, _, dtype = np.lib.format.read_array_header_2_0(fh)
            except (ValueError, OSError, zipfile.BadZipFile, EOFError) as err:
                raise ValueError(f"{path}: member {info.filename!r} is not a readable array "
                                 f"({err})") from None
            if dtype.hasobject:
                raise UnsafeFileError(f"{path}: member {info.filename!r} holds Python objects "
                                      "(reading them would unpickle)")
            count = int(np.prod(shape, dtype=np.float64))
            if count > MAX_ARRAY_ELEMENTS:
                raise UnsafeFileError(f"{path}: member {info.filename!r} declares shape "
                                      f"{shape} ({count:,} elements), more than the "
                                      f"{MAX_ARRAY_ELEMENTS:,} that are read")
            if count * dtype.itemsize > info.file_size + 1024:
                raise ValueError(f"{path}: member {info.filename!r} declares shape {shape} "
                                 f"but holds {info.file_size:,} bytes (a truncated or crafted "
                                 "file)")
