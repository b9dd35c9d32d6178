"""Tests of the fake transports shipped for users' tests."""

from __future__ import annotations

import time

import anyio
import anyio.lowlevel
import pytest

from j5aio.backends.hardware.transports import (
    SerialLink,
    SimulatorStream,
    memory_stream_pair,
    read_line,
)
from j5aio.errors import BoardDisconnectionError, CommunicationTimeoutError
from j5aio.testing.transports import (
    Fault,
    FaultKind,
    FaultyStream,
    RecordingStream,
    ScriptedStream,
    WireEvent,
    WrappingStream,
    flip_first_byte,
)


class UpperSimulator:
    baudrate = 115200
    boot_delay = 0.0
    connected = True

    def open(self) -> bytes:
        return b""

    def receive(self, data: bytes) -> bytes:
        return data.upper()


def simulated() -> SimulatorStream:
    return SimulatorStream(UpperSimulator(), name="sim")


# -- RecordingStream -----------------------------------------------------------------------


async def test_recording_stream_records_both_directions_with_timestamps() -> None:
    recording = RecordingStream(simulated())
    before = time.monotonic()
    await recording.send(b"ab\n")
    assert await recording.receive() == b"AB\n"
    await recording.send(b"c\n")
    assert recording.sent == b"ab\nc\n"
    assert recording.received == b"AB\n"
    assert [(e.direction, e.data) for e in recording.events] == [
        ("sent", b"ab\n"),
        ("received", b"AB\n"),
        ("sent", b"c\n"),
    ]
    assert all(isinstance(e, WireEvent) and e.time >= before for e in recording.events)
    assert recording.name == "sim" and recording.inner.name == "sim"
    recording.clear()
    assert recording.events == []


async def test_recording_stream_closes_what_it_wraps() -> None:
    inner = simulated()
    recording = RecordingStream(inner)
    await recording.aclose()
    assert inner.is_closed and recording.is_closed
    other = RecordingStream(simulated())
    other.close_now()
    assert other.is_closed


async def test_a_failed_send_is_not_recorded() -> None:
    a, b = memory_stream_pair()
    b.close_now()
    recording = RecordingStream(a)
    with pytest.raises(BoardDisconnectionError):
        await recording.send(b"x")
    assert recording.events == []


# -- FaultyStream --------------------------------------------------------------------------


async def test_faulty_stream_passes_everything_through_by_default() -> None:
    faulty = FaultyStream(simulated())
    await faulty.send(b"ok\n")
    assert await faulty.receive() == b"OK\n"
    assert faulty.sends == 1
    assert faulty.name == "sim" and faulty.inner.name == "sim"
    assert not faulty.is_disconnected and not faulty.is_silent


async def test_drop_next_reply_drops_exactly_one_line() -> None:
    faulty = FaultyStream(simulated())
    faulty.drop_next_reply()
    await faulty.send(b"one\ntwo\n")
    assert await faulty.receive() == b"TWO\n"


async def test_drop_a_reply_split_over_chunks() -> None:
    a, b = memory_stream_pair()
    faulty = FaultyStream(a)
    faulty.drop_next_reply()

    async def send_in_pieces() -> None:
        await b.send(b"lo")
        await anyio.sleep(0.01)
        await b.send(b"st\nkept\n")

    async with anyio.create_task_group() as tg:
        tg.start_soon(send_in_pieces)
        assert await faulty.receive() == b"kept\n"


async def test_drop_the_next_chunk() -> None:
    a, b = memory_stream_pair()
    faulty = FaultyStream(a)
    faulty.inject(Fault.drop(terminator=None))
    await b.send(b"no newline")
    await anyio.lowlevel.checkpoint()
    with anyio.move_on_after(0.01):
        await faulty.receive()
        pytest.fail("the chunk was not dropped")
    await b.send(b"next")
    assert await faulty.receive() == b"next"


async def test_corrupt_next_reply() -> None:
    faulty = FaultyStream(simulated())
    faulty.corrupt_next_reply()
    await faulty.send(b"+ ok\n")
    assert await faulty.receive() == b"\xd4 OK\n"
    faulty.corrupt_next_reply(lambda reply: reply[::-1])
    await faulty.send(b"ab\n")
    assert await faulty.receive() == b"\nBA"
    assert flip_first_byte(b"") == b""


async def test_delay_next_reply_holds_it_back() -> None:
    faulty = FaultyStream(simulated())
    faulty.delay_next_reply(0.05)
    await faulty.send(b"late\n")
    start = time.monotonic()
    assert await faulty.receive() == b"LATE\n"
    assert time.monotonic() - start >= 0.04
    with pytest.raises(ValueError, match="negative"):
        Fault.delay(-1)


async def test_a_cancelled_receive_during_a_delay_keeps_the_reply() -> None:
    faulty = FaultyStream(simulated())
    faulty.delay_next_reply(0.03)
    await faulty.send(b"kept\n")
    with anyio.move_on_after(0.005):
        await faulty.receive()
    assert await faulty.receive() == b"KEPT\n"


async def test_disconnect_wakes_a_waiting_receive_and_fails_everything_after() -> None:
    a, _ = memory_stream_pair()
    faulty = FaultyStream(a)

    async def unplug_soon() -> None:
        await anyio.sleep(0.01)
        faulty.disconnect()

    with anyio.fail_after(1):
        async with anyio.create_task_group() as tg:
            tg.start_soon(unplug_soon)
            with pytest.raises(BoardDisconnectionError, match="injected fault"):
                await faulty.receive()
    assert faulty.is_disconnected
    with pytest.raises(BoardDisconnectionError):
        await faulty.send(b"x")


async def test_silence_swallows_both_ways_until_resumed() -> None:
    a, b = memory_stream_pair()
    faulty = FaultyStream(a)
    faulty.silence()
    assert faulty.is_silent
    await faulty.send(b"unheard\n")
    await b.send(b"unseen\n")
    with anyio.move_on_after(0.02):
        await faulty.receive()
        pytest.fail("a silenced board answered")
    with anyio.move_on_after(0.01):
        await b.receive()
        pytest.fail("a silenced board listened")
    faulty.resume()
    await faulty.send(b"heard\n")
    assert await b.receive() == b"heard\n"
    await b.send(b"seen\n")
    assert await faulty.receive() == b"seen\n"


async def test_a_schedule_injects_faults_at_given_sends() -> None:
    faulty = FaultyStream(
        simulated(),
        schedule={1: Fault.drop(), 2: [Fault.corrupt()], 4: Fault.disconnect()},
    )
    link = SerialLink(faulty, quiet_time=0.01)
    assert await link.exchange(b"a\n", read_line(), timeout=1) == b"A"
    with pytest.raises(CommunicationTimeoutError):
        await link.exchange(b"b\n", read_line(), timeout=0.02)
    assert await link.exchange(b"c\n", read_line(), timeout=1) == b"\xbc"
    assert await link.exchange(b"d\n", read_line(), timeout=1) == b"D"
    with pytest.raises(BoardDisconnectionError, match="injected fault"):
        await link.exchange(b"e\n", read_line(), timeout=1)
    assert faulty.sends == 5


async def test_a_scheduled_silence_applies_to_its_send() -> None:
    faulty = FaultyStream(simulated(), schedule={0: Fault.silence()})
    await faulty.send(b"x\n")
    assert faulty.is_silent
    assert Fault.silence().kind is FaultKind.SILENCE


async def test_closing_a_faulty_stream_closes_the_inner_and_wakes_a_receive() -> None:
    a, _ = memory_stream_pair()
    faulty = FaultyStream(a)

    async def close_soon() -> None:
        await anyio.sleep(0.01)
        faulty.close_now()

    with anyio.fail_after(1):
        async with anyio.create_task_group() as tg:
            tg.start_soon(close_soon)
            with pytest.raises(BoardDisconnectionError, match="closed"):
                await faulty.receive()
    assert faulty.is_closed
    other = FaultyStream(simulated())
    await other.aclose()
    assert other.is_closed
    with pytest.raises(ValueError, match="max_bytes"):
        await other.receive(0)


async def test_receive_respects_max_bytes() -> None:
    faulty = FaultyStream(simulated())
    await faulty.send(b"abcdef")
    assert await faulty.receive(4) == b"ABCD"
    assert await faulty.receive(4) == b"EF"


# -- ScriptedStream ------------------------------------------------------------------------


async def test_scripted_stream_plays_its_script() -> None:
    stream = ScriptedStream(
        [(b"v", b"SRduino:2\n"), (b"ah", b""), (b"rb", b"h")],
        banner=b"# hello\n",
        name="ruggeduino",
    )
    link = SerialLink(stream)
    assert await link.read_line(timeout=1) == b"# hello"
    assert await link.exchange(b"v", read_line(), timeout=1) == b"SRduino:2"
    await link.send(b"a")  # a request may arrive in pieces
    await link.send(b"h")
    assert stream.used == 2 and stream.remaining == [(b"rb", b"h")]
    await link.send(b"rb")
    assert await link.read(read_line(b"h", keep_ends=True), timeout=1) == b"h"
    stream.assert_all_used()
    assert stream.name == "ruggeduino"


async def test_a_wrong_request_fails_with_a_diff() -> None:
    stream = ScriptedStream([(b"W 13 H\n", b"+ OK\n")])
    with pytest.raises(AssertionError) as caught:
        await stream.send(b"W 13 L\n")
    message = str(caught.value)
    assert "request 0 does not match the script" in message
    assert "expected: b'W 13 H\\n'" in message
    assert "got:      b'W 13 L\\n'" in message
    assert "first difference at byte 5: expected b'H', got b'L'" in message
    with pytest.raises(AssertionError, match="does not match"):
        stream.assert_all_used()  # remembered even if the first error was swallowed


async def test_a_request_longer_than_expected_is_a_mismatch() -> None:
    stream = ScriptedStream([(b"ab", b"")])
    with pytest.raises(AssertionError, match="unexpected request b'c'"):
        await stream.send(b"abc")


async def test_a_request_after_the_script_has_ended_fails() -> None:
    stream = ScriptedStream([])
    with pytest.raises(AssertionError, match=r"all 0 step\(s\) of the script have been played"):
        await stream.send(b"x")


async def test_assert_all_used_reports_unused_steps_and_partial_requests() -> None:
    stream = ScriptedStream([(b"first\n", b""), (b"second\n", b"")])
    with pytest.raises(AssertionError, match=r"2 step\(s\) .* never requested"):
        stream.assert_all_used()
    await stream.send(b"fir")
    with pytest.raises(AssertionError, match="partial request b'fir'"):
        stream.assert_all_used()


async def test_a_short_request_mismatch_points_past_the_end() -> None:
    stream = ScriptedStream([(b"abc", b"")])
    await stream.send(b"ab")
    with pytest.raises(
        AssertionError, match=r"first difference at byte 2: expected b'c', got b'x'"
    ):
        await stream.send(b"x")


async def test_closing_a_scripted_stream() -> None:
    stream = ScriptedStream([(b"x", b"y")])
    async with stream:
        pass
    assert stream.is_closed
    stream.close_now()
    with pytest.raises(BoardDisconnectionError, match="closed"):
        await stream.send(b"x")
    with pytest.raises(BoardDisconnectionError, match="closed"):
        await stream.receive()



async def test_a_held_reply_is_overtaken_by_later_replies() -> None:
    host, board = memory_stream_pair()
    faulty = FaultyStream(host)
    faulty.hold_next_reply(0.05)
    await board.send(b"first\n")
    await board.send(b"second\n")
    with anyio.fail_after(2):
        assert await faulty.receive() == b"second\n"  # at once, ahead of the held one
        assert await faulty.receive() == b"first\n"  # once its time has come
    with pytest.raises(ValueError, match="negative"):
        Fault.hold(-1)


async def test_a_wrapping_stream_passes_everything_on() -> None:
    host, board = memory_stream_pair()
    wrapped = WrappingStream(host)
    assert wrapped.inner is host
    assert wrapped.name == host.name
    await wrapped.send(b"ping\n")
    assert await board.receive() == b"ping\n"
    await board.send(b"pong\n")
    assert await wrapped.receive() == b"pong\n"
    assert not wrapped.is_closed
    await wrapped.aclose()
    assert wrapped.is_closed and host.is_closed
