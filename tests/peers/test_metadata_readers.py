"""j5aio reads a competition's metadata file as the competition's own library does.

sbot reads ``metadata.json`` below ``SBOT_METADATA_PATH``; sr-robot3 reads astoria's
``astoria.json`` (there in simulation, and astoria itself with the same schema). Each
file here is read by the peer, in a child Python that has it, and by j5aio: where the
peer reads a match, j5aio must read the same zone, mode and length; where the peer
refuses the file, so must j5aio. (j5aio is stricter where a peer guesses: sbot takes
``"zone": "2"`` as text, pydantic turns ``"2"`` into 2; j5aio refuses both, which the
fuzz tests in tests/competition cover.)

The peers' interpreters: ``J5AIO_SBOT_PYTHON`` / ``J5AIO_SR3_PYTHON`` if set, else this
one if it has the peer (``tox -e peers`` installs both); otherwise the tests skip.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from j5aio.competition.metadata import (
    MEDIA_ROOTS_VARIABLE,
    METADATA_VARIABLE,
    SBOT_METADATA_VARIABLE,
    MetadataError,
    load_metadata,
)

SBOT_READER = r"""
import json, os, sys
os.environ["SBOT_PYTEST"] = "1"  # import sbot without it finding boards and waiting
try:
    from sbot._comp import Comp
    from sbot.game_specific import GAME_LENGTH
except ImportError as error:
    print("RESULT " + json.dumps({"missing": str(error)}))
    sys.exit()
comp = Comp()
try:
    comp._load()
except Exception as error:
    print("RESULT " + json.dumps({"refused": repr(error)}))
else:
    print("RESULT " + json.dumps(
        {"zone": comp.zone, "competition": comp.is_competition, "length": GAME_LENGTH}
    ))
"""

SR3_READER = r"""
import json, sys
try:
    from sr.robot3.astoria import Metadata
except ImportError as error:
    print("RESULT " + json.dumps({"missing": str(error)}))
    sys.exit()
try:
    metadata = Metadata.parse_file(sys.argv[1])
except Exception as error:
    print("RESULT " + json.dumps({"refused": repr(error)}))
else:
    print("RESULT " + json.dumps({
        "zone": metadata.zone, "mode": metadata.mode.value, "arena": metadata.arena,
        "timeout": metadata.game_timeout, "offset": metadata.marker_offset,
    }))
"""


def peer_python(variable: str, module: str) -> str:
    named = os.environ.get(variable)
    if named:
        return named
    from importlib.util import find_spec

    if find_spec(module.split(".")[0]) is not None and find_spec(module) is not None:
        return sys.executable
    pytest.skip(
        f"{module} is not installed here and {variable} names no interpreter that has "
        "it: run `tox -e peers`, or set the variable"
    )


def run_reader(python: str, source: str, *args: str, env: dict[str, str]) -> dict[str, Any]:
    environment = {k: v for k, v in os.environ.items() if not k.startswith(("SBOT_", "J5AIO"))}
    environment.update(env)
    result = subprocess.run(
        [python, "-c", source, *args], capture_output=True, text=True, timeout=60,
        env=environment, check=False,
    )
    lines = [line for line in result.stdout.splitlines() if line.startswith("RESULT ")]
    assert lines, result.stderr
    answer: dict[str, Any] = json.loads(lines[-1].removeprefix("RESULT "))
    if "missing" in answer:
        pytest.skip(f"the peer cannot read metadata: {answer['missing']}")
    return answer


@pytest.fixture(autouse=True)
def _no_other_metadata(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.delenv(METADATA_VARIABLE, raising=False)
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, str(tmp_path / "no-media"))


SBOT_FILES = [
    '{"zone": 2, "is_competition": true}',
    '{"zone": 0, "is_competition": false}',
    '{"is_competition": true, "zone": 3}',
    '\n  {"zone": 1,\n   "is_competition": true}\n',
    '{"zone": 2}',
    '{"is_competition": true}',
    "[2, true]",
    '{"zone": 2, "is_competition": true',
    "",
]


@pytest.mark.parametrize("text", SBOT_FILES)
def test_sbots_files_are_read_as_sbot_reads_them(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, text: str
) -> None:
    python = peer_python("J5AIO_SBOT_PYTHON", "sbot")
    folder = tmp_path / "metadata"
    folder.mkdir()
    (folder / "metadata.json").write_text(text)
    peer = run_reader(python, SBOT_READER, env={SBOT_METADATA_VARIABLE: str(folder)})
    monkeypatch.setenv(SBOT_METADATA_VARIABLE, str(folder))
    if "refused" in peer:
        with pytest.raises(MetadataError):
            load_metadata([])
        return
    ours = load_metadata([])
    assert (ours.zone, ours.is_competition) == (peer["zone"], peer["competition"])
    assert ours.duration == (float(peer["length"]) if peer["competition"] else None)


ASTORIA_FILES = [
    '{"zone": 2, "mode": "COMP", "game_timeout": 150}',
    '{"arena": "B", "zone": 1, "mode": "COMP", "marker_offset": 40, "game_timeout": 180,'
    ' "wifi_enabled": false}',
    '{"zone": 3, "mode": "DEV"}',
    '{"mode": "COMP"}',
    "{}",
    '{"zone": 1, "mode": "MATCH"}',
    '{"zone": 1, "mode": "COMP", "game_timeout": null}',
    "[1]",
    '{"zone": 1,',
]


@pytest.mark.parametrize("text", ASTORIA_FILES)
def test_astorias_files_are_read_as_sr_robot3_reads_them(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, text: str
) -> None:
    python = peer_python("J5AIO_SR3_PYTHON", "sr.robot3")
    path = tmp_path / "stick" / "astoria.json"
    path.parent.mkdir()
    path.write_text(text)
    peer = run_reader(python, SR3_READER, str(path), env={})
    monkeypatch.setenv(SBOT_METADATA_VARIABLE, str(path.parent))  # as in sr-robot3's simulator
    if "refused" in peer:
        with pytest.raises(MetadataError):
            load_metadata([])
        return
    ours = load_metadata([])
    assert (ours.zone, ours.mode.value, ours.arena, ours.marker_offset) == (
        peer["zone"], peer["mode"], peer["arena"], peer["offset"],
    )
    assert ours.duration == (float(peer["timeout"]) if peer["timeout"] else None)
