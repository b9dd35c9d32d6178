import pytest

from j5aio.components import LED, LEDInterface

from .component_fakes import RecordingBackend


async def test_set_state_sends_the_state_and_get_state_reads_it() -> None:
    backend = RecordingBackend()
    led = LED(3, backend)

    await led.set_state(True)
    assert await led.get_state() is True
    await led.set_state(False)
    assert await led.get_state() is False

    assert backend.calls == [
        ("set_led_state", (3, True)),
        ("get_led_state", (3,)),
        ("set_led_state", (3, False)),
        ("get_led_state", (3,)),
    ]


@pytest.mark.parametrize("state", [1, 0, "on", None, 1.0])
async def test_set_state_refuses_anything_but_a_bool(state: object) -> None:
    backend = RecordingBackend()
    led = LED(0, backend)

    with pytest.raises(TypeError, match=r"LED state must be True \(on\) or False \(off\); got"):
        await led.set_state(state)  # type: ignore[arg-type]
    assert backend.calls == []


def test_identifier_and_interface() -> None:
    led = LED(7, RecordingBackend())
    assert led.identifier == 7
    assert LED.interface_class() is LEDInterface
    assert repr(led) == "<LED identifier=7>"
