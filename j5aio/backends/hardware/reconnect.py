"""Reconnection: a board that vanishes (a knocked cable, a brown-out) and comes back.

Every hardware backend (serial and USB) is a :class:`Reconnecting` backend:

* When the board vanishes, the call in flight fails with
  :class:`~j5aio.errors.BoardDisconnectionError` and the backend is *lost*. It keeps its
  place in the port registry and its :class:`~j5aio.boards.board.Board`, so discovery
  hands back the same object, never a duplicate.
* While lost, each call first looks for the same board again (by USB serial number, or
  at the same port path for a board attached by port), at most once every
  ``ReconnectPolicy.interval`` seconds; a call made when it is not back fails at
  once with :class:`~j5aio.errors.BoardDisconnectionError`. While every board is being
  made safe (:mod:`j5aio.safety.safe_state_pass`), a lost board is looked for once
  more whatever the interval, so that a board back by then is stopped too. There is
  no background task: the next call after the board is back finds it (so it answers
  again within ``interval`` of being back, plus its own boot time).
* Finding it re-runs the handshake on a new link, after calling the backend's
  :meth:`Reconnecting.reset_board_state` hook: the board has just been reset, so the
  backend forgets everything it remembered and starts again from the board's power-up
  state (or from what the handshake reads back or sets).
* **Retry policy.** A call that failed because the board vanished is retried once,
  transparently, if it is *idempotent* (a read, or setting a state: doing it twice is
  the same as once) and the policy allows (``ReconnectPolicy.retry_idempotent``);
  the retry waits up to ``ReconnectPolicy.retry_wait`` seconds for the board to come
  back. A call that is not idempotent (a piezo note) is never retried. Backends say which
  is which per command (``idempotent=False`` on the link calls); users choose the
  policy per backend class (``RECONNECT_POLICY``) or per board
  (``board.backend.reconnect_policy = ReconnectPolicy(...)``).
"""

from __future__ import annotations

import logging
import math
from abc import abstractmethod
from collections.abc import Awaitable, Callable
from typing import ClassVar, TypeVar

import anyio

from j5aio._records import FrozenRecord, frozen_record
from j5aio.errors import BoardDisconnectionError
from j5aio.safety.safe_state_pass import claim_attempt

__all__ = ["ReconnectPolicy", "Reconnecting"]

_log = logging.getLogger(__name__)

T = TypeVar("T")


# (It writes its own ``__init__`` and takes freezing, ``__repr__``, ``__eq__`` and
# ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: every
# program imports it, and making the generated ones costs a third of a millisecond. A
# test checks them against those.)
@frozen_record
class ReconnectPolicy(FrozenRecord):
    """How a hardware backend copes with its board vanishing and coming back.

    :param enabled: look for the board again at all; if false a lost board stays lost
        until it is discovered again after :meth:`~j5aio.backends.backend.Backend.close`.
    :param interval: the least time between two attempts to find a lost board, in
        seconds, so that a busy loop does not reopen the port thousands of times.
    :param retry_idempotent: retry an idempotent call once after its board vanished.
    :param retry_wait: how long that retry waits for the board to come back, in seconds
        (0: only if it is back already, as after a brief brown-out).
    """

    enabled: bool = True
    interval: float = 0.1
    retry_idempotent: bool = True
    retry_wait: float = 0.0

    def __init__(
        self,
        enabled: bool = True,
        interval: float = 0.1,
        retry_idempotent: bool = True,
        retry_wait: float = 0.0,
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "enabled", enabled)
        set_field(self, "interval", interval)
        set_field(self, "retry_idempotent", retry_idempotent)
        set_field(self, "retry_wait", retry_wait)
        self.__post_init__()

    def __post_init__(self) -> None:
        for name in ("interval", "retry_wait"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value >= 0):
                raise ValueError(f"{name} must be a finite number of seconds >= 0, not {value!r}")


class Reconnecting:
    """What every hardware backend does when its board vanishes; see the module's notes.

    Subclasses implement :meth:`_reopen` and override :meth:`reset_board_state`.
    """

    #: The policy of every backend of this class, unless a board is given its own.
    RECONNECT_POLICY: ClassVar[ReconnectPolicy] = ReconnectPolicy()

    _lost: bool = False
    _closed_for_good: bool = False
    _last_attempt: float = -math.inf
    _policy: ReconnectPolicy | None = None
    _reconnect_lock: anyio.Lock | None = None
    _reconnections: int = 0

    # -- public --------------------------------------------------------------------------

    @property
    def reconnect_policy(self) -> ReconnectPolicy:
        """The reconnection policy of this board (the class's unless set)."""
        return self._policy if self._policy is not None else self.RECONNECT_POLICY

    @reconnect_policy.setter
    def reconnect_policy(self, policy: ReconnectPolicy) -> None:
        if not isinstance(policy, ReconnectPolicy):
            raise TypeError(f"a reconnect policy must be a ReconnectPolicy, not {policy!r}")
        self._policy = policy

    @property
    def is_connected(self) -> bool:
        """Whether the board is there (False from its disappearance to its return)."""
        return not self._lost and not self._closed_for_good

    @property
    def reconnections(self) -> int:
        """How many times the board has been found again after vanishing."""
        return self._reconnections

    def reset_board_state(self) -> None:
        """Forget what was remembered of the board: it has been reset.

        **The hook for new backends.** Called when a vanished board has been found
        again, after the new link is open and before the handshake runs on it. Set
        every cache back to the board's power-up state (the handshake may then read
        back or set more). The default remembers nothing, so does nothing.
        """

    async def reconnect(self) -> bool:
        """Look for the vanished board now; return whether it is connected afterwards.

        Does nothing (and returns True) if the board is connected. Raises nothing: a
        failed attempt is logged, and the board stays lost.
        """
        if self.is_connected:
            return True
        if self._closed_for_good:
            return False
        if self._reconnect_lock is None:
            self._reconnect_lock = anyio.Lock()
        async with self._reconnect_lock:
            if not self._lost:
                return True
            self._last_attempt = anyio.current_time()
            try:
                await self._reopen()
            except Exception as exc:
                _log.debug("%r: the board is not back yet: %s", self, exc)
                return False
            self._lost = False
            self._reconnections += 1
            _log.info("%r: the board is back; its state was reset", self)
            return True

    # -- for subclasses ------------------------------------------------------------------

    @abstractmethod
    async def _reopen(self) -> None:
        """Find the board again, open a new link, call :meth:`reset_board_state`, handshake.

        :raises Exception: the board is not back (anything; it is logged).
        """

    def _mark_lost(self) -> None:
        """Note that the board has vanished (the caller closes the link).

        A board closed on purpose (at game over, say) has not vanished: the call it cut
        short fails, but nothing is logged and nothing will look for the board.
        """
        if not self._lost and not self._closed_for_good:
            _log.warning("%r: the board has vanished; j5aio will look for it again", self)
        self._lost = True

    def _forget(self) -> None:
        """Let go of the vanished board's link; called when a guarded call finally fails.

        The default only marks the board lost. A subclass closes its link here, and
        frees its port when the board will not be looked for again.
        """
        self._mark_lost()

    async def _guarded(self, call: Callable[[], Awaitable[T]], *, idempotent: bool) -> T:
        """Run one board call under the reconnection policy.

        Every call to the board goes through here (or through the same steps inline:
        see :meth:`_retry_after`). A lost board is looked for first; a call that fails
        because the board vanished is retried once if ``idempotent`` and the policy
        allow; when it fails for good, :meth:`_forget` lets go of the link and the
        :class:`~j5aio.errors.BoardDisconnectionError` is raised.

        :param call: does the call on the current link (it must look the link up
            when it runs, since a reconnection replaces it).
        :param idempotent: whether doing the call twice is the same as once.
        """
        try:
            if self._lost or self._closed_for_good:
                await self._check_connected()
            return await call()
        except BoardDisconnectionError as error:
            return await self._retry_after(error, call, idempotent=idempotent)

    async def _retry_after(
        self,
        error: BoardDisconnectionError,
        call: Callable[[], Awaitable[T]],
        *,
        idempotent: bool,
    ) -> T:
        """The rest of :meth:`_guarded` once a call has failed with ``error``.

        A backend's hot path may run a call on a connected board itself, and hand the
        disconnection it raises to this: the board is marked lost, the call is retried
        if ``idempotent`` and the policy allow, else (or if the retry fails) the link is
        let go of and the disconnection raised.
        """
        try:
            if not self._lost and not self._closed_for_good:
                self._mark_lost()
                policy = self.reconnect_policy
                if (
                    idempotent
                    and policy.enabled
                    and policy.retry_idempotent
                    and await self._wait_for_return(policy.retry_wait)
                ):
                    return await call()
            raise error
        except BoardDisconnectionError:
            self._forget()
            raise

    async def _check_connected(self) -> None:
        if self._closed_for_good:
            raise BoardDisconnectionError(f"{self!r}: the board has been closed")
        if not self._lost:
            return
        policy = self.reconnect_policy
        if policy.enabled and (
            anyio.current_time() - self._last_attempt >= policy.interval
            or claim_attempt(self)  # making the boards safe: one try, whatever the limit
        ):
            await self.reconnect()
        if self._lost:
            raise BoardDisconnectionError(
                f"{self!r}: the board is disconnected. Check its cable and power; "
                "j5aio will use it again as soon as it is back."
            )

    async def _wait_for_return(self, seconds: float) -> bool:
        deadline = anyio.current_time() + seconds
        while True:
            if await self.reconnect():
                return True
            remaining = deadline - anyio.current_time()
            if remaining <= 0:
                return False
            await anyio.sleep(min(self.reconnect_policy.interval, remaining))
