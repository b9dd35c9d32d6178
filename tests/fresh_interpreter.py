"""Run a short program in a fresh interpreter, for tests of what an import loads."""

from __future__ import annotations

import subprocess
import sys


def printed_words(program: str) -> list[str]:
    """The words ``program`` printed, run with ``python -c`` in a new interpreter.

    :raises subprocess.CalledProcessError: the program failed.
    """
    done = subprocess.run(
        [sys.executable, "-c", program], capture_output=True, text=True, check=True, timeout=60
    )
    return done.stdout.split()
