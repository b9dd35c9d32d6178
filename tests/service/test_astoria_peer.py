"""astoria's own daemons and tool as the peer, exactly as on a robot: astmetad publishes
the metadata, astprocd runs the team's code from a (static) stick and says where it is,
and astctl changes the metadata and sends the remote start.

Without astoria installed (see ``tests/service/astoria_stack.py``) these tests skip; the
other tests publish astoria's payloads themselves.
"""

from __future__ import annotations

import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path

import anyio
import pytest

from j5aio.competition import service_state
from j5aio.competition.metadata import Mode
from j5aio.competition.start import wait_for_start
from j5aio.service import RobotService, find_config
from tests.service.astoria_stack import AstoriaStack, astoria_missing
from tests.service.broker import Broker
from tests.service.helpers import eventually

pytest.importorskip("aiomqtt")

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def astoria(tmp_path: Path, broker: Broker) -> Iterator[AstoriaStack]:
    reason = astoria_missing()
    if reason is not None:
        pytest.skip(reason)
    stack = AstoriaStack(tmp_path, broker)
    stack.start()
    try:
        yield stack
    finally:
        stack.stop()


def zone_mode() -> tuple[int, Mode] | None:
    metadata = service_state.metadata()
    return None if metadata is None else (metadata.zone, metadata.mode)


async def test_astmetad_and_astctl_drive_the_program(
    astoria: AstoriaStack, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(astoria.directory)
    config = find_config(environ={})  # found as sr-robot3 finds it: ./astoria.toml
    assert config is not None and config.source == "astoria.toml"
    async with RobotService(config) as service:
        await service.wait_connected(timeout=10)
        # astmetad's retained status: the development defaults
        await eventually(lambda: zone_mode() == (0, Mode.DEV), timeout=30)
        output = await astoria.astctl("metadata", "set", "zone", "2")
        assert "Successfully set zone" in output
        await eventually(lambda: zone_mode() == (2, Mode.DEV), timeout=30)
        await astoria.astctl("metadata", "set", "mode", "COMP")
        await eventually(lambda: zone_mode() == (2, Mode.COMP), timeout=30)

        started: list[str] = []

        async def wait() -> None:
            started.append(await wait_for_start([], timeout=60))

        async with anyio.create_task_group() as group:
            group.start_soon(wait)
            await astoria.trigger(config.port)
        assert started == ["remote start"]


# The team's code on the stick: astprocd runs it with astoria's own interpreter, so it
# hands over to this test's interpreter, in the folder holding astoria.toml.
LAUNCHER = """
import os, sys
os.chdir({directory!r})
os.environ["PYTHONPATH"] = {repo!r}
os.execv({python!r}, [{python!r}, {program!r}, {stick!r}])
"""

PROGRAM = """
import sys
import anyio
from j5aio.competition import service_state
from j5aio.competition.start import wait_for_start
from j5aio.service import start_service

async def main():
    service = await start_service()
    await service.wait_connected(timeout=30)
    with anyio.fail_after(30):
        while service_state.usercode_path() is None:
            await anyio.sleep(0.05)
    print("WAITING", flush=True)
    how = await wait_for_start([], timeout=60)
    metadata = service_state.metadata()
    print(f"STARTED by {how} in zone {metadata.zone}, stick {service_state.usercode_path()}",
          flush=True)
    await service.stop()

anyio.run(main)
"""


async def test_a_program_run_by_astprocd_gets_its_stick_and_the_remote_start(
    astoria: AstoriaStack, broker: Broker, tmp_path: Path
) -> None:
    stick = tmp_path / "stick"
    stick.mkdir()
    program = tmp_path / "program.py"
    program.write_text(textwrap.dedent(PROGRAM))
    (stick / "robot.py").write_text(LAUNCHER.format(
        directory=str(astoria.directory), repo=str(REPO), python=sys.executable,
        program=str(program), stick=str(stick),
    ))
    log = stick / "log.txt"

    def logged(word: str) -> bool:
        return log.exists() and word in log.read_text(errors="replace")

    try:
        await astoria.ready(broker.port)
        await astoria.astctl("static-disk", "add", str(stick))
        await eventually(lambda: logged("WAITING"), timeout=60)
        await astoria.astctl("metadata", "set", "zone", "3")
        await astoria.trigger(broker.port)
        await eventually(lambda: logged("STARTED by"), timeout=60)
    except TimeoutError:
        raise AssertionError(astoria.explain(log)) from None
    line = next(x for x in log.read_text().splitlines() if "STARTED by" in x)
    assert line.endswith(f"STARTED by remote start in zone 3, stick {stick}"), log.read_text()
