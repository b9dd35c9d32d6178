"""Tests of the match metadata: parsing, validation, where the file is found."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from j5aio.competition.metadata import (
    DEV_DEFAULTS,
    MEDIA_ROOTS_VARIABLE,
    METADATA_VARIABLE,
    SBOT_METADATA_VARIABLE,
    Metadata,
    MetadataError,
    Mode,
    describe,
    detect_format,
    find_metadata_file,
    find_usb_sticks,
    load_metadata,
    media_roots,
    parse_astoria_metadata,
    parse_metadata,
    parse_sbot_metadata,
    read_metadata_file,
)

COMP = {"arena": "B", "zone": 2, "mode": "COMP", "duration": 150, "marker_offset": 100}


@pytest.fixture(autouse=True)
def _no_outside_files(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.delenv(METADATA_VARIABLE, raising=False)
    monkeypatch.delenv(SBOT_METADATA_VARIABLE, raising=False)
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, str(tmp_path / "no-media"))


def write(path: Path, data: object) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data))
    return path


def test_a_full_comp_file() -> None:
    metadata = parse_metadata(COMP, Path("/stick/metadata.json"))
    assert metadata == Metadata("B", 2, Mode.COMP, 150.0, 100, Path("/stick/metadata.json"))
    assert metadata.is_competition
    assert "zone 2" in describe(metadata) and "150 s" in describe(metadata)


def test_dev_fills_in_missing_fields() -> None:
    metadata = parse_metadata({"zone": 3})
    assert (metadata.arena, metadata.zone, metadata.mode, metadata.duration) == (
        "A", 3, Mode.DEV, None,
    )
    assert not metadata.is_competition
    assert "no time limit" in describe(metadata) and "defaults" in describe(DEV_DEFAULTS)


def test_mode_is_case_insensitive_and_null_duration_is_no_limit() -> None:
    metadata = parse_metadata({**COMP, "mode": "comp", "duration": None})
    assert metadata.mode is Mode.COMP and metadata.duration is None


@pytest.mark.parametrize("field", sorted(COMP))
def test_comp_never_defaults_a_field(field: str) -> None:
    data = {k: v for k, v in COMP.items() if k != field}
    if field == "mode":
        return  # without a mode it is DEV
    with pytest.raises(MetadataError, match=rf"x.json: in COMP mode every field.*'{field}'"):
        parse_metadata(data, Path("x.json"))


@pytest.mark.parametrize(
    ("field", "value", "allowed"),
    [
        ("zone", -1, "whole number from 0 to 99"),
        ("zone", True, "whole number"),
        ("zone", 1.5, "whole number"),
        ("arena", "", "string of 1 to 32"),
        ("arena", 7, "string of 1 to 32"),
        ("arena", " A", "no surrounding spaces"),
        ("mode", "MATCH", '"COMP" or "DEV"'),
        ("mode", 1, '"COMP" or "DEV"'),
        ("duration", 0, "from 0.1 to 3600"),
        ("duration", 1e-300, "from 0.1 to 3600"),
        ("duration", "150", "from 0.1 to 3600"),
        ("duration", 1e9, "from 0.1 to 3600"),
        ("marker_offset", -5, "from 0 to 10000"),
    ],
)
def test_bad_fields_name_file_field_and_what_is_allowed(
    field: str, value: object, allowed: str
) -> None:
    with pytest.raises(MetadataError) as caught:
        parse_metadata({**COMP, field: value}, Path("/media/stick/metadata.json"))
    message = str(caught.value)
    assert message.startswith("/media/stick/metadata.json:")
    assert repr(field) in message or field in message
    assert allowed in message


def test_not_an_object() -> None:
    with pytest.raises(MetadataError, match=r"must hold a JSON object.*not a list"):
        parse_metadata([1, 2])


def test_direct_construction_is_checked() -> None:
    with pytest.raises(MetadataError, match="'zone'"):
        Metadata(zone=500)
    with pytest.raises(MetadataError, match="mode must be a Mode"):
        Metadata(mode="COMP")  # type: ignore[arg-type]
    with pytest.raises(MetadataError, match="'duration'"):
        Metadata(duration=float("nan"))


def test_unknown_fields_are_refused_in_comp_and_logged_in_dev(
    caplog: pytest.LogCaptureFixture,
) -> None:
    with pytest.raises(MetadataError, match=r"in COMP mode.*unknown: 'durration'.*allowed"):
        parse_metadata({**COMP, "durration": 150})
    caplog.set_level("INFO")
    assert parse_metadata({"zone": 2, "wifi": "x"}).zone == 2
    assert "wifi" in caplog.text


def test_unreadable_and_malformed_files(tmp_path: Path) -> None:
    with pytest.raises(MetadataError, match="cannot be read"):
        read_metadata_file(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{zone: 2")
    with pytest.raises(MetadataError, match=r"bad.json: is not valid JSON"):
        read_metadata_file(bad)
    bad.write_bytes(b"\xff\xfe{}")
    with pytest.raises(MetadataError, match="not UTF-8"):
        read_metadata_file(bad)
    bad.write_text("[" * 100_000)
    with pytest.raises(MetadataError, match="larger than"):
        read_metadata_file(bad)
    bad.write_text("[" * 20_000 + "]" * 20_000)
    with pytest.raises(MetadataError, match=r"not valid JSON|must hold a JSON object"):
        read_metadata_file(bad)


def test_environment_variable_wins(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    named = write(tmp_path / "here.json", COMP)
    monkeypatch.setenv(METADATA_VARIABLE, str(named))
    assert find_metadata_file([]) == named
    assert load_metadata([]).source == named
    monkeypatch.setenv(SBOT_METADATA_VARIABLE, str(tmp_path / "not-used"))
    assert load_metadata([]).source == named  # J5AIO_METADATA wins over sbot's folder
    monkeypatch.setenv(METADATA_VARIABLE, str(tmp_path / "gone.json"))
    with pytest.raises(MetadataError, match=r"gone.json: no such file.*J5AIO_METADATA"):
        load_metadata([])


def test_sticks_are_mount_points_one_or_two_levels_down(tmp_path: Path) -> None:
    (tmp_path / "media" / "STICK").mkdir(parents=True)
    (tmp_path / "run" / "robot" / "USB").mkdir(parents=True)
    (tmp_path / "run" / "robot" / "notmounted").mkdir()
    mounts = {tmp_path / "media" / "STICK", tmp_path / "run" / "robot" / "USB"}
    found = find_usb_sticks(
        [tmp_path / "media", tmp_path / "run", tmp_path / "absent"],
        is_mount=lambda path: path in mounts,
    )
    assert found == sorted(mounts)


def test_media_roots_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, os.pathsep.join(["/a", "", "/b"]))
    assert media_roots() == [Path("/a"), Path("/b")]
    monkeypatch.delenv(MEDIA_ROOTS_VARIABLE)
    assert media_roots() == [Path("/media"), Path("/run/media")]


def test_sticks_that_agree_are_fine_and_disagreeing_ones_an_error(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    empty, first, second = tmp_path / "a", tmp_path / "b", tmp_path / "c"
    empty.mkdir()
    write(first / "metadata.json", COMP)
    write(second / "metadata.json", COMP)
    caplog.set_level("INFO")
    assert load_metadata([empty, first, second]).source == first / "metadata.json"
    assert "Metadata files agree" in caplog.text
    write(second / "metadata.json", {"zone": 1})
    with pytest.raises(MetadataError, match=r"c/metadata.json: disagrees with .*b/metadata"):
        load_metadata([empty, first, second])
    assert load_metadata([empty]) is DEV_DEFAULTS


@settings(max_examples=150, deadline=None)
@given(
    st.recursive(
        st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=40),
        lambda inner: st.lists(inner, max_size=4)
        | st.dictionaries(st.text(max_size=12), inner, max_size=6),
        max_leaves=12,
    )
    | st.fixed_dictionaries(
        {},
        optional={
            "arena": st.text(max_size=40) | st.integers(),
            "zone": st.integers() | st.floats() | st.text(max_size=3) | st.booleans(),
            "mode": st.sampled_from(["COMP", "DEV", "comp", "x", ""]) | st.integers(),
            "duration": st.none() | st.floats() | st.integers() | st.text(max_size=3),
            "marker_offset": st.integers() | st.floats(),
        },
    )
)
def test_fuzzed_files_give_metadata_or_a_clear_error(data: object) -> None:
    try:
        metadata = parse_metadata(data, Path("fuzz.json"))
    except MetadataError as error:
        assert str(error).startswith("fuzz.json: ")
        assert "must" in str(error) or "missing" in str(error)
    else:
        assert 0 <= metadata.zone <= 99
        assert metadata.duration is None or 0.1 <= metadata.duration <= 3600


@settings(max_examples=100, deadline=None)
@given(st.binary(max_size=200) | st.text(max_size=200).map(str.encode))
def test_fuzzed_bytes_give_metadata_or_a_clear_error(raw: bytes) -> None:
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "metadata.json"
        path.write_bytes(raw)
        try:
            read_metadata_file(path)
        except MetadataError as error:
            assert str(error).startswith(f"{path}: ")


ASTORIA = {
    "arena": "B",
    "zone": 2,
    "mode": "COMP",
    "marker_offset": 100,
    "game_timeout": 150,
    "wifi_enabled": False,
}
#: An astmetad status message's metadata object: the disk's fields and the software's.
ASTMETAD_MESSAGE = {
    **ASTORIA,
    "astoria_version": "0.11.3",
    "kernel_version": "6.1.0",
    "arch": "aarch64",
    "python_version": "3.11.2",
    "libc_ver": "glibc2.36",
    "os_name": "Student Robotics OS",
    "os_pretty_name": None,
    "os_version": "2026.1",
    "usercode_entrypoint": "robot.py",
    "wifi_ssid": "robot-ABC",
    "wifi_psk": "secret-password",
    "wifi_region": "GB",
}


def test_astoria_file_fields_become_metadata() -> None:
    metadata = parse_astoria_metadata(ASTORIA, Path("/media/meta/astoria.json"))
    assert metadata == Metadata(
        "B", 2, Mode.COMP, 150.0, 100, Path("/media/meta/astoria.json"), wifi_enabled=False
    )
    assert "150 s" in describe(metadata) and "astoria.json" in describe(metadata)


def test_astoria_message_metadata_is_read_and_the_password_is_not_kept() -> None:
    metadata = parse_astoria_metadata(ASTMETAD_MESSAGE, "astmetad message")
    assert (metadata.zone, metadata.mode, metadata.duration) == (2, Mode.COMP, 150.0)
    assert metadata.source is None and metadata.origin == "astmetad message"
    assert "from astmetad message" in describe(metadata)
    assert "secret-password" not in repr(metadata)


def test_astoria_defaults_are_astorias() -> None:
    metadata = parse_astoria_metadata({}, None)
    assert metadata == Metadata(wifi_enabled=True)
    assert parse_astoria_metadata({"mode": "COMP", "game_timeout": None}).duration is None
    assert parse_astoria_metadata({"mode": "COMP", "game_timeout": 0}).duration is None


@pytest.mark.parametrize(
    ("field", "value", "allowed"),
    [
        ("zone", "2", "whole number from 0 to 99"),
        ("zone", 100, "whole number from 0 to 99"),
        ("zone", False, "whole number"),
        ("arena", None, "string of 1 to 32"),
        ("mode", "comp", '"COMP" or "DEV"'),
        ("mode", None, '"COMP" or "DEV"'),
        ("marker_offset", 1.0, "from 0 to 10000"),
        ("game_timeout", 150.5, "whole number of seconds from 0 to 3600, or null"),
        ("game_timeout", "150", "whole number of seconds"),
        ("game_timeout", -1, "whole number of seconds"),
        ("game_timeout", True, "whole number of seconds"),
        ("wifi_enabled", 1, "true or false"),
        ("wifi_psk", 12345678, "text or null"),
    ],
)
def test_astoria_bad_fields_name_source_field_and_what_is_allowed(
    field: str, value: object, allowed: str
) -> None:
    with pytest.raises(MetadataError) as caught:
        parse_astoria_metadata({**ASTORIA, field: value}, Path("/m/astoria.json"))
    message = str(caught.value)
    assert message.startswith("/m/astoria.json: field ")
    assert repr(field) in message and allowed in message


def test_astoria_unknown_keys_are_refused_in_comp_and_logged_in_dev(
    caplog: pytest.LogCaptureFixture,
) -> None:
    with pytest.raises(MetadataError, match=r"astmetad: in COMP mode.*unknown: 'game_timout'"):
        parse_astoria_metadata({"mode": "COMP", "game_timout": 150}, "astmetad")
    caplog.set_level("INFO")
    assert parse_astoria_metadata({"game_timout": 150}).mode is Mode.DEV
    assert "game_timout" in caplog.text


def test_astoria_not_an_object() -> None:
    with pytest.raises(MetadataError, match=r"^astoria metadata: must hold a JSON object"):
        parse_astoria_metadata("COMP", None)


def test_metadata_wifi_enabled_is_checked() -> None:
    with pytest.raises(MetadataError, match="'wifi_enabled' must be true, false or null"):
        Metadata(wifi_enabled="yes")  # type: ignore[arg-type]


# -- sbot's format, format detection, where files are found ---------------------------


def test_sbot_file_is_read_as_a_match() -> None:
    metadata = parse_sbot_metadata({"zone": 2, "is_competition": True}, Path("/s/metadata.json"))
    assert metadata == Metadata(
        zone=2, mode=Mode.COMP, duration=150.0, source=Path("/s/metadata.json")
    )
    assert parse_sbot_metadata({"zone": 1, "is_competition": False}, "x").duration is None


@pytest.mark.parametrize(
    ("data", "message"),
    [
        ({"zone": 2}, "needs both 'zone' and 'is_competition'; missing: 'is_competition'"),
        ({"is_competition": True}, "missing: 'zone'"),
        ({"zone": 2, "is_competition": "yes"}, "'is_competition' must be true or false"),
        ({"zone": 2, "is_competition": 1}, "'is_competition' must be true or false"),
        ({"zone": 7.0, "is_competition": True}, "'zone' must be a whole number from 0 to 99"),
        ({"zone": 200, "is_competition": True}, "'zone' must be a whole number from 0 to 99"),
        ({"zone": 2, "is_competition": True, "zome": 3}, "unknown: 'zome'; allowed"),
        ([], "must hold a JSON object like"),
    ],
)
def test_sbot_bad_files_name_the_file_and_field(data: object, message: str) -> None:
    with pytest.raises(MetadataError) as caught:
        parse_sbot_metadata(data, Path("/s/metadata.json"))
    assert str(caught.value).startswith("/s/metadata.json: ")
    assert message in str(caught.value)


def test_sbot_unknown_fields_outside_a_match_are_logged(
    caplog: pytest.LogCaptureFixture,
) -> None:
    caplog.set_level("INFO")
    assert parse_sbot_metadata({"zone": 1, "is_competition": False, "note": 1}).zone == 1
    assert "note" in caplog.text


@pytest.mark.parametrize(
    ("name", "data", "expected"),
    [
        ("metadata.json", {"zone": 2, "is_competition": True}, (2, Mode.COMP, 150.0)),
        ("metadata.json", {"zone": 1, "mode": "COMP", "game_timeout": 120}, (1, Mode.COMP, 120.0)),
        ("metadata.json", COMP, (2, Mode.COMP, 150.0)),
        ("metadata.json", {"zone": 3}, (3, Mode.DEV, None)),
        ("astoria.json", {"zone": 1, "mode": "COMP", "game_timeout": 90}, (1, Mode.COMP, 90.0)),
        ("astoria.json", {"zone": 1, "mode": "COMP"}, (1, Mode.COMP, None)),
    ],
)
def test_each_format_is_read_from_its_file(
    tmp_path: Path, name: str, data: object, expected: tuple[object, ...]
) -> None:
    metadata = read_metadata_file(write(tmp_path / name, data))
    assert (metadata.zone, metadata.mode, metadata.duration) == expected


@pytest.mark.parametrize(
    ("data", "message"),
    [
        ({**COMP, "game_timeout": 150}, "mixes the fields of j5aio's format ('duration') and "
         "astoria's format ('game_timeout')"),
        ({"zone": 1, "is_competition": True, "duration": 5}, "mixes the fields"),
        ({"arena": "A", "zone": 1, "mode": "COMP", "marker_offset": 0},
         "in COMP mode the file must say how long the match is"),
    ],
)
def test_ambiguous_files_are_refused(tmp_path: Path, data: object, message: str) -> None:
    path = write(tmp_path / "metadata.json", data)
    with pytest.raises(MetadataError, match="^" + str(path)) as caught:
        read_metadata_file(path)
    assert message in str(caught.value)


def test_detect_format_of_a_non_object_is_j5aios() -> None:
    assert detect_format([1], Path("metadata.json")).value == "j5aio"
    assert detect_format([1], Path("astoria.json")).value == "astoria"


def test_astoria_json_on_a_stick_is_found(tmp_path: Path) -> None:
    stick = tmp_path / "META"
    write(stick / "astoria.json", {"mode": "COMP", "zone": 3, "game_timeout": 150})
    metadata = load_metadata([stick])
    assert (metadata.zone, metadata.mode, metadata.source) == (
        3, Mode.COMP, stick / "astoria.json"
    )


def test_a_stick_with_both_files_must_agree(tmp_path: Path) -> None:
    stick = tmp_path / "META"
    write(stick / "astoria.json", {"mode": "COMP", "zone": 3, "game_timeout": 150})
    write(stick / "metadata.json", {"zone": 3, "is_competition": True})
    assert load_metadata([stick]).zone == 3  # the same match, said twice
    write(stick / "metadata.json", {"zone": 1, "is_competition": True})
    with pytest.raises(MetadataError, match=r"astoria\.json: disagrees with"):
        load_metadata([stick])


def test_sbot_metadata_path_is_a_folder_searched_one_level_down(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    folder = tmp_path / "sbot"
    write(folder / "USB0" / "metadata.json", {"zone": 1, "is_competition": True})
    write(tmp_path / "stick" / "metadata.json", {"zone": 3})
    monkeypatch.setenv(SBOT_METADATA_VARIABLE, str(folder))
    assert load_metadata([tmp_path / "stick"]).zone == 1  # sbot's folder wins over sticks
    write(folder / "astoria.json", {"zone": 1, "mode": "COMP", "game_timeout": 150})
    assert load_metadata([]).source == folder / "astoria.json"  # its top first
    monkeypatch.setenv(SBOT_METADATA_VARIABLE, str(tmp_path / "absent"))
    with pytest.raises(MetadataError, match=r"absent: no such directory.*SBOT_METADATA_PATH"):
        load_metadata([])
    monkeypatch.setenv(SBOT_METADATA_VARIABLE, str(tmp_path / "stick" / "metadata.json"))
    with pytest.raises(MetadataError, match="no such directory"):
        load_metadata([])


def test_an_empty_sbot_folder_leaves_the_sticks(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    (tmp_path / "sbot").mkdir()
    write(tmp_path / "stick" / "metadata.json", {"zone": 3})
    monkeypatch.setenv(SBOT_METADATA_VARIABLE, str(tmp_path / "sbot"))
    assert load_metadata([tmp_path / "stick"]).zone == 3


def test_the_services_metadata_wins_over_every_file(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    from j5aio.competition import service_state

    monkeypatch.setenv(METADATA_VARIABLE, str(write(tmp_path / "m.json", COMP)))
    live = parse_astoria_metadata({"zone": 3, "mode": "COMP", "game_timeout": 150}, "astmetad")
    service_state.set_metadata(live)
    try:
        assert load_metadata([]) is live
    finally:
        service_state.clear()
    assert load_metadata([]).zone == 2


# -- files that are not what they seem --------------------------------------------------


def test_duplicate_keys_are_refused(tmp_path: Path) -> None:
    path = tmp_path / "metadata.json"
    path.write_text('{"zone": 1, "is_competition": true, "zone": 3}')
    with pytest.raises(MetadataError, match=r"metadata.json: field 'zone' is given more than once"):
        read_metadata_file(path)


def test_a_byte_order_mark_is_allowed(tmp_path: Path) -> None:
    path = tmp_path / "metadata.json"
    path.write_bytes(b"\xef\xbb\xbf" + json.dumps({"zone": 2, "is_competition": True}).encode())
    assert read_metadata_file(path).zone == 2


@pytest.mark.parametrize("kind", ["directory", "fifo", "link to /", "broken link"])
def test_a_metadata_file_that_is_not_a_file_is_an_error_not_dev_mode(
    tmp_path: Path, kind: str
) -> None:
    stick = tmp_path / "stick"
    stick.mkdir()
    path = stick / "metadata.json"
    if kind == "directory":
        path.mkdir()
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "link to /":
        path.symlink_to("/")
    else:
        path.symlink_to(tmp_path / "nowhere")
    with pytest.raises(MetadataError, match=f"^{path}: ") as caught:
        load_metadata([stick])
    assert "regular file" in str(caught.value) or "cannot be read" in str(caught.value)


def test_a_link_to_a_regular_file_is_followed(tmp_path: Path) -> None:
    target = write(tmp_path / "real.json", {"zone": 4})
    (tmp_path / "stick").mkdir()
    (tmp_path / "stick" / "metadata.json").symlink_to(target)
    assert load_metadata([tmp_path / "stick"]).zone == 4


def test_a_device_is_refused() -> None:
    with pytest.raises(MetadataError, match=r"/dev/null: must be a regular file.*not a device"):
        read_metadata_file(Path("/dev/null"))


def test_an_unreadable_file_is_an_error(tmp_path: Path) -> None:
    path = write(tmp_path / "stick" / "metadata.json", {"zone": 1})
    path.chmod(0)
    if os.access(path, os.R_OK):
        pytest.skip("running as root: every file is readable")
    with pytest.raises(MetadataError, match="cannot be read"):
        load_metadata([tmp_path / "stick"])


def test_a_file_that_fails_while_read_is_an_error() -> None:
    mem = Path("/proc/self/mem")  # a regular file whose first bytes cannot be read
    if not mem.exists():
        pytest.skip("needs Linux's /proc/self/mem")
    with pytest.raises(MetadataError, match="/proc/self/mem: cannot be read"):
        read_metadata_file(mem)


def test_in_sbots_folder_metadata_json_is_sbots_format(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    write(tmp_path / "stick" / "metadata.json", {"zone": 2})
    assert load_metadata([tmp_path / "stick"]).zone == 2  # on a stick: j5aio's, DEV
    monkeypatch.setenv(SBOT_METADATA_VARIABLE, str(tmp_path / "stick"))
    with pytest.raises(MetadataError, match="missing: 'is_competition'"):
        load_metadata([])  # sbot's folder: sbot's format, which needs both fields
