"""``python -m j5aio.syncgen MODULE... -o FILE [--check]``: the generator's command line."""

from j5aio.syncgen._cli import main

raise SystemExit(main())
