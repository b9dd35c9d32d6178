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


async def test_the_live_views_token_is_hidden_in_the_log(tmp_path: Path) -> None:
    pytest.importorskip("aiohttp", reason="the live view needs the 'view' extra")
    from j5aio.view import start_view

    log = RunLog(tmp_path)
    with teeing(log):
        view = start_view()  # prints its address, token and all, to standard output
    try:
        token = view.url.split("token=", 1)[1]
        assert len(token) >= 16
    finally:
        view.close()
    log.write("see http://x/?a=1&token=abc-DEF_123 and token=zz\n")
    log.close()
    text = log.path.read_text()
    assert "View: " in text and token not in text and "token=<hidden>" in text
    assert "abc-DEF_123" not in text and "token=zz" not in text


def test_the_log_is_readable_by_its_owner_only(tmp_path: Path) -> None:
    log = RunLog(tmp_path)
    log.close()
    assert log.path.stat().st_mode & 0o777 == 0o600


def test_a_stick_whose_logs_is_a_link_is_not_logged_to(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    stick = tmp_path / "media" / "STICK"
    stick.mkdir(parents=True)
    outside = tmp_path / "home"
    old = make_logs(outside, 25, 1)
    (stick / "logs").symlink_to(outside)
    monkeypatch.setattr("j5aio.competition.metadata.os.path.ismount", lambda p: Path(p) == stick)
    program = tmp_path / "code" / "robot.py"
    folder = choose_log_folder(program)
    assert folder == tmp_path / "code" / "j5aio-logs"
    assert "Not logging to" in caplog.text
    RunLog(folder).close()
    assert all(log.exists() for log in old)  # nothing outside the stick was rotated away
    (stick / "logs").unlink()
    (stick / "logs").write_text("a file")
    assert choose_log_folder(program) == tmp_path / "code" / "j5aio-logs"


def test_rotation_never_follows_a_link(tmp_path: Path) -> None:
    outside = tmp_path / "outside.log"
    outside.write_text("keep me")
    folder = tmp_path / "logs"
    folder.mkdir()
    (folder / "run-20200101-000000.log").symlink_to(outside)
    assert rotate(folder, max_files=1, reserve=0) == []
    assert outside.read_text() == "keep me"


def test_a_link_in_place_of_the_new_log_is_not_written_through(tmp_path: Path) -> None:
    when = datetime(2026, 11, 23, 9, 30, 0, tzinfo=UTC)
    outside = tmp_path / "outside.txt"
    outside.write_text("keep me")
    folder = tmp_path / "logs"
    folder.mkdir()
    (folder / "run-20261123-093000.log").symlink_to(outside)
    log = RunLog(folder, now=when)
    log.write("hello")
    log.close()
    assert log.path.name == "run-20261123-093000-2.log"
    assert outside.read_text() == "keep me"


def test_the_services_usercode_stick_is_preferred(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    from j5aio.competition import service_state

    stick = tmp_path / "media" / "STICK"
    stick.mkdir(parents=True)
    monkeypatch.setattr("j5aio.competition.metadata.os.path.ismount", lambda p: Path(p) == stick)
    service_state.set_usercode_path(tmp_path / "usercode")
    try:
        assert choose_log_folder(tmp_path / "robot.py") == tmp_path / "usercode" / "logs"
    finally:
        service_state.clear()
    assert choose_log_folder(tmp_path / "robot.py") == stick / "logs"


def test_a_log_that_vanishes_during_rotation_is_passed_over(tmp_path: Path) -> None:
    assert runlog._size(tmp_path / "gone.log") == 0
    assert not runlog._is_regular_file(tmp_path / "gone.log")
