"""Backends (how each board is driven) and environments (which backend for which board)."""

from j5aio.backends.backend import Backend, BackendMeta
from j5aio.backends.environment import Environment
from j5aio.errors import CommunicationError

__all__ = ["Backend", "BackendMeta", "CommunicationError", "Environment"]
