"""The base classes of the component layer: Interface, Component and DerivedComponent.

A *component* is the smallest logical part of a board that a student uses: an LED, a
motor, a pin. It checks what the user asked for and then calls its *interface*, an
abstract class of coroutines that a backend implements for one board in one environment.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

from j5aio.errors import NotSupportedByComponentError

__all__ = ["Component", "DerivedComponent", "Interface"]


class Interface(ABC):  # noqa: B024 - a marker base class, deliberately without methods
    """The base class of every interface: the low-level coroutines a component needs.

    Every method of an interface is a coroutine, so a backend can talk to its board
    without blocking other tasks.
    """

    __slots__ = ()


class Component(ABC):
    """The base class of every component: the smallest logical part of some hardware."""

    __slots__ = ()

    @property
    @abstractmethod
    def identifier(self) -> int:
        """The number that tells this component apart from its siblings on a board."""
        raise NotImplementedError

    @classmethod
    @abstractmethod
    def interface_class(cls) -> type[Interface]:
        """The interface a backend must implement for this component to work."""
        raise NotImplementedError

    def __repr__(self) -> str:
        try:
            ident = f"identifier={self.identifier}"
        except NotSupportedByComponentError:
            ident = "derived"
        return f"<{type(self).__name__} {ident}>"


class DerivedComponent(Component):
    """A component built from other components, such as an ultrasound sensor on two pins.

    A derived component has no identifier of its own: it is defined by the components
    it is made of.
    """

    __slots__ = ()

    @property
    def identifier(self) -> int:
        """Always raises: a derived component is identified by the parts it is made of.

        :raises NotSupportedByComponentError: always.
        """
        raise NotSupportedByComponentError(
            f"{type(self).__name__} is a derived component: it has no identifier of its "
            "own; it is identified by the components it is built from.",
        )
