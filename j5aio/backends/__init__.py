"""Backends (how each board is driven) and environments (which backend for which board)."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.acknowledgements import acknowledge_later, acknowledging_later
    from j5aio.backends.backend import Backend, BackendMeta
    from j5aio.backends.environment import Environment
    from j5aio.errors import CommunicationError

__all__ = [
    "Backend",
    "BackendMeta",
    "CommunicationError",
    "Environment",
    "acknowledge_later",
    "acknowledging_later",
]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.acknowledgements": ["acknowledge_later", "acknowledging_later"],
            "j5aio.backends.backend": ["Backend", "BackendMeta"],
            "j5aio.backends.environment": ["Environment"],
            "j5aio.errors": ["CommunicationError"],
        },
    )
