import pytest

from j5aio.components import StringCommandComponent, StringCommandComponentInterface

from .component_fakes import RecordingBackend


async def test_execute_sends_the_command_and_returns_the_reply() -> None:
    backend = RecordingBackend()
    command = StringCommandComponent(0, backend)

    assert await command.execute("abc") == "cba"
    assert await command("xyz") == "zyx"
    assert backend.calls == [
        ("execute_string_command", ("abc",)),
        ("execute_string_command", ("xyz",)),
    ]


@pytest.mark.parametrize("value", [b"abc", 1, None, ["a"]])
async def test_execute_refuses_anything_but_a_str(value: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(TypeError, match=r"^a command must be a non-empty str; got"):
        await StringCommandComponent(0, backend).execute(value)  # type: ignore[arg-type]
    assert backend.calls == []


async def test_execute_refuses_an_empty_command() -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=r"^a command must be a non-empty str; got ''"):
        await StringCommandComponent(0, backend)("")
    assert backend.calls == []


def test_identifier_and_interface() -> None:
    assert StringCommandComponent(9, RecordingBackend()).identifier == 9
    assert StringCommandComponent.interface_class() is StringCommandComponentInterface
