"""Tests of USBLink: ordered transfers on one worker thread, cancellation, error mapping."""

from __future__ import annotations

import array
import asyncio
import errno
import functools
import random
import struct
import threading
import time
from collections.abc import AsyncIterator, Callable
from typing import Any

import anyio
import pytest
import usb.core

from j5aio.backends.hardware.transports import (
    USBDisconnectionError,
    USBLink,
    USBTransferTimeoutError,
)
from j5aio.backends.hardware.transports.usb_link import MAX_POLL_INTERVAL, RUNG_INTERVAL_FACTOR
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationError,
    CommunicationTimeoutError,
    UnexpectedReplyError,
    USBCommunicationError,
)


class StandInDevice:
    """A pyusb-shaped device: reads return the wIndex as a little-endian uint32."""

    idVendor = 0x1BDA  # noqa: N815
    idProduct = 0x0010  # noqa: N815

    def __init__(self) -> None:
        self.calls: list[tuple[int, int, int, int, Any, int | None]] = []
        self.threads: set[int] = set()
        self.errors: dict[int, BaseException] = {}
        self.gate: threading.Event | None = None
        self.started = threading.Event()
        self.delay = 0.0
        self.short_write = False
        self.serial = "SRABC1"

    @property
    def serial_number(self) -> str:
        self.threads.add(threading.get_ident())
        return self.serial

    def ctrl_transfer(
        self,
        bmRequestType: int,  # noqa: N803
        bRequest: int,  # noqa: N803
        wValue: int = 0,  # noqa: N803
        wIndex: int = 0,  # noqa: N803
        data_or_wLength: Any = None,  # noqa: N803
        timeout: int | None = None,
    ) -> Any:
        self.threads.add(threading.get_ident())
        self.calls.append((bmRequestType, bRequest, wValue, wIndex, data_or_wLength, timeout))
        self.started.set()
        if self.gate is not None:
            self.gate.wait(5)
        if self.delay:
            time.sleep(self.delay)
        if wIndex in self.errors:
            raise self.errors[wIndex]
        if bmRequestType & 0x80:
            return array.array("B", struct.pack("<I", wIndex)[:data_or_wLength])
        return len(data_or_wLength) - (1 if self.short_write else 0)


@pytest.fixture
def device() -> StandInDevice:
    return StandInDevice()


@pytest.fixture
async def link(device: StandInDevice) -> AsyncIterator[USBLink]:
    usb_link = USBLink(device, board_name="Power Board SRABC1", timeout_ms=250)
    yield usb_link
    if device.gate is not None:
        device.gate.set()
    usb_link.close_now()


async def test_control_read_and_write_use_request_64(device: StandInDevice, link: USBLink) -> None:
    assert await link.control_read(9, 4) == struct.pack("<I", 9)
    await link.control_write(8, 0, struct.pack("<HH", 440, 500))
    await link.control_write(2, 1)
    assert device.calls == [
        (0x80, 64, 0, 9, 4, 250),
        (0x00, 64, 0, 8, struct.pack("<HH", 440, 500), 250),
        (0x00, 64, 1, 2, b"", 250),
    ]
    assert link.board_name == "Power Board SRABC1"
    assert link.device is device
    assert repr(link) == "<USBLink 'Power Board SRABC1' open>"


async def test_transfers_run_in_order_on_one_thread(device: StandInDevice, link: USBLink) -> None:
    async with anyio.create_task_group() as tg:
        for index in range(50):
            tg.start_soon(link.control_write, index, 1)
    assert [call[3] for call in device.calls] == list(range(50))
    assert device.threads == {link.thread.ident}
    assert link.thread.ident != threading.get_ident()


async def test_read_serial_number_on_the_worker_thread(
    device: StandInDevice, link: USBLink
) -> None:
    assert await link.read_serial_number() == "SRABC1"
    assert device.threads == {link.thread.ident}


async def test_call_runs_any_work_in_order(link: USBLink) -> None:
    assert await link.call(lambda: 6 * 7, description="arithmetic") == 42


# -- errors --------------------------------------------------------------------------------


async def test_enodev_is_a_usb_and_a_board_disconnection_error(
    device: StandInDevice, link: USBLink
) -> None:
    pyusb_error = usb.core.USBError("No such device", errno=errno.ENODEV)
    device.errors[7] = pyusb_error
    with pytest.raises(USBDisconnectionError) as caught:
        await link.control_read(7, 8)
    error = caught.value
    assert isinstance(error, BoardDisconnectionError)
    assert isinstance(error, USBCommunicationError)
    assert error.usb_error is pyusb_error and error.errno == errno.ENODEV
    assert error.__cause__ is pyusb_error
    assert "Power Board SRABC1 has been disconnected" in str(error)
    assert "wIndex 7" in str(error)


async def test_a_pyusb_timeout_is_a_communication_timeout(
    device: StandInDevice, link: USBLink
) -> None:
    device.errors[8] = usb.core.USBTimeoutError("Operation timed out", errno=errno.ETIMEDOUT)
    with pytest.raises(USBTransferTimeoutError, match="did not answer in time") as caught:
        await link.control_read(8, 4)
    assert isinstance(caught.value, CommunicationTimeoutError)


async def test_a_caller_names_what_an_errno_means(device: StandInDevice, link: USBLink) -> None:
    device.errors[8] = usb.core.USBError("Pipe error", errno=errno.EPIPE)
    with pytest.raises(USBCommunicationError) as caught:
        await link.control_write(
            8, 0, b"\x00" * 4, errors={errno.EPIPE: "the piezo queue is full: buzzing too fast"}
        )
    assert str(caught.value) == "Power Board SRABC1: the piezo queue is full: buzzing too fast"
    assert caught.value.errno == errno.EPIPE
    with pytest.raises(USBCommunicationError, match=r"writing wIndex 8 .* failed: Pipe error"):
        await link.control_write(8, 0, b"\x00" * 4)


@pytest.mark.parametrize(
    ("code", "kind"),
    [(errno.ENODEV, USBDisconnectionError), (errno.ETIMEDOUT, USBTransferTimeoutError)],
)
async def test_a_named_errno_keeps_its_error_class(
    device: StandInDevice, link: USBLink, code: int, kind: type[USBCommunicationError]
) -> None:
    device.errors[1] = usb.core.USBError("oops", errno=code)
    with pytest.raises(kind, match="Power Board SRABC1: custom words"):
        await link.control_read(1, 4, errors={code: "custom words"})


async def test_other_exceptions_from_pyusb_are_wrapped(
    device: StandInDevice, link: USBLink
) -> None:
    device.errors[3] = ValueError("The device has no langid")
    with pytest.raises(USBCommunicationError, match="no langid") as caught:
        await link.control_read(3, 4)
    assert isinstance(caught.value.usb_error, ValueError)
    assert caught.value.errno is None
    device.errors[4] = RuntimeError()
    with pytest.raises(USBCommunicationError, match="failed: RuntimeError"):
        await link.control_read(4, 4)


async def test_short_transfers_are_reported(device: StandInDevice, link: USBLink) -> None:
    with pytest.raises(UnexpectedReplyError, match="returned 4 bytes"):
        await link.control_read(1, 8)
    assert await link.control_read(1, 8, exact=False) == struct.pack("<I", 1)
    device.short_write = True
    with pytest.raises(USBCommunicationError, match="wrote only 3 bytes"):
        await link.control_write(8, 0, b"\x01\x02\x03\x04")


async def test_the_link_validates_its_timeout(device: StandInDevice) -> None:
    with pytest.raises(ValueError, match="timeout_ms"):
        USBLink(device, board_name="x", timeout_ms=0)


# -- cancellation --------------------------------------------------------------------------


async def test_a_caller_cancelled_mid_transfer_is_released_and_the_transfer_completes(
    device: StandInDevice, link: USBLink
) -> None:
    device.gate = threading.Event()
    start = time.monotonic()
    with anyio.move_on_after(0.05) as scope:
        await link.control_write(2, 1)
    assert scope.cancelled_caught
    assert time.monotonic() - start < 0.5  # released while the transfer was still blocked
    device.gate.set()
    assert await link.control_read(9, 4) == struct.pack("<I", 9)
    assert [call[3] for call in device.calls] == [2, 9]


async def test_a_caller_cancelled_while_queued_withdraws_its_transfer(
    device: StandInDevice, link: USBLink
) -> None:
    device.gate = threading.Event()
    async with anyio.create_task_group() as tg:
        tg.start_soon(link.control_write, 1, 1)
        await anyio.to_thread.run_sync(device.started.wait, 1)
        with anyio.move_on_after(0.02):
            await link.control_write(2, 1)  # queued behind the blocked transfer
        device.gate.set()
    await link.control_write(3, 1)
    assert [call[3] for call in device.calls] == [1, 3]


async def test_random_cancellations_never_deliver_a_result_to_the_wrong_caller(
    device: StandInDevice, link: USBLink
) -> None:
    rng = random.Random(99)
    device.delay = 0.0002
    wrong = delivered = cancelled = 0

    async def reader(worker: int) -> None:
        nonlocal wrong, delivered, cancelled
        for n in range(150):
            index = worker * 1000 + n
            with anyio.move_on_after(rng.uniform(0, 0.002)) as scope:
                reply = await link.control_read(index, 4)
                delivered += 1
                wrong += reply != struct.pack("<I", index)
            cancelled += scope.cancelled_caught

    async with anyio.create_task_group() as tg:
        for worker in range(4):
            tg.start_soon(reader, worker)
    assert wrong == 0
    assert delivered >= 20 and cancelled >= 100
    ran = [call[3] for call in device.calls]
    for worker in range(4):  # each caller's transfers ran in its own order
        mine = [i for i in ran if i // 1000 == worker]
        assert mine == sorted(mine)


# -- closing -------------------------------------------------------------------------------


async def test_close_now_stops_the_thread_after_queued_transfers(device: StandInDevice) -> None:
    link = USBLink(device, board_name="servo board")
    assert link.thread.is_alive()
    device.gate = threading.Event()
    async with anyio.create_task_group() as tg:
        tg.start_soon(link.control_write, 0, 1)
        tg.start_soon(link.control_write, 1, 1)
        await anyio.sleep(0.01)
        threading.Timer(0.02, device.gate.set).start()
        link.close_now()
    assert not link.thread.is_alive()
    assert [call[3] for call in device.calls] == [0, 1]
    assert link.is_closed
    with pytest.raises(USBDisconnectionError, match="servo board: the USB link is closed"):
        await link.control_read(0, 4)
    link.close_now()
    await link.aclose()  # both idempotent


async def test_aclose_stops_the_thread(device: StandInDevice) -> None:
    async with USBLink(device, board_name="power board") as link:
        await link.control_write(0, 1)
    assert not link.thread.is_alive()
    assert "closed" in repr(link)
    with pytest.raises(CommunicationError):
        await link.control_write(0, 0)


def test_close_now_works_without_an_event_loop(device: StandInDevice) -> None:
    link = USBLink(device, board_name="power board")
    link.close_now()
    assert not link.thread.is_alive()


async def test_a_real_pyusb_device_is_released_when_the_thread_stops(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    released: list[object] = []
    monkeypatch.setattr(usb.util, "dispose_resources", released.append)

    class RealLookingDevice(usb.core.Device):  # type: ignore[misc]
        def __init__(self) -> None:  # no libusb behind it
            pass

        def __del__(self) -> None:
            pass

    fake = RealLookingDevice()
    link = USBLink(fake, board_name="real")
    await link.aclose()
    assert released == [fake]


async def test_the_worker_survives_any_exception(link: USBLink) -> None:
    def exit_thread() -> None:
        raise SystemExit("not in this thread")

    with pytest.raises(USBCommunicationError, match="not in this thread"):
        await link.call(exit_thread, description="misbehaving")
    assert link.thread.is_alive()
    assert await link.control_read(5, 4) == struct.pack("<I", 5)


# -- writing synchronously (the safety net) ------------------------------------------------


def test_control_write_now_runs_on_the_worker_thread_in_order(device: StandInDevice) -> None:
    link = USBLink(device, board_name="Power Board SRABC1", timeout_ms=250)
    try:
        link.control_write_now(3, 0, timeout=1)
        assert device.calls == [(0x00, 64, 0, 3, b"", 250)]
        assert threading.get_ident() not in device.threads
        device.errors[4] = usb.core.USBError("gone", errno=errno.ENODEV)
        with pytest.raises(USBDisconnectionError, match="disconnected"):
            link.control_write_now(4, 0, timeout=1)
        device.gate = threading.Event()
        with pytest.raises(USBTransferTimeoutError, match=r"did not finish within 0\.05 s"):
            link.control_write_now(5, 0, timeout=0.05)
        device.gate.set()
    finally:
        link.close_now()
    with pytest.raises(USBDisconnectionError, match="closed"):
        link.control_write_now(3, 0, timeout=1)


# -- polling on the worker thread ---------------------------------------------------------


def _reads_of(device: StandInDevice, index: int) -> int:
    return sum(1 for call in device.calls if call[3] == index)


async def test_poll_control_read_reads_until_found(device: StandInDevice, link: USBLink) -> None:
    seen: list[bytes] = []

    def found(reply: bytes) -> bool:
        seen.append(reply)
        return len(seen) == 3

    reply = await link.poll_control_read(8, 4, found, interval=0.001)
    assert reply == struct.pack("<I", 8)
    assert len(seen) == 3
    assert device.threads == {link.thread.ident}  # every read on the worker thread
    assert device.calls[0] == (0x80, 64, 0, 8, 4, 250)
    await anyio.sleep(0.01)
    assert _reads_of(device, 8) == 3  # found: the reads stopped


async def test_polls_take_turns_with_other_transfers(device: StandInDevice, link: USBLink) -> None:
    async with anyio.create_task_group() as group:
        polled = anyio.Event()

        async def poll() -> None:
            await link.poll_control_read(8, 4, lambda _reply: _reads_of(device, 9) >= 3,
                                         interval=0.001)
            polled.set()

        group.start_soon(poll)
        for _ in range(3):
            assert await link.control_read(9, 4) == struct.pack("<I", 9)
        with anyio.fail_after(30):
            await polled.wait()


async def test_a_cancelled_poll_stops_reading(device: StandInDevice, link: USBLink) -> None:
    with anyio.move_on_after(0.02):
        await link.poll_control_read(8, 4, lambda _reply: False, interval=0.001)
    await link.control_read(9, 4)  # the thread has moved on past any read in flight
    await anyio.sleep(0.01)
    await link.control_read(9, 4)
    reads = _reads_of(device, 8)
    assert reads >= 1
    await anyio.sleep(0.02)
    assert _reads_of(device, 8) == reads


async def test_then_takes_a_found_reply_even_for_a_cancelled_caller(
    device: StandInDevice, link: USBLink
) -> None:
    taken: list[bytes] = []
    device.gate = threading.Event()
    with anyio.CancelScope() as scope:
        async with anyio.create_task_group() as group:
            group.start_soon(
                lambda: link.poll_control_read(8, 4, lambda _reply: True, interval=0.001,
                                               then=taken.append)
            )
            await anyio.to_thread.run_sync(device.started.wait, 5)
            scope.cancel()
    device.gate.set()
    # The found read finished before this one, and its callback was posted to the loop
    # before this read's answer: it has run.
    await link.control_read(9, 4)
    assert taken == [struct.pack("<I", 8)]


async def test_a_failed_poll_read_raises_as_a_transfer_does(
    device: StandInDevice, link: USBLink
) -> None:
    device.errors[8] = usb.core.USBError("No such device", -4, errno.ENODEV)
    with pytest.raises(USBDisconnectionError, match="polling 4 bytes from wIndex 8"):
        await link.poll_control_read(8, 4, lambda _reply: False, interval=0.001)


async def test_a_short_poll_reply_is_an_unexpected_reply(link: USBLink) -> None:
    with pytest.raises(UnexpectedReplyError, match="returned 4 bytes"):
        await link.poll_control_read(8, 5, lambda _reply: False, interval=0.001)


async def test_the_poll_interval_is_checked(link: USBLink) -> None:
    for bad in (0, -1.0, float("nan"), float("inf"), MAX_POLL_INTERVAL * 2):
        with pytest.raises(ValueError, match="positive number of seconds"):
            await link.poll_until(lambda: 1, bool, interval=bad, description="x")


async def test_closing_the_link_ends_a_poll(device: StandInDevice, link: USBLink) -> None:
    async def close_soon() -> None:
        await anyio.to_thread.run_sync(device.started.wait, 5)
        link.close_now()

    async with anyio.create_task_group() as group:
        group.start_soon(close_soon)
        with pytest.raises(USBDisconnectionError, match="closed while polling"):
            await link.poll_control_read(8, 4, lambda _reply: False, interval=0.001)
    with pytest.raises(USBDisconnectionError, match="link is closed"):
        await link.poll_control_read(8, 4, lambda _reply: False, interval=0.001)


async def test_a_failing_then_reaches_the_poller(link: USBLink) -> None:
    def then(_reply: bytes) -> None:
        raise RuntimeError("the cache could not be updated")

    with pytest.raises(RuntimeError, match="cache"):
        await link.poll_control_read(8, 4, lambda _reply: True, interval=0.001, then=then)


@pytest.mark.parametrize("with_then", [False, True])
async def test_idle_polls_do_not_wake_the_event_loop(
    device: StandInDevice, link: USBLink, monkeypatch: pytest.MonkeyPatch, with_then: bool
) -> None:
    # Every hand-off from the worker thread to the loop goes through call_soon_threadsafe:
    # count them while the reads find nothing, then find something.
    loop = asyncio.get_running_loop()
    real = loop.call_soon_threadsafe
    hops: list[int] = []

    def counted(callback: Any, *args: Any, **kwargs: Any) -> Any:
        hops.append(threading.get_ident())
        return real(callback, *args, **kwargs)

    monkeypatch.setattr(loop, "call_soon_threadsafe", counted)
    taken: list[bytes] = []
    replies: list[bytes] = []

    def found(reply: bytes) -> bool:
        replies.append(reply)
        assert hops == []  # nothing has reached the loop while the reads found nothing
        return len(replies) == 40

    reply = await link.poll_control_read(
        8, 4, found, interval=0.001, then=taken.append if with_then else None
    )
    assert reply == struct.pack("<I", 8)
    assert len(replies) == 40
    assert hops == [link.thread.ident]  # one wake-up of the loop, for the found reply
    assert taken == ([reply] if with_then else [])


async def test_transfers_asked_for_during_a_poll_run_without_waiting_for_its_next_read(
    device: StandInDevice, link: USBLink
) -> None:
    # The poll reads once, then not for an hour: each transfer, whether asked for by a
    # task or by another thread, must wake the worker thread itself (a lost wake-up would
    # leave it waiting for the poll's next read, and the test to its liveness bound).
    async with anyio.create_task_group() as group:
        group.start_soon(
            lambda: link.poll_control_read(8, 4, lambda _reply: False, interval=3600)
        )

        async def reads(count: int) -> None:
            for _ in range(count):
                assert await link.control_read(9, 4) == struct.pack("<I", 9)

        def writes(count: int) -> None:
            for _ in range(count):
                link.control_write_now(3, 0, timeout=30)

        with anyio.fail_after(60):
            async with anyio.create_task_group() as askers:
                for _ in range(4):
                    askers.start_soon(reads, 50)
                askers.start_soon(anyio.to_thread.run_sync, writes, 50)
        group.cancel_scope.cancel()
    assert _reads_of(device, 9) == 200
    assert _reads_of(device, 8) == 1
    assert sum(1 for call in device.calls if call[3] == 3) == 50


async def test_two_polls_at_once_take_turns_and_end_on_their_own(
    device: StandInDevice, link: USBLink
) -> None:
    # Two polls of one link (say two buttons): each is read at its own interval, each
    # ends at its own found reply, and one given up leaves the other reading.
    ended: list[int] = []

    async def poll(index: int, reads: int) -> None:
        await link.poll_control_read(
            index, 4, lambda _reply: _reads_of(device, index) >= reads, interval=0.001
        )
        ended.append(index)

    with anyio.fail_after(30):
        async with anyio.create_task_group() as group:
            group.start_soon(poll, 8, 5)
            group.start_soon(poll, 7, 30)
            with anyio.CancelScope() as given_up:
                given_up.cancel()  # a third poll, given up before it was ever read
                await link.poll_control_read(6, 4, lambda _reply: False, interval=0.001)
            async with anyio.create_task_group() as short:
                short.start_soon(poll, 5, 10**9)  # never found: cancelled below
                while _reads_of(device, 5) < 3:  # transfers take turns with the polls
                    assert await link.control_read(9, 4) == struct.pack("<I", 9)
                short.cancel_scope.cancel()
    assert sorted(ended) == [7, 8]
    assert _reads_of(device, 8) == 5
    assert _reads_of(device, 7) == 30
    reads_of_5 = _reads_of(device, 5)
    await link.control_read(9, 4)  # the thread has moved past any read in flight
    await anyio.sleep(0.01)
    assert _reads_of(device, 5) <= reads_of_5 + 1
    await link.control_read(9, 4)
    settled = _reads_of(device, 5)
    await anyio.sleep(0.01)
    assert _reads_of(device, 5) == settled  # given up: read no more


async def test_a_poll_given_up_while_the_thread_waits_is_dropped_at_its_next_read(
    device: StandInDevice, link: USBLink
) -> None:
    # Nothing else is asked of the link: the thread itself notices, when the read falls
    # due, that nobody waits for it any more, and goes back to waiting for jobs.
    with anyio.move_on_after(0.01):
        await link.poll_control_read(8, 4, lambda _reply: False, interval=0.002)
    with anyio.fail_after(30):
        while link._polls:  # noqa: ASYNC110 - the worker thread's state, no event
            await anyio.sleep(0.001)
    reads = _reads_of(device, 8)
    await anyio.sleep(0.02)
    assert _reads_of(device, 8) == reads
    assert await link.control_read(9, 4) == struct.pack("<I", 9)  # the thread still serves


async def test_a_read_failing_after_idle_reads_reaches_the_caller(
    device: StandInDevice, link: USBLink
) -> None:
    def found(_reply: bytes) -> bool:
        if _reads_of(device, 8) == 3:  # the board goes away after three idle reads
            device.errors[8] = usb.core.USBError("No such device", -4, errno.ENODEV)
        return False

    with anyio.fail_after(30), pytest.raises(USBDisconnectionError, match="polling 4 bytes"):
        await link.poll_control_read(8, 4, found, interval=0.001)
    assert _reads_of(device, 8) == 4
    assert not link._polls


class RingingStandIn(StandInDevice):
    """A stand-in with a doorbell, as a board simulator has (see ``RingingDevice``)."""

    def __init__(self) -> None:
        super().__init__()
        self.doorbells: list[Callable[[], None]] = []
        self.value = 0  # what reads of wIndex 8 answer

    def add_doorbell(self, ring: Callable[[], None]) -> Callable[[], None]:
        self.doorbells.append(ring)
        return lambda: self.doorbells.remove(ring)

    def change(self, value: int) -> None:
        """Change what a poll reads, and ring, as a simulator's button does."""
        self.value = value
        for ring in self.doorbells:
            ring()

    def ctrl_transfer(self, *args: Any, **kwargs: Any) -> Any:
        value = self.value  # the board is read as the transfer starts
        reply = super().ctrl_transfer(*args, **kwargs)
        if args[0] & 0x80 and args[3] == 8:
            return array.array("B", struct.pack("<I", value))
        return reply


def _found_value(reply: bytes) -> bool:
    return reply != bytes(4)


def test_a_pyusb_device_has_no_doorbell(device: StandInDevice) -> None:
    usb_link = USBLink(device, board_name="Power Board SRABC1")
    try:
        assert not usb_link.rung
        assert usb_link._interval_factor == 1  # a real board is read every interval
    finally:
        usb_link.close_now()


async def test_a_ring_reads_at_once_and_the_reads_in_between_are_rare() -> None:
    device = RingingStandIn()
    usb_link = USBLink(device, board_name="Power Board SRABC1")
    assert usb_link.rung
    assert usb_link._interval_factor == RUNG_INTERVAL_FACTOR
    reads: list[int] = []

    def found(reply: bytes) -> bool:
        reads.append(int.from_bytes(reply, "little"))
        return _found_value(reply)

    async def press_after_the_first_read() -> None:
        while not reads:  # noqa: ASYNC110 - the worker thread's state, no event
            await anyio.sleep(0.001)
        device.change(1)  # from the event loop's thread
        await anyio.sleep(0.001)

    # An hour between reads (50 hours, rung): only the doorbell can end this wait.
    with anyio.fail_after(30):
        async with anyio.create_task_group() as group:
            group.start_soon(press_after_the_first_read)
            reply = await usb_link.poll_control_read(8, 4, found, interval=3600)
    assert reply == struct.pack("<I", 1)
    assert reads == [0, 1]  # the first read, then the one the ring asked for
    await usb_link.aclose()
    assert device.doorbells == []  # a closed link is rung no more


async def test_a_ring_from_another_thread_during_a_read_is_not_lost() -> None:
    # The button is pressed while the poll's read runs (after the board was read): the
    # ring is kept, and the read after it sees the press.
    device = RingingStandIn()
    usb_link = USBLink(device, board_name="Power Board SRABC1")
    device.gate = threading.Event()

    def press_mid_read() -> None:
        device.started.wait(5)
        device.change(1)
        device.gate.set()  # type: ignore[union-attr]

    presser = threading.Thread(target=press_mid_read)
    presser.start()
    with anyio.fail_after(30):
        reply = await usb_link.poll_control_read(8, 4, _found_value, interval=3600)
    presser.join()
    assert reply == struct.pack("<I", 1)
    assert _reads_of(device, 8) == 2
    await usb_link.aclose()


async def test_a_ring_reads_every_poll_of_the_link_at_once() -> None:
    device = RingingStandIn()
    usb_link = USBLink(device, board_name="Power Board SRABC1")
    seen: dict[int, list[int]] = {8: [], 7: []}

    def watcher(index: int) -> Callable[[bytes], bool]:
        def found(reply: bytes) -> bool:
            seen[index].append(device.value)
            return device.value == 2

        return found

    async def ring_once_both_read() -> None:
        while not (seen[8] and seen[7]):  # noqa: ASYNC110 - the worker thread's state
            await anyio.sleep(0.001)
        device.change(2)

    with anyio.fail_after(30):
        async with anyio.create_task_group() as group:
            for index in (8, 7):
                group.start_soon(
                    functools.partial(
                        usb_link.poll_control_read, index, 4, watcher(index), interval=3600
                    )
                )
            group.start_soon(ring_once_both_read)
    assert seen == {8: [0, 2], 7: [0, 2]}
    await usb_link.aclose()


async def test_a_ring_with_no_poll_reads_nothing() -> None:
    device = RingingStandIn()
    usb_link = USBLink(device, board_name="Power Board SRABC1")
    device.change(1)
    assert await usb_link.control_read(9, 4) == struct.pack("<I", 9)  # the thread serves
    assert _reads_of(device, 8) == 0
    # A poll started later reads once, at once, and the ring before it is not read again.
    assert await usb_link.poll_control_read(8, 4, _found_value, interval=3600) == struct.pack(
        "<I", 1
    )
    assert _reads_of(device, 8) == 1
    await usb_link.aclose()


async def test_poll_until_runs_any_read_until_found(device: StandInDevice, link: USBLink) -> None:
    results = iter(range(10))
    taken: list[int] = []
    value = await link.poll_until(
        lambda: next(results), lambda n: n == 3, interval=0.001, description="counting",
        then=taken.append,
    )
    assert value == 3
    assert taken == [3]
    with pytest.raises(USBCommunicationError, match="counting failed") as info:
        await link.poll_until(
            lambda: 1 // 0, bool, interval=0.001, description="counting",
        )
    assert isinstance(info.value.usb_error, ZeroDivisionError)
    device.errors[8] = usb.core.USBError("No such device", -4, errno.ENODEV)
    with pytest.raises(USBDisconnectionError, match="pulled out"):
        await link.poll_until(
            lambda: device.ctrl_transfer(0x80, 64, 0, 8, 4), bool, interval=0.001,
            description="x", errors={errno.ENODEV: "pulled out"},
        )


async def test_a_read_failing_while_two_polls_run_fails_its_own_caller_only(
    device: StandInDevice, link: USBLink
) -> None:
    async def fail_at_the_third_read() -> None:
        reads = 0

        def work() -> int:
            nonlocal reads
            reads += 1
            if reads == 3:
                raise usb.core.USBError("Pipe error", -9, errno.EPIPE)
            return reads

        with pytest.raises(USBCommunicationError, match="second poll failed"):
            await link.poll_until(work, lambda _n: False, interval=0.001,
                                  description="second poll")

    with anyio.fail_after(30):
        async with anyio.create_task_group() as group:
            group.start_soon(
                functools.partial(
                    link.poll_control_read, 8, 4, lambda _r: _reads_of(device, 8) >= 20,
                    interval=0.001,
                )
            )
            while not _reads_of(device, 8):  # noqa: ASYNC110 - the worker thread's state
                await anyio.sleep(0.001)
            await fail_at_the_third_read()  # beside the first poll, which goes on
    assert _reads_of(device, 8) == 20
