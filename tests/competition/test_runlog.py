"""Tests of run logs: where they go, rotation, the size cap, the header and the tee."""

from __future__ import annotations

import logging
import sys
from datetime import UTC, datetime
from pathlib import Path

import pytest

from j5aio.competition import runlog
from j5aio.competition.metadata import MEDIA_ROOTS_VARIABLE, Metadata, MetadataError, Mode
from j5aio.competition.runlog import LOG_DIR_VARIABLE, RunLog, choose_log_folder, rotate, teeing


@pytest.fixture(autouse=True)
def _no_outside(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.delenv(LOG_DIR_VARIABLE, raising=False)
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, str(tmp_path / "media"))


def test_folder_choice(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    program = tmp_path / "code" / "robot.py"
    assert choose_log_folder(program) == tmp_path / "code" / "j5aio-logs"
    sticks = [tmp_path / "media" / "A", tmp_path / "media" / "B"]
    for stick in sticks:
        stick.mkdir(parents=True)
    monkeypatch.setattr("j5aio.competition.metadata.os.path.ismount", lambda p: Path(p) in sticks)
    assert choose_log_folder(program) == sticks[0] / "logs"
    on_b = Metadata(mode=Mode.DEV, source=sticks[1] / "metadata.json")
    assert choose_log_folder(program, on_b) == sticks[1] / "logs"
    monkeypatch.setenv(LOG_DIR_VARIABLE, str(tmp_path / "chosen"))
    assert choose_log_folder(program, on_b) == tmp_path / "chosen"


def make_logs(folder: Path, count: int, size: int) -> list[Path]:
    folder.mkdir(parents=True, exist_ok=True)
    logs = [folder / f"run-2026010{n}-000000.log" for n in range(count)]
    for log in logs:
        log.write_bytes(b"x" * size)
    (folder / "notes.txt").write_text("not a log: never deleted")
    return logs


def test_rotation_keeps_count_total_and_free_space(tmp_path: Path) -> None:
    logs = make_logs(tmp_path, 5, 100)
    plenty = lambda folder: 10**9  # noqa: E731
    assert rotate(tmp_path, max_files=3, max_total=10**6, reserve=0, free_bytes=plenty) == logs[:3]
    logs = make_logs(tmp_path / "b", 5, 100)
    assert rotate(tmp_path / "b", max_files=99, max_total=250, reserve=0, free_bytes=plenty) == (
        logs[:3]
    )
    logs = make_logs(tmp_path / "c", 3, 100)
    free = [0]

    def filling(folder: Path) -> int:
        free[0] += 1
        return 0 if free[0] < 3 else 10**9

    assert rotate(tmp_path / "c", max_total=10**6, reserve=1, free_bytes=filling) == logs[:2]
    assert (tmp_path / "c" / "notes.txt").exists()
    assert rotate(tmp_path / "empty") == []


def test_a_log_is_capped_and_named_by_time(tmp_path: Path) -> None:
    when = datetime(2026, 11, 23, 9, 30, 0, tzinfo=UTC)
    log = RunLog(tmp_path, now=when, max_bytes=30)
    second = RunLog(tmp_path, now=when)
    assert log.path.name == "run-20261123-093000.log"
    assert second.path.name == "run-20261123-093000-2.log"
    log.write("a" * 20)
    log.write("b" * 20)  # over the cap
    log.write("c")
    log.close()
    log.write("after close")
    second.close()
    text = log.path.read_text()
    assert text.startswith("a" * 20) and "b" not in text and "this log is full" in text


def test_header_and_tee(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    make_logs(tmp_path, 25, 1)
    log = RunLog(tmp_path)
    log.write_header(Path("/x/robot.py"), Metadata(zone=2))
    logger = logging.getLogger("j5aio.test")
    with teeing(log):
        print("to stdout")
        print("to stderr", file=sys.stderr)
        logger.info("an info line")
        logger.warning("a warning")
        assert sys.stdout.encoding  # other attributes pass through
        sys.stdout.flush()
    print("not logged")
    log.close()
    text = log.path.read_text()
    for expected in (
        "# j5aio: ", "# python: ", "# program: /x/robot.py", "zone 2", "# rotated: deleted",
        "to stdout", "to stderr", "INFO j5aio.test: an info line", "WARNING j5aio.test: a warning",
    ):
        assert expected in text
    assert "not logged" not in text
    captured = capsys.readouterr()
    assert "to stdout" in captured.out and "a warning" in captured.err
    assert "an info line" not in captured.err


def test_header_with_unusable_metadata(tmp_path: Path) -> None:
    log = RunLog(tmp_path)
    log.write_header(Path("r.py"), MetadataError("m.json: field 'zone' must be ..."))
    log.close()
    assert "# metadata: unusable: m.json: field 'zone'" in log.path.read_text()


def test_constants_keep_a_stick_from_filling() -> None:
    assert runlog.MAX_FILE_BYTES * runlog.MAX_LOG_FILES <= 2 * runlog.MAX_TOTAL_BYTES
    assert runlog.RESERVE_BYTES >= runlog.MAX_FILE_BYTES
