"""The async console example runs end to end, and its tasks interleave while a prompt waits."""

from __future__ import annotations

import os
import queue
import subprocess
import sys
import threading
import time
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "async_console_robot.py"


def _start() -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, str(EXAMPLE)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )


def test_runs_with_piped_input() -> None:
    result = subprocess.run(
        [sys.executable, str(EXAMPLE)],
        input="12.1\n11.8\n10.2\n",
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "battery: 12.1 V" in out
    assert "battery: 10.2 V" in out
    assert "battery low" in out
    assert "Setting motor 0 to 0.6." in out
    assert "Setting motor 1 to BRAKE." in out


PROMPT = "Battery voltage [volts]: "


def test_other_tasks_keep_running_while_a_prompt_waits() -> None:
    proc = _start()
    assert proc.stdout is not None and proc.stdin is not None
    chunks: queue.Queue[str] = queue.Queue()
    threading.Thread(target=_pump_chars, args=(proc.stdout.fileno(), chunks), daemon=True).start()
    text = ""
    answered = 0
    try:
        deadline = time.monotonic() + 30
        while answered < 3 and time.monotonic() < deadline:
            try:
                text += chunks.get(timeout=0.1)
            except queue.Empty:
                continue
            if text.count(PROMPT) > answered:
                # A prompt is waiting: give the other tasks time to show they still run.
                time.sleep(0.5)
                while not chunks.empty():
                    text += chunks.get()
                after_prompt = text.rsplit(PROMPT, 1)[1]
                assert "Setting motor" in after_prompt or "Set LED" in after_prompt, text
                proc.stdin.write(f"{12 - answered}\n")
                proc.stdin.flush()
                answered += 1
        assert answered == 3, text
        proc.stdin.close()
        assert proc.wait(timeout=20) == 0, text
    finally:
        if proc.poll() is None:
            proc.kill()


def _pump_chars(fd: int, chunks: queue.Queue[str]) -> None:
    while data := os.read(fd, 4096):
        chunks.put(data.decode())
