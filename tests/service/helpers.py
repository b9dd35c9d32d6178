"""Payloads exactly as astoria 0.11.3 and sbot 2026.1.0 send them, and small waits."""

from __future__ import annotations

from collections.abc import Callable, Sized
from typing import Any

import anyio


def astmetad_message(status: str = "RUNNING", **fields: Any) -> dict[str, object]:
    """An astmetad status message (the software facts as astoria adds them)."""
    metadata: dict[str, object] = {
        "arena": "A",
        "zone": 0,
        "mode": "DEV",
        "marker_offset": 0,
        "game_timeout": None,
        "wifi_enabled": True,
        "astoria_version": "0.11.3",
        "kernel_version": "6.1.0",
        "arch": "aarch64",
        "python_version": "3.11.2",
        "libc_ver": "glibc2.36",
        "os_name": "Student Robotics OS",
        "os_pretty_name": "Student Robotics OS 2026",
        "os_version": "2026",
        "usercode_entrypoint": "robot.py",
        "wifi_ssid": None,
        "wifi_psk": None,
        "wifi_region": None,
    }
    metadata.update(fields)
    return {"status": status, "astoria_version": "0.11.3", "metadata": metadata}


def astprocd_message(mount_path: str | None, status: str = "RUNNING") -> dict[str, object]:
    disk = None if mount_path is None else {
        "uuid": "1234-ABCD", "mount_path": mount_path, "disk_type": "USERCODE",
    }
    return {
        "status": status, "astoria_version": "0.11.3", "code_status": "code_running",
        "disk_info": disk, "pid": 4242,
    }


def start_event(sender: str = "astctl-test") -> dict[str, object]:
    return {"event_name": "start_button", "sender_name": sender, "priority": 0}


async def eventually(check: Callable[[], bool], timeout: float = 10.0) -> None:
    """Wait until ``check()`` is true (a generous limit: no timing is asserted)."""
    with anyio.fail_after(timeout):
        while not check():  # noqa: ASYNC110 - state changed by other tasks and threads
            await anyio.sleep(0.01)


def longer_than(items: Sized, length: int) -> Callable[[], bool]:
    """A check that ``items`` has grown past ``length``."""
    return lambda: len(items) > length
