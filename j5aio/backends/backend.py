"""The Backend base class: the code that drives one board in one environment."""

from __future__ import annotations

import functools
import inspect
import logging
from abc import ABCMeta, abstractmethod
from collections.abc import Callable, Coroutine, Sequence
from typing import Any, ClassVar, Generic

from typing_extensions import TypeVar

from j5aio.boards.board import Board
from j5aio.errors import CommunicationError as CommunicationError  # j5's path to it
from j5aio.errors import NotSupportedByHardwareError

__all__ = ["Backend", "BackendMeta", "BoardT"]

BoardT = TypeVar("BoardT", bound=Board, default=Board, covariant=True)
"""The class of board a backend drives, for typing: ``Backend[MotorBoard]``.

It defaults to :class:`~j5aio.boards.board.Board`, so a backend declared without it
(``class MyBackend(Backend)``) still type-checks; name the board to have
:meth:`Backend.attach` and friends return it typed.
"""


class BackendMeta(ABCMeta):
    """The metaclass of backends: checks a backend's interfaces when its class is made.

    A concrete backend must implement the interface of every component its board has; a
    class that does not is refused at once with a ``TypeError`` naming what is missing,
    rather than failing later on a student's robot. Each interface coroutine is also
    wrapped so that its calls are logged at DEBUG level, as j5 does.
    """

    def __new__(
        mcs,
        name: str,
        bases: tuple[type, ...],
        namespace: dict[str, Any],
        **kwargs: Any,
    ) -> BackendMeta:
        """Create the backend class, then check and instrument it."""
        cls = super().__new__(mcs, name, bases, namespace, **kwargs)
        board = namespace.get("board")
        if board is None or inspect.isabstract(cls):
            return cls
        missing = [
            (component, component.interface_class())
            for component in sorted(board.supported_components(), key=lambda c: c.__name__)
            if not issubclass(cls, component.interface_class())
        ]
        if missing:
            needs = "; ".join(
                f"{interface.__name__} (for {component.__name__})"
                for component, interface in missing
            )
            raise TypeError(
                f"backend {name} cannot drive {board.__name__}: it does not implement "
                f"{needs}. Add the interface to the class's bases and implement its methods.",
            )
        _wrap_interface_methods_with_logging(cls, board)
        return cls


def _wrap_interface_methods_with_logging(cls: type, board: type[Board]) -> None:
    for component in board.supported_components():
        logger = logging.getLogger(component.__module__)
        interface = component.interface_class()
        for method_name in interface.__abstractmethods__:
            method = getattr(cls, method_name)
            if getattr(method, "__j5aio_logged__", False):
                continue
            setattr(cls, method_name, _logged(method, method_name, logger))


def _logged(
    method: Callable[..., Coroutine[Any, Any, Any]],
    method_name: str,
    logger: logging.Logger,
) -> Callable[..., Coroutine[Any, Any, Any]]:
    signature = inspect.signature(method)

    @functools.wraps(method)
    async def logged_method(*args: Any, **kwargs: Any) -> Any:
        result = await method(*args, **kwargs)
        if logger.isEnabledFor(logging.DEBUG):
            arguments = signature.bind(*args, **kwargs).arguments
            shown = ", ".join(f"{k}={v!r}" for k, v in arguments.items() if k != "self")
            suffix = f" -> {result!r}" if result is not None else ""
            logger.debug("%s(%s)%s", method_name, shown, suffix)
        return result

    logged_method.__j5aio_logged__ = True  # type: ignore[attr-defined]
    return logged_method


class Backend(Generic[BoardT], metaclass=BackendMeta):
    """The code that drives one board in one environment (console, hardware, simulated).

    A backend subclasses the interfaces of its board's components and implements their
    coroutines. There is one backend instance per board instance. Backends do not check
    what the user meant (components do that); they refuse only what the hardware cannot
    do, with :class:`~j5aio.errors.NotSupportedByHardwareError`.

    Name the board class as the type argument and as :attr:`board`, and the coroutines
    that make boards return it typed, with no ``isinstance`` check at the call site::

        class BeeBackend(SerialHardwareBackend[BeeBoard], MotorInterface, LEDInterface):
            board = BeeBoard

        bee = await BeeBackend.attach("/dev/ttyUSB0")   # typed as BeeBoard
    """

    #: The class of board this backend drives.
    board: ClassVar[type[Board]]

    @classmethod
    @abstractmethod
    async def discover(cls) -> Sequence[BoardT]:
        """Find every board this backend can drive, connected and ready to set up."""
        raise NotImplementedError

    @classmethod
    async def attach(cls, port: str) -> BoardT:
        """Connect to a board on an explicit port, without discovery.

        :param port: a device path (a pseudo-terminal works) or a pyserial URL.
        :raises NotSupportedByHardwareError: this backend does not use ports.
        """
        raise NotSupportedByHardwareError(
            f"{cls.__name__} cannot attach to an explicit port ({port!r}): only serial "
            "hardware backends can. Use discovery (get_board_group without ports) instead.",
        )

    @property
    @abstractmethod
    def firmware_version(self) -> str | None:
        """The firmware version the board reported, or ``None`` if it has none."""
        raise NotImplementedError

    async def close(self) -> None:
        """Release whatever the backend holds (a port, a USB handle). Does nothing here."""
