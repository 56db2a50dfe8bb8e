"""Reading files from strangers without running code from them, and without letting a small
crafted file allocate gigabytes.

Policies, checkpoints and run folders may come from strangers. The numpy policies
(:class:`~agents.policies.numpy_policy.NumpyPolicy`) and the normalisation statistics are
written as ``.npz`` files, arrays and a JSON header, nothing pickled; :func:`check_npz` checks
one before ``np.load`` reads it. Every file is size-checked before it is read
(:data:`MAX_FILE_BYTES`, and each array of an ``.npz`` by its header,
:data:`MAX_ARRAY_ELEMENTS`; :func:`check_file_size`, :func:`open_archive`). What cannot be
read without unpickling (a stable-baselines3 ``.pkl``, the serialized entries of a model
``.zip``, :mod:`agents.sb3.model_files`) is refused with :class:`UnsafeFileError` unless
trusted (``trust=True``, ``--trust`` on the command line): only for files from a source you
trust, since unpickling runs whatever code the file names.
"""

from __future__ import annotations

import os
import zipfile
from pathlib import Path

import numpy as np

__all__ = ["UnsafeFileError", "MAX_FILE_BYTES", "MAX_ARRAY_ELEMENTS", "TRUST_HELP",
           "check_file_size", "open_archive", "check_npz"]

#: The largest file (and the largest total unpacked size of an archive) that is read, bytes.
#: Policies of this package are tens of kB; a large stable-baselines3 model a few MB.
MAX_FILE_BYTES = 256 * 2**20
#: The most elements one array of an ``.npz`` may hold (a 4,096 x 4,096 weight matrix).
MAX_ARRAY_ELEMENTS = 4096 * 4096

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
    return archive


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
