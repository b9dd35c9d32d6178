from __future__ import annotations

import json
import logging
from pathlib import Path

import anyio
import pytest

from j5aio.competition import service_state
from j5aio.competition.metadata import Mode
from j5aio.service.config import ServiceConfig
from j5aio.service.inbox import Inbox
from j5aio.service.messages import Topics
from j5aio.service.payloads import MAX_PAYLOAD_BYTES, PayloadError, decode_object
from tests.service.helpers import astmetad_message, astprocd_message, start_event

TOPICS = Topics.for_config(ServiceConfig(host="localhost"))


def make_inbox() -> tuple[Inbox, list[int]]:
    starts: list[int] = []
    return Inbox(TOPICS, lambda: starts.append(1), lambda: True), starts  # a robot waits


def send(inbox: Inbox, topic: str, payload: object, retained: bool = False) -> None:
    raw = payload if isinstance(payload, bytes | str) else json.dumps(payload)
    inbox.receive(topic, raw, retained)


def test_topics_are_astorias() -> None:
    assert TOPICS.subscriptions == (
        "astoria/astmetad", "astoria/astprocd", "astoria/broadcast/start_button",
        "astoria/start_button",
    )
    assert TOPICS.frames == "camera/annotated"


def test_metadata_message_sets_and_updates_the_metadata() -> None:
    inbox, _ = make_inbox()
    send(inbox, TOPICS.metadata, astmetad_message(zone=2, mode="COMP", game_timeout=150))
    metadata = service_state.metadata()
    assert metadata is not None
    assert (metadata.zone, metadata.mode, metadata.duration) == (2, Mode.COMP, 150)
    send(inbox, TOPICS.metadata, astmetad_message(zone=3, arena="B", wifi_enabled=False))
    metadata = service_state.metadata()
    assert metadata is not None
    assert (metadata.zone, metadata.arena, metadata.wifi_enabled) == (3, "B", False)


def test_stopped_astmetad_keeps_the_last_metadata() -> None:
    inbox, _ = make_inbox()
    send(inbox, TOPICS.metadata, astmetad_message(zone=2))
    send(inbox, TOPICS.metadata, astmetad_message("STOPPED", zone=0))
    metadata = service_state.metadata()
    assert metadata is not None and metadata.zone == 2


def test_astprocd_gives_the_usercode_stick() -> None:
    inbox, _ = make_inbox()
    send(inbox, TOPICS.process, astprocd_message("/media/ABCD-1234"))
    assert service_state.usercode_path() == Path("/media/ABCD-1234")
    send(inbox, TOPICS.process, astprocd_message(None))  # no stick now: keep the last
    send(inbox, TOPICS.process, astprocd_message("/media/other", status="STOPPED"))
    assert service_state.usercode_path() == Path("/media/ABCD-1234")


def test_remote_starts_astoria_and_sbot() -> None:
    inbox, starts = make_inbox()
    send(inbox, TOPICS.start, start_event())
    assert len(starts) == 1
    send(inbox, TOPICS.sbot_start, {"pressed": True})
    assert len(starts) == 2
    send(inbox, TOPICS.sbot_start, {"pressed": False})
    assert len(starts) == 2 and inbox.starts == 2


def test_retained_remote_start_is_stale(caplog: pytest.LogCaptureFixture) -> None:
    inbox, starts = make_inbox()
    with caplog.at_level(logging.INFO, "j5aio.service"):
        send(inbox, TOPICS.start, start_event(), retained=True)
        send(inbox, TOPICS.sbot_start, {"pressed": True}, retained=True)
    assert starts == []
    assert "kept from before" in caplog.text


def test_other_topics_are_ignored() -> None:
    inbox, starts = make_inbox()
    send(inbox, "astoria/astdiskd", b"not even json")
    assert starts == [] and service_state.metadata() is None


BAD = [
    (TOPICS.metadata, b"{not json", "not JSON"),
    (TOPICS.metadata, b"\xff\xfe", "not JSON"),
    (TOPICS.metadata, b"[1, 2]", "not an object"),
    (TOPICS.metadata, b" " * (MAX_PAYLOAD_BYTES + 1), "bytes was ignored"),
    (TOPICS.metadata, json.dumps(astmetad_message(zone="2")), "zone"),
    (TOPICS.metadata, json.dumps(astmetad_message(mode="comp")), "mode"),
    (TOPICS.metadata, json.dumps({"status": "RUNNING"}), "without 'metadata'"),
    (TOPICS.metadata, json.dumps({"status": "MAYBE", "metadata": {}}), "status is 'MAYBE'"),
    (TOPICS.metadata, json.dumps({"status": 1, "metadata": {}}), "'status' is 1"),
    (TOPICS.process, json.dumps({"status": "RUNNING", "disk_info": "x"}), "'disk_info'"),
    (TOPICS.process, json.dumps(astprocd_message("relative/path")), "absolute path"),
    (TOPICS.process, json.dumps({"status": "RUNNING", "disk_info": {}}), "mount_path"),
    (TOPICS.start, json.dumps({"event_name": "start_button"}), "sender_name"),
    (TOPICS.start, json.dumps({**start_event(), "priority": "high"}), "priority"),
    (TOPICS.start, json.dumps({**start_event(), "priority": True}), "priority"),
    (TOPICS.sbot_start, json.dumps({"pressed": 1}), "pressed"),
    (TOPICS.sbot_start, json.dumps({}), "pressed"),
]


@pytest.mark.parametrize(("topic", "payload", "words"), BAD)
def test_bad_message_is_ignored_and_logged_once(
    caplog: pytest.LogCaptureFixture, topic: str, payload: bytes | str, words: str
) -> None:
    inbox, starts = make_inbox()
    send(inbox, TOPICS.metadata, astmetad_message(zone=4))
    send(inbox, TOPICS.process, astprocd_message("/media/stick"))
    with caplog.at_level(logging.DEBUG, "j5aio.service"):
        for _ in range(5):
            inbox.receive(topic, payload, False)
    warnings = [r for r in caplog.records if r.levelno >= logging.WARNING]
    assert len(warnings) == 1, caplog.text
    assert words in warnings[0].getMessage()
    assert starts == []
    metadata = service_state.metadata()
    assert metadata is not None and metadata.zone == 4  # the last good metadata stays
    assert service_state.usercode_path() == Path("/media/stick")


def test_a_failing_start_does_not_escape(caplog: pytest.LogCaptureFixture) -> None:
    def broken() -> None:
        raise RuntimeError("boom")

    inbox = Inbox(TOPICS, broken, lambda: True)
    for _ in range(3):
        send(inbox, TOPICS.start, start_event())
    tracebacks = [r for r in caplog.records if r.exc_info is not None]
    assert len(tracebacks) == 1 and "boom" in caplog.text


async def test_default_start_triggers_wait_for_start() -> None:
    from j5aio.competition.start import wait_for_start
    from j5aio.service.inbox import robot_is_waiting

    inbox = Inbox(TOPICS)
    send(inbox, TOPICS.start, start_event())  # nothing waits yet: this starts nothing
    async with anyio.create_task_group() as tasks:

        async def wait() -> None:
            assert await wait_for_start([], timeout=10) == "remote start"

        tasks.start_soon(wait)
        with anyio.fail_after(10):
            while not robot_is_waiting():  # noqa: ASYNC110 - a state another task sets
                await anyio.sleep(0.01)
        send(inbox, TOPICS.start, start_event())


def test_decode_object_accepts_text_and_bytes() -> None:
    assert decode_object('{"a": 1}', "t") == {"a": 1}
    with pytest.raises(PayloadError) as caught:
        decode_object(b"[" * 100_000, "t")
    assert caught.value.kind in ("oversized", "not JSON")


def test_a_remote_start_counts_only_while_the_robot_waits(
    caplog: pytest.LogCaptureFixture,
) -> None:
    waiting = False
    starts: list[int] = []
    inbox = Inbox(TOPICS, lambda: starts.append(1), lambda: waiting)
    with caplog.at_level(logging.INFO, "j5aio.service"):
        send(inbox, TOPICS.start, start_event())
        send(inbox, TOPICS.sbot_start, {"pressed": True})
    assert starts == [] and "not waiting" in caplog.text
    waiting = True
    send(inbox, TOPICS.start, start_event())
    assert starts == [1] and inbox.starts == 1


async def test_whether_the_robot_waits_comes_from_the_start_module() -> None:
    from j5aio.competition.start import clear_trigger, trigger_start, wait_for_start
    from j5aio.service.inbox import robot_is_waiting

    assert not robot_is_waiting()  # nothing waits: a remote start now would count for nothing
    async with anyio.create_task_group() as tasks:
        tasks.start_soon(wait_for_start, [])
        for _ in range(200):
            if robot_is_waiting():
                break
            await anyio.sleep(0.01)
        assert robot_is_waiting()
        trigger_start("remote start")
    assert not robot_is_waiting()
    clear_trigger()
