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
