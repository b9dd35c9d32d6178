"""Tests of serving a simulator on a pseudo-terminal."""

from __future__ import annotations

import logging
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import pytest
import serial

pytest.importorskip("termios", reason="pseudo-terminals exist on POSIX systems only")

from j5aio.simulator import serve
from j5aio.simulator.serve import OPEN_SETTLE_TIME, PtyServer, reply_due, serve_on_pty


class FakeSimulator:
    """A tiny simulator: replies ``ok:<bytes>`` and counts opens."""

    baudrate = 115200

    def __init__(self, boot: bytes = b"# Booted\r\n", boot_delay: float = 0.0) -> None:
        self.boot = boot
        self.boot_delay = boot_delay
        self.connected = True
        self.opens = 0
        self.received: list[bytes] = []
        self.fail = False

    def open(self) -> bytes:
        self.opens += 1
        return self.boot

    def receive(self, data: bytes) -> bytes:
        if self.fail:
            self.fail = False
            raise RuntimeError("simulator bug")
        self.received.append(data)
        return b"ok:" + data


def open_port(path: str, timeout: float = 2.0) -> serial.Serial:
    return serial.Serial(path, 115200, timeout=timeout)


def wait_for(condition: Callable[[], bool], timeout: float = 2.0) -> None:
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError("condition not reached")
        time.sleep(0.005)


def test_boot_output_appears_after_the_port_is_opened() -> None:
    simulator = FakeSimulator(boot_delay=0.15)
    with serve_on_pty(simulator) as server:
        assert os.path.exists(server.path)
        assert server.is_serving
        time.sleep(0.05)
        assert simulator.opens == 0  # nothing happens until a program opens the port
        started = time.monotonic()
        with open_port(server.path) as port:
            assert port.readline() == b"# Booted\r\n"
            assert time.monotonic() - started >= 0.15
        assert simulator.opens == 1


def test_time_scale_shortens_the_boot_delay_but_not_below_the_settle_time() -> None:
    simulator = FakeSimulator(boot_delay=5.0)
    with serve_on_pty(simulator, time_scale=0) as server:
        started = time.monotonic()
        with open_port(server.path) as port:
            assert port.readline() == b"# Booted\r\n"
        elapsed = time.monotonic() - started
    assert OPEN_SETTLE_TIME <= elapsed < 1.0


def test_requests_reach_the_simulator_and_replies_come_back() -> None:
    simulator = FakeSimulator(boot=b"")
    with serve_on_pty(simulator, time_scale=0) as server, open_port(server.path) as port:
        port.write(b"PIN:2:DIGITAL:GET?\n")
        assert port.read(22) == b"ok:PIN:2:DIGITAL:GET?\n"
    assert b"".join(simulator.received) == b"PIN:2:DIGITAL:GET?\n"


def test_the_port_is_raw_no_echo_and_no_newline_translation() -> None:
    simulator = FakeSimulator(boot=b"")
    with serve_on_pty(simulator, time_scale=0) as server:
        fd = os.open(server.path, os.O_RDWR | os.O_NOCTTY)
        try:
            os.write(fd, b"a\r\x03\x04b\n")
            wait_for(lambda: len(b"".join(simulator.received)) >= 6)
            time.sleep(0.05)
            reply = b""
            while len(reply) < 9:
                reply += os.read(fd, 100)
        finally:
            os.close(fd)
    assert b"".join(simulator.received) == b"a\r\x03\x04b\n"
    assert reply == b"ok:a\r\x03\x04b\n"


def test_each_open_resets_the_board_and_replays_the_boot_output() -> None:
    simulator = FakeSimulator()
    with serve_on_pty(simulator, time_scale=0) as server:
        for expected in (1, 2):
            with open_port(server.path) as port:
                assert port.readline() == b"# Booted\r\n"
                assert server.is_port_open
            wait_for(lambda: not server.is_port_open)
            assert server.opened_count == expected
    assert simulator.opens == 2


def test_a_large_reply_is_written_in_full() -> None:
    simulator = FakeSimulator(boot=b"")
    payload = bytes(range(256)) * 64
    with serve_on_pty(simulator, time_scale=0) as server, open_port(server.path, 0.3) as port:
        port.write(payload)
        reply = b""
        while chunk := port.read(100_000):
            reply += chunk
    assert b"".join(simulator.received) == payload
    assert reply == b"".join(b"ok:" + chunk for chunk in simulator.received)


def test_unplugging_hangs_up_the_port_and_plugging_in_makes_a_new_one(tmp_path: Path) -> None:
    simulator = FakeSimulator(boot=b"")
    link = tmp_path / "board"
    with serve_on_pty(simulator, time_scale=0, link=link) as server:
        assert server.link == str(link) == server.port
        assert os.readlink(link) == server.path
        with open_port(str(link), 0.5) as port:
            wait_for(lambda: server.opened_count == 1)
            simulator.connected = False  # the cable comes out
            wait_for(lambda: not server.is_port_open)
            with pytest.raises(serial.SerialException):
                for _ in range(50):  # the hang-up may take a poll of the server to show
                    port.write(b"hello\n")
                    port.read(1)
                    time.sleep(0.01)
        assert simulator.received in ([], [b"hello\n"])
        assert not server.has_pty
        simulator.connected = True  # and goes back in: a new pseudo-terminal
        wait_for(lambda: server.has_pty)  # (its number may be the one just freed)
        assert os.readlink(link) == server.path
        with open_port(str(link), 2) as port:
            port.write(b"again\n")
            assert port.read(9) == b"ok:again\n"
    assert not os.path.lexists(link)  # removed at exit


def test_a_link_refuses_to_replace_a_file(tmp_path: Path) -> None:
    path = tmp_path / "file"
    path.write_text("keep me")
    with pytest.raises(FileExistsError, match="not a symbolic link"):
        serve_on_pty(FakeSimulator(), link=path)
    assert path.read_text() == "keep me"


def test_a_failing_simulator_is_logged_and_serving_continues(
    caplog: pytest.LogCaptureFixture,
) -> None:
    simulator = FakeSimulator(boot=b"")
    simulator.fail = True
    with (
        caplog.at_level(logging.ERROR, logger="j5aio.simulator.serve"),
        serve_on_pty(simulator, time_scale=0) as server,
        open_port(server.path) as port,
    ):
        port.write(b"first\n")
        wait_for(lambda: "simulator bug" in caplog.text)
        port.write(b"second\n")
        assert port.read(10) == b"ok:second\n"
    assert "failed; still serving" in caplog.text


async def test_serves_inside_async_code_as_an_async_context_manager() -> None:
    simulator = FakeSimulator()
    async with serve_on_pty(simulator, time_scale=0) as server:
        with open_port(server.path) as port:
            assert port.readline() == b"# Booted\r\n"
    assert not server.is_serving


def test_close_is_idempotent_and_a_closed_server_cannot_start() -> None:
    server = serve_on_pty(FakeSimulator())
    assert "serving" in repr(server)
    server.close()
    server.close()
    assert not server.is_serving
    assert "stopped" in repr(server)
    with pytest.raises(RuntimeError, match="closed"):
        server.start()


def test_a_program_still_connected_when_the_server_closes_sees_the_end() -> None:
    server = serve_on_pty(FakeSimulator(boot=b""), time_scale=0)
    port = open_port(server.path, 0.5)
    try:
        server.close()
        with pytest.raises(serial.SerialException):
            port.read(1)
    finally:
        port.close()


def test_negative_time_scale_is_refused() -> None:
    with pytest.raises(ValueError, match="time_scale must be zero or more, not -1"):
        PtyServer(FakeSimulator(), time_scale=-1)


def test_reads_that_find_nothing_are_ignored() -> None:
    simulator = FakeSimulator()
    server = PtyServer(simulator)  # not started: the test drives it by hand
    try:
        server._read_master()  # no program has the port open: the read fails with EIO
        fd = os.open(server.path, os.O_RDWR | os.O_NOCTTY)
        try:
            server._read_master()  # open, but nothing written: the read would block
        finally:
            os.close(fd)
    finally:
        server.close()
    assert simulator.received == []


def test_output_waits_while_the_program_is_not_reading() -> None:
    server = PtyServer(FakeSimulator())  # not started: the test drives it by hand
    payload = bytes(range(256)) * 400  # far more than a pseudo-terminal buffers
    fd = os.open(server.path, os.O_RDWR | os.O_NOCTTY)
    try:
        server._pending.append((time.monotonic(), payload))
        server._write_due()
        assert server._pending, "everything fitted: the test needs a bigger payload"
        received = b""
        deadline = time.monotonic() + 5
        while len(received) < len(payload) and time.monotonic() < deadline:
            received += os.read(fd, 65536)
            server._write_due()
    finally:
        os.close(fd)
        server.close()
    assert received == payload


def test_the_simulator_is_exposed() -> None:
    simulator = FakeSimulator()
    with serve_on_pty(simulator) as server:
        assert server.simulator is simulator


def exchange(port: serial.Serial, command: bytes) -> list[bytes]:
    """Send an SB Arduino command; return its reply lines, up to the final ``+``/``-`` line."""
    port.write(command)
    lines = [port.readline()]
    while not lines[-1].startswith((b"+", b"-")):
        assert lines[-1], f"no complete reply to {command!r}: {lines!r}"
        lines.append(port.readline())
    return lines


def test_the_command_line_serves_an_sb_arduino_that_pyserial_can_drive() -> None:
    command = [sys.executable, "-m", "j5aio", "simulate", "sb-arduino", "--pty"]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert process.stdout is not None
        path = process.stdout.readline().strip()
        assert path.startswith("/dev/")
        with serial.Serial(path, 115200, timeout=5) as port:
            # Opening the port resets the board, as on a real Arduino: it boots first.
            assert port.readline() == b"# Booted\n"
            port.readline()  # the version comment printed at boot
            version = exchange(port, b"V\n")
            assert version[0] == b"# V\n"  # the firmware echoes each command
            assert version[1].startswith(b"> SBDuino GPIO v2019")
            assert version[-1] == b"+ OK\r\n"
            assert exchange(port, b"W 7 H\n") == [b"# W 7 H\n", b"+ OK\r\n"]
            assert exchange(port, b"R 7\n") == [b"# R 7\n", b"> H\r\n", b"+ OK\r\n"]
        process.send_signal(signal.SIGINT)
        _, errors = process.communicate(timeout=10)
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    assert process.returncode == 0
    assert f"on {path}" in errors
    assert "Stopped." in errors


def test_uart_timing_delays_each_reply_by_its_time_on_the_wire() -> None:
    class SlowLine(FakeSimulator):
        baudrate = 300  # 10 bits a byte: 30 bytes a second, so timings are clear

    simulator = SlowLine(boot=b"")
    request = b"x" * 9  # 9 bytes in, 12 bytes ("ok:" + 9) out: 21 bytes, 0.7 s
    with serve_on_pty(simulator, uart_timing=True) as server, open_port(server.path) as port:
        wait_for(lambda: server.opened_count == 1)
        started = time.monotonic()
        port.write(request)
        assert port.read(12) == b"ok:" + request
        assert time.monotonic() - started >= 21 * 10 / 300 - 0.005
    instant = FakeSimulator(boot=b"")
    with serve_on_pty(instant) as server, open_port(server.path) as port:
        wait_for(lambda: server.opened_count == 1)
        started = time.monotonic()
        port.write(request)
        assert port.read(12) == b"ok:" + request
        # well below the 0.7 s the same bytes take at UART timing, however loaded the machine
        assert time.monotonic() - started < 0.35


def _start_simulator(link: Path) -> subprocess.Popen[str]:
    command = [
        sys.executable, "-m", "j5aio", "simulate", "sb-arduino", "--pty", "--link", str(link),
        "--time-scale", "0", "--serial-number", "LINKED",
    ]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert process.stdout is not None
    assert process.stdout.readline().strip() == str(link)
    return process


def _stop(process: subprocess.Popen[str], *, kill: bool = False) -> None:
    if kill:
        process.kill()
    else:
        process.send_signal(signal.SIGINT)
    process.communicate(timeout=10)


async def test_a_killed_and_restarted_simulator_at_the_same_link_serves_the_same_board(
    tmp_path: Path,
) -> None:
    from j5aio.backends.hardware import registry
    from j5aio.backends.hardware.reconnect import ReconnectPolicy
    from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
    from j5aio.errors import BoardDisconnectionError

    link = tmp_path / "arduino"
    process = _start_simulator(link)
    try:
        board = await SBArduinoHardwareBackend.attach(str(link), time_scale=0.1)
        backend = board.backend
        assert isinstance(backend, SBArduinoHardwareBackend)
        backend.reconnect_policy = ReconnectPolicy(interval=0.0)
        await board.setup()
        assert 0 <= await board.pins[14].analogue_read() <= 5
        _stop(process, kill=True)
        with pytest.raises(BoardDisconnectionError):
            await board.pins[14].analogue_read()
        with pytest.raises(BoardDisconnectionError):
            await board.pins[14].analogue_read()  # gone: the link is dangling
        process = _start_simulator(link)
        assert 0 <= await board.pins[14].analogue_read() <= 5
        assert backend.reconnections == 1
        assert registry.holder(str(link)) is board
        await board.close()
    finally:
        if process.poll() is None:
            _stop(process)
    assert not link.exists()


@pytest.mark.parametrize("uart_timing", [False, True])
def test_the_poll_fallback_for_descriptors_beyond_select_serves_alike(
    monkeypatch: pytest.MonkeyPatch, uart_timing: bool
) -> None:
    monkeypatch.setattr(serve, "_SELECT_LIMIT", 0)  # as if every descriptor were >= 1024
    simulator = FakeSimulator(boot=b"")
    with serve_on_pty(simulator, uart_timing=uart_timing) as server, open_port(
        server.path
    ) as port:
        wait_for(lambda: server.opened_count == 1)
        for request in (b"a", b"bc"):
            port.write(request)
            assert port.read(3 + len(request)) == b"ok:" + request


def test_a_reply_is_due_once_the_request_has_arrived_and_the_line_is_free() -> None:
    # An instant board (no UART timing: zero wire times) answers as the request comes.
    assert reply_due(5.0, 0.0, 0.0) == 5.0
    # The request arrived at 5.0; the reply takes 2 on the wire.
    assert reply_due(5.0, 2.0, 0.0) == 7.0
    assert reply_due(5.0, 2.0, 4.5) == 7.0  # earlier output done before: no matter
    # Earlier output (a banner, a reply) still on the line until 6.0: the reply follows it.
    assert reply_due(5.0, 2.0, 6.0) == 8.0
