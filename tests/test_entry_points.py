"""Finding a group's entry points without importlib.metadata, as importlib.metadata does."""

from __future__ import annotations

import importlib.metadata
import os
import sys
import zipfile
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from j5aio import _entry_points
from j5aio._entry_points import PluginEntryPoint, find


def by_importlib_metadata(group: str) -> list[tuple[str, str, str]]:
    return [
        (e.name, e.value, e.dist.name if e.dist is not None else "?")
        for e in importlib.metadata.entry_points(group=group)
    ]


def as_tuples(found: list[PluginEntryPoint]) -> list[tuple[str, str, str]]:
    return [(e.name, e.value, e.package) for e in found]


@pytest.mark.parametrize("group", ["j5aio.boards", "console_scripts", "pytest11"])
def test_the_installed_entry_points_are_those_importlib_metadata_finds(group: str) -> None:
    expected = by_importlib_metadata(group)
    assert as_tuples(find(group)) == expected
    if group == "j5aio.boards":
        assert ("beekit", "beekit.kinds:entries", "beekit") in expected  # the example kit


def distribution(folder: Path, stem: str, entry_points: str, name: str | None = None) -> None:
    info = folder / f"{stem}.dist-info"
    info.mkdir(parents=True)
    (info / "entry_points.txt").write_text(entry_points, encoding="utf-8")
    if name is not None:
        (info / "METADATA").write_text(
            f"Metadata-Version: 2.1\nName: {name}\nVersion: 1.0\n\nName: not this one\n",
            encoding="utf-8",
        )


@pytest.fixture
def path(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    first, second = tmp_path / "first", tmp_path / "second"
    module = tmp_path / "code"
    module.mkdir()
    (module / "plugin_for_test.py").write_text(
        "class Holder:\n    class Inner:\n        value = 42\n\ndef entries():\n    return 7\n",
        encoding="utf-8",
    )
    distribution(
        first,
        "Bee_Kit-1.0",
        "# a comment\n; another\n[console_scripts]\nbee = bee:main\n\n"
        "[test.group]\n  one = plugin_for_test:entries\n"
        "two=plugin_for_test:Holder.Inner [extra]\n",
        name="bee-kit",
    )
    # The same distribution again later on the path: hidden, as importlib.metadata does.
    distribution(second, "bee_kit-0.9", "[test.group]\nold = plugin_for_test:entries\n")
    distribution(second, "nameless-2.0", "[test.group]\nthree = plugin_for_test\n", "nameless")
    (second / "unrelated.txt").write_text("", encoding="utf-8")
    monkeypatch.setattr(
        sys,
        "path",
        [str(module), str(first), str(tmp_path / "missing"), str(second)],
    )
    monkeypatch.delitem(sys.modules, "plugin_for_test", raising=False)
    yield tmp_path


@pytest.mark.usefixtures("path")
def test_a_group_is_read_from_the_path_in_order_first_distribution_winning() -> None:
    found = find("test.group")
    assert as_tuples(found) == [
        ("one", "plugin_for_test:entries", "bee-kit"),
        ("two", "plugin_for_test:Holder.Inner [extra]", "bee-kit"),
        ("three", "plugin_for_test", "nameless"),
    ]
    assert as_tuples(found) == by_importlib_metadata("test.group")
    assert found[0].load()() == 7  # type: ignore[operator]
    assert found[1].load().value == 42  # type: ignore[attr-defined]
    assert found[2].load() is sys.modules["plugin_for_test"]
    assert find("no.such.group") == []


def test_a_line_that_is_no_entry_point_is_passed_over(path: Path) -> None:
    entry_points = path / "second" / "nameless-2.0.dist-info" / "entry_points.txt"
    entry_points.write_text("[test.group]\nnot an entry\nthree = plugin_for_test\n")
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]


def test_an_entry_point_naming_nothing_fails_to_load() -> None:
    with pytest.raises(ModuleNotFoundError):
        PluginEntryPoint("x", "no_module_called_this:thing", "pkg").load()
    with pytest.raises(AttributeError):
        PluginEntryPoint("x", "json:no_such_function", "pkg").load()


def put_a_zipped_plugin_on_the_path(path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A zip file holding a distribution with one entry point of test.group, on the path."""
    archive = path / "plugins.zip"
    with zipfile.ZipFile(archive, "w") as zipped:
        zipped.writestr("zipped-1.0.dist-info/entry_points.txt", "[test.group]\nz = zmod:z\n")
        zipped.writestr("zipped-1.0.dist-info/METADATA", "Name: zipped\nVersion: 1.0\n")
    monkeypatch.setattr(sys, "path", [*sys.path, str(archive)])


def test_a_zip_on_the_path_is_left_to_importlib_metadata(
    path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    put_a_zipped_plugin_on_the_path(path, monkeypatch)
    assert ("z", "zmod:z", "zipped") in as_tuples(find("test.group"))


@pytest.mark.usefixtures("path")
def test_an_import_hook_listing_distributions_is_left_to_importlib_metadata(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    asked = []

    class Finder:
        @staticmethod
        def find_spec(*args: object) -> None:
            return None

        @staticmethod
        def find_distributions(*args: object, **kwargs: object) -> list[object]:
            asked.append(True)
            return []

    monkeypatch.setattr(sys, "meta_path", [*sys.meta_path, Finder])
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert asked


def test_unreadable_files_are_passed_over(path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (path / "second" / "nameless-2.0.dist-info" / "entry_points.txt").write_bytes(b"\xff\xfe[")
    monkeypatch.setattr(os, "listdir", _listdir_failing_for(path / "first"))
    # The first folder unseen, the older copy of bee-kit is no longer hidden.
    assert as_tuples(find("test.group")) == [("old", "plugin_for_test:entries", "bee_kit")]


def _listdir_failing_for(folder: Path) -> Callable[[str], list[str]]:
    real = os.listdir

    def listdir(target: str) -> list[str]:
        if Path(target) == folder:
            raise PermissionError(target)
        names: list[str] = real(target)
        return names

    return listdir


def test_dotted_folder_names_and_distributions_without_the_group_are_read_as_importlib_does(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    group = "[test.group]\n"
    distribution(tmp_path, "spaced.kit-1.0", f"{group}sp = plugin_for_test:entries\n", "spaced.kit")
    distribution(tmp_path, "spaced_kit-0.5", f"{group}old = plugin_for_test:e\n", "spaced_kit")
    distribution(tmp_path, "other-1.0", "[console_scripts]\nx = y:z\n", "other")
    (tmp_path / "bare-1.0.dist-info").mkdir()  # no entry_points.txt at all
    monkeypatch.setattr(sys, "path", [str(tmp_path)])
    found = as_tuples(find("test.group"))
    assert len(found) == 1  # (two spellings of one distribution: the first listed wins)
    assert found == by_importlib_metadata("test.group")
    assert as_tuples(find("console_scripts")) == by_importlib_metadata("console_scripts")


def test_an_entry_point_is_a_value_with_a_readable_repr() -> None:
    one = PluginEntryPoint("beekit", "beekit.kinds:entries", "beekit")
    assert one == PluginEntryPoint("beekit", "beekit.kinds:entries", "beekit")
    assert one != PluginEntryPoint("beekit", "beekit.kinds:entries", "other")
    assert one != ("beekit", "beekit.kinds:entries", "beekit")
    assert len({one, PluginEntryPoint("beekit", "beekit.kinds:entries", "beekit")}) == 1
    assert repr(one) == (
        "PluginEntryPoint(name='beekit', value='beekit.kinds:entries', package='beekit')"
    )


def test_entry_points_that_cannot_be_read_or_decoded_are_passed_over(path: Path) -> None:
    nameless = path / "second" / "nameless-2.0.dist-info" / "entry_points.txt"
    # Naming the group, but not UTF-8.
    nameless.write_bytes(b"[test.group]\nthree = plugin_for_test \xff\n")
    assert [e.name for e in find("test.group")] == ["one", "two"]
    # A folder where the file should be: opened, but not read.
    nameless.unlink()
    nameless.mkdir()
    assert [e.name for e in find("test.group")] == ["one", "two"]


def test_a_long_entry_points_file_is_read_to_its_end(path: Path) -> None:
    nameless = path / "second" / "nameless-2.0.dist-info" / "entry_points.txt"
    filler = "".join(f"script{number} = module:main\n" for number in range(8000))
    nameless.write_text(
        f"[console_scripts]\n{filler}[test.group]\nthree = plugin_for_test\n", encoding="utf-8"
    )
    assert len(filler) > 3 * 65536
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]


def test_a_file_naming_the_group_elsewhere_than_its_header_gives_nothing(path: Path) -> None:
    nameless = path / "second" / "nameless-2.0.dist-info" / "entry_points.txt"
    nameless.write_text("[console_scripts]\ntest.group = plugin_for_test\n", encoding="utf-8")
    assert [e.name for e in find("test.group")] == ["one", "two"]
    nameless.write_text("[test.group]\n# none yet\n", encoding="utf-8")
    assert [e.name for e in find("test.group")] == ["one", "two"]


def test_a_file_gone_between_asking_and_opening_is_passed_over(
    path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (path / "second" / "nameless-2.0.dist-info" / "entry_points.txt").unlink()
    monkeypatch.setattr(os, "access", lambda *args, **kwargs: True)  # (every file "is there")
    assert [e.name for e in find("test.group")] == ["one", "two"]


# --- the answer remembered between programs ---

LONG_AGO = 1_600_000_000  # (2020: a time every folder of a test can be set back to)


def settle(*paths: Path) -> None:
    """Set the modification times of ``paths`` (and what is in them) well in the past."""
    for path in paths:
        for inner in [path, *path.rglob("*")]:
            os.utime(inner, (LONG_AGO, LONG_AGO))


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    folder = tmp_path / "cache"
    monkeypatch.setenv("J5AIO_CACHE_DIR", str(folder))
    return folder


def scans(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """Count the path's scans from now on (each group scanned is added)."""
    seen: list[str] = []
    real = _entry_points._scan

    def scan(group: str, holders: list[str] | None = None) -> list[PluginEntryPoint] | None:
        seen.append(group)
        return real(group, holders)

    monkeypatch.setattr(_entry_points, "_scan", scan)
    return seen


def test_an_answer_is_remembered_and_read_again_while_the_path_is_unchanged(
    path: Path,
    cache: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    settle(path)
    seen = scans(monkeypatch)
    first = find("test.group")
    assert [e.name for e in first] == ["one", "two", "three"]
    assert len(list(cache.iterdir())) == 1
    assert find("test.group") == first  # (read back: no second scan)
    assert find("test.group") == first
    assert seen == ["test.group"]
    # Another group is remembered beside it.
    assert find("no.such.group") == []
    assert find("no.such.group") == []
    assert seen == ["test.group", "no.such.group"]
    assert len(list(cache.iterdir())) == 2


def test_a_distribution_installed_later_is_found(
    path: Path,
    cache: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    settle(path)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    distribution(path / "second", "wasp-1.0", "[test.group]\nwasp = plugin_for_test\n", "wasp")
    settle(path / "second" / "wasp-1.0.dist-info")  # (the folder holding it is new)
    seen = scans(monkeypatch)
    # (in the order the folder lists them, as importlib.metadata gives them)
    assert sorted(e.name for e in find("test.group")) == ["one", "three", "two", "wasp"]
    assert seen == ["test.group"]
    # Removed again, it is gone (the folder changed again; settled at another time).
    for file in (path / "second" / "wasp-1.0.dist-info").iterdir():
        file.unlink()
    (path / "second" / "wasp-1.0.dist-info").rmdir()
    os.utime(path / "second", (LONG_AGO + 5, LONG_AGO + 5))
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]


def test_a_changed_file_naming_the_group_is_read_again(path: Path, cache: Path) -> None:
    settle(path)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    entry_points = path / "second" / "nameless-2.0.dist-info" / "entry_points.txt"
    entry_points.write_text("[test.group]\nfour = plugin_for_test\n", encoding="utf-8")
    os.utime(entry_points, (LONG_AGO, LONG_AGO))  # (its size tells it apart)
    assert [e.name for e in find("test.group")] == ["one", "two", "four"]


def test_a_file_naming_the_group_that_is_gone_is_noticed(path: Path, cache: Path) -> None:
    settle(path)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    (path / "second" / "nameless-2.0.dist-info" / "entry_points.txt").unlink()
    settle(path)
    assert [e.name for e in find("test.group")] == ["one", "two"]


def test_a_folder_that_became_a_file_while_being_read_is_left_to_importlib_metadata(
    path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    put_a_zipped_plugin_on_the_path(path, monkeypatch)
    monkeypatch.setattr(_entry_points, "_folder_states", lambda: [])  # (seen as a folder)
    assert ("z", "zmod:z", "zipped") in as_tuples(find("test.group"))


def test_a_path_of_other_folders_is_scanned_again(
    path: Path,
    cache: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    settle(path)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    monkeypatch.setattr(sys, "path", [str(path / "code"), str(path / "second")])
    assert [e.name for e in find("test.group")] == ["old", "three"]


def test_folders_changed_a_moment_ago_are_not_remembered(
    path: Path,
    cache: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # (the fixture's folders were made just now: a change within the same tick of the
    # file system's clock might not show in their times)
    seen = scans(monkeypatch)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert seen == ["test.group", "test.group"]
    assert not cache.exists()


def test_remembering_can_be_turned_off(
    path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    settle(path)
    monkeypatch.setenv("J5AIO_CACHE_DIR", "")
    seen = scans(monkeypatch)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert seen == ["test.group", "test.group"]


@pytest.mark.parametrize(
    "text",
    [
        "",
        "j5aio entry points 1\n",
        "something else\n",
        "\xff\xfe",
        "j5aio entry points 1\ntest.group\n4\n{folders}\n0\nlots\n",
        "j5aio entry points 1\ntest.group\n4\n{folders}\n"
        "0\n2\none\tplugin_for_test:entries\tbee-kit\n",
        "j5aio entry points 1\ntest.group\n4\n{folders}\n"
        "0\n2\none\tplugin_for_test:entries\tbee-kit\ntwo\tplugin_for_test:entries\tbee-kit",
        "j5aio entry points 1\ntest.group\n4\n{folders}\n"
        "0\n1\none\tplugin_for_test:entries\tbee-kit\nmore\n",
    ],
)
def test_a_cache_file_that_does_not_read_back_is_written_again(
    path: Path,
    cache: Path,
    monkeypatch: pytest.MonkeyPatch,
    text: str,
) -> None:
    settle(path)
    find("test.group")
    (remembered,) = cache.iterdir()
    folders = remembered.read_text(encoding="utf-8").split("\n")[3:7]
    remembered.write_bytes(text.format(folders="\n".join(folders)).encode("utf-8", "replace"))
    seen = scans(monkeypatch)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert seen == ["test.group"]


def test_a_cache_folder_that_cannot_be_written_is_passed_over(
    path: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    settle(path)
    blocker = tmp_path / "a-file"
    blocker.write_text("", encoding="utf-8")
    monkeypatch.setenv("J5AIO_CACHE_DIR", str(blocker / "cache"))
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert list(tmp_path.glob("**/*.tmp")) == []


def test_names_that_would_not_read_back_are_not_remembered(
    path: Path,
    cache: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    entry_points = path / "second" / "nameless-2.0.dist-info" / "entry_points.txt"
    entry_points.write_text("[test.group]\nthree = plugin\tfor_test\n", encoding="utf-8")
    settle(path)
    assert [e.value for e in find("test.group")][-1] == "plugin\tfor_test"
    assert not cache.exists()
    tabbed = path / "tab\tbed"
    tabbed.mkdir()
    settle(tabbed)
    monkeypatch.setattr(sys, "path", [str(tabbed), str(path / "first")])
    assert [e.name for e in find("test.group")] == ["one", "two"]
    assert not cache.exists()


def test_the_cache_folder_is_the_users_cache_folder_unless_chosen(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.delenv("J5AIO_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert _entry_points._cache_folder() == str(tmp_path / "xdg" / "j5aio")
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert _entry_points._cache_folder() == str(tmp_path / "home" / ".cache" / "j5aio")
    monkeypatch.setenv("HOME", "")
    monkeypatch.setattr(os.path, "expanduser", lambda text: text)  # (no home at all)
    assert _entry_points._cache_folder() is None
    monkeypatch.setenv("J5AIO_CACHE_DIR", "relative")
    assert _entry_points._cache_folder() == os.path.abspath("relative")
    one, other = _entry_points._cache_file("a.group"), _entry_points._cache_file("b.group")
    assert one is not None and other is not None and one != other
    # Another path has a file of its own, but not another program's folder.
    monkeypatch.setattr(sys, "path", ["program", *sys.path[1:], "more"])
    assert _entry_points._cache_file("a.group") not in {one, None}
    monkeypatch.setattr(sys, "path", ["another program", *sys.path[1:-1]])
    assert _entry_points._cache_file("a.group") == one


def test_a_file_naming_the_group_without_entries_yet_is_watched(path: Path, cache: Path) -> None:
    nameless = path / "second" / "nameless-2.0.dist-info" / "entry_points.txt"
    nameless.write_text("[test.group]\n# none yet\n", encoding="utf-8")
    settle(path)
    assert [e.name for e in find("test.group")] == ["one", "two"]
    nameless.write_text("[test.group]\nthree = plugin_for_test\n", encoding="utf-8")
    os.utime(nameless, (LONG_AGO, LONG_AGO))  # (its size tells it apart)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]


@pytest.mark.skipif(not hasattr(os, "getuid"), reason="file owners are POSIX's")
def test_a_cache_file_others_may_write_is_not_read(
    path: Path, cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    settle(path)
    find("test.group")
    (remembered,) = cache.iterdir()
    remembered.chmod(0o666)
    seen = scans(monkeypatch)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert seen == ["test.group"]  # (scanned, and written again: this user's alone)
    assert remembered.stat().st_mode & 0o022 == 0
    monkeypatch.setattr(os, "getuid", lambda: remembered.stat().st_uid + 1)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert seen == ["test.group", "test.group"]


def test_a_folder_where_the_cache_file_should_be_is_passed_over(
    path: Path, cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    settle(path)
    find("test.group")
    (remembered,) = cache.iterdir()
    remembered.unlink()
    remembered.mkdir()
    seen = scans(monkeypatch)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
    assert seen == ["test.group", "test.group"]
    assert sorted(item.name for item in cache.iterdir()) == [remembered.name]  # (no leftovers)


def test_a_working_folder_that_is_gone_is_passed_over(
    path: Path, cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    def gone() -> str:
        raise FileNotFoundError("the working folder was removed")

    settle(path)
    monkeypatch.setattr(sys, "path", ["", *sys.path])
    monkeypatch.setattr(os, "getcwd", gone)
    assert [e.name for e in find("test.group")] == ["one", "two", "three"]
