"""Peer libraries for the benches, each in a virtual environment of its own.

A bench that compares j5aio with a peer (j5 0.12 above all) runs the peer's side in a child
process of the peer's own interpreter, so that neither library's imports, versions or
dependencies touch the other's figures. The environment is made on first use, from the
package registry, and kept for later runs::

    python = peer_python("j5-0.12", ["j5==0.12.0"])
    subprocess.run([str(python), "-c", "import j5"], check=True)

The environments live under ``$J5AIO_BENCH_PEERS`` or, by default,
``<tempdir>/j5aio-bench-peers/<name>``. Delete the folder to start again.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import venv
from pathlib import Path

__all__ = ["J5_PEER", "peer_python", "peers_root"]

#: The peer every issue-12 bench measures against: j5 0.12 from the package registry.
#: Its hardware backends import typing_extensions, which it does not declare.
J5_PEER: tuple[str, list[str]] = ("j5-0.12", ["j5==0.12.0", "typing-extensions"])


def peers_root() -> Path:
    """The folder holding every peer environment."""
    configured = os.environ.get("J5AIO_BENCH_PEERS")
    if configured:
        return Path(configured)
    return Path(tempfile.gettempdir()) / "j5aio-bench-peers"


def _interpreter(folder: Path) -> Path:
    if sys.platform == "win32":
        return folder / "Scripts" / "python.exe"
    return folder / "bin" / "python"


def peer_python(name: str, requirements: list[str]) -> Path:
    """The interpreter of the peer environment ``name``, made and filled on first use.

    :param name: the environment's folder name, e.g. ``"j5-0.12"``.
    :param requirements: what pip installs into it, e.g. ``["j5==0.12.0"]``.
    :raises RuntimeError: if the environment cannot be made or pip fails; the message says
        which requirement and how to retry.
    """
    folder = peers_root() / name
    python = _interpreter(folder)
    stamp = folder / "requirements.txt"
    wanted = "\n".join(requirements) + "\n"
    if python.exists() and stamp.exists() and stamp.read_text() == wanted:
        return python
    print(f"bench: making the peer environment {folder} ({', '.join(requirements)}) ...",
          file=sys.stderr)
    venv.EnvBuilder(with_pip=True, clear=True).create(folder)
    result = subprocess.run(
        [str(python), "-m", "pip", "install", "--quiet", *requirements],
        capture_output=True,
        text=True,
    )
    if result.returncode != 0:
        raise RuntimeError(
            f"could not install {requirements} into {folder}:\n{result.stderr.strip()}\n"
            "Check that the package registry is reachable, then run the bench again.",
        )
    stamp.write_text(wanted)
    return python
