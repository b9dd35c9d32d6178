"""Backends (how each board is driven) and environments (which backend for which board)."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.acknowledgements import acknowledge_later as acknowledge_later
    from j5aio.backends.acknowledgements import acknowledging_later as acknowledging_later
    from j5aio.backends.backend import Backend as Backend
    from j5aio.backends.backend import BackendMeta as BackendMeta
    from j5aio.backends.environment import Environment as Environment
    from j5aio.errors import CommunicationError as CommunicationError

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.acknowledgements": ["acknowledge_later", "acknowledging_later"],
            "j5aio.backends.backend": ["Backend", "BackendMeta"],
            "j5aio.backends.environment": ["Environment"],
            "j5aio.errors": ["CommunicationError"],
        },
    )
