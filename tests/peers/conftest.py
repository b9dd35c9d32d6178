"""The fixture of the peer tests (see :mod:`.peer_support`)."""

from .peer_support import served

__all__ = ["served"]
