"""The Backend base class: the code that drives one board in one environment."""

from __future__ import annotations

import functools
import inspect
import logging
import weakref
from abc import ABCMeta, abstractmethod
from collections.abc import Callable, Coroutine, Sequence
from typing import Any, ClassVar, Generic

from typing_extensions import TypeVar

from j5aio.boards.board import Board
from j5aio.errors import CommunicationError as CommunicationError  # j5's path to it
from j5aio.errors import NotSupportedByHardwareError

__all__ = ["CALL_OBSERVERS", "Backend", "BackendMeta", "BoardT", "CallObserver"]

BoardT = TypeVar("BoardT", bound=Board, default=Board, covariant=True)
"""The class of board a backend drives, for typing: ``Backend[MotorBoard]``.

It defaults to :class:`~j5aio.boards.board.Board`, so a backend declared without it
(``class MyBackend(Backend)``) still type-checks; name the board to have
:meth:`Backend.attach` and friends return it typed.
"""

CallObserver = Callable[["Backend", str, tuple[Any, ...], Any, BaseException | None], None]
"""A function told of every interface call: ``(backend, method_name, arguments, result, error)``.

``arguments`` are the call's arguments after ``self``, in the order the interface declares
them; ``error`` is the exception the call raised (then ``result`` is ``None``).
"""

#: The observers of every backend's interface calls (the live view adds one). Each is called
#: in the event loop's thread right after a call returns or raises, so it must be quick (store
#: the value, never wait) and must not raise; a failing observer is logged and ignored. While
#: this list is empty a call costs one truth test more than it did without observers.
CALL_OBSERVERS: list[CallObserver] = []

#: ``inspect.markcoroutinefunction`` where there is one (Python 3.12 and later): the
#: wrapper round each interface method returns a coroutine without being one.
_mark_coroutine_function: Callable[[Callable[..., Any]], object] | None = getattr(
    inspect, "markcoroutinefunction", None
)


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
    # One function per interface method, and no more: what a call does round the backend's
    # coroutine, when it does anything, is _observed's (every backend class made on a
    # start wraps each of its interface methods, so each closure made here is paid for
    # on every start, once per method).

    # Not a coroutine function itself: when there is nothing to do round the call (no
    # acknowledgement owed, no observer, no debug log) it hands over the backend's own
    # coroutine, so that a request's every wait and wake-up is a frame shorter. What it
    # decides, it decides when called: an interface method is called where it is awaited.
    @functools.wraps(method)
    def logged_method(*args: Any, **kwargs: Any) -> Coroutine[Any, Any, Any]:
        backend = args[0]
        if (
            CALL_OBSERVERS
            or (backend._acknowledges_later and backend._link.unconfirmed is not None)
            or logger.isEnabledFor(logging.DEBUG)
        ):
            return _observed(method, method_name, logger, args, kwargs)
        return method(*args, **kwargs)

    if _mark_coroutine_function is not None:  # (Python 3.12 and later)
        _mark_coroutine_function(logged_method)
    logged_method.__j5aio_logged__ = True  # type: ignore[attr-defined]
    return logged_method


async def _observed(
    method: Callable[..., Coroutine[Any, Any, Any]],
    method_name: str,
    logger: logging.Logger,
    args: tuple[Any, ...],
    kwargs: dict[str, Any],
) -> Any:
    """Call ``method`` for an interface call that is observed, logged or owes a reply first."""
    backend = args[0]
    if backend._acknowledges_later and backend._link.unconfirmed is not None:
        # An earlier command's reply is still to be read (it was confirmed later): read
        # it first, so that what the backend remembers of its board is up to date.
        await backend.confirm_acknowledgement()
    try:
        result = await method(*args, **kwargs)
    except Exception as error:
        if CALL_OBSERVERS:
            _tell_observers(method, method_name, args, kwargs, None, error)
        raise
    if CALL_OBSERVERS:
        _tell_observers(method, method_name, args, kwargs, result, None)
    if logger.isEnabledFor(logging.DEBUG):
        arguments = _signature_of(method).bind(*args, **kwargs).arguments
        shown = ", ".join(f"{k}={v!r}" for k, v in arguments.items() if k != "self")
        suffix = f" -> {result!r}" if result is not None else ""
        logger.debug("%s(%s)%s", method_name, shown, suffix)
    return result


#: The signature of each interface method whose calls were observed or logged, read then
#: (when a call is first bound to its parameter names), not when its class is made: that
#: is rare, and every backend class made on a start would pay for it.
_SIGNATURES: weakref.WeakKeyDictionary[Callable[..., Any], inspect.Signature] = (
    weakref.WeakKeyDictionary()
)


def _signature_of(method: Callable[..., Any]) -> inspect.Signature:
    signature = _SIGNATURES.get(method)
    if signature is None:
        signature = _SIGNATURES[method] = inspect.signature(method)
    return signature


def _tell_observers(
    method: Callable[..., Any],
    method_name: str,
    args: tuple[Any, ...],
    kwargs: dict[str, Any],
    result: Any,
    error: BaseException | None,
) -> None:
    arguments = args[1:]
    if kwargs:
        arguments = tuple(_signature_of(method).bind(*args, **kwargs).arguments.values())[1:]
    for observer in list(CALL_OBSERVERS):
        try:
            observer(args[0], method_name, arguments, result, error)
        except Exception:
            logging.getLogger(__name__).exception("call observer %r failed", observer)


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
    #: Whether commands may be confirmed later on this backend's link: then it has a
    #: ``_link`` whose ``unconfirmed`` is not ``None`` while an acknowledgement is owed,
    #: which every interface call tests first (an attribute read, no call: see
    #: :meth:`owes_acknowledgement`, which says the same).
    _acknowledges_later: ClassVar[bool] = False

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

    def make_safe_now(self, timeout: float) -> bool:
        """Put the board in its safe state at once, synchronously, through its own link.

        This is the safety net's contract with a backend (see :mod:`j5aio.lifetime`); every
        backend of a board that can move or power something must override it:

        * **Synchronous**: it needs no running event loop. It is called from the thread that
          runs the board's event loop (between callbacks, never during an await of this
          backend), or after that loop has stopped, or at interpreter exit.
        * **Own link only**: it sends through the backend's own link with the link's
          synchronous path (:meth:`.SerialLink.send_now`,
          :meth:`.USBLink.control_write_now`); no discovery, no other board.
        * **Bounded**: it returns or raises within ``timeout`` seconds.
        * **Idempotent** and harmless on a link that is already closed (return ``False``).
        * **The same safe state as the board's** :meth:`~j5aio.boards.board.Board.make_safe`
          (motors braked, power outputs off); where that leaves things as they are (a
          servo, an Arduino pin), there is nothing to send.
        * Failures raise :class:`~j5aio.errors.CommunicationError` (or a subclass); the
          caller logs them and goes on to the next board.

        :param timeout: the most seconds it may take.
        :returns: whether anything was sent (``False``: nothing to send). The default
            sends nothing, which suits backends with no actuators (consoles, sensors).
        """
        return False

    def owes_acknowledgement(self) -> bool:
        """Whether a command's acknowledgement is still to be read from the board.

        Only where commands are confirmed later
        (:func:`~j5aio.backends.acknowledgements.acknowledge_later`); ``False`` here.
        Every interface method of a backend reads it (with
        :meth:`confirm_acknowledgement`) before it runs.
        """
        return False

    async def confirm_acknowledgement(self) -> None:
        """Read and check the acknowledgement still owed, if any (nothing to do here).

        :raises ~j5aio.errors.EarlierCommandError: the earlier command had failed.
        """

    def close_now(self) -> None:
        """Release the backend's port synchronously (at exit); does nothing here.

        Like :meth:`make_safe_now`, it needs no running event loop; idempotent.
        """

    async def close(self) -> None:
        """Release whatever the backend holds (a port, a USB handle). Does nothing here."""

    def _check_single(self, identifier: int, what: str) -> None:
        """Refuse any ``identifier`` but 0 for a component the board has only one of.

        :raises ValueError: naming the board, the component and the identifier given.
        """
        if identifier != 0:
            raise ValueError(f"{self.board.name} has only {what} 0, not {identifier!r}")
