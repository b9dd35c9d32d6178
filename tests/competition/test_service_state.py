from collections.abc import Iterator
from pathlib import Path

import pytest

from j5aio.competition import service_state
from j5aio.competition.metadata import Metadata, Mode


@pytest.fixture(autouse=True)
def _clean() -> Iterator[None]:
    service_state.clear()
    yield
    service_state.clear()


def test_nothing_is_known_until_the_service_says_so() -> None:
    assert service_state.metadata() is None
    assert service_state.usercode_path() is None


def test_listeners_hear_each_change_once() -> None:
    heard: list[tuple[Metadata | None, Path | None]] = []
    listener = lambda: heard.append((service_state.metadata(), service_state.usercode_path()))  # noqa: E731
    service_state.add_listener(listener)
    service_state.add_listener(listener)  # added once only
    comp = Metadata(zone=2, mode=Mode.COMP, duration=150)
    service_state.set_metadata(comp)
    service_state.set_metadata(comp)  # unchanged: nobody is told
    service_state.set_usercode_path(Path("/media/usercode"))
    assert heard == [(comp, None), (comp, Path("/media/usercode"))]
    service_state.remove_listener(listener)
    service_state.set_metadata(None)
    assert len(heard) == 2
    service_state.remove_listener(listener)  # a second removal is harmless


def test_a_failing_listener_is_logged_and_the_others_still_run(
    caplog: pytest.LogCaptureFixture,
) -> None:
    heard: list[str] = []

    def broken() -> None:
        raise RuntimeError("boom")

    service_state.add_listener(broken)
    service_state.add_listener(lambda: heard.append("ok"))
    service_state.set_usercode_path(Path("/media/x"))
    assert heard == ["ok"]
    assert "listener of the robot service" in caplog.text
