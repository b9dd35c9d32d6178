"""The conformance suite of :class:`~j5aio.components.button.ButtonInterface`."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

import anyio
import pytest

from j5aio.components.button import ButtonInterface

from ._base import InterfaceConformance, Subject, require

__all__ = ["ButtonInterfaceConformance", "ButtonSubject"]

_Hook = Callable[[int], Awaitable[None]]


@dataclass(kw_only=True)
class ButtonSubject(Subject):
    """A backend implementing :class:`.ButtonInterface`, for :class:`ButtonInterfaceConformance`.

    :param set_pressed: holds button ``identifier`` down (``True``) or lets it go, so that
        the next :meth:`~j5aio.components.button.ButtonInterface.get_button_state` sees
        it. For a console backend: queue the answer to the next prompt.
    :param press: presses button ``identifier`` once, so that a waiting
        :meth:`~j5aio.components.button.ButtonInterface.wait_until_button_pressed` returns.
        It is called while
        the wait is in progress. With ``release`` given, it only has to *latch* the press
        (hold the button down and return at once); otherwise it presses and releases,
        holding the button long enough for a polling backend to see it.
    :param release: lets button ``identifier`` go after a latched ``press``; the suite
        calls it once the wait has returned, so no hook sleeps for the backend's poll
        interval. Without ``press``, a subject with ``set_pressed`` is pressed the same
        way: held down until the wait has returned, then released.
    """

    optional_hooks: ClassVar[tuple[str, ...]] = ("cleanup", "release")

    backend: ButtonInterface
    set_pressed: Callable[[int, bool], Awaitable[None]] | None = None
    press: Callable[[int], Awaitable[None]] | None = None
    release: Callable[[int], Awaitable[None]] | None = None

    def missing_hooks(self) -> list[str]:
        """The hooks left out; ``press`` is not missed when ``set_pressed`` stands in for it."""
        missing = super().missing_hooks()
        if self.set_pressed is not None and "press" in missing:
            missing.remove("press")
        return missing

    def latching_press(self) -> tuple[_Hook, _Hook | None] | None:
        """Return (press, release) hooks for a wait test, or ``None`` if there are none.

        ``release`` is ``None`` when ``press`` presses and releases on its own.
        """
        if self.press is not None:
            return self.press, self.release
        set_pressed = self.set_pressed
        if set_pressed is None:
            return None

        async def hold(identifier: int) -> None:
            await set_pressed(identifier, True)

        async def let_go(identifier: int) -> None:
            await set_pressed(identifier, False)

        return hold, let_go


class ButtonInterfaceConformance(InterfaceConformance[ButtonSubject]):
    """What every implementation of :class:`~j5aio.components.button.ButtonInterface` must do.

    * the state read is a ``bool`` and follows the button;
    * ``wait_until_button_pressed`` returns after a press, not before, and is cancellable
      through an anyio scope, leaving the backend usable;
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How long the suite waits to be sure that a wait has not returned early, in seconds.
    settle_time: ClassVar[float] = 0.1

    async def test_state_is_a_bool(self, subject: ButtonSubject) -> None:
        """Reading any button gives ``True`` or ``False``."""
        with self.bounded():
            for identifier in subject.identifiers:
                if subject.set_pressed is not None:
                    await subject.set_pressed(identifier, False)
                state = await subject.backend.get_button_state(identifier)
                assert isinstance(state, bool), f"button {identifier} read as {state!r}"

    async def test_state_follows_the_button(self, subject: ButtonSubject) -> None:
        """A held button reads as pressed, a released one as not pressed."""
        set_pressed = require(subject.set_pressed, "set_pressed")
        with self.bounded():
            for identifier in subject.identifiers:
                for pressed in (True, False, True, False):
                    await set_pressed(identifier, pressed)
                    got = await subject.backend.get_button_state(identifier)
                    assert got is pressed, (
                        f"button {identifier} is {'held' if pressed else 'released'} "
                        f"but reads {got!r}"
                    )

    async def _wait_then_press(self, subject: ButtonSubject, identifier: int) -> None:
        hooks = subject.latching_press()
        if hooks is None:
            pytest.skip(
                "needs the 'press' (or 'set_pressed') hook of the subject; give it to test this",
            )
        press, release = hooks
        returned = anyio.Event()

        async def wait() -> None:
            await subject.backend.wait_until_button_pressed(identifier)
            returned.set()

        with self.bounded():
            async with anyio.create_task_group() as group:
                group.start_soon(wait)
                await anyio.sleep(self.settle_time)
                early = returned.is_set()
                if not early:
                    await press(identifier)
                    await returned.wait()
                    if release is not None:
                        await release(identifier)
        assert not early, f"wait_until_button_pressed({identifier}) returned before any press"

    async def test_wait_returns_after_a_press(self, subject: ButtonSubject) -> None:
        """Waiting for each button returns once it is pressed, and not before."""
        for identifier in subject.identifiers:
            await self._wait_then_press(subject, identifier)

    async def test_wait_is_cancellable(self, subject: ButtonSubject) -> None:
        """A wait with no press ends promptly when its scope is cancelled."""
        identifier = subject.identifiers[0]
        with self.bounded():
            with anyio.move_on_after(self.settle_time) as scope:
                await subject.backend.wait_until_button_pressed(identifier)
            assert scope.cancelled_caught, "the wait returned although nobody pressed"

    async def test_wait_works_after_a_cancelled_wait(self, subject: ButtonSubject) -> None:
        """A cancelled wait leaves nothing behind: the next wait sees the next press."""
        identifier = subject.identifiers[0]
        with self.bounded(), anyio.move_on_after(self.settle_time):
            await subject.backend.wait_until_button_pressed(identifier)
        await self._wait_then_press(subject, identifier)

    async def test_out_of_range_identifier_raises(self, subject: ButtonSubject) -> None:
        """A button the board does not have is refused, also by the wait (which must not hang)."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_button_state)
        await self.assert_refused(subject, backend.wait_until_button_pressed)
