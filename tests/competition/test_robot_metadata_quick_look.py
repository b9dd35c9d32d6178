"""A robot with no match metadata anywhere starts without reading any (development mode)."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from j5aio import robot as robot_module
from j5aio.competition import metadata as metadata_module
from j5aio.competition.metadata import (
    DEV_DEFAULTS,
    MEDIA_ROOTS_VARIABLE,
    METADATA_VARIABLE,
    SBOT_METADATA_VARIABLE,
    Mode,
)
from j5aio.robot import BaseRobot


@pytest.fixture(autouse=True)
def _nothing_set(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Path:
    media = tmp_path / "media"
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, str(media))
    monkeypatch.delenv(METADATA_VARIABLE, raising=False)
    monkeypatch.delenv(SBOT_METADATA_VARIABLE, raising=False)
    return media


def test_the_quick_look_reads_the_variables_and_folders_the_reader_reads() -> None:
    assert set(robot_module._METADATA_VARIABLES) == {METADATA_VARIABLE, SBOT_METADATA_VARIABLE}
    assert robot_module._MEDIA_ROOTS_VARIABLE == MEDIA_ROOTS_VARIABLE
    assert tuple(map(Path, robot_module._DEFAULT_MEDIA_ROOTS)) == (
        metadata_module.DEFAULT_MEDIA_ROOTS
    )


def test_no_variable_and_empty_or_missing_media_folders_mean_no_metadata(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, _nothing_set: Path
) -> None:
    assert not robot_module._metadata_may_be_there()  # the folder is missing
    _nothing_set.mkdir()
    empty = tmp_path / "empty"
    empty.mkdir()
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, os.pathsep.join([str(_nothing_set), "", str(empty)]))
    assert not robot_module._metadata_may_be_there()
    (empty / "STICK").mkdir()  # something mounted, maybe
    assert robot_module._metadata_may_be_there()


@pytest.mark.parametrize("variable", [METADATA_VARIABLE, SBOT_METADATA_VARIABLE])
def test_a_variable_naming_metadata_means_there_may_be_some(
    monkeypatch: pytest.MonkeyPatch, variable: str
) -> None:
    monkeypatch.setenv(variable, "/somewhere")
    assert robot_module._metadata_may_be_there()


def test_the_default_media_folders_are_looked_in(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.delenv(MEDIA_ROOTS_VARIABLE)
    stick = tmp_path / "stick"
    stick.mkdir()
    monkeypatch.setattr(robot_module, "_DEFAULT_MEDIA_ROOTS", (str(tmp_path / "none"),))
    assert not robot_module._metadata_may_be_there()
    monkeypatch.setattr(robot_module, "_DEFAULT_MEDIA_ROOTS", (str(tmp_path),))
    assert robot_module._metadata_may_be_there()


async def test_with_nothing_to_read_the_robot_is_in_development_mode_from_its_start(
    _nothing_set: Path,
) -> None:
    async with BaseRobot() as robot:
        assert robot._no_metadata_at_start
        assert robot.metadata is DEV_DEFAULTS
        assert robot.mode is Mode.DEV
        assert robot._watcher is None  # nothing to watch in development mode
    # A stick put in once the robot runs is not read: its metadata is fixed until the start.
    async with BaseRobot() as robot:
        stick = _nothing_set / "STICK"
        stick.mkdir(parents=True)
        (stick / "metadata.json").write_text(json.dumps({"zone": 2, "mode": "COMP"}))
        assert robot.zone == 0
        assert robot.metadata is DEV_DEFAULTS


async def test_metadata_there_at_the_start_is_read_at_the_start(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    path = tmp_path / "metadata.json"
    path.write_text(json.dumps({"arena": "B", "zone": 3, "mode": "DEV"}))
    monkeypatch.setenv(METADATA_VARIABLE, str(path))
    async with BaseRobot() as robot:
        assert not robot._no_metadata_at_start
        assert robot._metadata is not None and robot._metadata.zone == 3
        path.write_text("not JSON")  # read once, at the start
        assert robot.zone == 3


def test_the_match_names_are_imported_when_first_looked_up() -> None:
    from j5aio.competition.start import wait_for_start
    from j5aio.competition.timer import MatchTimer

    assert robot_module._wait_for_start() is wait_for_start
    assert robot_module._match_timer() is MatchTimer
    with pytest.raises(AttributeError, match="has no attribute 'nothing_here'"):
        robot_module.nothing_here  # noqa: B018
