"""``python -m j5aio sync-gen``: its options, and writing or checking the file."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path

__all__ = ["add_arguments", "check_or_write", "check_or_write_package", "main", "run"]


def check_or_write(source: str, output: Path, *, check: bool, command: str) -> int:
    """Write ``source`` to ``output`` if it differs; with ``check``, only compare.

    :param command: how to regenerate, for the message when ``output`` is stale.
    :returns: the exit status: 1 if ``check`` found ``output`` stale, else 0.
    """
    current = output.read_text(encoding="utf-8") if output.exists() else None
    if check:
        if current != source:
            print(f"{output} is stale: run {command}", file=sys.stderr)
            return 1
        print(f"{output} is up to date")
        return 0
    if current != source:
        output.write_text(source, encoding="utf-8")
        print(f"wrote {output}")
    else:
        print(f"{output} is up to date")
    return 0


def check_or_write_package(
    sources: Mapping[str, str], folder: Path, *, check: bool, command: str,
) -> int:
    """Write the modules ``sources`` (file name -> source) into ``folder``; or only compare.

    A module of ``folder`` that ``sources`` does not hold (a family no longer generated) is
    stale too: it is removed (or, with ``check``, reported).

    :param command: how to regenerate, for the message when ``folder`` is stale.
    :returns: the exit status: 1 if ``check`` found a module stale, missing or extra, else 0.
    """
    extra = sorted(
        path.name for path in folder.glob("*.py") if path.name not in sources
    ) if folder.is_dir() else []
    if check:
        stale = [
            name for name, source in sources.items()
            if not (folder / name).exists()
            or (folder / name).read_text(encoding="utf-8") != source
        ]
        if stale or extra:
            print(f"{folder} is stale ({', '.join([*stale, *extra])}): run {command}",
                  file=sys.stderr)
            return 1
        print(f"{folder} is up to date")
        return 0
    folder.mkdir(parents=True, exist_ok=True)
    for name in extra:
        (folder / name).unlink()
        print(f"removed {folder / name}")
    for name, source in sources.items():
        check_or_write(source, folder / name, check=False, command=command)
    return 0


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the options of ``python -m j5aio sync-gen`` to ``parser``."""
    parser.add_argument(
        "modules",
        nargs="+",
        metavar="MODULE",
        help="the modules (or packages) that define the kit's boards and components, "
        "e.g. beekit.boards",
    )
    parser.add_argument(
        "-o",
        "--output",
        type=Path,
        required=True,
        help="the file to write, e.g. beekit/sync.py",
    )
    parser.add_argument(
        "--check",
        action="store_true",
        help="write nothing; exit with status 1 if the file is missing or stale (for CI)",
    )


def run(options: argparse.Namespace) -> int:
    """Run ``sync-gen`` with parsed ``options`` (see :func:`add_arguments`)."""
    modules: list[str] = list(options.modules)
    command = f"python -m j5aio sync-gen {' '.join(modules)} -o {options.output}"
    from j5aio.syncgen._module_writer import generate  # (here: only sync-gen needs it)

    try:
        source = generate(modules)
    except (ImportError, ValueError) as exc:
        print(f"sync-gen: {exc}", file=sys.stderr)
        return 2
    return check_or_write(source, options.output, check=options.check, command=command)


def main(argv: Sequence[str] | None = None) -> int:
    """The command line ``python -m j5aio.syncgen MODULE... -o FILE [--check]``."""
    parser = argparse.ArgumentParser(
        prog="python -m j5aio sync-gen",
        description="Generate the typed sync facade of a kit's boards and components.",
    )
    add_arguments(parser)
    return run(parser.parse_args(argv))
