"""Tests of USBLink with a device that answers at once: no worker thread until a poll."""

from __future__ import annotations

import array
import errno
import struct
import threading
from collections.abc import Callable
from typing import Any

import anyio
import pytest
import usb.core

from j5aio.backends.hardware.transports import (
    USBDisconnectionError,
    USBLink,
    USBTransferTimeoutError,
)
from j5aio.backends.hardware.transports.usb_link import ANSWERS_AT_ONCE, answers_at_once
from j5aio.errors import USBCommunicationError


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


async def test_the_first_poll_starts_the_thread_which_then_runs_every_transfer() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    try:
        await link.control_write(2, 1)
        assert not link.thread.is_alive()
        device.value = 5
        reply = await link.poll_control_read(8, 4, lambda r: r != bytes(4), interval=0.001)
        assert reply == struct.pack("<I", 5)
        assert link.thread.is_alive()
        await link.control_write(2, 0)
        assert [thread for _, _, thread in device.calls] == [
            threading.get_ident(),
            link.thread.ident,
            link.thread.ident,
        ]
    finally:
        link.close_now()
    assert not link.thread.is_alive()


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


async def test_control_write_now_takes_the_thread_once_a_poll_started_it() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    device.value = 1
    await link.poll_control_read(8, 4, lambda r: r != bytes(4), interval=0.001)
    await anyio.to_thread.run_sync(lambda: link.control_write_now(2, 1, timeout=5))
    assert device.calls[-1] == (0x00, 2, link.thread.ident)
    await link.aclose()
    assert not link.thread.is_alive()


def test_a_link_closed_before_any_transfer_ends_at_once() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    assert device.doorbells
    link.close_now()
    link.close_now()
    assert not device.doorbells
    assert repr(link) == "<USBLink 'Power Board SRABC1' closed>"


async def test_a_transfer_asked_for_as_a_poll_starts_the_thread_takes_the_thread() -> None:
    device = AtOnceDevice()
    link = USBLink(device, board_name="Power Board SRABC1")
    device.value = 1

    async def poll() -> None:
        await link.poll_control_read(8, 4, lambda r: r != bytes(4), interval=0.001)

    async with anyio.create_task_group() as group:
        group.start_soon(link.control_write, 2, 1)  # (its checkpoint lets the poll start)
        group.start_soon(poll)
    assert link.thread.is_alive()
    assert {thread for _, _, thread in device.calls} == {link.thread.ident}
    assert sorted(index for _, index, _ in device.calls) == [2, 8]
    await link.aclose()
