import pytest

from j5aio.components import PowerOutput, PowerOutputGroup, PowerOutputInterface
from j5aio.errors import CommunicationError

from .component_fakes import RecordingBackend


async def test_set_is_enabled_switches_the_output_and_get_is_enabled_reads_it() -> None:
    backend = RecordingBackend()
    output = PowerOutput(4, backend)

    await output.set_is_enabled(True)
    assert await output.get_is_enabled() is True
    await output.set_is_enabled(False)
    assert await output.get_is_enabled() is False
    assert backend.calls == [
        ("set_power_output_enabled", (4, True)),
        ("get_power_output_enabled", (4,)),
        ("set_power_output_enabled", (4, False)),
        ("get_power_output_enabled", (4,)),
    ]


async def test_get_current_reads_the_current() -> None:
    backend = RecordingBackend()
    backend.current = 2.75
    assert await PowerOutput(1, backend).get_current() == 2.75
    assert backend.calls == [("get_power_output_current", (1,))]


@pytest.mark.parametrize("enabled", [1, 0, "yes", None])
async def test_set_is_enabled_refuses_anything_but_a_bool(enabled: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(
        TypeError, match=r"^power output state must be True \(on\) or False \(off\); got",
    ):
        await PowerOutput(0, backend).set_is_enabled(enabled)  # type: ignore[arg-type]
    assert backend.calls == []


def make_group(backend: RecordingBackend) -> PowerOutputGroup[str]:
    return PowerOutputGroup({name: PowerOutput(i, backend) for i, name in enumerate("HABC")})


async def test_group_power_on_and_off_switch_every_output_in_order() -> None:
    backend = RecordingBackend()
    group = make_group(backend)

    await group.power_on()
    assert backend.enabled == {0: True, 1: True, 2: True, 3: True}
    await group.power_off()
    assert backend.enabled == {0: False, 1: False, 2: False, 3: False}
    assert backend.calls == [
        ("set_power_output_enabled", (i, state)) for state in (True, False) for i in range(4)
    ]


async def test_group_tries_every_output_and_reraises_a_single_failure() -> None:
    backend = RecordingBackend()
    backend.enabled = dict.fromkeys(range(4), True)
    backend.broken_outputs = {1}

    with pytest.raises(CommunicationError, match=r"output 1 did not answer"):
        await make_group(backend).power_off()
    assert backend.enabled == {0: False, 1: True, 2: False, 3: False}


async def test_group_collects_several_failures_in_an_exception_group() -> None:
    backend = RecordingBackend()
    backend.broken_outputs = {0, 3}

    with pytest.raises(ExceptionGroup, match=r"2 power outputs failed to switch on") as info:
        await make_group(backend).power_on()
    assert [str(e) for e in info.value.exceptions] == [
        "output 0 did not answer",
        "output 3 did not answer",
    ]
    assert backend.enabled == {1: True, 2: True}


def test_group_lookup_iteration_and_length() -> None:
    backend = RecordingBackend()
    group = make_group(backend)

    assert len(group) == 4
    assert [output.identifier for output in group] == [0, 1, 2, 3]
    assert group["B"].identifier == 2
    expected = r"no power output 'Z': use one of H, A, B, C, or a number \(0, 1, 2, 3\)"
    with pytest.raises(KeyError, match=expected):
        group["Z"]
    assert repr(group) == "<PowerOutputGroup of 4 outputs>"


def test_identifier_and_interface() -> None:
    assert PowerOutput(6, RecordingBackend()).identifier == 6
    assert PowerOutput.interface_class() is PowerOutputInterface


def test_group_lookup_by_output_number() -> None:
    group = make_group(RecordingBackend())
    assert group[0] is group["H"]
    assert group[3] is group["C"]
    with pytest.raises(KeyError, match="no power output 7"):
        group[7]
    with pytest.raises(KeyError, match="no power output True"):
        group[True]
