"""Take the live view's screenshot for the docs, in a real browser (Debian's chromium).

    python tools/view_screenshot.py              # the sr2019 kit: docs/images/live-view-sr2019.png
    python tools/view_screenshot.py --kit sr2023 # writes docs/images/live-view-sr2023.png
    python tools/view_screenshot.py --arena      # writes docs/images/live-view-arena.png

It runs ``python -m j5aio demo --view`` (on the sr2019 kit, or ``--kit``), opens the printed
address in headless chromium driven by selenium and chromedriver, waits until the robot
has been driving for a few seconds, and saves the page (with ``--arena``, only the drawing
of the simulated arena, larger). The browser tests load this file
for :func:`launch_chromium` and :func:`start_demo`.

Needs ``pip install 'j5aio[view-test]'`` and ``apt-get install chromium chromium-driver``.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import IO, TYPE_CHECKING

if TYPE_CHECKING:
    from selenium.webdriver.remote.webdriver import WebDriver

ROOT = Path(__file__).resolve().parent.parent
SCREENSHOT = ROOT / "docs" / "images" / "live-view-sr2019.png"

#: The flags chromium needs to run headless in a container, quietly.
CHROMIUM_FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
)


def missing_browser() -> str | None:
    """Why the browser cannot be driven here, or ``None`` when it can."""
    if importlib.util.find_spec("selenium") is None:
        return "selenium is not installed (pip install 'j5aio[view-test]')"
    if importlib.util.find_spec("aiohttp") is None:
        return "the view extra is not installed (pip install 'j5aio[view]')"
    for program, package in (("chromium", "chromium"), ("chromedriver", "chromium-driver")):
        if shutil.which(program) is None:
            return f"no {program} on PATH (apt-get install {package})"
    return None


def launch_chromium(width: int = 1280, height: int = 1000) -> tuple[WebDriver, Path]:
    """Start headless chromium with a fresh profile; return the driver and the profile folder."""
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service

    profile = Path(tempfile.mkdtemp(prefix="j5aio-chromium-"))
    options = Options()
    options.binary_location = shutil.which("chromium") or "chromium"
    for flag in (*CHROMIUM_FLAGS, f"--user-data-dir={profile}", f"--window-size={width},{height}"):
        options.add_argument(flag)
    service = Service(executable_path=shutil.which("chromedriver") or "chromedriver")
    try:
        return webdriver.Chrome(service=service, options=options), profile
    except BaseException:
        shutil.rmtree(profile, ignore_errors=True)
        raise


def start_demo(
    seconds: float, *, env: dict[str, str] | None = None, kit: str | None = None
) -> tuple[subprocess.Popen[str], str]:
    """Run ``python -m j5aio demo --view`` for ``seconds``; return it and the view's address."""
    kit_arguments = ["--kit", kit] if kit is not None else []
    process = subprocess.Popen(
        [sys.executable, "-m", "j5aio", "demo", "--view", "--seconds", str(seconds),
         *kit_arguments],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env=env if env is not None else {**os.environ, "PYTHONPATH": str(ROOT)},
    )
    url = _read_url(process.stdout, deadline=time.monotonic() + 30)
    if url is None:
        stop(process)
        raise RuntimeError("the demo printed no 'View:' line")
    return process, url


def _read_url(stream: IO[str] | None, *, deadline: float) -> str | None:
    assert stream is not None
    while time.monotonic() < deadline:
        line = stream.readline()
        if not line:
            return None
        found = re.match(r"View: (http://\S+)", line)
        if found:
            return found.group(1)
    return None


def stop(process: subprocess.Popen[str]) -> str:
    """Interrupt a demo (as Ctrl-C does), wait for it to end; return what it printed last."""
    if process.poll() is None:
        process.send_signal(signal.SIGINT)
    try:
        rest, _ = process.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        process.kill()
        rest, _ = process.communicate()
    return rest or ""


def take_screenshot(
    path: Path, *, settle: float = 5.0, kit: str | None = None, arena: bool = False
) -> None:
    """Screenshot the view of the demo after it has run ``settle`` seconds, into ``path``.

    :param arena: save only the drawing of the simulated arena (shown 640 px wide).
    """
    process, url = start_demo(settle + 30, kit=kit)
    driver, profile = launch_chromium()
    try:
        driver.get(url)
        if arena:
            driver.execute_script(
                "const style = document.createElement('style');"
                "style.textContent = '#arena-figure { flex: 0 0 640px !important; }';"
                "document.head.append(style);"
            )
        time.sleep(settle)
        path.parent.mkdir(parents=True, exist_ok=True)
        height = driver.execute_script("return document.documentElement.scrollHeight")
        driver.set_window_size(1280, min(int(height) + 40, 3000))
        time.sleep(0.5)
        if arena:
            driver.find_element("css selector", "#arena-figure").screenshot(str(path))
        else:
            driver.save_screenshot(str(path))
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)
        stop(process)


def main() -> int:
    """Take the docs' screenshot (or say why not); return the exit status."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=None, help="where to save the PNG")
    parser.add_argument("--kit", default="sr2019", help="the simulated kit (default: sr2019)")
    parser.add_argument(
        "--arena", action="store_true", help="only the drawing of the simulated arena"
    )
    args = parser.parse_args()
    if args.out is None:
        name = "arena" if args.arena else args.kit
        args.out = SCREENSHOT.with_name(f"live-view-{name}.png")
    reason = missing_browser()
    if reason is not None:
        print(f"cannot take the screenshot: {reason}", file=sys.stderr)
        return 2
    take_screenshot(args.out, kit=args.kit, arena=args.arena)
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
