"""sbot's overrides: ``SBOT_<NAME>`` environment variables and the ``override.env`` file.

sbot reads settings such as ``SKIP_WAIT_START``, ``ENABLE_DEBUG_LOGGING`` or
``SORT_MOTOR_ORDER`` from environment variables prefixed ``SBOT_`` and from a file
``override.env`` in the working directory, whose ``NAME=value`` lines win over the
environment. Names are upper-cased.
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["OVERRIDE_FILE", "get_overrides", "is_set", "load_overrides", "parse_env_file"]

#: The file of overrides sbot reads from the working directory.
OVERRIDE_FILE = "override.env"

_OVERRIDES: dict[str, str | None] = {}


def parse_env_file(text: str) -> dict[str, str | None]:
    """Parse ``NAME=value`` lines (``#`` comments, ``export``, quotes) into a dict.

    A line with a name and no ``=`` gives ``None``, as python-dotenv does.
    """
    found: dict[str, str | None] = {}
    for raw in text.splitlines():
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        line = line.removeprefix("export ").strip()
        name, equals, value = line.partition("=")
        name = name.strip()
        if not name:
            continue
        if not equals:
            found[name.upper()] = None
            continue
        value = value.strip()
        if len(value) >= 2 and value[0] == value[-1] and value[0] in "\"'":
            value = value[1:-1]
        else:
            value = value.split(" #", 1)[0].rstrip()
        found[name.upper()] = value
    return found


def load_overrides(directory: Path | None = None) -> dict[str, str | None]:
    """Read the overrides again, from the environment and ``override.env``; return them."""
    _OVERRIDES.clear()
    _OVERRIDES.update(
        {
            name.removeprefix("SBOT_"): value
            for name, value in os.environ.items()
            if name.startswith("SBOT_")
        },
    )
    path = (directory or Path.cwd()) / OVERRIDE_FILE
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        text = ""
    _OVERRIDES.update(parse_env_file(text))
    return _OVERRIDES


def get_overrides() -> dict[str, str | None]:
    """The overrides read when the package was imported (or last :func:`load_overrides`)."""
    return _OVERRIDES


def is_set(name: str) -> bool:
    """Whether override ``name`` is given as anything but ``0`` (as sbot tests them)."""
    return (_OVERRIDES.get(name) or "0") != "0"


load_overrides()
