"""The shared base of the components that a board numbers: an identifier and a backend."""

from __future__ import annotations

from typing import Generic, TypeVar

from j5aio.components.component import Component, Interface

__all__ = ["IdentifiedComponent"]

InterfaceT = TypeVar("InterfaceT", bound=Interface)


class IdentifiedComponent(Component, Generic[InterfaceT]):
    """A component known by a number on its board, driven through one backend.

    :param identifier: the number of the component on its board.
    :param backend: the backend that implements this component's interface.
    """

    __slots__ = ("_backend", "_identifier")

    def __init__(self, identifier: int, backend: InterfaceT) -> None:
        self._identifier = identifier
        self._backend = backend

    @property
    def identifier(self) -> int:
        """The number that tells this component apart from its siblings on a board."""
        return self._identifier
