"""Generate the Python classes of the RoboCup SSL protocols from the official ``.proto`` files.

Usage (from a clean checkout of each source at its pinned commit, with ``grpcio-tools==1.85.1``
installed in the Python that runs this)::

    git clone https://github.com/RoboCup-SSL/ssl-game-controller
    git -C ssl-game-controller checkout v3.23.0
    git clone https://github.com/RoboCup-SSL/ssl-simulation-protocol
    git -C ssl-simulation-protocol checkout 65ad6148671a2b1ead58be0b625ca0f8d269ced8
    python generate.py --game-controller ssl-game-controller \\
        --simulation-protocol ssl-simulation-protocol

What it does, and nothing else:

1. copies every ``.proto`` file of the game controller's ``proto/`` folder (vision, referee,
   game events, the CI mode, ...) to ``proto/ssl_protocol/<folder>/``, and the simulation
   protocol's ``ssl_simulation_*.proto`` files to ``proto/ssl_protocol/sim/``;
2. rewrites each ``import "x.proto"`` to its copy's path under ``ssl_protocol/`` (the
   simulation protocol's own copies of the vision and common files are left out: it imports
   the game controller's, which differ from them in comments and formatting only), so that
   the generated modules import each other as ``ssl_protocol.<folder>.<name>_pb2``;
3. runs ``grpc_tools.protoc`` with ``--python_out`` and ``--pyi_out`` into
   ``src/ssl_protocol/``.

Messages keep their names and field numbers: the wire format is the league's.
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
PACKAGE = "ssl_protocol"
#: The simulation protocol's copies of files the game controller owns: their imports are
#: pointed at the game controller's.
SHARED = {"ssl_gc_common.proto": "state/ssl_gc_common.proto",
          "ssl_vision_detection.proto": "vision/ssl_vision_detection.proto",
          "ssl_vision_geometry.proto": "vision/ssl_vision_geometry.proto"}
IMPORT = re.compile(r'^import "([^"]+)";', re.M)


def rewrite(text: str, folder: str) -> str:
    """``text`` with every import of a league file pointed at its copy under the package
    (``google/protobuf/...`` imports are left as they are)."""

    def repl(m: re.Match) -> str:
        name = m.group(1)
        if name.startswith("google/"):
            return m.group(0)
        if folder == "sim":
            name = SHARED.get(name, f"sim/{name}")
        return f'import "{PACKAGE}/{name}";'

    return IMPORT.sub(repl, text)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--game-controller", type=Path, required=True)
    p.add_argument("--simulation-protocol", type=Path, required=True)
    args = p.parse_args()
    proto, out = HERE / "proto", HERE / "src"
    shutil.rmtree(proto, ignore_errors=True)
    shutil.rmtree(out / PACKAGE, ignore_errors=True)
    files = []
    for src in sorted((args.game_controller / "proto").rglob("*.proto")):
        rel = src.relative_to(args.game_controller / "proto")
        files.append((src, Path(PACKAGE) / rel, rel.parts[0]))
    for src in sorted((args.simulation_protocol / "proto").glob("ssl_simulation_*.proto")):
        files.append((src, Path(PACKAGE) / "sim" / src.name, "sim"))
    for src, rel, folder in files:
        dst = proto / rel
        dst.parent.mkdir(parents=True, exist_ok=True)
        dst.write_text(rewrite(src.read_text(), folder))
    (out / PACKAGE).mkdir(parents=True)
    cmd = [sys.executable, "-m", "grpc_tools.protoc", f"-I{proto}",
           f"--python_out={out}", f"--pyi_out={out}",
           *(str(rel) for _, rel, _ in files)]
    subprocess.run(cmd, check=True, cwd=proto)
    for folder in sorted({d.parent for d in (out / PACKAGE).rglob("*_pb2.py")}):
        init = folder / "__init__.py"
        if not init.exists():
            init.write_text("")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
