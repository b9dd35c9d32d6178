"""Transports: how bytes reach a board.

* :class:`~j5aio.backends.hardware.transports.stream.ByteStream` — the seam every transport
  implements (:mod:`.stream`).
* :func:`~j5aio.backends.hardware.transports.serial_stream.open_serial_stream` — serial ports and
  pyserial URLs (:mod:`.serial_stream`).
* :func:`~j5aio.backends.hardware.transports.memory.memory_stream_pair`,
  :class:`~j5aio.backends.hardware.transports.memory.SimulatorStream` — in memory (:mod:`.memory`).
* :class:`~j5aio.backends.hardware.transports.serial_link.SerialLink` — serialised,
  cancellation-safe requests over a stream (:mod:`.serial_link`), with reply readers from
  :mod:`.readers`.
* :class:`~j5aio.backends.hardware.transports.usb_link.USBLink` — ordered USB control transfers on a
  worker thread (:mod:`.usb_link`).
* :func:`~j5aio.backends.hardware.transports.discovery.list_serial_ports`,
  :func:`~j5aio.backends.hardware.transports.discovery.match_ports`,
  :func:`~j5aio.backends.hardware.transports.discovery.find_usb_devices` — discovery
  (:mod:`.discovery`).
* :data:`~j5aio.backends.hardware.transports.trace.TRACE` — the log level of wire traffic
  (:mod:`.trace`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.hardware.transports.discovery import (
        FTDI_VENDOR_ID,
        PortInfo,
        find_port,
        find_usb_devices,
        list_serial_ports,
        match_ports,
    )
    from j5aio.backends.hardware.transports.memory import (
        MemoryStream,
        SerialSimulatorLike,
        SimulatorStream,
        memory_stream_pair,
    )
    from j5aio.backends.hardware.transports.readers import (
        ReplyReader,
        line_starts_with,
        read_exactly,
        read_line,
        read_lines,
        read_lines_until,
    )
    from j5aio.backends.hardware.transports.serial_link import SerialLink
    from j5aio.backends.hardware.transports.serial_stream import SerialStream, open_serial_stream
    from j5aio.backends.hardware.transports.stream import ByteStream
    from j5aio.backends.hardware.transports.trace import TRACE, wire_logger
    from j5aio.backends.hardware.transports.usb_link import (
        USBDeviceLike,
        USBDisconnectionError,
        USBLink,
        USBTransferTimeoutError,
    )

__all__ = [
    "FTDI_VENDOR_ID",
    "TRACE",
    "ByteStream",
    "MemoryStream",
    "PortInfo",
    "ReplyReader",
    "SerialLink",
    "SerialSimulatorLike",
    "SerialStream",
    "SimulatorStream",
    "USBDeviceLike",
    "USBDisconnectionError",
    "USBLink",
    "USBTransferTimeoutError",
    "find_port",
    "find_usb_devices",
    "line_starts_with",
    "list_serial_ports",
    "match_ports",
    "memory_stream_pair",
    "open_serial_stream",
    "read_exactly",
    "read_line",
    "read_lines",
    "read_lines_until",
    "wire_logger",
]

# Each name is imported from its module when first used: a program on the simulated kit,
# say, never imports pyserial's stream (serial_stream) this way.
if not TYPE_CHECKING:
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.hardware.transports.discovery": [
                "FTDI_VENDOR_ID", "PortInfo", "find_port", "find_usb_devices",
                "list_serial_ports", "match_ports",
            ],
            "j5aio.backends.hardware.transports.memory": [
                "MemoryStream", "SerialSimulatorLike", "SimulatorStream", "memory_stream_pair",
            ],
            "j5aio.backends.hardware.transports.readers": [
                "ReplyReader", "line_starts_with", "read_exactly", "read_line", "read_lines",
                "read_lines_until",
            ],
            "j5aio.backends.hardware.transports.serial_link": ["SerialLink"],
            "j5aio.backends.hardware.transports.serial_stream": [
                "SerialStream", "open_serial_stream",
            ],
            "j5aio.backends.hardware.transports.stream": ["ByteStream"],
            "j5aio.backends.hardware.transports.trace": ["TRACE", "wire_logger"],
            "j5aio.backends.hardware.transports.usb_link": [
                "USBDeviceLike", "USBDisconnectionError", "USBLink", "USBTransferTimeoutError",
            ],
        },
    )
