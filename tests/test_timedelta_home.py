"""Tests of j5aio._timedelta: datetime's own timedelta class, without datetime's source."""

from __future__ import annotations

import sys

import pytest

from tests.fresh_interpreter import printed_words


def test_it_is_the_class_of_the_datetime_module() -> None:
    import datetime

    from j5aio._timedelta import timedelta

    assert timedelta is datetime.timedelta
    assert timedelta(milliseconds=1) == datetime.timedelta(microseconds=1000)


@pytest.mark.skipif(
    sys.implementation.name != "cpython", reason="the C module _datetime is CPython's"
)
def test_a_start_does_not_run_the_datetime_module() -> None:
    # What the interpreter's start loaded (coverage's subprocess hook imports datetime) is
    # forgotten first: the question is whether j5aio brings it back.
    program = (
        "import sys\n"
        "sys.modules.pop('datetime', None)\n"
        "from j5aio._timedelta import timedelta\n"
        "import j5aio.components.piezo\n"
        "print('datetime' in sys.modules)\n"
        "import datetime\n"
        "print(timedelta is datetime.timedelta)\n"
    )
    assert printed_words(program) == ["False", "True"]


def test_without_the_c_module_it_comes_from_datetime() -> None:
    program = (
        "import sys\n"
        "sys.modules['_datetime'] = None  # as on a Python without it\n"
        "from j5aio._timedelta import timedelta\n"
        "import datetime\n"
        "print(timedelta is datetime.timedelta, timedelta(seconds=1).total_seconds())\n"
    )
    assert printed_words(program) == ["True", "1.0"]
