"""Fixtures for every sync facade test."""

from __future__ import annotations

import signal
from collections.abc import Iterator

import pytest


@pytest.fixture(autouse=True)
def ctrl_c_raises() -> Iterator[None]:
    """Make Ctrl-C raise KeyboardInterrupt, as in a fresh program, for the test's length.

    The safety net ignores Ctrl-C once it has printed its one-line message, and a test of
    that message (in another directory) leaves that in place for the rest of the run; the
    tests here that interrupt a call need Python's own handler.
    """
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


@pytest.fixture
def handoff_portal(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """The facade on the hand-off portal (a loop thread), as where callers cannot drive."""
    from j5aio.sync import _runtime

    _runtime.shutdown()
    monkeypatch.setattr(_runtime, "CALLER_DRIVES", False)
    yield
    _runtime.shutdown()


@pytest.fixture(params=["caller drives", "hand-off"])
def either_portal(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """The facade on each kind of portal in turn: the loop its callers drive, the loop thread."""
    from j5aio.sync import _runtime

    _runtime.shutdown()
    if request.param == "hand-off":
        monkeypatch.setattr(_runtime, "CALLER_DRIVES", False)
    yield request.param
    _runtime.shutdown()
