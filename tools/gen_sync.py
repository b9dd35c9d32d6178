"""Regenerate j5aio's own sync facade, the package ``j5aio/sync/_generated``.

Run ``python tools/gen_sync.py`` after changing a public async class; ``--check`` only
reports whether the committed modules are up to date. The generator itself is
:mod:`j5aio.syncgen` (``python -m j5aio sync-gen`` for a third-party kit's boards).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def main(argv: Sequence[str] | None = None) -> int:
    """Write (or with ``--check``, only compare) j5aio's generated facade."""
    from j5aio.syncgen import CORE_OUTPUT, check_or_write_package, generate_core

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="fail if a module is stale")
    parser.add_argument("--output", type=Path, default=CORE_OUTPUT, help="the folder to write")
    options = parser.parse_args(argv)
    return check_or_write_package(
        generate_core(), options.output, check=options.check,
        command="python tools/gen_sync.py",
    )


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    raise SystemExit(main())
