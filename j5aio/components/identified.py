"""The base class of a component that its board numbers: an identifier and a backend.

Most new kinds of component subclass :class:`IdentifiedComponent`: the board makes one
per part it has (``Thing(0, backend)``, ``Thing(1, backend)``), and each passes its own
number to its interface's coroutines. :doc:`/new-component` walks through one.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Generic, TypeVar

from j5aio.components.component import Component, Interface

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend

__all__ = ["IdentifiedComponent", "checked_backend"]

InterfaceT = TypeVar("InterfaceT", bound=Interface)


class IdentifiedComponent(Component, Generic[InterfaceT]):
    """A component known by a number on its board, driven through one backend.

    A subclass names its interface as the type argument
    (``IdentifiedComponent[ThingInterface]``), sets ``__slots__ = ()`` (so that a misspelt
    attribute is an error), returns the interface from the classmethod
    :meth:`~j5aio.components.component.Component.interface_class`, and writes one
    coroutine per thing a program may do, each checking its arguments and then awaiting
    ``self._backend.<interface method>(self._identifier, ...)``. ``_backend`` (typed as
    the interface) and ``_identifier`` are set here; :attr:`identifier` is public.

    A board passes its backend as it is (typed as any :class:`~j5aio.backends.backend.Backend`,
    with no ``cast``): that the backend implements the component's interface is checked
    when the backend class is made (see :class:`~j5aio.backends.backend.BackendMeta`) and
    again here.

    :param identifier: the number of the component on its board.
    :param backend: the backend that implements this component's interface.
    :raises TypeError: ``backend`` does not implement
        :meth:`~j5aio.components.component.Component.interface_class`.
    """

    __slots__ = ("_backend", "_identifier")

    def __init__(self, identifier: int, backend: InterfaceT | Backend) -> None:
        self._identifier = identifier
        self._backend: InterfaceT = checked_backend(type(self), backend)

    @property
    def identifier(self) -> int:
        """The number that tells this component apart from its siblings on a board."""
        return self._identifier


def checked_backend(component: type[Component], backend: object) -> Any:
    """Return ``backend`` if it implements ``component``'s interface.

    :raises TypeError: it does not; the message names both.
    """
    interface = component.interface_class()
    if not isinstance(backend, interface):
        raise TypeError(
            f"{component.__name__} needs a backend that implements {interface.__name__}, "
            f"but {type(backend).__name__} does not",
        )
    return backend
