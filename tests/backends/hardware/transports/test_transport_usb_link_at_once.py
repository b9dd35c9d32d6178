"""Tests of USBLink with a device that answers at once: no worker thread at all."""

from __future__ import annotations

import array
import errno
import struct
import threading
from collections.abc import Callable
from typing import Any

import anyio
import anyio.to_thread
import pytest
import usb.core

from j5aio.backends.hardware.transports import (
    USBDisconnectionError,
    USBLink,
    USBTransferTimeoutError,
)
from j5aio.backends.hardware.transports.usb_link import ANSWERS_AT_ONCE, answers_at_once
from j5aio.errors import UnexpectedReplyError, USBCommunicationError


class AtOnceDevice:
    """A device that says it answers at once, as a simulator does; records its threads."""

    idVendor = 0x1BDA  # noqa: N815
    idProduct = 0x0010  # noqa: N815
    answers_at_once = True
    serial_number = "SRABC1"

    def __init__(self) -> None:
        self.calls: list[tuple[int, int, int]] = []  # (request type, wIndex, thread)
        self.errors: dict[int, BaseException] = {}
        self.value = 0  # what reads of wIndex 8 answer
        self.gate: threading.Event | None = None
        self.entered = threading.Event()
        self.doorbells: list[Callable[[], None]] = []
        #: Called during each read of wIndex 8, after the value was read (a change then).
        self.during_read: Callable[[], None] | None = None

    def add_doorbell(self, ring: Callable[[], None]) -> Callable[[], None]:
        self.doorbells.append(ring)
        return lambda: self.doorbells.remove(ring)

    def ctrl_transfer(
        self,
        bmRequestType: int,  # noqa: N803
        bRequest: int,  # noqa: N803
        wValue: int = 0,  # noqa: N803
        wIndex: int = 0,  # noqa: N803
        data_or_wLength: Any = None,  # noqa: N803
        timeout: int | None = None,
    ) -> Any:
        self.calls.append((bmRequestType, wIndex, threading.get_ident()))
        self.entered.set()
        if self.gate is not None:
            self.gate.wait(5)
        if wIndex in self.errors:
            raise self.errors[wIndex]
        if bmRequestType & 0x80:
            value = self.value if wIndex == 8 else wIndex
            if wIndex == 8 and self.during_read is not None:
                self.during_read()
            return array.array("B", struct.pack("<I", value)[:data_or_wLength])
        return len(data_or_wLength)


def _threads(device: AtOnceDevice) -> set[int]:
    return {thread for _, _, thread in device.calls}


def test_answers_at_once_is_said_only_by_a_true_attribute() -> None:
    assert answers_at_once(AtOnceDevice())
    assert not answers_at_once(object())
    thing = type("Thing", (), {ANSWERS_AT_ONCE: "yes"})()
    assert not answers_at_once(thing)  # only True itself


async def test_transfers_run_in_the_loop_and_no_thread_starts() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1", timeout_ms=250)
    try:
        assert await link.control_read(9, 4) == struct.pack("<I", 9)
        await link.control_write(2, 1)
        assert await link.read_serial_number() == "SRABC1"
        assert await link.call(lambda: 6 * 7, description="arithmetic") == 42
        assert [(kind, index) for kind, index, _ in device.calls] == [(0x80, 9), (0x00, 2)]
        assert _threads(device) == {threading.get_ident()}
        assert not link.thread.is_alive()
    finally:
        link.close_now()
    assert link.is_closed
    assert not link.thread.is_alive()
    assert not device.doorbells  # the link stopped listening when it closed


async def test_many_tasks_transfer_in_the_order_they_asked() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    async with anyio.create_task_group() as group:
        for index in range(20):
            group.start_soon(link.control_write, index, 1)
    assert [index for _, index, _ in device.calls] == list(range(20))
    await link.aclose()
    await link.aclose()  # idempotent
    assert not link.thread.is_alive()


async def test_a_caller_cancelled_before_its_turn_sends_nothing() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    with anyio.CancelScope() as scope:
        scope.cancel()
        await link.control_write(2, 1)
    assert device.calls == []
    link.close_now()


async def test_errors_are_translated_and_then_runs_on_success_only() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    device.errors[3] = usb.core.USBError("No such device", -4, errno.ENODEV)
    seen: list[int] = []
    with pytest.raises(USBDisconnectionError, match="disconnected"):
        await link.control_write(3, 1, then=lambda: seen.append(3))
    await link.control_write(4, 1, then=lambda: seen.append(4))
    assert seen == [4]

    def failing_then() -> None:
        raise KeyError("cache")

    with pytest.raises(KeyError, match="cache"):
        await link.control_write(5, 1, then=failing_then)
    await link.aclose()
    with pytest.raises(USBDisconnectionError, match="closed"):
        await link.control_read(9, 4)


def test_control_write_now_runs_in_its_callers_thread() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    link.control_write_now(2, 1, timeout=1)
    assert device.calls == [(0x00, 2, threading.get_ident())]
    device.errors[2] = usb.core.USBError("Pipe error", -9, errno.EPIPE)
    with pytest.raises(USBCommunicationError, match="Pipe error"):
        link.control_write_now(2, 1, timeout=1)
    link.close_now()
    with pytest.raises(USBDisconnectionError, match="closed"):
        link.control_write_now(2, 0, timeout=1)
    assert not link.thread.is_alive()


async def test_control_write_now_waits_for_a_transfer_running_in_the_loop() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    device.gate = gate = threading.Event()
    outcomes: list[str] = []

    def safe_state(timeout: float) -> None:
        try:
            link.control_write_now(7, 0, timeout=timeout)
            outcomes.append("written")
        except USBTransferTimeoutError:
            outcomes.append("timed out")

    def from_another_thread() -> None:
        assert device.entered.wait(5)  # the loop's transfer holds the link
        safe_state(0.01)  # too short: it gives up, and sends nothing
        threading.Timer(0.05, gate.set).start()
        safe_state(5)  # waits for the loop's transfer, then writes

    other = threading.Thread(target=from_another_thread)
    other.start()
    await link.control_write(2, 1)  # holds the loop (and the link) until the gate opens
    other.join(10)
    assert outcomes == ["timed out", "written"]
    assert [index for _, index, _ in device.calls] == [2, 7]
    link.close_now()


def test_a_link_closed_before_any_transfer_ends_at_once() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    assert device.doorbells
    link.close_now()
    link.close_now()
    assert not device.doorbells
    assert repr(link) == "<USBLink 'Power Board SRABC1' closed>"


class QuietDevice(AtOnceDevice):
    """A device that answers at once but has no doorbell: polls read every interval."""

    add_doorbell = None  # type: ignore[assignment]


def _reads(device: AtOnceDevice) -> int:
    return sum(1 for kind, index, _ in device.calls if kind & 0x80 and index == 8)


def _changed(reply: bytes) -> bool:
    return reply != bytes(4)


async def test_a_poll_reads_in_the_loop_every_interval_without_a_doorbell() -> None:
    device = QuietDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    assert not link.rung

    def found(reply: bytes) -> bool:
        return _reads(device) == 3

    with anyio.fail_after(10):
        assert await link.poll_control_read(8, 4, found, interval=0.001) == bytes(4)
    assert _reads(device) == 3
    assert _threads(device) == {threading.get_ident()}
    assert not link.thread.is_alive()
    assert not link._polls_here
    link.close_now()


async def test_a_ring_from_another_thread_reads_at_once() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    assert link.rung

    def press() -> None:
        assert device.entered.wait(5)
        device.value = 7
        for ring in list(device.doorbells):
            ring()

    presser = threading.Thread(target=press)
    presser.start()
    # A second between reads (fifty, as the device rings): only the ring can end this.
    with anyio.fail_after(10):
        reply = await link.poll_control_read(8, 4, _changed, interval=1)
    presser.join()
    assert reply == struct.pack("<I", 7)
    assert _reads(device) == 2  # the first read, and the one the ring asked for
    link.close_now()


async def test_a_ring_during_a_read_is_not_lost() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")

    def change_after_the_read() -> None:
        device.during_read = None
        device.value = 3  # after this read took its value
        for ring in list(device.doorbells):
            ring()

    device.during_read = change_after_the_read
    with anyio.fail_after(10):
        reply = await link.poll_control_read(8, 4, _changed, interval=1)
    assert reply == struct.pack("<I", 3)
    assert _reads(device) == 2
    link.close_now()


async def test_a_cancelled_poll_stops_reading_and_leaves_nothing_behind() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    with anyio.move_on_after(0.05):
        await link.poll_control_read(8, 4, _changed, interval=0.001)
    reads = _reads(device)
    assert reads >= 1
    assert not link._polls_here
    await anyio.sleep(0.02)
    assert _reads(device) == reads
    link.close_now()


async def test_closing_the_link_ends_a_poll() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")

    async def close_soon() -> None:
        await anyio.sleep(0.01)
        link.close_now()

    with anyio.fail_after(10):
        async with anyio.create_task_group() as group:
            group.start_soon(close_soon)
            with pytest.raises(USBDisconnectionError, match="closed while polling"):
                await link.poll_control_read(8, 4, _changed, interval=1)


async def test_poll_failures_reach_the_poller_as_on_the_thread() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    with pytest.raises(ValueError, match="interval"):
        await link.poll_until(lambda: 1, bool, interval=0, description="nothing")
    with pytest.raises(UnexpectedReplyError, match="returned 4 bytes"):
        await link.poll_control_read(9, 8, _changed, interval=0.001)  # 4 bytes, not 8

    def broken_check(_: int) -> bool:
        raise ArithmeticError("bad check")

    with pytest.raises(USBCommunicationError, match="counting failed: bad check"):
        await link.poll_until(lambda: 1, broken_check, interval=0.001, description="counting")

    def short_check(_: int) -> bool:
        raise UnexpectedReplyError("too short")

    with pytest.raises(UnexpectedReplyError, match="too short"):
        await link.poll_until(lambda: 1, short_check, interval=0.001, description="counting")
    device.errors[8] = usb.core.USBError("Pipe error", -9, errno.EPIPE)
    with pytest.raises(USBCommunicationError, match="Pipe error"):
        await link.poll_control_read(8, 4, _changed, interval=0.001)
    link.close_now()


async def test_then_takes_what_a_poll_found() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    taken: list[object] = []
    count = iter(range(100))
    assert (
        await link.poll_until(
            lambda: next(count),
            lambda n: n == 2,
            interval=0.001,
            description="counting",
            then=taken.append,
        )
        == 2
    )
    device.value = 1
    reply = await link.poll_control_read(8, 4, _changed, interval=0.001, then=taken.append)
    assert taken == [2, reply]
    link.close_now()


async def test_control_write_now_runs_beside_a_waiting_poll() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    with anyio.fail_after(10):
        async with anyio.create_task_group() as group:

            async def poll() -> None:
                await link.poll_control_read(8, 4, _changed, interval=1)

            group.start_soon(poll)
            await anyio.sleep(0.01)
            await anyio.to_thread.run_sync(lambda: link.control_write_now(2, 1, timeout=5))
            group.cancel_scope.cancel()
    writes = [thread for kind, index, thread in device.calls if index == 2]
    assert writes and writes[0] != threading.get_ident()  # in the caller's own thread
    assert not link.thread.is_alive()
    link.close_now()
