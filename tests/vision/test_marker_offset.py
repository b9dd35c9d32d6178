"""The metadata's marker_offset: read by the program, never applied to marker numbers.

sr-robot3 reads astoria's ``marker_offset`` into its metadata and never uses it;
april_vision and sbot do not know it. j5aio's camera reports each marker's own number
too, and the docs say so.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest

from j5aio.competition.metadata import METADATA_VARIABLE

DOCS = Path(__file__).resolve().parents[2] / "docs"


def test_no_page_says_the_offset_is_added_to_marker_numbers() -> None:
    claims = [
        f"{page.name}: {line.strip()}"
        for page in sorted(DOCS.glob("*.rst"))
        for line in page.read_text(encoding="utf-8").splitlines()
        if "marker_offset" in line and re.search(r"\badded to marker", line)
    ]
    assert claims == []
    described = (DOCS / "competition-volunteers.rst").read_text(encoding="utf-8")
    assert "does not change the marker" in described


@pytest.mark.usefixtures("fresh_kit")
async def test_the_camera_reports_each_markers_own_number_whatever_the_offset(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
) -> None:
    pytest.importorskip("numpy")
    pytest.importorskip("cv2")
    pytest.importorskip("pyapriltags")
    from j5aio.kit import KitRobot
    from j5aio.simulator.arena import Pose
    from j5aio.simulator.camera import visible_markers
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
    from j5aio.simulator.kit import use_kit

    metadata = tmp_path / "metadata.json"
    metadata.write_text(json.dumps({"mode": "DEV", "marker_offset": 100}))
    monkeypatch.setenv(METADATA_VARIABLE, str(metadata))
    kit = use_kit()
    kit.world.place_robot(Pose(2875.0, 1000.0, math.pi / 2))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.metadata.marker_offset == 100
        assert robot.camera is not None
        truth = {marker.marker_id for marker in visible_markers(kit.world, kit.camera)}  # type: ignore[arg-type]
        seen = await robot.camera.see_ids()
    assert seen, "the robot looks at the arena's wall of markers"
    assert set(seen) <= truth  # the arena's own numbers, not shifted by 100
