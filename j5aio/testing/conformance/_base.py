"""What every conformance suite shares: the subject under test and the suite base class."""

from __future__ import annotations

import abc
import dataclasses
from collections.abc import AsyncIterator, Awaitable, Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any, ClassVar, Generic, TypeVar

import anyio
import pytest
import pytest_asyncio

from j5aio.backends.backend import Backend

__all__ = ["InterfaceConformance", "Subject", "SubjectT"]


@dataclass(kw_only=True)
class Subject:
    """A backend handed to a conformance suite, with what the suite needs to know about it.

    Each interface's suite has its own subclass that adds hooks: ways for the suite to
    *observe* what the board did (read a simulator's state) and to *feed* it inputs (press
    a simulated button, answer a console prompt). A hook left as ``None`` makes the tests
    that need it skip, saying which hook to give.

    :param backend: the backend instance under test.
    :param identifiers: the identifiers of the components of this interface that the
        board has.
    :param invalid_identifiers: identifiers the board does not have; the suite checks that
        each is refused. Defaults to one past the largest identifier, and ``-1``.
    :param traffic: returns every byte the backend has sent to its board so far (for
        example :attr:`RecordingStream.sent <j5aio.testing.transports.RecordingStream>`);
        when given, the suite checks that refused calls send nothing.
    :param cleanup: awaited after each test; when ``None``, the backend's ``close()``
        is awaited instead.
    """

    #: Hooks whose absence leaves no check out (``cleanup`` has a default behaviour).
    optional_hooks: ClassVar[tuple[str, ...]] = ("cleanup",)

    backend: Any
    identifiers: Sequence[int] = ()
    invalid_identifiers: Sequence[int] | None = None
    traffic: Callable[[], bytes] | None = None
    cleanup: Callable[[], Awaitable[None]] | None = None

    def bad_identifiers(self) -> list[int]:
        """The identifiers the suite expects the backend to refuse."""
        if self.invalid_identifiers is not None:
            return list(self.invalid_identifiers)
        return [max(self.identifiers, default=-1) + 1, -1]

    def missing_hooks(self) -> list[str]:
        """The names of the hooks this subject leaves as ``None``, but for optional ones."""
        return [
            f.name
            for f in dataclasses.fields(self)
            if "Callable" in str(f.type)
            and f.name not in self.optional_hooks
            and getattr(self, f.name) is None
        ]

    def sent_so_far(self) -> bytes | None:
        """Return what the backend has sent so far, or ``None`` without a traffic hook."""
        return None if self.traffic is None else bytes(self.traffic())

    async def aclose(self) -> None:
        """Release the backend after a test."""
        if self.cleanup is not None:
            await self.cleanup()
        elif isinstance(self.backend, Backend):
            await self.backend.close()


SubjectT = TypeVar("SubjectT", bound=Subject)
ValueT = TypeVar("ValueT")


#: Every skip reason for a missing hook contains this, so that reports can find them.
HOOK_SKIP_MARK = "hook of the subject"


def require(hook: Callable[..., Any] | None, name: str) -> Callable[..., Any]:
    """Return ``hook``, or skip the running test because the subject lacks it."""
    if hook is None:
        pytest.skip(f"needs the {name!r} {HOOK_SKIP_MARK}; give it to test this")
    return hook


class InterfaceConformance(abc.ABC, Generic[SubjectT]):
    """The base of every conformance suite.

    Subclass a suite in a class whose name starts with ``Test`` and implement
    :meth:`make_backend`; pytest then collects every test of the suite for your backend.
    A fresh backend is made for each test and released afterwards. Tests that your
    subject gives no hook for are skipped, saying which hook would enable them, and
    :meth:`test_every_hook_is_given` skips naming every hook left out, since some checks
    (comparing what the board shows with what the backend reports, through ``observe``)
    are folded into other tests and silently left out without their hook. The pytest
    plugin lists all such skips at the end of the run, so a green run cannot hide them.

    To use pytest fixtures while making the backend, add an autouse fixture to your
    class that stores what it needs on ``self``; it runs before :meth:`make_backend`.

    The tests are marked for pytest-asyncio, so they run in its strict mode too.
    """

    pytestmark: ClassVar[list[pytest.MarkDecorator]] = [pytest.mark.asyncio]

    #: Seconds any one test may spend awaiting the backend before it counts as a hang.
    call_timeout: ClassVar[float] = 5.0

    #: The exceptions a backend may raise for an identifier its board does not have.
    bad_identifier_errors: ClassVar[tuple[type[BaseException], ...]] = (ValueError, LookupError)

    @abc.abstractmethod
    async def make_backend(self) -> SubjectT:
        """Make a fresh backend to test, and describe it."""
        raise NotImplementedError

    @pytest_asyncio.fixture
    async def subject(self) -> AsyncIterator[SubjectT]:
        """The subject of one test: made by :meth:`make_backend`, released afterwards."""
        with anyio.fail_after(self.call_timeout):
            made = await self.make_backend()
        try:
            yield made
        finally:
            with anyio.fail_after(self.call_timeout):
                await made.aclose()

    async def test_every_hook_is_given(self, subject: SubjectT) -> None:
        """Skips, naming them, if the subject leaves hooks out: their checks did not run."""
        missing = subject.missing_hooks()
        if missing:
            names = ", ".join(repr(name) for name in missing)
            pytest.skip(
                f"no {names} (each a {HOOK_SKIP_MARK}): the checks that need them were "
                "left out of this run; give them to run every check",
            )

    @contextmanager
    def bounded(self) -> Iterator[None]:
        """Fail the test if the block takes longer than :attr:`call_timeout` (a hang)."""
        with anyio.move_on_after(self.call_timeout) as scope:
            yield
        if scope.cancelled_caught:
            pytest.fail(
                f"the backend did not finish within call_timeout ({self.call_timeout} s): "
                "a call hangs, or waits for an input the subject's hooks never gave",
            )

    async def assert_read_back(
        self,
        told: str,
        identifier: int,
        read: Callable[[int], Awaitable[ValueT]],
        observe: Callable[[int], Awaitable[ValueT]] | None,
        matches: Callable[[ValueT], bool],
    ) -> None:
        """Check that ``identifier`` reads back what was done, and that the board shows it.

        What the board shows is looked at only when the subject gives ``observe``.

        :param told: what was done, for the failure messages: ``"LED 0 was set to True"``.
        :param matches: whether a value read or shown is the one that was set.
        """
        got = await read(identifier)
        assert matches(got), f"{told} but reads back {got!r}"
        if observe is not None:
            seen = await observe(identifier)
            assert matches(seen), f"{told} but the board shows {seen!r}"

    async def assert_each_alone(
        self,
        identifiers: Sequence[int],
        set_state: Callable[[int, bool], Awaitable[Any]],
        read: Callable[[int], Awaitable[object]],
        failure: Callable[[int, int, object], str],
    ) -> None:
        """Raise each identifier's state on its own: only that identifier may read raised.

        Each is set true, every identifier is read (``True`` for that one, ``False`` for
        the others, else the test fails with ``failure(raised, read, got)``) and it is set
        false again.
        """
        for identifier in identifiers:
            await set_state(identifier, True)
            for other in identifiers:
                got = await read(other)
                assert got is (other == identifier), failure(identifier, other, got)
            await set_state(identifier, False)

    async def assert_refused(
        self, subject: Subject, call: Callable[[int], Awaitable[Any]], what: str | None = None,
    ) -> None:
        """Check that ``call`` refuses every bad identifier, sending nothing to the board.

        :param what: the call's name in the failure messages; by default its
            ``__name__`` (a backend's method names itself; a ``lambda`` needs one).
        """
        what = what if what is not None else getattr(call, "__name__", repr(call))
        allowed = " or ".join(error.__name__ for error in self.bad_identifier_errors)
        for identifier in subject.bad_identifiers():
            before = subject.sent_so_far()
            try:
                with self.bounded():
                    await call(identifier)
            except self.bad_identifier_errors:
                pass
            else:
                pytest.fail(f"{what} accepted bad identifier {identifier}; expected {allowed}")
            assert subject.sent_so_far() == before, (
                f"{what} with bad identifier {identifier} sent bytes to the board"
            )
